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
 * grad_max_d: the exact distance at the band's largest |grad u| (grad_max);
 * grad_max_interior and grad_max_interior_d: the same off the grid's
 * boundary nodes (where the domain, not the field, ends the band).
 * Rows: one per sweep point and delta.  Files: <curve>_u<tag>.vti/.exr (u,
 * reference = exact distance) and <curve>_exact<tag>.vti/.exr at the first
 * sweep point.
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
#include "cfg/field_cfg.h"
#include "harness/field_out.h"
#include "geom/polygonize.h"
#include "io/path.h"
#include "cfg/field_cost.h"
#include "cfg/grid_cfg.h"
#include "cfg/rfunc_cfg.h"
#include "rfunc/join.h"

typedef struct scurve_keys {
    dfl_rfunc_field_spec spec; /* [field] as parsed: the curve and its polygonization */
    const char *curve_sec, *join, *trim; /* the spec's curve section and names */
    double eps;
    long p;
    double *levels;
    size_t nlevels;
    long rays, cap_rays, max_joints, csamples, crounds;
    dfl_bs04_offset_opts search;
    dfl_grid grid;
    dfl_field_write_opts out;
} scurve_keys;

static dfl_status read_keys(const dfl_cfg *cfg, scurve_keys *k, dfl_err *err)
{
    const dfl_field_kind *kind;
    dfl_status st;
    if ((st = dfl_field_kind_from_cfg(cfg, "field", &kind, err))) return st;
    if (kind->build == dfl_rfunc_field_from_cfg &&
        (st = dfl_rfunc_spec_from_cfg(cfg, "field", &k->spec, err)))
        return st;
    if (kind->build != dfl_rfunc_field_from_cfg || !k->spec.curve)
        return dfl_cfg_reject(cfg, "field", "kind", err,
                              "bs04_scurve needs kind = rfunc with a curve (curve = <section>)");
    k->curve_sec = k->spec.curve;
    k->eps = k->spec.eps;
    k->p = k->spec.p;
    k->join = dfl_rfunc_join_name(k->spec.join);
    k->trim = dfl_rfunc_trim_name(k->spec.trim);
    if ((st = dfl_cfg_doubles(cfg, "study", "levels", 1, &k->levels, &k->nlevels, err))) return st;
    for (size_t i = 0; i < k->nlevels; i++)
        if (!(k->levels[i] > 0.0))
            return dfl_cfg_reject(cfg, "study", "levels", err, "expected offsets > 0, got %g",
                                  k->levels[i]);
    if ((st = dfl_cfg_int_opt(cfg, "study", "rays", 801, 2, 1000000, &k->rays, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "cap_rays", 32, 0, 100000, &k->cap_rays, err)))
        return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "max_joints", 200, 0, 1000000, &k->max_joints, err)))
        return st;
    if ((st = dfl_bs04_offset_opts_from_cfg(cfg, "study", &k->search, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "curve_samples", 16, 2, 1024, &k->csamples, err)))
        return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "curve_rounds", 8, 0, 40, &k->crounds, err)))
        return st;
    if ((st = dfl_grid_from_cfg(cfg, "grid", 2, &k->grid, err))) return st;
    return dfl_field_out_from_cfg(cfg, &k->out, err);
}

/* C of the header comment. */
static double curve_bound_factor(const scurve_keys *k, double bound, double seg_min, int closed)
{
    const int smooth = dfl_rfunc_trim_smooth(k->spec.trim);
    const double kj = (closed && k->spec.join == DFL_RFUNC_REQUIV_CORRECTED) ? 2.0 : 1.0;
    const double b = 1.0 + bound / seg_min + (smooth ? bound / 2.0 : 0.0);
    return kj * sqrt(1.0 + b * b);
}

/* Rays from the curve: rays side origins, cap_rays around each end, and
 * joint rays at every j-th vertex, j chosen so that at most max_joints
 * vertices are used (the joints' count grows like eps^-1/2 and every ray
 * costs one field evaluation per part). */
/* Where the band's largest |grad u| lies: the exact distance at the
 * overall maximum over the nodes with |d| <= delta (the band of metrics.h),
 * and the maximum and its d over the interior nodes only (off the grid's
 * boundary rows and columns, where the domain cuts the field). */
typedef struct grad_where {
    double all_d, in_max, in_d;
} grad_where;

static void grad_extremes(const dfl_grid *g, const double *ug, const double *d, double delta,
                          grad_where *w)
{
    double all = -1.0;
    w->all_d = w->in_d = NAN;
    w->in_max = -1.0;
    const size_t m = dfl_grid_size(g), nx = (size_t)g->n[0], ny = (size_t)g->n[1];
    for (size_t i = 0; i < m; i++) {
        if (!(fabs(d[i]) <= delta)) continue;
        const double gn = hypot(ug[2 * i], ug[2 * i + 1]);
        if (gn > all) all = gn, w->all_d = d[i];
        const size_t ix = i % nx, iy = i / nx;
        if (ix == 0 || iy == 0 || ix + 1 == nx || iy + 1 == ny) continue;
        if (gn > w->in_max) w->in_max = gn, w->in_d = d[i];
    }
    if (w->in_max < 0.0) w->in_max = NAN;
}

static dfl_status make_rays(const scurve_keys *k, const dfl_polyline *pl, int closed,
                            dfl_rayset *out, dfl_err *err)
{
    const size_t nseg = pl->n - 1;
    const double *vt = closed ? pl->t : pl->t + 1;
    const size_t nv = closed ? nseg : nseg - 1;
    const size_t stride =
        k->max_joints > 0 ? (nv + (size_t)k->max_joints - 1) / (size_t)k->max_joints : 0;
    double *jt = malloc((nv ? nv : 1) * sizeof *jt);
    if (!jt) return dfl_err_set(err, DFL_E_NOMEM, "bs04_scurve: out of memory");
    size_t nj = 0;
    for (size_t i = 0; stride && i < nv; i += stride) jt[nj++] = vt[i];
    dfl_status st = dfl_curveprobe_rays(&k->spec.bspline, (size_t)k->rays, (size_t)k->cap_rays,
                                        jt, nj, out, err);
    free(jt);
    return st;
}

static dfl_status scurve_run_point(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_table *t,
                                   dfl_err *err)
{
    scurve_keys k;
    dfl_bs04_offsets r;
    dfl_shape shape;
    int have_shape = 0;
    memset(&k, 0, sizeof k);
    memset(&r, 0, sizeof r);
    dfl_status st = read_keys(cfg, &k, err);
    if (st == DFL_OK) st = dfl_rfunc_field_from_spec(cfg, "field", &k.spec, &r.u, err);
    if (st == DFL_OK && k.spec.dim != 2)
        st = dfl_cfg_reject(cfg, "field", "curve", err, "a planar curve is required");
    if (st == DFL_OK) {
        st = dfl_param_shape_from_cfg(cfg, k.curve_sec, "bspline_curve", &shape, err);
        have_shape = st == DFL_OK;
    }
    if (st == DFL_OK) st = dfl_cfg_check_used(cfg, err);
    /* everything read and validated: compute */
    if (st == DFL_OK) {
        st = dfl_field_exact_new(&shape, &r.exact, err);
        if (st == DFL_OK) have_shape = 0;
    }
    /* u's polygonization, which the spec hands over */
    r.pl = k.spec.pl;
    memset(&k.spec.pl, 0, sizeof k.spec.pl);
    const dfl_bspline *curve = &k.spec.bspline;
    const int closed = curve->closed ||
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
        st = dfl_curveprobe_max(&r.u, curve, r.pl.t, r.pl.n, (int)k.csamples, (int)k.crounds,
                                ctx->threads, &umax, &tmax, err);
    const size_t nseg = r.pl.n - 1;
    if (st == DFL_OK) st = make_rays(&k, &r.pl, closed, &r.rays, err);
    const size_t m = dfl_grid_size(&k.grid);
    if (st == DFL_OK) st = dfl_bs04_offsets_alloc(&r, m, "bs04_scurve", err);
    if (st == DFL_OK) st = dfl_bs04_offsets_sample(&r, &k.grid, ctx->threads, err);
    char ustem[128], dstem[128], upath[4400], dpath[4400];
    snprintf(ustem, sizeof ustem, "%s_u", k.curve_sec ? k.curve_sec : "curve");
    snprintf(dstem, sizeof dstem, "%s_exact", k.curve_sec ? k.curve_sec : "curve");
    dfl_study_path(ctx, ustem, "vti", upath, sizeof upath);
    /* the exact image is written once, at the first sweep point */
    dfl_study_path_at(ctx, 0, dstem, "vti", dpath, sizeof dpath);
    const double C = st == DFL_OK ? curve_bound_factor(&k, r.pl.bound, seg_min, closed) : NAN;
    for (size_t l = 0; l < k.nlevels && st == DFL_OK; l++) {
        const double delta = k.levels[l];
        dfl_ray_stats rs;
        dfl_bandstats bs;
        st = dfl_bs04_offsets_level(&r, m, delta, &k.search, ctx->threads, &rs, &bs, err);
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
        if (!st) st = dfl_table_set_string(t, "u_vti", dfl_path_base(upath), err);
        if (!st) st = dfl_table_set_string(t, "exact_vti", dfl_path_base(dpath), err);
        grad_where gw;
        grad_extremes(&k.grid, r.ug, r.dv, delta, &gw);
        if (!st) st = dfl_table_set_double(t, "grad_max_d", gw.all_d, err);
        if (!st) st = dfl_table_set_double(t, "grad_max_interior", gw.in_max, err);
        if (!st) st = dfl_table_set_double(t, "grad_max_interior_d", gw.in_d, err);
    }
    if (st == DFL_OK) st = dfl_field_out_write(ctx, ustem, &k.grid, r.uv, r.ug, r.dv, &k.out, err);
    if (st == DFL_OK && ctx->point == 0)
        st = dfl_field_out_write(ctx, dstem, &k.grid, r.dv, r.dg, NULL, &k.out, err);
    dfl_bs04_offsets_free(&r);
    if (have_shape) dfl_shape_free(&shape);
    dfl_rfunc_spec_free(&k.spec);
    free(k.levels);
    return st;
}

/* Peak memory: the field (its polygonization, [field]'s cost: at most
 * dfl_polygonize_curve_segments_bound segments at eps), the offset
 * measurement's grid and rays (dfl_bs04_offsets_cost: 2 per side origin,
 * cap ray and joint, at most max_joints joints) and the writer's buffers.
 * Work: dfl_bs04_offsets_cost, the files (the exact one at point 0) and
 * the on-curve maximum: per segment curve_samples + 2 curve_rounds
 * evaluations of u.  The keys are read
 * without polygonizing (read_keys builds the spec). */
static dfl_status scurve_estimate(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_cost *c,
                                  dfl_err *err)
{
    scurve_keys k;
    memset(&k, 0, sizeof k);
    double parts;
    const char *pkey;
    dfl_status st = dfl_study_estimate_default(cfg, ctx, c, err);
    if (!st && dfl_cfg_has(cfg, "field", "curve"))
        st = dfl_rfunc_parts_bound(cfg, "field", &parts, &pkey, err);
    else if (!st)
        return DFL_OK; /* not this study's field: run() says so */
    if (!st) st = dfl_cfg_doubles(cfg, "study", "levels", 1, &k.levels, &k.nlevels, err);
    if (!st) st = dfl_cfg_int_opt(cfg, "study", "rays", 801, 2, 1000000, &k.rays, err);
    if (!st) st = dfl_cfg_int_opt(cfg, "study", "cap_rays", 32, 0, 100000, &k.cap_rays, err);
    if (!st) st = dfl_cfg_int_opt(cfg, "study", "max_joints", 200, 0, 1000000, &k.max_joints, err);
    if (!st) st = dfl_bs04_offset_opts_from_cfg(cfg, "study", &k.search, err);
    if (!st) st = dfl_cfg_int_opt(cfg, "study", "curve_samples", 16, 2, 1024, &k.csamples, err);
    if (!st) st = dfl_cfg_int_opt(cfg, "study", "curve_rounds", 8, 0, 40, &k.crounds, err);
    if (!st) st = dfl_grid_from_cfg(cfg, "grid", 2, &k.grid, err);
    if (!st) st = dfl_field_out_from_cfg(cfg, &k.out, err);
    if (!st) {
        const double nodes = (double)dfl_grid_size(&k.grid);
        const double rays = 2.0 * (double)(k.rays + k.cap_rays) + 2 * fmin((double)k.max_joints, parts);
        dfl_cost_add_bytes(c, "grid", "n", dfl_field_out_bytes(&k.out, nodes),
                           "the field files' buffers");
        const double units = parts + DFL_RFUNC_EVAL_UNITS;
        dfl_bs04_offsets_cost("grid", nodes, "study", rays, units, k.nlevels, &k.search, c);
        dfl_cost_add_work(c, "grid", "n", DFL_COST_CHEAP,
                          (ctx->point == 0 ? 2 : 1) * dfl_field_out_units(&k.out, nodes),
                          "the files of %.3g nodes", nodes);
        dfl_cost_add_work(c, "study", "curve_samples", DFL_COST_CHEAP,
                          parts * (double)(k.csamples + 2 * k.crounds) * units,
                          "the maximum on the curve over %.3g segments", parts);
    }
    free(k.levels);
    return st;
}

DFL_STUDY_DEFINE_ESTIMATED(bs04_scurve, scurve_run_point, scurve_estimate,
                 "bs04 Fig. 7: polygonized 'S' curve, R-equivalence vs R-conjunction, eps sweep");
