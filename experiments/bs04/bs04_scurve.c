/* bs04 Fig. 7 / Sec. 2.4: fields of the polygonized 'S' curve, joined by
 * R-equivalence or R-conjunction, against the polygonization bound eps.
 *
 * Per sweep point ([field] eps x join):
 *   segments, bound (certified Hausdorff bound <= eps), seg_min, seg_max
 *     (segment lengths);
 *   u_curve_max: max |u| on the original curve (curveprobe.h: sampled per
 *     segment and refined), with u_curve_bound = C bound, the bound derived
 *     below; bs04 claims O(eps);
 *   per offset delta of [study] levels:
 *     band statistics of u against the exact curve distance d over the grid
 *     nodes with d <= delta (bias, relative bias, L1, RMS, Linf, |grad u|
 *     min/mean/max; metrics.h);
 *     the level set u = delta against the true offset d = delta along the
 *     curve's normal rays (curveprobe.h): offset_* = (s - delta) / delta,
 *     s the first crossing of u = delta; mean, max, min, and the means on
 *     the flattest and most curved thirds of the curve (split into the
 *     inner and outer sides of the turns).
 * "Widening" (bs04 Sec. 2.4: "the widening of the distance field near the
 * flatter sections of the curve with the increase of segments") is measured
 * as widening = offset_flat_mean - offset_curved_mean: how much farther out,
 * relative to delta, the level set u = delta lies along the flattest third
 * of the curve than along the most curved third.  (The offsets themselves
 * fall as segments are added: far from short disk-trimmed segments h grows
 * like r^2 / L, so u steepens; flat sections have longer segments and lag.)
 *
 * Bound on the curve (derived here; bs04 states only O(eps)).  Every point c
 * of the curve is within r <= bound of a point q of some segment [a, b] of
 * length L >= seg_min.  Write c = q + w, |w| <= r.  The carrier term is
 * |f| <= r.  The trim term: disk, -t L = (c - a).(c - b) = (q - a).(q - b)
 * + w.(2q - a - b) + |w|^2 <= 0 + r L + r^2 (q between a and b, |2q - a - b|
 * <= L), so max(-t, 0) <= r + r^2 / L; strip, -t = |(p1, p2)| - L with p1 +
 * p2 = L and p2 >= -r gives the same or less.  Eq. 4 then gives h <= r
 * sqrt(1 + (1 + r/L)^2); eq. 5 (g/2 <= max(-t, 0) + f^2/2) adds r/2 inside
 * the bracket.  Every join used here satisfies u <= min_i h_i on an open
 * polyline (R-equivalence: the sum has the term h_min^-p; R-conjunction:
 * a ^ b <= min(a, b) for a, b >= 0, folded; corrected: join.h), and u <= 2
 * min h on a closed one for the corrected join (its floor).  So
 *     max |u| on C <= C bound,  C = k sqrt(1 + (1 + bound/seg_min + s
 *     bound/2)^2),  s = 1 for smooth trims, k = 2 for the corrected join on
 *     a closed polyline, else 1 (C -> sqrt 2 as eps -> 0).
 *
 * Keys.  [field] kind = rfunc with curve = <section> and eps (rfunc_cfg.h;
 * sweep eps and join there).  [grid] (grid_cfg.h).  [study]:
 *   levels        = d1 d2 ...   offsets delta (> 0)
 *   rays = 801, cap_rays = 32   ray origins along the curve, rays per end
 *   max_joints = 200            joint rays start at every j-th polygon vertex,
 *                               j the smallest stride giving <= max_joints
 *                               vertices (0: none)
 *   smax = 8, steps = 128, rounds = 6, valid_tol = 1e-6   as bs04_bulging
 *   curve_samples = 16, curve_rounds = 8   the on-curve maximum search
 * [output] as field_out.h.
 * Rows: one per sweep point and delta.  Files: <curve>_u<tag>.vti/.exr (u,
 * reference = exact distance) and <curve>_exact<tag>.vti/.exr at the first
 * sweep point.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cfg/curve_cfg.h"
#include "field/curveprobe.h"
#include "harness/experiment.h"
#include "field/exact.h"
#include "field/metrics.h"
#include "field/sample.h"
#include "cfg/field_cfg.h"
#include "harness/field_out.h"
#include "geom/polygonize.h"
#include "cfg/grid_cfg.h"
#include "rfunc/join.h"

typedef struct scurve_keys {
    const char *curve_sec, *join, *trim;
    double eps;
    long p;
    double *levels;
    size_t nlevels;
    long rays, cap_rays, max_joints, steps, rounds, csamples, crounds;
    double smax, valid_tol;
    dfl_grid grid;
    dfl_field_write_opts out;
} scurve_keys;

static dfl_status read_keys(const dfl_cfg *cfg, scurve_keys *k, dfl_err *err)
{
    char w[600];
    const char *kind;
    dfl_status st;
    if ((st = dfl_cfg_string(cfg, "field", "kind", &kind, err))) return st;
    if (strcmp(kind, "rfunc") != 0 || !dfl_cfg_has(cfg, "field", "curve"))
        return dfl_err_set(err, DFL_E_INPUT,
                           "%s: bs04_scurve needs kind = rfunc with a curve (curve = <section>)",
                           dfl_cfg_where(cfg, "field", "kind", w, sizeof w));
    if ((st = dfl_cfg_string(cfg, "field", "curve", &k->curve_sec, err))) return st;
    if ((st = dfl_cfg_double(cfg, "field", "eps", 1e-300, 1e300, &k->eps, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, "field", "p", 2, 1, DFL_RFUNC_P_MAX, &k->p, err))) return st;
    if ((st = dfl_cfg_string_opt(cfg, "field", "join", "requiv", &k->join, err))) return st;
    if ((st = dfl_cfg_string_opt(cfg, "field", "trim", "disk", &k->trim, err))) return st;
    if ((st = dfl_cfg_doubles(cfg, "study", "levels", 1, &k->levels, &k->nlevels, err))) return st;
    for (size_t i = 0; i < k->nlevels; i++)
        if (!(k->levels[i] > 0.0))
            return dfl_err_set(err, DFL_E_INPUT, "%s: expected offsets > 0, got %g",
                               dfl_cfg_where(cfg, "study", "levels", w, sizeof w), k->levels[i]);
    if ((st = dfl_cfg_int_opt(cfg, "study", "rays", 801, 2, 1000000, &k->rays, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "cap_rays", 32, 0, 100000, &k->cap_rays, err)))
        return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "max_joints", 200, 0, 1000000, &k->max_joints, err)))
        return st;
    if ((st = dfl_cfg_double_opt(cfg, "study", "smax", 8.0, 1.0, 1e6, &k->smax, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "steps", 128, 1, DFL_CROSS_MAX_STEPS, &k->steps, err)))
        return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "rounds", 6, 0, 40, &k->rounds, err))) return st;
    if ((st = dfl_cfg_double_opt(cfg, "study", "valid_tol", 1e-6, 0.0, 0.5, &k->valid_tol, err)))
        return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "curve_samples", 16, 2, 1024, &k->csamples, err)))
        return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "curve_rounds", 8, 0, 40, &k->crounds, err)))
        return st;
    if ((st = dfl_grid_from_cfg(cfg, "grid", 2, &k->grid, err))) return st;
    return dfl_field_out_from_cfg(cfg, &k->out, err);
}

typedef struct scurve_run {
    dfl_bspline curve;
    dfl_shape shape;
    int have_curve, have_shape;
    dfl_field u, exact;
    dfl_polyline pl;
    dfl_rayset rays;
    double *uv, *ug, *dv, *dg, *s;
    int *valid, *branch;
} scurve_run;

static void run_free(scurve_run *r)
{
    if (r->have_curve) dfl_bspline_free(&r->curve);
    if (r->have_shape) dfl_shape_free(&r->shape);
    dfl_field_destroy(&r->u);
    dfl_field_destroy(&r->exact);
    dfl_polyline_free(&r->pl);
    dfl_curveprobe_free(&r->rays);
    free(r->uv), free(r->ug), free(r->dv), free(r->dg), free(r->s);
    free(r->valid), free(r->branch);
}

/* C of the header comment. */
static double curve_bound_factor(const scurve_keys *k, double bound, double seg_min, int closed)
{
    const int smooth = strstr(k->trim, "smooth") != NULL;
    const double kj = (closed && strcmp(k->join, "requiv_corrected") == 0) ? 2.0 : 1.0;
    const double b = 1.0 + bound / seg_min + (smooth ? bound / 2.0 : 0.0);
    return kj * sqrt(1.0 + b * b);
}

static const char *base_name(const char *path)
{
    const char *b = strrchr(path, '/');
    return b ? b + 1 : path;
}

static dfl_status scurve_run_point(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_table *t,
                                   dfl_err *err)
{
    scurve_keys k;
    scurve_run r;
    char w[600];
    memset(&k, 0, sizeof k);
    memset(&r, 0, sizeof r);
    dfl_status st = read_keys(cfg, &k, err);
    if (st == DFL_OK) st = dfl_field_from_cfg(cfg, "field", &r.u, err);
    if (st == DFL_OK) {
        /* [field] curve was checked to exist by dfl_field_from_cfg */
        st = dfl_curve_from_cfg(cfg, k.curve_sec, &r.curve, err);
        r.have_curve = st == DFL_OK;
    }
    if (st == DFL_OK && r.curve.dim != 2)
        st = dfl_err_set(err, DFL_E_INPUT, "%s: a planar curve is required",
                         dfl_cfg_where(cfg, "field", "curve", w, sizeof w));
    if (st == DFL_OK) {
        st = dfl_param_shape_from_cfg(cfg, k.curve_sec, "bspline_curve", &r.shape, err);
        r.have_shape = st == DFL_OK;
    }
    if (st == DFL_OK) st = dfl_cfg_check_used(cfg, err);
    /* everything read and validated: compute */
    if (st == DFL_OK) {
        st = dfl_field_exact_new(&r.shape, &r.exact, err);
        if (st == DFL_OK) r.have_shape = 0;
    }
    if (st == DFL_OK) st = dfl_polygonize_curve(&r.curve, k.eps, 0, &r.pl, err);
    const int closed = r.curve.closed ||
                       (r.pl.n >= 4 && memcmp(r.pl.pts, r.pl.pts + 2 * (r.pl.n - 1),
                                              2 * sizeof *r.pl.pts) == 0);
    double seg_min = INFINITY, seg_max = 0, seg_sum = 0;
    for (size_t i = 0; st == DFL_OK && i + 1 < r.pl.n; i++) {
        const double L = hypot(r.pl.pts[2 * i + 2] - r.pl.pts[2 * i],
                               r.pl.pts[2 * i + 3] - r.pl.pts[2 * i + 1]);
        if (L < seg_min) seg_min = L;
        if (L > seg_max) seg_max = L;
        seg_sum += L;
    }
    double umax = NAN, tmax = NAN;
    if (st == DFL_OK)
        st = dfl_curveprobe_max(&r.u, &r.curve, r.pl.t, r.pl.n, (int)k.csamples, (int)k.crounds,
                                ctx->threads, &umax, &tmax, err);
    const size_t nseg = r.pl.n - 1;
    /* joint rays at every j-th vertex, j chosen so that at most max_joints
     * vertices are used (the joints' count grows like eps^-1/2 and every ray
     * costs one field evaluation per part) */
    double *jt = NULL;
    size_t nj = 0;
    if (st == DFL_OK) {
        const double *vt = closed ? r.pl.t : r.pl.t + 1;
        const size_t nv = closed ? nseg : nseg - 1;
        const size_t stride =
            k.max_joints > 0 ? (nv + (size_t)k.max_joints - 1) / (size_t)k.max_joints : 0;
        jt = malloc((nv ? nv : 1) * sizeof *jt);
        if (!jt) st = dfl_err_set(err, DFL_E_NOMEM, "bs04_scurve: out of memory");
        for (size_t i = 0; st == DFL_OK && stride && i < nv; i += stride) jt[nj++] = vt[i];
    }
    if (st == DFL_OK)
        st = dfl_curveprobe_rays(&r.curve, (size_t)k.rays, (size_t)k.cap_rays, jt, nj, &r.rays,
                                 err);
    free(jt);
    const size_t m = dfl_grid_size(&k.grid);
    if (st == DFL_OK) {
        r.uv = malloc(m * sizeof *r.uv), r.ug = malloc(2 * m * sizeof *r.ug);
        r.dv = malloc(m * sizeof *r.dv), r.dg = malloc(2 * m * sizeof *r.dg);
        r.s = malloc(r.rays.n * sizeof *r.s), r.valid = malloc(r.rays.n * sizeof *r.valid);
        r.branch = malloc(r.rays.n * sizeof *r.branch);
        if (!r.uv || !r.ug || !r.dv || !r.dg || !r.s || !r.valid || !r.branch)
            st = dfl_err_set(err, DFL_E_NOMEM, "bs04_scurve: out of memory");
    }
    if (st == DFL_OK) st = dfl_field_sample(&r.u, &k.grid, ctx->threads, r.uv, r.ug, err);
    if (st == DFL_OK) st = dfl_field_sample(&r.exact, &k.grid, ctx->threads, r.dv, r.dg, err);
    char ustem[128], dstem[128], upath[4400], dpath[4400];
    snprintf(ustem, sizeof ustem, "%s_u", k.curve_sec ? k.curve_sec : "curve");
    snprintf(dstem, sizeof dstem, "%s_exact", k.curve_sec ? k.curve_sec : "curve");
    dfl_study_path(ctx, ustem, "vti", upath, sizeof upath);
    /* the exact image is written once, at the first sweep point */
    dfl_study_path_at(ctx, 0, dstem, "vti", dpath, sizeof dpath);
    const double C = st == DFL_OK ? curve_bound_factor(&k, r.pl.bound, seg_min, closed) : NAN;
    for (size_t l = 0; l < k.nlevels && st == DFL_OK; l++) {
        const double delta = k.levels[l];
        const dfl_cross_opts co = {k.smax * delta, (int)k.steps, (int)k.rounds};
        dfl_ray_stats rs;
        dfl_bandstats bs;
        st = dfl_curveprobe_valid(&r.exact, &r.rays, delta, k.valid_tol, ctx->threads, r.valid,
                                  err);
        if (st == DFL_OK)
            st = dfl_curveprobe_cross(&r.u, &r.rays, delta, &co, ctx->threads, r.s, err);
        if (st == DFL_OK)
            st = dfl_curveprobe_on_branch(&r.exact, &r.rays, r.s, k.valid_tol, ctx->threads,
                                          r.branch, err);
        if (st == DFL_OK) dfl_curveprobe_stats(&r.rays, r.s, r.valid, r.branch, delta, &rs);
        if (st == DFL_OK) st = dfl_metrics_bandstats(m, 2, r.uv, r.ug, r.dv, delta, &bs, err);
        if (st != DFL_OK) break;
        st = dfl_table_row(t, err);
        if (!st) st = dfl_table_set_string(t, "curve", k.curve_sec, err);
        if (!st) st = dfl_table_set_double(t, "eps", k.eps, err);
        if (!st) st = dfl_table_set_string(t, "join", k.join, err);
        if (!st) st = dfl_table_set_int(t, "p", k.p, err);
        if (!st) st = dfl_table_set_string(t, "trim", k.trim, err);
        if (!st) st = dfl_table_set_int(t, "segments", (long)nseg, err);
        if (!st) st = dfl_table_set_double(t, "bound", r.pl.bound, err);
        if (!st) st = dfl_table_set_double(t, "seg_min", seg_min, err);
        if (!st) st = dfl_table_set_double(t, "seg_max", seg_max, err);
        if (!st) st = dfl_table_set_double(t, "seg_mean", seg_sum / (double)nseg, err);
        if (!st) st = dfl_table_set_double(t, "u_curve_max", umax, err);
        if (!st) st = dfl_table_set_double(t, "u_curve_max_t", tmax, err);
        if (!st) st = dfl_table_set_double(t, "u_curve_max_over_eps", umax / k.eps, err);
        if (!st) st = dfl_table_set_double(t, "u_curve_bound", C * r.pl.bound, err);
        if (!st) st = dfl_table_set_double(t, "delta", delta, err);
        if (!st) st = dfl_metrics_put_bandstats(t, &bs, err);
        if (!st) st = dfl_table_set_int(t, "rays", (long)r.rays.n, err);
        if (!st) st = dfl_table_set_int(t, "rays_valid", (long)rs.valid, err);
        if (!st) st = dfl_table_set_int(t, "unresolved", (long)rs.unresolved, err);
        if (!st) st = dfl_table_set_int(t, "beyond", (long)rs.beyond, err);
        if (!st) st = dfl_table_set_double(t, "merged", rs.merged, err);
        if (!st) st = dfl_table_set_double(t, "offset_mean", rs.mean, err);
        if (!st) st = dfl_table_set_double(t, "offset_max", rs.max, err);
        if (!st) st = dfl_table_set_double(t, "offset_min", rs.min, err);
        if (!st) st = dfl_table_set_double(t, "offset_joint_max", rs.joint_max, err);
        if (!st) st = dfl_table_set_double(t, "offset_flat_mean", rs.flat_mean, err);
        if (!st) st = dfl_table_set_double(t, "offset_curved_mean", rs.curved_mean, err);
        if (!st) st = dfl_table_set_double(t, "offset_outer_mean", rs.outer_mean, err);
        if (!st) st = dfl_table_set_double(t, "offset_inner_mean", rs.inner_mean, err);
        if (!st) st = dfl_table_set_double(t, "widening", rs.flat_mean - rs.curved_mean, err);
        if (!st) st = dfl_table_set_string(t, "u_vti", base_name(upath), err);
        if (!st) st = dfl_table_set_string(t, "exact_vti", base_name(dpath), err);
    }
    if (st == DFL_OK) st = dfl_field_out_write(ctx, ustem, &k.grid, r.uv, r.ug, r.dv, &k.out, err);
    if (st == DFL_OK && ctx->point == 0)
        st = dfl_field_out_write(ctx, dstem, &k.grid, r.dv, r.dg, NULL, &k.out, err);
    run_free(&r);
    free(k.levels);
    return st;
}

const dfl_study dfl_study_bs04_scurve = {
    .name = "bs04_scurve",
    .summary = "bs04 Fig. 7: polygonized 'S' curve, R-equivalence vs R-conjunction, eps sweep",
    .run = scurve_run_point,
};
