/* hvb25 Tables 1-3 and the accuracy studies (footpoint noise, storage,
 * clip radius, convergence, error per stored scalar): the field [field]
 * defines (a proxy grid, a grid peer, ...) against the exact SDF of a
 * reference shape on the paper's 217^3 node grid.
 *
 * Keys.  [study]
 *   reference = <section>   the reference shape (default shape); the
 *                           ground truth is its distance as
 *                           experiments/cfg/proxy_input_cfg.h's
 *                           dfl_proxy_truth_from_cfg gives it (exact SDFs of
 *                           analytic shapes and CSG, brute-force-seeded
 *                           footpoints on parametric surfaces, certified
 *                           footpoints on implicit ones)
 *   filters   = nearest hermite ...   proxy fields only: decode the one
 *                           grid with each of these filters (each with its
 *                           default clip, proxy/filter.h, or [field]
 *                           clip_radius when given, and [field] clip's kind; signedness of
 *                           [field]), one row each; absent: the field as
 *                           [field] configures it, one row
 *   band      = 0.05        the band |d| <= band of the *_band metrics
 *   medial    = 1           medial threshold in cell sizes (hvb25_eval.h)
 * [eval] n = 217, lo = -1 -1 -1, hi = 1 1 1: the node grid.
 * Rows: one per decoding: what was built (field kind, order, res, storage,
 * stored scalars and bytes, build time, uncertified / failed / moved
 * footpoints, cells with a scalar clamped to the storage range; proxy
 * grids: wrong_footpoints, judged by the truth, not by the method's own
 * certificate: see count_wrong),
 * the decoding (filter, clip, signed) and the metrics of hvb25_eval.h:
 * l1, mse (beside the paper's undefined "L2"), rms, linf over the grid, *_band in the band,
 * *_off off the medial region, the worst point and its footpoint jump.
 * The time columns are for the report's Table 4 (gen_seconds: building
 * the field from the input, one thread per the run's thread count;
 * eval_ns_per_query: decoding time per point of the node grid), vti: the
 * decoding's volume.
 * [output] vti = true, vti_n (harness/field_out.h; default: [eval] n, at
 * most 33): volume.vti (the field as [field] decodes it) or
 * volume_<filter>.vti per filter, over the [eval] box: value, gradient,
 * reference (|d| for unsigned decodings), error = value - reference.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cfg/field_cfg.h"
#include "cfg/field_cost.h"
#include "cfg/proxy_input_cfg.h"
#include "field/gridpeer.h"
#include "harness/experiment.h"
#include "harness/field_out.h"
#include "hvb25/hvb25.h"
#include "hvb25/hvb25_eval.h"
#include "io/manifest.h"
#include "proxy/proxy_field.h"

/* The default [output] vti_n: the error grid's n, at most this (33^3
 * nodes, about 1 MB a volume after zlib: the 314 volumes of the paper
 * configs take some 300 MB; at 65^3 a volume is 7.3 MB, 2.3 GB in all). */
#define VOLUME_MAX_N 33

typedef struct acc_keys {
    const char *ref_sec;
    int nfilters;
    dfl_proxy_filter filters[HVB25_MAX_DECODINGS];
    double band, medial;
    dfl_grid eval;
    dfl_volume_opts vol;
} acc_keys;

static dfl_status read_eval(const dfl_cfg *cfg, dfl_grid *g, dfl_err *err)
{
    static const double dlo[3] = {-1, -1, -1}, dhi[3] = {1, 1, 1};
    long n;
    g->dim = 3;
    dfl_status st = dfl_cfg_int_opt(cfg, "eval", "n", 217, 2, 1024, &n, err);
    if (!st) st = dfl_cfg_vec_opt(cfg, "eval", "lo", 3, dlo, g->lo, err);
    if (!st) st = dfl_cfg_vec_opt(cfg, "eval", "hi", 3, dhi, g->hi, err);
    if (st) return st;
    for (int a = 0; a < 3; a++) {
        g->n[a] = (int)n;
        if (!(g->lo[a] < g->hi[a]))
            return dfl_cfg_reject(cfg, "eval", "hi", err, "expected hi > lo on axis %d", a);
    }
    return DFL_OK;
}

static dfl_status read_keys(const dfl_cfg *cfg, acc_keys *k, dfl_err *err)
{
    memset(k, 0, sizeof *k);
    dfl_status st = dfl_cfg_string_opt(cfg, "study", "reference", "shape", &k->ref_sec, err);
    if (!st && !dfl_cfg_has_section(cfg, k->ref_sec))
        return dfl_cfg_reject(cfg, "study", "reference", err, "no section [%s]", k->ref_sec);
    if (!st) st = hvb25_filters_from_cfg(cfg, "study", "filters", k->filters, &k->nfilters, err);
    if (!st) st = dfl_cfg_double_opt(cfg, "study", "band", 0.05, 0, 1e300, &k->band, err);
    if (!st) st = dfl_cfg_double_opt(cfg, "study", "medial", 1, 0, 1e300, &k->medial, err);
    if (!st) st = read_eval(cfg, &k->eval, err);
    /* the volume: at the error grid up to VOLUME_MAX_N nodes per axis */
    if (!st)
        st = dfl_volume_opts_from_cfg(cfg, k->eval.n[0] < VOLUME_MAX_N ? k->eval.n[0] : VOLUME_MAX_N,
                                      &k->vol, err);
    return st;
}

/* What the field stores and how it was built. */
typedef struct build_info {
    long order, res;
    size_t scalars, bytes, ncells;
    const char *storage;
    dfl_proxy_stats ps;
    hvb25_cells cells;
    long wrong; /* count_wrong; -1 for fields that are not proxy grids */
} build_info;

static void field_info(const dfl_field *f, build_info *b)
{
    const dfl_proxy_grid *g = dfl_proxy_field_grid(f);
    dfl_gridpeer_opts po;
    memset(b, 0, sizeof *b);
    b->storage = "";
    if (g) {
        b->order = g->order, b->res = g->res, b->scalars = dfl_proxy_grid_scalars(g);
        b->bytes = b->scalars * dfl_proxy_storage_size(g->storage) + (g->side ? g->ncells : 0);
        b->storage = dfl_proxy_storage_name(g->storage), b->ps = g->stats, b->ncells = g->ncells;
        b->cells.n = g->res;
        memcpy(b->cells.lo, g->lo, sizeof b->cells.lo);
        memcpy(b->cells.h, g->h, sizeof b->cells.h);
    } else if (dfl_gridpeer_field_info(f, &po)) {
        b->res = po.n, b->scalars = dfl_gridpeer_scalars(po.kind, po.n);
        b->bytes = b->scalars * (po.storage == DFL_GRIDPEER_FLOAT16 ? 2 : 8);
        b->storage = dfl_gridpeer_storage_name(po.storage);
        b->ncells = (size_t)po.n * po.n * po.n;
        b->cells.n = po.n;
        for (int a = 0; a < 3; a++)
            b->cells.lo[a] = po.lo[a], b->cells.h[a] = (po.hi[a] - po.lo[a]) / po.n;
    }
}

/* Cells whose stored footpoint p is not a closest surface point of the
 * cell centre x_c by the truth: p is off the surface (|ref(p)| > tol) or
 * farther than the truth's distance (|x_c - p| > |ref(x_c)| + tol), with
 * tol = 0.1 cell sizes; a failed (non-finite) footpoint is wrong.  Ties of
 * the truth (cells on the medial axis) are not wrong: every closest point
 * passes.  Moved cells (a centre on the surface) move by far less than tol.
 * Chunks of 256 cells in parallel; the count does not depend on threads. */
#define WRONG_CHUNK 256
static long count_wrong(const dfl_proxy_grid *g, const dfl_field *ref, int threads)
{
    const double tol = 0.1 * dfl_proxy_cell_size(g);
    const size_t nch = (g->ncells + WRONG_CHUNK - 1) / WRONG_CHUNK;
    long wrong = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : wrong) num_threads(threads)
    for (size_t ch = 0; ch < nch; ch++) {
        double xc[3 * WRONG_CHUNK], p[3 * WRONG_CHUNK], dx[WRONG_CHUNK], dp[WRONG_CHUNK];
        const size_t c0 = ch * WRONG_CHUNK;
        const size_t m = g->ncells - c0 < WRONG_CHUNK ? g->ncells - c0 : WRONG_CHUNK;
        for (size_t q = 0; q < m; q++) {
            dfl_proxy_geom pg;
            dfl_proxy_cell_centre(g, c0 + q, xc + 3 * q);
            dfl_proxy_cell_decode(g, c0 + q, &pg);
            for (int j = 0; j < 3; j++) p[3 * q + j] = pg.p[j];
        }
        ref->ops->eval(ref->ctx, m, xc, dx, NULL);
        ref->ops->eval(ref->ctx, m, p, dp, NULL);
        for (size_t q = 0; q < m; q++) {
            const double *a = xc + 3 * q, *b = p + 3 * q;
            const double r = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                                  (a[2] - b[2]) * (a[2] - b[2]));
            /* written so that NaN anywhere counts as wrong */
            if (!(fabs(dp[q]) <= tol && r <= fabs(dx[q]) + tol)) wrong++;
        }
    }
    return wrong;
}

static dfl_status put_build(dfl_table *t, const dfl_field *f, const build_info *b, double gen,
                            dfl_err *err)
{
    dfl_status st = dfl_table_set_string(t, "field_kind", f->ops->name, err);
    if (!st) st = dfl_table_set_int(t, "order", b->order, err);
    if (!st) st = dfl_table_set_int(t, "res", b->res, err);
    if (!st) st = dfl_table_set_string(t, "storage", b->storage, err);
    if (!st) st = dfl_table_set_int(t, "scalars", (long)b->scalars, err);
    if (!st) st = dfl_table_set_int(t, "bytes", (long)b->bytes, err);
    if (!st) st = dfl_table_set_double(t, "gen_seconds", gen, err);
    if (!st) st = dfl_table_set_double(t, "gen_ns_per_cell",
                                       b->ncells ? 1e9 * gen / (double)b->ncells : NAN, err);
    if (!st) st = dfl_table_set_int(t, "uncertified", (long)b->ps.uncertified, err);
    if (!st) st = dfl_table_set_int(t, "failed", (long)b->ps.failed, err);
    if (!st) st = dfl_table_set_int(t, "moved", (long)b->ps.moved, err);
    if (!st) st = dfl_table_set_int(t, "clamped", (long)b->ps.clamped, err);
    if (!st) st = dfl_table_set_int(t, "wrong_footpoints", b->wrong, err);
    return st;
}

static dfl_status write_volume(const acc_keys *k, const hvb25_acc_spec *s, int i,
                               const dfl_study_ctx *ctx, dfl_err *err);

static dfl_status acc_run(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_table *table,
                          dfl_err *err)
{
    acc_keys k;
    dfl_field f = {0};
    dfl_field ref = {0};
    dfl_status st = read_keys(cfg, &k, err);
    const double t0 = dfl_wall_seconds();
    if (!st) st = dfl_field_from_cfg(cfg, "field", &f, err);
    const double gen = dfl_wall_seconds() - t0;
    if (!st) st = dfl_proxy_truth_from_cfg(cfg, "field", k.ref_sec, &ref, err);
    if (!st && ref.dim != 3)
        st = dfl_cfg_reject(cfg, "study", "reference", err, "a 3D shape is required");
    if (!st && f.dim != 3) st = dfl_cfg_reject(cfg, "field", "kind", err, "a 3D field is required");
    const dfl_proxy_grid *grid = st ? NULL : dfl_proxy_field_grid(&f);
    if (!st && k.nfilters && !grid)
        st = dfl_cfg_reject(cfg, "study", "filters", err, "filters need a proxy field");
    if (!st) st = dfl_cfg_check_used(cfg, err);
    hvb25_acc_spec s = {.field = &f, .grid = grid, .ndec = k.nfilters, .ref = &ref,
                        .eval = k.eval, .band = k.band, .medial = k.medial,
                        .threads = ctx->threads > 0 ? ctx->threads : 1};
    const dfl_proxy_filter_opts *fo = grid ? dfl_proxy_field_opts(&f) : NULL;
    s.field_signed = fo ? fo->is_signed : 1;
    for (int i = 0; !st && i < k.nfilters; i++) {
        dfl_proxy_filter_opts_default(k.filters[i], grid, &s.dec[i]);
        s.dec[i].is_signed = fo->is_signed;
        /* [field] clip_radius, when given, is every filter's clip */
        if (dfl_cfg_has(cfg, "field", "clip_radius")) s.dec[i].clip = fo->clip;
        /* and [field] clip its formula (off: no radius at all) */
        s.dec[i].clip_kind = fo->clip_kind;
        if (fo->clip_kind == DFL_PROXY_CLIP_OFF) s.dec[i].clip = 0;
    }
    hvb25_acc_result res[HVB25_MAX_DECODINGS];
    build_info bi;
    if (!st) {
        field_info(&f, &bi);
        bi.wrong = grid ? count_wrong(grid, &ref, s.threads) : -1;
        s.cells = bi.cells;
        st = hvb25_acc_run(&s, res, err);
    }
    const size_t npts = dfl_grid_size(&k.eval);
    for (int i = 0; !st && i < (k.nfilters ? k.nfilters : 1); i++) {
        const dfl_proxy_filter_opts *o = k.nfilters ? &s.dec[i] : fo;
        st = dfl_table_row(table, err);
        if (!st) st = put_build(table, &f, &bi, gen, err);
        if (!st) st = dfl_table_set_string(table, "filter", o ? dfl_proxy_filter_name(o->filter) : "", err);
        if (!st) st = dfl_table_set_double(table, "clip", o ? o->clip : NAN, err);
        if (!st)
            st = dfl_table_set_string(table, "clip_kind",
                                      o ? dfl_proxy_clip_name(o->clip > 0 ? o->clip_kind
                                                                          : DFL_PROXY_CLIP_OFF)
                                        : "", err);
        if (!st) st = dfl_table_set_int(table, "signed", o ? o->is_signed : 1, err);
        if (!st) st = dfl_table_set_double(table, "band", k.band, err);
        if (!st) st = dfl_table_set_int(table, "eval_n", k.eval.n[0], err);
        if (!st) st = hvb25_acc_put(table, &res[i], npts, err);
        char stem[64] = "volume";
        if (k.nfilters) snprintf(stem, sizeof stem, "volume_%s", dfl_proxy_filter_name(o->filter));
        if (!st) st = dfl_study_put_file(table, "vti", ctx, stem, "vti", k.vol.vti, err);
    }
    for (int i = 0; !st && k.vol.vti && i < (k.nfilters ? k.nfilters : 1); i++)
        st = write_volume(&k, &s, i, ctx, err);
    dfl_field_destroy(&f);
    dfl_field_destroy(&ref);
    return st;
}

/* The volume of decoding i: "volume" for the field as [field] decodes
 * it, "volume_<filter>" for each of [study] filters; over the box of
 * [eval] at [output] vti_n nodes per axis, the reference |d| for unsigned
 * decodings (the error the rows measure). */
static dfl_status write_volume(const acc_keys *k, const hvb25_acc_spec *s, int i,
                               const dfl_study_ctx *ctx, dfl_err *err)
{
    dfl_grid g;
    dfl_volume_grid(k->eval.lo, k->eval.hi, k->vol.n, &g);
    char stem[64] = "volume";
    dfl_field view = *s->field;
    hvb25_view v;
    int is_signed = s->field_signed;
    if (s->ndec) {
        v.g = s->grid, v.o = s->dec[i];
        hvb25_view_field(&v, &view);
        is_signed = v.o.is_signed;
        snprintf(stem, sizeof stem, "volume_%s", dfl_proxy_filter_name(v.o.filter));
    }
    return dfl_volume_write(ctx, stem, &view, s->ref, !is_signed, &g, NULL, 0, k->vol.compress,
                            err);
}

/* Peak memory: the field ([field]'s cost) and the evaluation's slab
 * buffers (hvb25_eval.c: about 83 bytes per node of one z-slab, doubled for
 * slack).  Work: every node of the [eval] grid decoded once per decoding,
 * and its reference distance at the reference shape's cost class. */
static dfl_status acc_estimate(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_cost *c,
                               dfl_err *err)
{
    acc_keys k;
    dfl_status st = read_keys(cfg, &k, err);
    if (!st) st = dfl_study_estimate_default(cfg, ctx, c, err);
    if (st) return st;
    const double n = k.eval.n[0], nodes = n * n * n;
    dfl_cost_add_bytes(c, "eval", "n", 2 * 83 * n * n, "evaluation slabs of %.0f^2 nodes", n);
    const int dec = k.nfilters ? k.nfilters : 1;
    if (k.vol.vti)
        dfl_cost_add_bytes(c, "output", "vti_n", dfl_volume_bytes(k.vol.n, 0),
                           "a volume of %ld^3 nodes", k.vol.n);
    dfl_cost_add_work(c, "eval", "n", DFL_COST_DECODE, nodes * dec, "%.3g nodes x %d decodings",
                      nodes, dec);
    dfl_cost_add_work(c, "eval", "n", dfl_shape_cost_class(cfg, k.ref_sec), nodes,
                      "%.3g reference distances", nodes);
    return DFL_OK;
}

DFL_STUDY_DEFINE_ESTIMATED(hvb25_accuracy, acc_run, acc_estimate,
                 "hvb25 Tables 1-3: a proxy grid (or a grid peer) vs the exact SDF on 217^3 nodes");
