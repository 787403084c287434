/* Footpoints (closest points) on parametric curves and surfaces, the signed
 * distance of a closed planar curve with derivatives to order 3, and
 * dfl_shape wrappers.
 *
 * Footpoint search (both backends):
 *   1. initial guesses: the curve (patch) is sampled at `samples_per_span`
 *      parameters per knot span (per span and direction for surfaces),
 *      precomputed once; for a query x the discrete local minima of |x - P|
 *      over the samples are ranked and the `candidates` best are kept;
 *   2. each guess is refined:
 *      newton: Newton's method on g(t) = |C(t) - x|^2 / 2 (g' = C'.(C - x),
 *        g'' = |C'|^2 + C''.(C - x)); where g'' <= 0 the Gauss-Newton
 *        (geometric first-order) step -g'/|C'|^2 is taken instead; every
 *        step is halved until g does not increase (step control); open
 *        curves and patches keep the parameters in the domain (projection
 *        plus an active set for bounds the gradient pushes against), closed
 *        curves wrap.  Surfaces: the same with the 2x2 Hessian (Newton when
 *        positive definite, first fundamental form otherwise).
 *      ceres: Levenberg-Marquardt (solve/lsq.h) in two phases: first on
 *        the residual C(t) - x with the parameter domain as bounds (closed
 *        curves: unbounded, the residual wraps the parameter); LM is
 *        Gauss-Newton at heart and, with a non-zero residual, stops on its
 *        cost tolerance ~sqrt(eps) away from the footpoint (much worse near
 *        a centre of curvature), so it is followed by LM on the footpoint
 *        condition g'(t) = 0 (zero residual, Jacobian g''), kept only if not
 *        farther.  Surfaces: bounds the gradient pushes against are made
 *        explicit (that parameter is held, LM runs on the other one), since
 *        Ceres' projected steps stall on active bounds.
 *   3. the best refined candidate wins.  Ties within tie_rel (relative to the
 *      distance, plus 1e-14 of the curve's size) between footpoints more
 *      than 1e-7 of the size apart set DFL_FOOT_MEDIAL, and the footpoint
 *      with the smallest parameter (surfaces: smallest patch, then u, then v)
 *      among the tied ones is returned: deterministic.
 *
 * Signed distance of a closed planar curve (dim 2, periodic, or clamped with
 * C(t0) = C(t1)).  Conventions, stated once:
 *   d < 0 inside, where the winding number of the curve around x is
 *   non-zero; N is the unit normal at the footpoint pointing to the outside
 *   (the right normal of a counter-clockwise curve), T = C'/|C'| the unit
 *   tangent, kappa the signed curvature with dT/ds = kappa N (so a convex
 *   curve has kappa < 0: a circle of radius R has kappa = -1/R), and
 *   kappa_s = d kappa / ds its arc-length derivative.  With x = C(s) + d N
 *   and g = 1 - kappa d (> 0 off the focal set):
 *     grad d = N
 *     H = -kappa / g  T T^T                       (Hessian)
 *     d_ijk = -kappa_s / g^3  T_i T_j T_k
 *             - kappa^2 / g^2 (T_i T_j N_k + T_i N_j T_k + N_i T_j T_k)
 *   Derivation: dx = (1 - kappa d) T ds + N dd gives grad s = T / g and
 *   grad d = N; grad N = (dN/ds) grad s^T = -kappa T T^T / g; differentiate
 *   H = -f T T^T with f(s, d) = kappa/(1 - kappa d): df/ds = kappa_s / g^2,
 *   df/dd = kappa^2 / g^2, dT/dx_k = kappa N T_k / g.  Parametric forms:
 *   kappa = o (C' x C'') / |C'|^3 with o = -1 for a counter-clockwise curve
 *   (+1 clockwise), kappa_s = o [(C' x C''')/|C'|^3
 *   - 3 (C' x C'')(C'.C'')/|C'|^5] / |C'|.
 *   The sign comes from the winding number of a certified polygonization
 *   (Hausdorff bound h, 1e-4 of the curve's size) when |d| > h (the curve and
 *   the polygon are homotopic inside the h-tube, so their winding numbers
 *   around x agree), else from N.(x - C), which agrees for the global
 *   footpoint.  Flags: DFL_FOOT_MEDIAL (see above: d is then not
 *   differentiable and the derivatives are those of the chosen footpoint's
 *   branch), DFL_FOOT_FOCAL when |g| < 1e-6 (derivatives blow up; they are
 *   still returned).
 *
 * Thread safety: locators and SDF objects are read-only after creation.
 * The newton backend allocates nothing per query; the ceres backend
 * allocates inside Ceres (it is meant for verification and hard cases).
 * Lifetimes: a locator keeps a pointer to its curve/surface, which must
 * outlive it; the shape wrappers own everything.
 */
#ifndef DFL_GEOM_FOOTPOINT_H
#define DFL_GEOM_FOOTPOINT_H

#include <stddef.h>

#include "core/jet.h"
#include "core/status.h"
#include "geom/foot_backend.h"
#include "geom/bspline.h"
#include "geom/shape.h"
#include "geom/surface.h"


#define DFL_FOOT_MAX_CAND 16

typedef struct dfl_foot_opts {
    dfl_foot_backend backend;  /* default newton */
    int samples_per_span;      /* >= 2, default 16 (surfaces: per direction) */
    int candidates;            /* 1..DFL_FOOT_MAX_CAND, default 4 */
    int max_iter;              /* per refinement, default 100 */
    double tie_rel;            /* medial-axis tie tolerance, default 1e-9 */
} dfl_foot_opts;

void dfl_foot_opts_default(dfl_foot_opts *o);
/* DFL_E_INPUT naming the offending field. */
dfl_status dfl_foot_opts_check(const dfl_foot_opts *o, dfl_err *err);

#define DFL_FOOT_MEDIAL 1  /* several distinct footpoints at equal distance */
#define DFL_FOOT_FOCAL 2   /* x at a centre of curvature of the footpoint */
#define DFL_FOOT_END 4     /* footpoint on the boundary of the parameter domain (open) */

typedef struct dfl_curve_foot {
    double t;        /* footpoint parameter in [t0, t1] */
    double p[3];     /* C(t) */
    double dist;     /* |x - C(t)| >= 0 */
    int flags;       /* DFL_FOOT_* */
    int iterations;  /* of the winning refinement */
} dfl_curve_foot;

typedef struct dfl_curve_locator dfl_curve_locator;

/* Precomputes the samples (and a Ceres context for the ceres backend).
 * opt may be NULL (defaults).  DFL_E_INPUT for bad options, DFL_E_NOMEM. */
dfl_status dfl_curve_locator_new(const dfl_bspline *c, const dfl_foot_opts *opt,
                                 dfl_curve_locator **out, dfl_err *err);
void dfl_curve_locator_free(dfl_curve_locator *L);

/* Footpoint of x (c->dim doubles).  DFL_E_NUMERIC if the ceres backend
 * fails (newton cannot fail). */
dfl_status dfl_curve_footpoint(const dfl_curve_locator *L, const double *x, dfl_curve_foot *out,
                               dfl_err *err);

/* All distinct refined local minima found for x, sorted by distance (ties:
 * by parameter), at most max; returns the count written. */
int dfl_curve_footpoints(const dfl_curve_locator *L, const double *x, dfl_curve_foot *out,
                         int max, dfl_err *err);

typedef struct dfl_surface_foot {
    size_t patch;
    double u, v;
    double p[3];
    double dist;
    int flags;
    int iterations;
} dfl_surface_foot;

typedef struct dfl_surface_locator dfl_surface_locator;

dfl_status dfl_surface_locator_new(const dfl_surface_set *s, const dfl_foot_opts *opt,
                                   dfl_surface_locator **out, dfl_err *err);
void dfl_surface_locator_free(dfl_surface_locator *L);
dfl_status dfl_surface_footpoint(const dfl_surface_locator *L, const double x[3],
                                 dfl_surface_foot *out, dfl_err *err);

/* ---- signed distance of a closed planar curve ---- */
typedef struct dfl_curve_sdf_val {
    double d;        /* signed distance, negative inside */
    double g[2];     /* gradient = N */
    double h[3];     /* d_xx, d_xy, d_yy (order >= 2) */
    double t3[4];    /* d_xxx, d_xxy, d_xyy, d_yyy (order >= 3) */
    double t;        /* footpoint parameter */
    double foot[2];  /* footpoint */
    double kappa;    /* signed curvature (convention above) */
    double kappa_s;  /* d kappa / ds */
    int winding;     /* winding number around x (0 outside; from N when |d| <= h) */
    int flags;       /* DFL_FOOT_MEDIAL | DFL_FOOT_FOCAL */
} dfl_curve_sdf_val;

typedef struct dfl_curve_sdf dfl_curve_sdf;

/* c must be planar (dim 2) and closed (dfl_bspline_is_closed(c, 1e-12)):
 * DFL_E_INPUT "a closed curve is required" otherwise.  c must outlive S. */
dfl_status dfl_curve_sdf_new(const dfl_bspline *c, const dfl_foot_opts *opt,
                             dfl_curve_sdf **out, dfl_err *err);
void dfl_curve_sdf_free(dfl_curve_sdf *S);

/* Orientation of the curve: +1 counter-clockwise, -1 clockwise. */
int dfl_curve_sdf_orientation(const dfl_curve_sdf *S);

/* Value and derivatives up to `order` (0..3) at x. */
dfl_status dfl_curve_sdf_eval(const dfl_curve_sdf *S, const double x[2], int order,
                              dfl_curve_sdf_val *out, dfl_err *err);

/* Exact jet of s -> d(x + s dir) to order K (<= DFL_JET_MAX): the footpoint
 * is followed in Taylor arithmetic (Newton steps on the footpoint
 * condition, each doubling the number of exact orders).  On the medial axis
 * the branch valid for small s > 0 is taken.  Exact within one polynomial
 * piece of the curve (a footpoint exactly on a knot uses the piece the
 * footpoint moves into). */
dfl_status dfl_curve_sdf_jet(const dfl_curve_sdf *S, const double x[2], const double dir[2], int K,
                             dfl_jet *out, dfl_err *err);

/* ---- shapes ---- */
/* Distance shape of a curve; takes ownership of *c (zeroed on success and
 * failure).  signed_dist != 0 requires a closed planar curve (signed
 * distance as above); otherwise the unsigned distance |x - C| (dim 2 or 3,
 * >= 0 everywhere).  Jets exist for both (unsigned: off the curve, or with a
 * footpoint inside the domain). */
dfl_status dfl_shape_param_curve(dfl_bspline *c, const dfl_foot_opts *opt, int signed_dist,
                                 dfl_shape *out, dfl_err *err);

/* Unsigned distance shape of a surface; takes ownership of *s (zeroed).  No
 * jets.  Gradient (x - S)/|x - S|; on the surface the unit normal. */
dfl_status dfl_shape_param_surface(dfl_surface_set *s, const dfl_foot_opts *opt, dfl_shape *out,
                                   dfl_err *err);

#endif
