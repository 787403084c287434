/* Signed distance of a closed planar curve with derivatives to order 3 and
 * exact jets along rays, from the footpoint (geom/footpoint.h).
 *
 * The curve is planar (dim 2) and closed: periodic, or clamped with
 * C(t0) = C(t1).  Conventions:
 *   d < 0 inside, where the winding number of the curve around x is
 *   non-zero; N is the unit normal at the footpoint pointing to the outside
 *   (the right normal of a counter-clockwise curve), T = C'/|C'| the unit
 *   tangent, kappa the curvature in geom/curvature.h's convention for the
 *   normal N: dN/ds = kappa T (a circle of radius R has kappa = +1/R, a
 *   convex curve kappa >= 0), and kappa_s = d kappa / ds its arc-length
 *   derivative.  With x = C(s) + d N and g = 1 + kappa d (> 0 off the focal
 *   set):
 *     grad d = N
 *     H = kappa / g  T T^T                        (Hessian)
 *     d_ijk = kappa_s / g^3  T_i T_j T_k
 *             - kappa^2 / g^2 (T_i T_j N_k + T_i N_j T_k + N_i T_j T_k)
 *   Derivation: dT/ds = -kappa N, so dx = (1 + kappa d) T ds + N dd gives
 *   grad s = T / g and grad d = N; grad N = (dN/ds) grad s^T = kappa T T^T / g;
 *   differentiate H = f T T^T with f(s, d) = kappa / (1 + kappa d):
 *   df/ds = kappa_s / g^2, df/dd = -kappa^2 / g^2, dT/dx_k = -kappa N T_k / g.
 *   Parametric forms: kappa = o (C' x C'') / |C'|^3 with o = +1 for a
 *   counter-clockwise curve (-1 clockwise), kappa_s = o [(C' x C''')/|C'|^3
 *   - 3 (C' x C'')(C'.C'')/|C'|^5] / |C'|.
 * The sign comes from the winding number of a certified polygonization
 * (Hausdorff bound h, 1e-4 of the curve's size) when |d| > h (the curve and
 * the polygon are homotopic inside the h-tube, so their winding numbers
 * around x agree), else from N.(x - C), which agrees for the global
 * footpoint.  Flags: DFL_FOOT_MEDIAL (several footpoints tie: d is then not
 * differentiable and the derivatives are those of the chosen footpoint's
 * branch), DFL_FOOT_FOCAL when |g| < 1e-6 (derivatives blow up; they are
 * still returned).
 *
 * Thread safety: an SDF object is read-only after creation; queries may run
 * concurrently (allocation only inside Ceres, as for the locators).
 *
 * Files: curve_sdf.c (value and derivatives), curve_jet.c (jets).
 */
#ifndef DFL_GEOM_CURVE_SDF_H
#define DFL_GEOM_CURVE_SDF_H

#include "core/jet.h"
#include "core/status.h"
#include "geom/bspline.h"
#include "geom/footpoint.h"

typedef struct dfl_curve_sdf_val {
    double d;        /* signed distance, negative inside */
    double g[2];     /* gradient = N */
    double h[3];     /* d_xx, d_xy, d_yy (order >= 2) */
    double t3[4];    /* d_xxx, d_xxy, d_xyy, d_yyy (order >= 3) */
    double t;        /* footpoint parameter */
    double foot[2];  /* footpoint */
    double kappa;    /* curvature at the footpoint (convention above) */
    double kappa_s;  /* d kappa / ds */
    int winding;     /* winding number around x (0 outside; from N when |d| <= h) */
    int flags;       /* DFL_FOOT_MEDIAL | DFL_FOOT_FOCAL */
} dfl_curve_sdf_val;

typedef struct dfl_curve_sdf dfl_curve_sdf;

/* c must be planar (dim 2) and closed (dfl_bspline_is_closed(c, 1e-12)):
 * DFL_E_INPUT "a closed curve is required" otherwise, or for a curve that
 * encloses no area; opt as for dfl_curve_locator_new (NULL: defaults);
 * DFL_E_NOMEM.  c must outlive S. */
dfl_status dfl_curve_sdf_new(const dfl_bspline *c, const dfl_foot_opts *opt,
                             dfl_curve_sdf **out, dfl_err *err);
void dfl_curve_sdf_free(dfl_curve_sdf *S);

/* Orientation of the curve: +1 counter-clockwise, -1 clockwise. */
int dfl_curve_sdf_orientation(const dfl_curve_sdf *S);

/* Value and derivatives up to `order` (0..3) at x (DFL_E_INPUT for another
 * order; DFL_E_NUMERIC if the ceres backend fails). */
dfl_status dfl_curve_sdf_eval(const dfl_curve_sdf *S, const double x[2], int order,
                              dfl_curve_sdf_val *out, dfl_err *err);

/* Exact jet of s -> d(x + s dir) to order K (<= DFL_JET_MAX): the footpoint
 * is followed in Taylor arithmetic (Newton steps on the footpoint
 * condition, each doubling the number of exact orders).  On the medial axis
 * the branch valid for small s > 0 is taken.  Exact within one polynomial
 * piece of the curve (a footpoint exactly on a knot uses the piece the
 * footpoint moves into).  DFL_E_INPUT for K out of range, DFL_E_NUMERIC if
 * the footpoint search or the series division fails. */
dfl_status dfl_curve_sdf_jet(const dfl_curve_sdf *S, const double x[2], const double dir[2], int K,
                             dfl_jet *out, dfl_err *err);

#endif
