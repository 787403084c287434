/* bs04 eq. 13-14: bounds on |grad u| near the joining point of two parts,
 * u = F(h1, h2), in polar coordinates of the (h1, h2) plane:
 * h1 = rho cos(phi), h2 = rho sin(phi), phi = atan2(h2, h1) in [0, pi/2].
 *
 * grad u = F1 grad h1 + F2 grad h2 with F_i = dF/dh_i, so the triangle
 * inequality gives, for any part gradients of norms g1, g2,
 *     |F1 g1 - F2 g2| <= |grad u| <= F1 g1 + F2 g2                  (*)
 * and, for normalized parts (g1 = g2 = 1), eq. 13:
 *     |F1 - F2| <= |grad u| <= F1 + F2.
 * Both joins are homogeneous of degree 1, so F_i depend on phi only.
 *
 * R-equivalence (eq. 14, from rfunc/join.h):
 *     F1 = sin^(p+1) / (cos^p + sin^p)^((p+1)/p),  F2 = same with cos^(p+1).
 * R-conjunction (extension; bs04 only says "similar analysis applies"):
 *     u = h1 + h2 - (h1^p + h2^p)^(1/p),  dF/dh1 = 1 - (h1/N)^(p-1),
 *     N = (h1^p + h2^p)^(1/p), hence in polar coordinates
 *     F1 = 1 - cos^(p-1) / (cos^p + sin^p)^((p-1)/p),
 *     F2 = 1 - sin^(p-1) / (cos^p + sin^p)^((p-1)/p).
 * At phi = pi/4 (h1 = h2): F1 = F2 = 2^(-(p+1)/p) (R-equivalence; F1 + F2 =
 * 2^(-1/p)) and 1 - 2^(-(p-1)/p) (R-conjunction; F1 + F2 = 2 - 2^(1/p)).
 *
 * Near a vertex where two straight parts meet at the angle alpha' =
 * min(alpha, 2 pi - alpha) of their directions and the parts are exact
 * distances, the field is homogeneous (|grad u| depends on the direction
 * only) and has three regimes (derivations in gradbound.c):
 *   both closest points interior (convex sector): the part gradients are
 *     the two segment normals, at angle pi - alpha'; on the bisector
 *     (phi = pi/4) |grad u| = 2 F(pi/4) sin(alpha'/2);
 *   one closest point interior, the other the vertex: with s = h_int/q in
 *     (0, 1] (q = distance to the vertex), phi = atan2(1, s) and the
 *     gradients at angle acos(s):
 *         |grad u|^2 = F1^2 + F2^2 + 2 F1 F2 s;
 *     directions with this regime exist for s in [max(cos alpha', 0), 1];
 *   both closest points the vertex (hatched sector): |grad u| = 2 F(pi/4).
 *
 * All functions are pure.  join must be DFL_RFUNC_REQUIV or DFL_RFUNC_RCONJ
 * (the corrected join has three arguments; eq. 13 does not apply) and p a
 * valid order for it (rfunc/join.h); dfl_gradbound_check says so.
 */
#ifndef DFL_EXPERIMENTS_GRADBOUND_H
#define DFL_EXPERIMENTS_GRADBOUND_H

#include "core/status.h"
#include "rfunc/join.h"

/* DFL_E_INPUT unless join is requiv or rconj and p is valid for it. */
dfl_status dfl_gradbound_check(dfl_rfunc_join join, int p, dfl_err *err);

/* R-conjunction's partials in polar coordinates (formula above), p >= 2,
 * phi in [0, pi/2]. */
void dfl_gradbound_rconj_partials_polar(double phi, int p, double *F1, double *F2);

/* F1, F2 of the join at phi in [0, pi/2]. */
void dfl_gradbound_partials(dfl_rfunc_join join, int p, double phi, double *F1, double *F2);

/* eq. 13 (g1 = g2 = 1) or (*) for part gradient norms g1, g2 >= 0:
 * *lo = |F1 g1 - F2 g2|, *hi = F1 g1 + F2 g2. */
void dfl_gradbound_band(double F1, double F2, double g1, double g2, double *lo, double *hi);

/* |grad u| of the joined exact distances on the bisector of the convex
 * sector: 2 F(pi/4) sin(alpha'/2), alpha in (0, 2 pi) (radians). */
double dfl_gradbound_bisector(dfl_rfunc_join join, int p, double alpha);

/* |grad u| in the mixed regime as a function of s in (0, 1]. */
double dfl_gradbound_mixed(dfl_rfunc_join join, int p, double s);

/* Minimum of |grad u| over all directions around the vertex of two exact
 * segment distances meeting at alpha (radians, in (0, 2 pi)): the least of
 * the bisector value, the mixed regime's minimum over its available s
 * (dense scan + golden section, absolute accuracy ~1e-12) and the hatched
 * value.  *where (may be NULL) receives 0 when the bisector value is the
 * least (ties within 1e-12 included), 1 when the mixed regime is; *s_min
 * (may be NULL) the minimizing s of the mixed regime. */
double dfl_gradbound_vertex_min(dfl_rfunc_join join, int p, double alpha, int *where,
                                double *s_min);

/* Minimizer of f on [a, b] by golden-section search to the interval width
 * tol > 0; the minimum value to *fmin (may be NULL).  f must be unimodal on
 * [a, b] for the result to be the global minimum there. */
double dfl_gradbound_golden(double (*f)(void *ctx, double x), void *ctx, double a, double b,
                            double tol, double *fmin);

/* Minimum of F1 + F2 over phi in [0, pi/2] (dense scan of 2001 points +
 * golden section); its location to *phi_min, and to *sum_max the maximum of
 * F1 + F2 and to *diff_max the maximum of |F1 - F2| over the scan.  Any
 * output may be NULL. */
double dfl_gradbound_sum_min(dfl_rfunc_join join, int p, double *phi_min, double *sum_max,
                             double *diff_max);

#endif
