/* bs04 trimming: composition of a carrier function f with a trim function t
 * (eq. 4 and eq. 5), and Rvachev's R0-conjunction used to build trim regions
 * (strip, prism) including the conditional form of eq. 15.
 *
 * Conventions.  A carrier is given through F = f^2 >= 0 (a line in 2D, a
 * line in 3D with f^2 = s^2 + q^2, a plane), so 2D and 3D share one code
 * path.  t >= 0 inside the trim region, t = 0 on its boundary, and t is
 * normalized to first order there (|grad t| = 1).  All functions are pure,
 * thread-safe and allocation-free.
 *
 * Composition (bs04 sec. 2.1; the extracted text garbles the radicals, the
 * forms below are re-derived):
 *   eq. 4  h = sqrt(f^2 + (|t| - t)^2 / 4) = sqrt(f^2 + max(-t, 0)^2)
 *   eq. 5  h = sqrt(f^2 + g^2 / 4),  g = sqrt(t^2 + f^4) - t
 * h = 0 exactly on {f = 0, t >= 0}, h > 0 elsewhere.  For t > 0, eq. 4 is
 * h = |f| (exact distance to the carrier: normalized to every order), and
 * for eq. 5, g = f^4 / (sqrt(t^2 + f^4) + t) = f^4/(2t) - f^8/(8 t^3) + ...,
 * h^2 = f^2 + f^8/(16 t^2) - f^12/(32 t^4) + ..., so
 *     h = |f| + |f|^7 / (32 t^2) - |f|^11 / (64 t^4) + O(f^13)
 * (t itself varies along the normal; its Taylor terms multiply these):
 * eq. 5 is normalized to order 6 exactly (d^7 h / dn^7 = 7! / (32 t^2) != 0)
 * at every point interior to the trim region.  That is the limit the smooth
 * trim puts on every joined field (see join.h).
 *
 * R0-conjunction (bs04 eq. 15 with the conditional term c >= 0):
 *   x ^ y = x + y - sqrt(x^2 + y^2 + c)
 * c = 0 is Rvachev's R0 (the order-2 member of eq. 7 for signed arguments);
 * c = a |f|^k is the conditional conjunction of eq. 15.  Evaluated as
 * (2 x y - c) / (x + y + r) when x + y > 0, which is x + y - r without the
 * cancellation near the zero set.
 */
#ifndef DFL_RFUNC_TRIM_H
#define DFL_RFUNC_TRIM_H

#include "core/jet.h"
#include "core/status.h"

/* Relative tolerance under which a quantity that vanishes in exact
 * arithmetic (a line function at a point on the line, a trim function at an
 * end point) is set to exactly 0 when building jets, so that valuations are
 * exact.  Values (eval) are never snapped. */
#define DFL_RFUNC_SNAP_TOL 1e-13

/* h of eq. 4 (smooth = 0) or eq. 5 (smooth = 1) and, when gh != NULL, its
 * gradient (dim doubles).  Inputs: fa = |f| >= 0; hgF = grad(f^2) / 2
 * (dim doubles; f grad f); t and its gradient gt.  The gradient is 0 where
 * h = 0 (the zero set, where h is not differentiable). */
double dfl_rfunc_compose(int dim, int smooth, double fa, const double *hgF, double t,
                         const double *gt, double *gh);

/* Jet of h along a ray from the jets of F = f^2 and of t (both to the same
 * absolute order).  F must be a square (even valuation, positive leading
 * coefficient) or a zero jet.  The result is exact on the zero set: with
 * F = (s c)^2 and t > 0 it is |c| s (+ the eq. 5 term at s^7).
 * DFL_E_NUMERIC only if the jet arithmetic fails (never for valid input). */
dfl_status dfl_rfunc_compose_jet(int smooth, const dfl_jet *F, const dfl_jet *t, dfl_jet *out,
                                 dfl_err *err);

/* x ^ y of the conditional R0-conjunction with c >= 0 (c = 0: plain R0).
 * Partial derivatives to *dx, *dy, *dc (each may be NULL).  At the single
 * point x = y = c = 0 the function is not differentiable; the partials are
 * then set to the values along the bisector x = y > 0, c = 0:
 * 1 - 1/sqrt(2), 1 - 1/sqrt(2), 0. */
double dfl_rfunc_conj0(double x, double y, double c, double *dx, double *dy, double *dc);

/* Jet of x ^ y; c may be NULL (plain R0), otherwise a jet of a function
 * >= 0. */
dfl_status dfl_rfunc_conj0_jet(const dfl_jet *x, const dfl_jet *y, const dfl_jet *c,
                               dfl_jet *out, dfl_err *err);

/* Helpers shared by the primitives.  Sign of a jet near s = 0+: +1, -1, or
 * 0 for a zero jet. */
int dfl_rfunc_jet_sign(const dfl_jet *a);
/* The exact zero jet. */
void dfl_rfunc_jet_zero(dfl_jet *out);
/* max(a, 0) near s = 0+: a if its sign is positive, else the exact zero. */
void dfl_rfunc_jet_pos(const dfl_jet *a, dfl_jet *out);
/* v, or exactly 0 when |v| <= DFL_RFUNC_SNAP_TOL * scale. */
double dfl_rfunc_snap(double v, double scale);

#endif
