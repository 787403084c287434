/* Sparse polynomials in three variables (u, v, w), the representation of
 * dflab's implicit surfaces (geom/implicit.h).
 *
 *   dfl_poly3_term(P, c, e0, e1, e2)    P += c u^e0 v^e1 w^e2
 *   dfl_poly3_axpy(k, A, P)             P += k A
 *   dfl_poly3_mul(A, B, out)            out = A B
 *   dfl_poly3_deriv(P, axis, out)       out = dP / d(axis)
 *   dfl_poly3_eval(P, q, order, ...)    value and partials up to order 3
 *   dfl_poly3_eval_series(P, X, K, out) value at a power-series point
 *
 * A dfl_poly3 is a fixed-size value (no allocation): at most
 * DFL_POLY3_MAX_TERMS monomials of total degree <= DFL_POLY3_MAX_DEGREE,
 * like terms merged (their coefficients added in insertion order), zero
 * coefficients never stored.  Zero-initialize one ({0} or memset) to get
 * the zero polynomial.  The functions that can overflow the term table
 * return 0 then (1 on success) and leave P partly updated; callers that
 * build from validated input (no more terms than the table holds) may
 * ignore it.  Evaluation sums the terms in storage order, so equal inputs
 * give equal bits; orders 0 to 2 run a written-out loop that gives the
 * value, gradient and Hessian bit for bit as order 3 does (a NaN's sign
 * and payload aside, which C leaves to the compiler). */
#ifndef DFL_GEOM_POLY3_H
#define DFL_GEOM_POLY3_H

#include "core/series.h"

#define DFL_POLY3_MAX_TERMS 96
#define DFL_POLY3_MAX_DEGREE 12

typedef struct dfl_poly3 {
    int n;                              /* stored terms */
    int deg;                            /* largest total degree stored */
    double c[DFL_POLY3_MAX_TERMS];
    int e[DFL_POLY3_MAX_TERMS][3];
} dfl_poly3;

/* Adds c u^e0 v^e1 w^e2 (exponents >= 0, total <= DFL_POLY3_MAX_DEGREE,
 * asserted), merging with a like term; c == 0 is a no-op.  0 if the table
 * is full. */
int dfl_poly3_term(dfl_poly3 *P, double c, int e0, int e1, int e2);
/* P += k A.  0 if the table overflows. */
int dfl_poly3_axpy(double k, const dfl_poly3 *A, dfl_poly3 *P);
/* out = A B (out must not alias A or B).  0 if the product does not fit
 * (or its degree exceeds DFL_POLY3_MAX_DEGREE). */
int dfl_poly3_mul(const dfl_poly3 *A, const dfl_poly3 *B, dfl_poly3 *out);
/* out = partial derivative of P along axis (0, 1, 2); never overflows. */
void dfl_poly3_deriv(const dfl_poly3 *P, int axis, dfl_poly3 *out);

/* Value at q and, for order >= 1, 2, 3, the gradient gr (3), Hessian H (9,
 * row-major) and third derivatives T (27, T[9i + 3j + k]), all as full
 * symmetric arrays; arrays above `order` are not touched and may be NULL. */
double dfl_poly3_eval(const dfl_poly3 *P, const double q[3], int order, double gr[3],
                      double H[9], double T[27]);

/* P at the point X (three series) as a series to order K: powers by
 * repeated dfl_series_mul, monomials u^a (v^b w^c), terms accumulated in
 * storage order. */
void dfl_poly3_eval_series(const dfl_poly3 *P, const dfl_series X[3], int K, dfl_series *out);

#endif
