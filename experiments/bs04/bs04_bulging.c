/* bs04 Fig. 6 and Fig. 2: bulging of the level sets of R-function fields of
 * polygonized curves near the joining points, against the order p and the
 * offset delta.
 *
 * Bulge measure (curveprobe.h).  For an offset delta, rays leave the exact
 * curve C along its normals (and around its end points); a ray from o in
 * direction v is kept when o + delta v lies on the true offset {d = delta}
 * (d(o + delta v) >= delta (1 - valid_tol)), and along it the first
 * crossing s of the level set {u = delta} is found by bracketing and
 * subdivision.  The ray's bulge is r = (s - delta) / delta: the distance,
 * along the true gradient, from the true offset curve to the level set of
 * u, in units of delta (r > 0: the level set of u lies outside the true
 * offset, u grows too slowly; r < 0: inside).  The study reports
 * max r (the bulge), min r, mean r, the maxima over side / end-cap /
 * joint rays (joint rays start at the polygon's vertices, where bs04's
 * normalization is lost), and mean r on the flattest and most curved thirds
 * of the curve, the latter split into the inner side of the turns (towards
 * the centre of curvature: bs04's "convex sector", angle < pi) and the outer.
 *
 * Theory (join.h, bs04 eq. 6): at a joint of two collinear parts whose
 * fields both equal the distance to their carrier line there (strip trims
 * at the joint; disk trims to first order in delta / segment length),
 * u = (2 h^-p)^(-1/p) = 2^(-1/p) h, so the level set u = delta is at
 * s = 2^(1/p) delta: r -> 2^(1/p) - 1 (0.414, 0.260, 0.149, 0.104, 0.059 for
 * p = 2, 3, 5, 7, 12).  Column joint_limit holds this value for R-equivalence
 * (NAN for the other joins).
 *
 * Keys.  [study]
 *   cases     = <section> ...   blank-separated case sections (below)
 *   p         = integer 1..64   order of the join (a comma list sweeps it)
 *   smax      = 8               crossings are searched in [0, smax delta]
 *   steps     = 128             bracketing samples per ray
 *   rounds    = 6               16-fold refinements (final bracket
 *                               smax delta / steps / 16^rounds)
 *   valid_tol = 1e-6            relative tolerance of the offset test
 * A case section:
 *   curve    = <section>        kind = bspline_curve (order 2 for a
 *                               polyline): the exact set C, polygonized
 *                               with eps; its footpoint keys (backend,
 *                               samples, candidates) serve the exact distance
 *   eps      = 1e-3             polygonization bound (> 0)
 *   join     = requiv | rconj | requiv_corrected   (default requiv)
 *   trim     = disk | disk_smooth | strip | strip_smooth   (default disk)
 *   levels   = d1 d2 ...        offsets delta (> 0)
 *   rays     = 801              ray origins along C (2 rays each)
 *   cap_rays = 64               rays around each end point (open curves)
 *   grid     = <section>        [grid]-style section for the images and
 *                               the band statistics
 * [output] vti, exr, compress, half (field_out.h).
 * Rows: one per case and delta.  Files per case: <case>_u<tag>.vti/.exr (u,
 * with the exact distance as reference and error = u - d) and, at the first
 * sweep point, <case>_exact<tag>.vti/.exr (the exact distance).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bs04/bs04_offsets.h"
#include "cfg/curve_cfg.h"
#include "field/curveprobe.h"
#include "harness/experiment.h"
#include "field/exact.h"
#include "field/metrics.h"
#include "field/sample.h"
#include "harness/field_out.h"
#include "geom/polygonize.h"
#include "io/path.h"
#include "cfg/field_cost.h"
#include "cfg/grid_cfg.h"
#include "cfg/list_cfg.h"
#include "cfg/rfunc_cfg.h"
#include "rfunc/rfield.h"

#define MAX_CASES 8
#define NAME_LEN DFL_SECTION_NAME_LEN

typedef struct bulge_case {
    char name[NAME_LEN];
    const char *curve_sec;
    double eps;
    dfl_rfunc_join join;
    dfl_rfunc_trim trim;
    double *levels;
    size_t nlevels;
    long rays, cap_rays;
    dfl_grid grid;
    dfl_bspline curve;   /* owned */
    dfl_shape shape;     /* exact distance; moved into a field when used */
    int have_curve, have_shape;
} bulge_case;

typedef struct bulge_keys {
    int ncases;
    bulge_case c[MAX_CASES];
    long p;
    dfl_bs04_offset_opts search;
    dfl_field_write_opts out;
} bulge_keys;

static void keys_free(bulge_keys *k)
{
    for (int i = 0; i < k->ncases; i++) {
        free(k->c[i].levels);
        if (k->c[i].have_curve) dfl_bspline_free(&k->c[i].curve);
        if (k->c[i].have_shape) dfl_shape_free(&k->c[i].shape);
    }
}

static dfl_status read_case(const dfl_cfg *cfg, bulge_case *c, dfl_err *err)
{
    const char *sec = c->name, *gsec;
    dfl_status st;
    if (!dfl_cfg_has_section(cfg, sec))
        return dfl_cfg_reject(cfg, "study", "cases", err, "no section [%s]", sec);
    if ((st = dfl_cfg_string(cfg, sec, "curve", &c->curve_sec, err))) return st;
    if (!dfl_cfg_has_section(cfg, c->curve_sec))
        return dfl_cfg_reject(cfg, sec, "curve", err, "no section [%s]", c->curve_sec);
    if ((st = dfl_curve_section_from_cfg(cfg, c->curve_sec, &c->curve, err))) return st;
    c->have_curve = 1;
    if (c->curve.dim != 2)
        return dfl_cfg_reject(cfg, c->curve_sec, "control", err, "a planar curve is required");
    if ((st = dfl_param_shape_from_cfg(cfg, c->curve_sec, "bspline_curve", &c->shape, err)))
        return st;
    c->have_shape = 1;
    /* >= 1e-12: see the eps of experiments/cfg/rfunc_cfg.c (segment count
     * and coordinate rounding) */
    if ((st = dfl_cfg_double(cfg, sec, "eps", 1e-12, 1e300, &c->eps, err))) return st;
    if ((st = dfl_rfunc_join_from_cfg(cfg, sec, &c->join, err))) return st;
    if ((st = dfl_rfunc_trim_from_cfg(cfg, sec, &c->trim, err))) return st;
    if ((st = dfl_cfg_doubles(cfg, sec, "levels", 1, &c->levels, &c->nlevels, err))) return st;
    for (size_t i = 0; i < c->nlevels; i++)
        if (!(c->levels[i] > 0.0))
            return dfl_cfg_reject(cfg, sec, "levels", err, "expected offsets > 0, got %g",
                                  c->levels[i]);
    if ((st = dfl_cfg_int_opt(cfg, sec, "rays", 801, 2, 1000000, &c->rays, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "cap_rays", 64, 0, 100000, &c->cap_rays, err))) return st;
    if ((st = dfl_cfg_string(cfg, sec, "grid", &gsec, err))) return st;
    if (!dfl_cfg_has_section(cfg, gsec))
        return dfl_cfg_reject(cfg, sec, "grid", err, "no section [%s]", gsec);
    return dfl_grid_from_cfg(cfg, gsec, 2, &c->grid, err);
}

static dfl_status read_keys(const dfl_cfg *cfg, bulge_keys *k, dfl_err *err)
{
    char names[MAX_CASES][NAME_LEN];
    char w[600];
    dfl_status st;
    memset(k, 0, sizeof *k);
    if ((st = dfl_section_names_from_cfg(cfg, "study", "cases", MAX_CASES, names, &k->ncases,
                                         "case section", err)))
        return st;
    for (int i = 0; i < k->ncases; i++) memcpy(k->c[i].name, names[i], NAME_LEN);
    if ((st = dfl_cfg_int(cfg, "study", "p", 1, DFL_RFUNC_P_MAX, &k->p, err))) return st;
    if ((st = dfl_bs04_offset_opts_from_cfg(cfg, "study", &k->search, err))) return st;
    for (int i = 0; i < k->ncases; i++) {
        if ((st = read_case(cfg, &k->c[i], err))) return st;
        if ((st = dfl_rfunc_join_check(k->c[i].join, (int)k->p, err)))
            return dfl_err_prefix(err, "%s (join %s of [%s])",
                                  dfl_cfg_where(cfg, "study", "p", w, sizeof w),
                                  dfl_rfunc_join_name(k->c[i].join), k->c[i].name);
    }
    return dfl_field_out_from_cfg(cfg, &k->out, err);
}

/* The R-function field of c's polygonization and the vertex parameters of
 * its joints (interior vertices; every vertex of a closed curve). */
static dfl_status build_field(const bulge_case *c, int p, dfl_polyline *pl, dfl_field *u,
                              size_t *nseg, dfl_err *err)
{
    dfl_status st = dfl_polygonize_curve(&c->curve, c->eps, 0, pl, err);
    if (st != DFL_OK) return dfl_err_prefix(err, "[%s] eps", c->name);
    size_t n = pl->n;
    const int dim = pl->dim;
    const int closed = n >= 4 && memcmp(pl->pts, pl->pts + (n - 1) * (size_t)dim,
                                        (size_t)dim * sizeof *pl->pts) == 0;
    *nseg = n - 1;
    if (closed) n--;
    st = dfl_rfield_polyline(dim, pl->pts, n, closed, c->join, p, c->trim, u, err);
    if (st != DFL_OK) return dfl_err_prefix(err, "[%s]", c->name);
    return DFL_OK;
}

static dfl_status put_row(dfl_table *t, const bulge_keys *k, const bulge_case *c, size_t nseg,
                          double delta, const dfl_rayset *rs, const dfl_ray_stats *rst,
                          const dfl_bandstats *bs, const char *uname, const char *dname,
                          dfl_err *err)
{
    const char *const *joins = dfl_rfunc_join_names, *const *trims = dfl_rfunc_trim_names;
    const double limit =
        c->join == DFL_RFUNC_REQUIV ? pow(2.0, 1.0 / (double)k->p) - 1.0 : NAN;
    const size_t a = rst->argmax;
    const int has = a != (size_t)-1;
    dfl_status st = dfl_table_row(t, err);
    if (!st) st = dfl_table_set_string(t, "case", c->name, err);
    if (!st) st = dfl_table_set_int(t, "p", k->p, err);
    if (!st) st = dfl_table_set_string(t, "join", joins[c->join], err);
    if (!st) st = dfl_table_set_string(t, "trim", trims[c->trim], err);
    if (!st) st = dfl_table_set_double(t, "eps", c->eps, err);
    if (!st) st = dfl_table_set_int(t, "segments", (long)nseg, err);
    if (!st) st = dfl_table_set_double(t, "delta", delta, err);
    if (!st) st = dfl_table_set_int(t, "rays", (long)rs->n, err);
    if (!st) st = dfl_table_set_int(t, "rays_valid", (long)rst->valid, err);
    if (!st) st = dfl_table_set_int(t, "unresolved", (long)rst->unresolved, err);
    if (!st) st = dfl_table_set_int(t, "beyond", (long)rst->beyond, err);
    if (!st) st = dfl_table_set_double(t, "merged", rst->merged, err);
    if (!st) st = dfl_table_set_double(t, "bulge_max", rst->max, err);
    if (!st) st = dfl_table_set_double(t, "bulge_min", rst->min, err);
    if (!st) st = dfl_table_set_double(t, "bulge_mean", rst->mean, err);
    if (!st) st = dfl_table_set_double(t, "bulge_side_max", rst->side_max, err);
    if (!st) st = dfl_table_set_double(t, "bulge_cap_max", rst->cap_max, err);
    if (!st) st = dfl_table_set_double(t, "bulge_joint_max", rst->joint_max, err);
    if (!st) st = dfl_table_set_double(t, "joint_limit", limit, err);
    if (!st) st = dfl_table_set_double(t, "bulge_flat_mean", rst->flat_mean, err);
    if (!st) st = dfl_table_set_double(t, "bulge_curved_mean", rst->curved_mean, err);
    if (!st) st = dfl_table_set_double(t, "bulge_outer_mean", rst->outer_mean, err);
    if (!st) st = dfl_table_set_double(t, "bulge_inner_mean", rst->inner_mean, err);
    if (!st) st = dfl_table_set_double(t, "max_x", has ? rs->o[2 * a] : NAN, err);
    if (!st) st = dfl_table_set_double(t, "max_y", has ? rs->o[2 * a + 1] : NAN, err);
    if (!st) st = dfl_table_set_double(t, "max_vx", has ? rs->v[2 * a] : NAN, err);
    if (!st) st = dfl_table_set_double(t, "max_vy", has ? rs->v[2 * a + 1] : NAN, err);
    if (!st) st = dfl_table_set_string(t, "max_kind",
                                       !has ? "" : rs->kind[a] == DFL_RAY_JOINT ? "joint"
                                                 : rs->kind[a] == DFL_RAY_CAP  ? "cap"
                                                                              : "side",
                                       err);
    if (!st) st = dfl_metrics_put_bandstats(t, bs, err);
    if (!st) st = dfl_table_set_string(t, "u_vti", uname, err);
    if (!st) st = dfl_table_set_string(t, "exact_vti", dname, err);
    return st;
}

static dfl_status run_case(const bulge_keys *k, bulge_case *c, const dfl_study_ctx *ctx,
                           dfl_table *table, dfl_err *err)
{
    dfl_bs04_offsets r;
    memset(&r, 0, sizeof r);
    size_t nseg = 0;
    dfl_status st = build_field(c, (int)k->p, &r.pl, &r.u, &nseg, err);
    if (st == DFL_OK) {
        st = dfl_field_exact_new(&c->shape, &r.exact, err);
        if (st == DFL_OK) c->have_shape = 0;
    }
    if (st == DFL_OK) {
        const int closed = c->curve.closed;
        const size_t nj = closed ? r.pl.n - 1 : r.pl.n - 2;
        st = dfl_curveprobe_rays(&c->curve, (size_t)c->rays, (size_t)c->cap_rays,
                                 closed ? r.pl.t : r.pl.t + 1, nj, &r.rays, err);
    }
    const size_t m = dfl_grid_size(&c->grid);
    char what[NAME_LEN + 2];
    snprintf(what, sizeof what, "[%s]", c->name);
    if (st == DFL_OK) st = dfl_bs04_offsets_alloc(&r, m, what, err);
    if (st == DFL_OK) st = dfl_bs04_offsets_sample(&r, &c->grid, ctx->threads, err);
    char ustem[NAME_LEN + 8], dstem[NAME_LEN + 8], upath[4400], dpath[4400];
    snprintf(ustem, sizeof ustem, "%s_u", c->name);
    snprintf(dstem, sizeof dstem, "%s_exact", c->name);
    dfl_study_path(ctx, ustem, "vti", upath, sizeof upath);
    /* the exact image is written once, at the first sweep point */
    dfl_study_path_at(ctx, 0, dstem, "vti", dpath, sizeof dpath);
    for (size_t l = 0; l < c->nlevels && st == DFL_OK; l++) {
        const double delta = c->levels[l];
        dfl_ray_stats rst;
        dfl_bandstats bs;
        st = dfl_bs04_offsets_level(&r, m, delta, &k->search, ctx->threads, &rst, &bs, err);
        if (st == DFL_OK)
            st = put_row(table, k, c, nseg, delta, &r.rays, &rst, &bs, dfl_path_base(upath),
                         dfl_path_base(dpath), err);
    }
    if (st == DFL_OK) st = dfl_field_out_write(ctx, ustem, &c->grid, r.uv, r.ug, r.dv, &k->out, err);
    if (st == DFL_OK && ctx->point == 0)
        st = dfl_field_out_write(ctx, dstem, &c->grid, r.dv, r.dg, NULL, &k->out, err);
    dfl_bs04_offsets_free(&r);
    return st;
}

static dfl_status bulging_run(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_table *table,
                              dfl_err *err)
{
    bulge_keys k;
    dfl_status st = read_keys(cfg, &k, err);
    if (st == DFL_OK) st = dfl_cfg_check_used(cfg, err);
    for (int i = 0; i < k.ncases && st == DFL_OK; i++) st = run_case(&k, &k.c[i], ctx, table, err);
    keys_free(&k);
    return st;
}

/* Peak memory: the cases run one after another; a case holds its field
 * (the polygonization, at most dfl_polygonize_curve_segments_bound
 * segments at eps, DFL_RFUNC_PART_BYTES each), the offset measurement's
 * grid and rays (dfl_bs04_offsets_cost: 2 rays per side origin, per cap
 * ray and per joint, a vertex of the polygon) and the writer's buffers.
 * Work: dfl_bs04_offsets_cost (an evaluation: one CHEAP per part and
 * DFL_RFUNC_EVAL_UNITS) and the files (the exact one at point 0). */
static dfl_status bulging_estimate(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_cost *c,
                                   dfl_err *err)
{
    bulge_keys k;
    dfl_status st = read_keys(cfg, &k, err);
    for (int i = 0; i < k.ncases && !st; i++) {
        const bulge_case *b = &k.c[i];
        const char *sec = dfl_cfg_section_name(cfg, b->name), *gsec = "grid";
        dfl_cfg_string(cfg, sec, "grid", &gsec, NULL);
        gsec = dfl_cfg_section_name(cfg, gsec);
        const double parts = dfl_polygonize_curve_segments_bound(&b->curve, b->eps) + 1;
        const double nodes = (double)dfl_grid_size(&b->grid);
        const double rays = 2.0 * (double)(b->rays + b->cap_rays) + 2 * parts;
        dfl_cost one;
        memset(&one, 0, sizeof one);
        dfl_cost_add_bytes(&one, sec, "eps", parts * DFL_RFUNC_PART_BYTES,
                           "an R-function field of up to %.3g segments", parts);
        dfl_cost_add_bytes(&one, gsec, "n", dfl_field_out_bytes(&k.out, nodes),
                           "the field files' buffers");
        dfl_bs04_offsets_cost(gsec, nodes, sec, rays, parts + DFL_RFUNC_EVAL_UNITS, b->nlevels,
                              &k.search, &one);
        dfl_cost_add_work(&one, gsec, "n", DFL_COST_CHEAP,
                          (ctx->point == 0 ? 2 : 1) * dfl_field_out_units(&k.out, nodes),
                          "the files of %.3g nodes", nodes);
        dfl_cost_add_step(c, &one);
    }
    keys_free(&k);
    return st;
}

DFL_STUDY_DEFINE_ESTIMATED(bs04_bulging, bulging_run, bulging_estimate,
                 "bs04 Fig. 6 / Fig. 2: bulging of R-function level sets vs order p and offset");
