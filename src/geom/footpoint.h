/* Footpoints (closest points) on parametric curves and surfaces: the
 * locators.  Built on them: the signed distance of a closed planar curve
 * (geom/curve_sdf.h) and the distance shapes of curves and surfaces
 * (geom/param_shape.h), both included at the end of this header.
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
 * Thread safety: locators are read-only after creation.
 * The newton backend allocates nothing per query; the ceres backend
 * allocates inside Ceres (it is meant for verification and hard cases).
 * Lifetimes: a locator keeps a pointer to its curve/surface, which must
 * outlive it.
 *
 * Files: footpoint.c (options, the shared ranking of candidates),
 * foot_curve.c, foot_surface.c.
 */
#ifndef DFL_GEOM_FOOTPOINT_H
#define DFL_GEOM_FOOTPOINT_H

#include <stddef.h>

#include "core/status.h"
#include "geom/foot_backend.h"
#include "geom/bspline.h"
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

/* The modules built on the locators (they include this header first). */
#include "geom/curve_sdf.h"
#include "geom/param_shape.h"

#endif
