/* Principal curvatures and directions of surfaces (and curvature of plane
 * curves), from an implicit function's gradient and Hessian or from a
 * parametrization's first and second partial derivatives.
 *
 * SIGN CONVENTION (stated here once; every dflab module, comment and test
 * uses it): curvatures are
 * the eigenvalues of the differential of the unit normal n that the caller's
 * data define (implicit: n = grad g / |grad g|, the outward normal when g < 0
 * inside; parametric: n = S_u x S_v / |S_u x S_v|, or the side of n_ref),
 *     dn(e_i) = kappa_i e_i,
 * so a sphere of radius r with outward normal has kappa = +1/r and the
 * signed distance d (positive on the side n points to) has, at x = p + d n,
 *     Hess d(x) = sum_i kappa_i / (1 + kappa_i d) e_i e_i^T.
 * In the classical notation with the second fundamental form
 * L = S_uu . n, M = S_uv . n, N = S_vv . n the classical shape operator
 * -dn has eigenvalues -kappa_i: the Gaussian curvature is the same,
 *     K = kappa_1 kappa_2 = (L N - M^2) / (E G - F^2),
 * (hvb25 prints (L M - N^2) / (E G - F^2): a typo), and the mean curvature
 * changes sign: H = (kappa_1 + kappa_2) / 2 = -(E N - 2 F M + G L) / (2 (E G - F^2)).
 */
#ifndef DFL_GEOM_CURVATURE_H
#define DFL_GEOM_CURVATURE_H

#include "core/status.h"

typedef struct dfl_curvature {
    double k1, k2;        /* principal curvatures, k1 <= k2 (convention above) */
    double e1[3], e2[3];  /* unit principal directions (tangent; e1 x e2 = n) */
    double n[3];          /* the unit normal the signs refer to */
    double K;             /* Gaussian curvature k1 k2 */
    double H;             /* mean curvature (k1 + k2) / 2 */
} dfl_curvature;

/* From grad g (3) and Hessian (9, row-major, symmetric) at a point of g = 0.
 * DFL_E_NUMERIC if grad g = 0. */
dfl_status dfl_curvature_implicit(const double grad[3], const double hess[9], dfl_curvature *out,
                                  dfl_err *err);

/* From the partials S_u, S_v, S_uu, S_uv, S_vv of a regular parametrization.
 * n_ref (may be NULL) picks the normal's side: n is flipped if n . n_ref < 0.
 * DFL_E_NUMERIC if S_u x S_v = 0 (singular parametrization). */
dfl_status dfl_curvature_parametric(const double Su[3], const double Sv[3], const double Suu[3],
                                    const double Suv[3], const double Svv[3],
                                    const double *n_ref, dfl_curvature *out, dfl_err *err);

/* First and second fundamental forms w.r.t. the unit normal n. */
typedef struct dfl_fundamental_forms {
    double E, F, G;       /* S_u.S_u, S_u.S_v, S_v.S_v */
    double L, M, N;       /* S_uu.n, S_uv.n, S_vv.n */
} dfl_fundamental_forms;
void dfl_fundamental_forms_eval(const double Su[3], const double Sv[3], const double Suu[3],
                                const double Suv[3], const double Svv[3], const double n[3],
                                dfl_fundamental_forms *out);
/* K = (L N - M^2) / (E G - F^2) (the corrected hvb25 formula). */
double dfl_gaussian_curvature_ff(const dfl_fundamental_forms *f);
/* H in the convention above: -(E N - 2 F M + G L) / (2 (E G - F^2)). */
double dfl_mean_curvature_ff(const dfl_fundamental_forms *f);

/* Plane curves, same convention: dn/ds = kappa t for the unit normal n the
 * caller's data define and the unit tangent t (a circle with outward normal
 * has kappa = +1/r).  Where nothing else defines n (open curves,
 * field/curveprobe.h), dflab takes the right normal n = (t_y, -t_x) of the
 * parametrization, for which kappa = (c' x c'') / |c'|^3 is positive where
 * the curve turns left; the right normal of a counter-clockwise closed
 * curve is its outward one.  The closed-curve SDF (geom/curve_sdf.h) takes
 * the outward normal, so kappa >= 0 on a convex curve of either
 * orientation and Hess d = kappa / (1 + kappa d) t t^T.
 * Implicit: kappa = t^T Hess g t / |grad g|, t a unit tangent,
 * n = grad g / |grad g|.  NAN if grad g = 0. */
double dfl_curvature_implicit2(const double grad[2], const double hess[4]);
/* Parametric c(u) with c' = d1, c'' = d2 and unit normal n (either side):
 * kappa = -(c'' . n) / |c'|^2.  NAN if c' = 0. */
double dfl_curvature_curve2(const double d1[2], const double d2[2], const double n[2]);

#endif
