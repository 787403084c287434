/* Truncated multivariate Taylor polynomials in 2 or 3 variables, for the
 * recursive normalization of appendix A (normalize.h), which needs mixed
 * partial derivatives of nested expressions that univariate jets cannot
 * give.
 *
 * A dfl_mt holds the Taylor coefficients a_alpha of a function at a point,
 * f(x + delta) = sum_{|alpha| <= deg} a_alpha delta^alpha, in graded order:
 * all monomials of total degree 0, then 1, ... deg.  Within degree d:
 *   2D: (i, j) = (d - t, t), t = 0..d, index d(d+1)/2 + t;
 *   3D: (i, j, l) with e = j + l, local index e(e+1)/2 + l (e = 0..d,
 *       l = 0..e), global offset d(d+1)(d+2)/6.
 * So c[0] is the value and c[1..dim] the first partial derivatives.
 *
 * Storage is the caller's: c points to dfl_mt_size(dim, deg) doubles.  No
 * function allocates.  Outputs must not alias inputs unless stated.  An
 * operation's result is truncated at out->deg; inputs of lower degree than
 * out->deg make the result's high terms unknown, so callers keep degrees
 * consistent (the functions assert it where it matters).
 */
#ifndef DFL_RFUNC_MTAYLOR_H
#define DFL_RFUNC_MTAYLOR_H

#include <stddef.h>

#include "core/jet.h"
#include "core/status.h"

typedef struct dfl_mt {
    int dim;     /* 2 or 3 */
    int deg;     /* >= 0 */
    double *c;   /* dfl_mt_size(dim, deg) coefficients, not owned */
} dfl_mt;

/* Number of coefficients of total degree <= deg. */
size_t dfl_mt_size(int dim, int deg);
/* Index of the monomial with exponents e[0..dim-1]. */
size_t dfl_mt_index(int dim, const int *e);

/* out = the constant a. */
void dfl_mt_const(double a, dfl_mt *out);
/* out = a truncated/zero-padded to out->deg (out may have another degree;
 * aliasing not allowed). */
void dfl_mt_copy(const dfl_mt *a, dfl_mt *out);
/* out = a + k b (degrees: out->deg <= a->deg, b->deg; out may alias a). */
void dfl_mt_axpy(const dfl_mt *a, double k, const dfl_mt *b, dfl_mt *out);
/* out = k a (may alias). */
void dfl_mt_scale(const dfl_mt *a, double k, dfl_mt *out);
/* out = a * b truncated at out->deg (<= min(a->deg, b->deg)); out must
 * not alias a or b. */
void dfl_mt_mul(const dfl_mt *a, const dfl_mt *b, dfl_mt *out);
/* out = a^e for real e; needs a's constant term > 0.  Graded Miller
 * recurrence: with a = a0 (1 + g), the homogeneous parts b_d of b = a^e obey
 *   d b_d = sum_{j=1..d} ((e + 1) j - d) g_j b_(d-j)
 * (the univariate recurrence in t for a(t delta), where t^d picks the
 * degree-d part).  DFL_E_NUMERIC if a's constant term is not positive.
 * out must not alias a. */
dfl_status dfl_mt_pow(const dfl_mt *a, double e, dfl_mt *out, dfl_err *err);
/* out = d a / d x_var, truncated at out->deg (<= a->deg - 1). */
void dfl_mt_deriv(const dfl_mt *a, int var, dfl_mt *out);
/* Jet of s -> a(s dir) at s = 0, absolute order K = min(K, a->deg). */
void dfl_mt_ray(const dfl_mt *a, const double *dir, int K, dfl_jet *out);

/* Taylor expansion at x, to degree out->deg, of the polynomial
 * sum_t coef[t] x^exps[t] (exps: nterms * dim non-negative integers). */
void dfl_mt_poly_expand(int nterms, const double *coef, const int *exps, const double *x,
                        dfl_mt *out);

#endif
