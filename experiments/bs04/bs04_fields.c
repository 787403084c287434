/* bs04 Fig. 1 and Fig. 3(b): the approximate distance fields of two line
 * segments (Fig. 1 a, b: each trimmed by its own region, eq. 4 or 5), their
 * join (Fig. 1 c: R-equivalence of order 2 in the paper), and one
 * segment's field under each trim (Fig. 3 b: the disk; also the strip and
 * the smooth composition eq. 5), sampled on a grid, with |grad u|
 * statistics and errors against the exact (unsigned) distance to the set.
 *
 * Keys.  [field] kind = rfunc (cfg/rfunc_cfg.h): the joined field of Fig.
 * 1(c), so `dflab probe` evaluates it:
 *   vertices  = x0 y0; x1 y1; x2 y2   the open polyline A = v0-v1, B = v1-v2
 *                                (v1 is the shared vertex of the corrected join)
 *   join      = requiv | rconj | requiv_corrected   (default requiv)
 *   correction = guarded | eq20  (corrected join; default guarded)
 *   p         = order (default 2; rconj needs >= 2)
 *   trim      = disk | disk_smooth | strip | strip_smooth   (default disk)
 * Fields a and b are A's and B's own fields (same trim).
 * [study]:
 *   band      = 0.1   |grad u| and errors also over the nodes with exact
 *                     distance d <= band (> 0)
 * [grid] n, lo, hi (2D; grid_cfg.h), [output] (field_out.h).
 *
 * Rows (one per field: a, b, join): field, nodes, offset nodes (u > 0:
 * the gradient is 0 by convention on the zero set, those nodes are left
 * out of the |grad u| statistics), gradnorm_min/mean/max (all off-set
 * nodes), the same over the band, l1/linf of u - d (all, band);
 * single segments also: trim_nodes (t > 0 and u > 0) and on them
 * trim_value_maxdev = max |u - |f|| and trim_gradnorm_maxdev =
 * max ||grad u| - 1| (theory: 0 for eq. 4, where h = |f| exactly);
 * the join also: ratio_min/max of u / min(h_a, h_b) with the theory
 * bounds ratio_lo (2^(-1/p) for requiv, 2 - 2^(1/p) for rconj, the values
 * at h_a = h_b) and ratio_hi = 1 (both joins lie below min(h_a, h_b));
 * vti: the file.
 * Files: field_a, field_b, field_join (.vti with value, gradient,
 * grad_norm, error = u - d, reference = d; .exr with value, grad_norm,
 * error).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/experiment.h"
#include "field/sample.h"
#include "harness/field_out.h"
#include "cfg/field_cost.h"
#include "cfg/grid_cfg.h"
#include "cfg/list_cfg.h"
#include "cfg/rfunc_cfg.h"
#include "rfunc/rfield.h"
#include "rfunc/segment.h"
#include "geom/segdist.h"

typedef struct fields_keys {
    dfl_rfunc_field_spec spec; /* [field] (owned) */
    double seg[2][4];   /* a0 a1 b0 b1 per segment */
    dfl_rfunc_join join;
    dfl_rfunc_trim trim;
    int p;
    double band;
    dfl_grid grid;
    dfl_field_write_opts out;
} fields_keys;

static dfl_status read_keys(const dfl_cfg *cfg, fields_keys *k, dfl_err *err)
{
    dfl_status st;
    memset(k, 0, sizeof *k);
    if ((st = dfl_rfunc_spec_from_kind_cfg(cfg, "field", "bs04_fields", &k->spec, err))) return st;
    const dfl_rfunc_field_spec *sp = &k->spec;
    if (sp->dim != 2 || sp->n != 3 || sp->closed || sp->curve || sp->nregion || sp->npoints ||
        sp->ntris)
        return dfl_err_set(err, DFL_E_INPUT,
                           "%s: [field] of bs04_fields: expected an open 2D polyline of 3"
                           " vertices (two segments), nothing else",
                           dfl_cfg_path(cfg));
    if ((st = dfl_rfunc_join_check(sp->join, sp->p, err)))
        return dfl_cfg_err_at(cfg, "field", "p", st, err);
    memcpy(k->seg[0], sp->v, 4 * sizeof *sp->v);
    memcpy(k->seg[1], sp->v + 2, 4 * sizeof *sp->v);
    k->join = sp->join;
    k->p = sp->p;
    k->trim = sp->trim;
    if ((st = dfl_cfg_double_opt(cfg, "study", "band", 0.1, 0.0, 1e300, &k->band, err))) return st;
    if (!(k->band > 0.0))
        return dfl_cfg_reject(cfg, "study", "band", err, "expected band > 0, got %g", k->band);
    if ((st = dfl_grid_from_cfg(cfg, "grid", 2, &k->grid, err))) return st;
    return dfl_field_out_from_cfg(cfg, &k->out, err);
}

/* The field of the segments sel (bit 0: A, bit 1: B) joined by k's join. */
static dfl_status build(const fields_keys *k, int sel, const char *where, dfl_field *out,
                        dfl_err *err)
{
    dfl_rfield *r = NULL;
    dfl_status st = dfl_rfield_new(2, k->join, k->p, &r, err);
    for (int i = 0; i < 2 && st == DFL_OK; i++)
        if (sel >> i & 1)
            st = dfl_rfield_add_segment(r, k->seg[i], k->seg[i] + 2, k->trim, err);
    if (st == DFL_OK && sel == 3 && k->seg[0][2] == k->seg[1][0] && k->seg[0][3] == k->seg[1][1])
        st = dfl_rfield_add_vertex(r, k->seg[1], 0, 1, err);
    if (st != DFL_OK) {
        dfl_rfield_free(r);
        dfl_err_prefix(err, "%s", where);
        return st;
    }
    st = dfl_rfield_finish(&r, out, err);
    if (st != DFL_OK) dfl_err_prefix(err, "%s", where);
    return st;
}

typedef struct gstats {
    long n;
    double min, max, sum;
} gstats;

static void gs_init(gstats *s)
{
    s->n = 0;
    s->min = INFINITY;
    s->max = -INFINITY;
    s->sum = 0;
}

static void gs_add(gstats *s, double v)
{
    s->n++;
    s->sum += v;
    if (v < s->min) s->min = v;
    if (v > s->max) s->max = v;
}

/* u, grad u of the three fields (a, b, join) on the grid, and as their
 * references the exact distances to A, to B and to their union; the
 * buffers are allocated here (the caller frees them, also on failure). */
static dfl_status sample_fields(const fields_keys *k, const dfl_field *f, int threads,
                                dfl_field_bufs *b, dfl_err *err)
{
    const size_t m = dfl_grid_size(&k->grid);
    for (int i = 0; i < 3; i++)
        if (!dfl_field_bufs_alloc(&b[i], m, 2, true))
            return dfl_err_set(err, DFL_E_NOMEM, "out of memory for %zu nodes", m);
    dfl_status st = DFL_OK;
    for (int i = 0; i < 3 && st == DFL_OK; i++)
        st = dfl_field_sample(&f[i], &k->grid, threads, b[i].u, b[i].gu, err);
    if (st != DFL_OK) return st;
    for (size_t j = 0; j < m; j++) {
        double x[2];
        dfl_grid_node(&k->grid, j, x);
        b[0].ref[j] = dfl_point_segment_dist_hypot(x, k->seg[0], k->seg[0] + 2);
        b[1].ref[j] = dfl_point_segment_dist_hypot(x, k->seg[1], k->seg[1] + 2);
        b[2].ref[j] = fmin(b[0].ref[j], b[1].ref[j]);
    }
    return DFL_OK;
}

/* One field's statistics over the grid (see the rows at the top). */
typedef struct field_stats {
    gstats all, band, trim;   /* |grad u| off the set; in the band; ||grad u| - 1| in the trim */
    double l1, linf, l1b, linfb; /* sum and max of |u - d|: all nodes, band */
    long nb;                  /* band nodes */
    double vdev;              /* single segments: max |u - |f|| where t > 0 */
    double rmin, rmax;        /* the join: range of u / min(h_a, h_b) */
} field_stats;

static void field_stats_compute(const fields_keys *k, const dfl_rfunc_seg *seg, int i, size_t m,
                                const dfl_field_bufs *b, field_stats *fs)
{
    const double *const u[3] = {b[0].u, b[1].u, b[2].u};
    const double *const gu = b[i].gu, *const d = b[i].ref;
    gstats all, band, trim;
    gs_init(&all);
    gs_init(&band);
    gs_init(&trim);
    double l1 = 0, linf = 0, l1b = 0, linfb = 0, vdev = 0, rmin = INFINITY, rmax = -INFINITY;
    long nb = 0;
    for (size_t j = 0; j < m; j++) {
        const double e = fabs(u[i][j] - d[j]);
        l1 += e;
        if (e > linf) linf = e;
        if (d[j] <= k->band) {
            nb++;
            l1b += e;
            if (e > linfb) linfb = e;
        }
        if (!(u[i][j] > 0.0)) continue;
        const double gn = hypot(gu[2 * j], gu[2 * j + 1]);
        gs_add(&all, gn);
        if (d[j] <= k->band) gs_add(&band, gn);
        double x[2];
        dfl_grid_node(&k->grid, j, x);
        if (i < 2 && dfl_rfunc_seg_trim(&seg[i], x, NULL) > 0.0) {
            gs_add(&trim, fabs(gn - 1.0));
            const double fe = fabs(fabs(dfl_rfunc_seg_line(&seg[i], x, NULL)) - u[i][j]);
            if (fe > vdev) vdev = fe;
        }
        if (i == 2) {
            const double r = u[2][j] / fmin(u[0][j], u[1][j]);
            if (r < rmin) rmin = r;
            if (r > rmax) rmax = r;
        }
    }
    *fs = (field_stats){all, band, trim, l1, linf, l1b, linfb, nb, vdev, rmin, rmax};
}

static dfl_status fields_run(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_table *table,
                             dfl_err *err)
{
    fields_keys k;
    dfl_field f[3];
    dfl_field_bufs b[3];
    char w[2][600];
    memset(f, 0, sizeof f);
    memset(b, 0, sizeof b);
    dfl_status st = read_keys(cfg, &k, err);
    if (st == DFL_OK) dfl_cfg_where(cfg, "field", "vertices", w[0], sizeof w[0]);
    /* building validates the geometry (degenerate segments) before any
     * file; the join is [field]'s own field */
    for (int i = 0; i < 2 && st == DFL_OK; i++) st = build(&k, i + 1, w[0], &f[i], err);
    if (st == DFL_OK) st = dfl_rfunc_field_from_spec(cfg, "field", &k.spec, &f[2], err);
    if (st == DFL_OK) st = dfl_cfg_check_used(cfg, err);
    if (st != DFL_OK) goto done;

    dfl_rfunc_seg seg[2];
    for (int i = 0; i < 2 && st == DFL_OK; i++)
        st = dfl_rfunc_seg_init(2, k.seg[i], k.seg[i] + 2, k.trim, &seg[i], err);
    if (st == DFL_OK) st = sample_fields(&k, f, ctx->threads, b, err);
    if (st != DFL_OK) goto done;

    const size_t m = dfl_grid_size(&k.grid);
    const int p = (int)k.p;
    static const char *const names[3] = {"a", "b", "join"};
    for (int i = 0; i < 3 && st == DFL_OK; i++) {
        field_stats fs;
        field_stats_compute(&k, seg, i, m, b, &fs);
        const gstats all = fs.all, band = fs.band, trim = fs.trim;
        const double l1 = fs.l1, linf = fs.linf, l1b = fs.l1b, linfb = fs.linfb, vdev = fs.vdev;
        const double rmin = fs.rmin, rmax = fs.rmax;
        const long nb = fs.nb;
        char stem[32];
        snprintf(stem, sizeof stem, "field_%s", names[i]);
        st = dfl_table_row(table, err);
#define SETI(c, v) \
    if (!st) st = dfl_table_set_int(table, c, (long)(v), err)
#define SETD(c, v) \
    if (!st) st = dfl_table_set_double(table, c, v, err)
        if (!st) st = dfl_table_set_string(table, "field", names[i], err);
        if (!st) st = dfl_table_set_string(table, "join", i == 2 ? dfl_rfunc_join_name((dfl_rfunc_join)k.join) : "", err);
        SETI("p", p);
        if (!st) st = dfl_table_set_string(table, "trim", dfl_rfunc_trim_name((dfl_rfunc_trim)k.trim), err);
        SETI("nodes", m);
        SETI("offset_nodes", all.n);
        SETD("gradnorm_min", all.min);
        SETD("gradnorm_mean", all.sum / (double)all.n);
        SETD("gradnorm_max", all.max);
        SETD("band", k.band);
        SETI("band_nodes", band.n);
        if (band.n) {
            SETD("gradnorm_min_band", band.min);
            SETD("gradnorm_mean_band", band.sum / (double)band.n);
            SETD("gradnorm_max_band", band.max);
        }
        SETD("l1", l1 / (double)m);
        SETD("linf", linf);
        if (nb) {
            SETD("l1_band", l1b / (double)nb);
            SETD("linf_band", linfb);
        }
        if (i < 2) {
            SETI("trim_nodes", trim.n);
            if (trim.n) {
                SETD("trim_value_maxdev", vdev);
                SETD("trim_gradnorm_maxdev", trim.max);
            }
        } else {
            SETD("ratio_min", rmin);
            SETD("ratio_max", rmax);
            if (k.join != DFL_RFUNC_REQUIV_CORRECTED) {
                SETD("ratio_lo", k.join == DFL_RFUNC_REQUIV ? pow(2.0, -1.0 / p)
                                                            : 2.0 - pow(2.0, 1.0 / p));
                SETD("ratio_hi", 1.0);
            }
        }
        if (!st) st = dfl_study_put_file(table, "vti", ctx, stem, "vti", k.out.vti, err);
#undef SETI
#undef SETD
    }
    for (int i = 0; i < 3 && st == DFL_OK; i++) {
        char stem[32];
        snprintf(stem, sizeof stem, "field_%s", names[i]);
        st = dfl_field_out_write(ctx, stem, &k.grid, b[i].u, b[i].gu, b[i].ref, &k.out, err);
    }
done:
    for (int i = 0; i < 3; i++) dfl_field_bufs_free(&b[i]);
    for (int i = 0; i < 3; i++) dfl_field_destroy(&f[i]); /* zeroed when not built */
    dfl_rfunc_spec_free(&k.spec);
    return st;
}

/* Peak memory: the join ([field]'s parts) and the three fields' samples
 * on [grid], held together (u, grad u, reference: 32 bytes a node each),
 * and the writer's buffers of one file (dfl_field_out_bytes).  Work per
 * node: the join (dfl_field_eval_cost), the two one-part fields and the two
 * exact segment distances; three files. */
static dfl_status fields_estimate(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_cost *c,
                                  dfl_err *err)
{
    dfl_field_write_opts out;
    dfl_grid g;
    dfl_cost_class cls;
    double units;
    dfl_status st = dfl_study_estimate_default(cfg, ctx, c, err);
    if (!st) st = dfl_field_eval_cost(cfg, "field", &cls, &units, err);
    if (!st) st = dfl_grid_cost_from_cfg(cfg, "grid", 2, 3 * 32.0, "three fields' samples", c, &g, err);
    if (!st) st = dfl_field_out_from_cfg(cfg, &out, err);
    if (st) return st;
    const double m = (double)dfl_grid_size(&g);
    dfl_cost_add_bytes(c, "grid", "n", dfl_field_out_bytes(&out, m), "the field files' buffers");
    dfl_cost_add_work(c, "grid", "n", cls, m * (units + 2 * (1 + DFL_RFUNC_EVAL_UNITS) + 2),
                      "%.3g nodes x 3 fields", m);
    dfl_cost_add_work(c, "grid", "n", DFL_COST_CHEAP, 3 * dfl_field_out_units(&out, m),
                      "the files of 3 fields");
    return DFL_OK;
}

DFL_STUDY_DEFINE_ESTIMATED(bs04_fields, fields_run, fields_estimate,
                 "bs04 Fig. 1, 3b: two segment fields, their join, the trims; |grad u| statistics");
