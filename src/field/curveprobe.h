/* Probing a field along a planar curve: rays normal to the curve, the first
 * crossing of a level set along each ray, and the maximum of the field on
 * the curve itself.  Used by the bs04 bulging and 'S' curve studies to turn
 * "how far is the level set u = delta from the true offset d = delta" into
 * numbers.
 *
 * Rays (dfl_curveprobe_rays).  Origins o_k lie on the curve C, directions v_k
 * are unit vectors:
 *   SIDE  nside origins uniform in arc length (end points included), each
 *         with v = +N and v = -N, N = (-T_y, T_x) the left unit normal;
 *   CAP   open curves only: ncap rays at each end point, v = cos(th) N +
 *         sin(th) T_out (T_out the outward tangent: -T at t0, +T at t1),
 *         th = pi j/(ncap+1), j = 1..ncap (the half circle between +N and
 *         -N, whose end directions are SIDE rays already);
 *   JOINT +N and -N at given parameters (the vertices of a polygonization:
 *         where bs04's parts are joined).
 * Each ray records the curvature kappa at its origin, in geom/curvature.h's
 * convention for the right normal n = (T_y, -T_x) = -N: kappa =
 * (C' x C'') / |C'|^3, positive where the curve turns left (towards N), so
 * a ray with side = +1 (v = +N) points to the inner side of the turn,
 * towards the centre of curvature, iff kappa > 0; and side = +1 / -1
 * (CAP: 0).  Tangents at knots are the right-sided ones (left-sided at t1).
 *
 * Displacement along a ray.  For an exact distance d to C, o + delta v lies
 * on the true offset curve {d = delta} iff o is its footpoint, i.e. iff
 * d(o + delta v) = delta (it is never more).  Such a ray is VALID for
 * delta; on it the true gradient at the offset point is v, so the distance
 * from the true offset to the level set {u = delta} measured along the
 * true gradient is s - delta, where s is the first crossing of u = delta
 * along the ray.  dfl_curveprobe_stats reports r = (s - delta) / delta:
 * r > 0 where u lags the distance (the level set bulges outwards), r < 0
 * where u runs ahead.
 *
 * Costs: fields are evaluated in batches (one eval call per ray stage, no
 * per-point dispatch), rays in parallel (OpenMP); no allocation per ray.
 */
#ifndef DFL_FIELD_CURVEPROBE_H
#define DFL_FIELD_CURVEPROBE_H

#include <stddef.h>

#include "core/status.h"
#include "field/field.h"
#include "geom/bspline.h"

typedef enum dfl_ray_kind { DFL_RAY_SIDE = 0, DFL_RAY_CAP = 1, DFL_RAY_JOINT = 2 } dfl_ray_kind;

typedef struct dfl_rayset {
    size_t n;          /* rays */
    double *o;         /* 2n origins (on the curve) */
    double *v;         /* 2n unit directions */
    double *t;         /* n curve parameters of the origins */
    double *kappa;     /* n curvatures at the origins (convention above) */
    int *side;         /* n: +1 (v = +N), -1 (v = -N), 0 (CAP) */
    int *kind;         /* n: dfl_ray_kind */
    double kflat;      /* 1/3 quantile of |kappa| over SIDE rays */
    double kcurved;    /* 2/3 quantile of |kappa| over SIDE rays */
} dfl_rayset;

/* Rays of the planar curve c (dim 2): nside >= 2 origins, ncap >= 0 rays
 * per end (ignored for closed curves), njoint parameters joint_t (may be
 * NULL when njoint == 0; clamped/wrapped into the domain).  Arc length is
 * tabulated on 64 intervals per knot span (3-point Gauss-Legendre on the
 * speed) and inverted by interpolation plus Newton steps, so origins are
 * uniform in arc length to ~1e-10 of the length for smooth pieces.  DFL_E_INPUT for a curve that is not planar or has a
 * zero tangent at an origin, nside < 2; DFL_E_NOMEM.  Release with
 * dfl_curveprobe_free (also after failure: *out is then empty). */
dfl_status dfl_curveprobe_rays(const dfl_bspline *c, size_t nside, size_t ncap,
                               const double *joint_t, size_t njoint, dfl_rayset *out,
                               dfl_err *err);
void dfl_curveprobe_free(dfl_rayset *rs);

/* valid[k] = 1 iff exact(o_k + level v_k) >= level (1 - tol), else 0;
 * exact is an unsigned distance field (dim 2).  level > 0, 0 <= tol < 1.
 * DFL_E_INPUT for bad arguments. */
dfl_status dfl_curveprobe_valid(const dfl_field *exact, const dfl_rayset *rs, double level,
                                double tol, int threads, int *valid, dfl_err *err);

/* Search controls for dfl_curveprobe_cross. */
typedef struct dfl_cross_opts {
    double smax;   /* search s in [0, smax] (> 0, units of the field) */
    int steps;     /* bracketing samples in (0, smax]: 1..DFL_CROSS_MAX_STEPS */
    int rounds;    /* refinements, each divides the bracket by 16: 0..40 */
} dfl_cross_opts;

#define DFL_CROSS_MAX_STEPS 1024

/* s[k] = the first s in [0, smax] with u(o_k + s v_k) >= level: u is
 * sampled at s = smax i / steps, i = 0..steps; the first sample >= level
 * and its predecessor bracket the crossing, which `rounds` 16-fold
 * subdivisions narrow (first sub-sample >= level each time); the result is
 * the linear interpolation of u between the final bracket ends (exact for
 * u linear along the ray).  s[k] = 0 if u(o_k) >= level; NAN if no sample
 * reaches level (or u is NaN there): the crossing lies beyond smax or a
 * crossing and re-crossing fell between two samples.  Bracket width at the
 * end: smax / steps / 16^rounds.  DFL_E_INPUT for bad options or a field
 * that is not 2D. */
dfl_status dfl_curveprobe_cross(const dfl_field *u, const dfl_rayset *rs, double level,
                                const dfl_cross_opts *opt, int threads, double *s,
                                dfl_err *err);

/* ok[k] = 1 iff the point o_k + s_k v_k is still on the ray's branch of the
 * exact distance: exact(o_k + s_k v_k) >= s_k (1 - tol), i.e. o_k is (up to
 * tol) its footpoint and the true gradient there is v_k; beyond the medial
 * axis the ray no longer follows the true gradient.  NAN s_k: ok = 0.
 * Same arguments and errors as dfl_curveprobe_valid. */
dfl_status dfl_curveprobe_on_branch(const dfl_field *exact, const dfl_rayset *rs, const double *s,
                                    double tol, int threads, int *ok, dfl_err *err);

/* Statistics of r_k = (s_k - level) / level over the valid rays (valid may
 * be NULL: all rays).  A valid ray is left out of every statistic when
 * s_k = NAN (counted in `unresolved`: no crossing up to smax) or when
 * branch[k] == 0 (counted in `beyond`: the crossing lies beyond the medial
 * axis of the exact curve, where the ray has stopped following the true
 * gradient; the level set u = level has been pushed past it, e.g. the
 * sublevel sets of two arms of the curve have merged).  branch may be NULL
 * (no such test).  `merged` = (unresolved + beyond) / valid.  Groups: flat
 * = SIDE rays with |kappa| <= kflat, curved = SIDE rays with |kappa| >
 * kcurved (empty when the curve has constant |kappa|), outer / inner =
 * curved rays whose direction points away from / towards the centre of
 * curvature (bs04 Sec. 2.3 calls the inner side of a joint, where the
 * angle between the segments is < pi, the "convex sector").  Empty groups give NAN; argmax = (size_t)-1 when no ray
 * enters. */
typedef struct dfl_ray_stats {
    size_t valid;         /* valid rays (resolved or not) */
    size_t unresolved;    /* valid rays with s = NAN */
    size_t beyond;        /* valid rays crossing beyond the medial axis */
    double merged;        /* (unresolved + beyond) / valid (NAN if none valid) */
    double max, min, mean;
    size_t argmax;        /* ray index of max */
    double joint_max;     /* max over JOINT rays */
    double side_max;      /* max over SIDE rays */
    double cap_max;       /* max over CAP rays */
    double flat_mean, curved_mean, outer_mean, inner_mean;
} dfl_ray_stats;

void dfl_curveprobe_stats(const dfl_rayset *rs, const double *s, const int *valid,
                          const int *branch, double level, dfl_ray_stats *out);

/* Maximum of |u| on the curve over the parameter intervals [t_i, t_(i+1)],
 * i = 0..n-2 (t increasing, e.g. the vertex parameters of a
 * polygonization): each interval is sampled at `samples` + 1 points (ends
 * included), then the best sample's neighbourhood (one sample either side)
 * is narrowed by `rounds` 16-fold subdivisions, keeping the best point.  A
 * lower estimate of the true maximum that converges for u smooth on each
 * interval.  *tmax receives the parameter (may be NULL).  DFL_E_INPUT for
 * n < 2, samples < 2 or decreasing t; DFL_E_NOMEM. */
dfl_status dfl_curveprobe_max(const dfl_field *u, const dfl_bspline *c, const double *t,
                              size_t n, int samples, int rounds, int threads, double *max,
                              double *tmax, dfl_err *err);

#endif
