/* Rvachev's recursive normalization to order m (bs04 appendix A).
 *
 * Input: a function f with non-vanishing gradient near its zero set, given
 * by its multivariate Taylor expansions (mtaylor.h) through a callback; a
 * polynomial source (implicit curves and surfaces, e.g. the ellipse
 * x^2/a^2 + y^2/b^2 - 1) is provided.
 *
 *   A.1  f1 = f / sqrt(f^2 + |grad f|^2)
 *   A.4  fk = f(k-1) - (1/k!) f1^k D^k f(k-1),   k = 2..m
 *
 * where D^k g (y) = d^k/ds^k g(y + s nu(y)) at s = 0 is the k-th derivative
 * along the direction nu(y) frozen at y, nu = grad f / |grad f| (the
 * extracted text writes d^k/dnu^k; any continuous unit field equal to the
 * normal on the zero set works, see below).  Why this gives order m: along
 * the normal ray p + s nu(p) from a zero p, if f(k-1) = s + c s^k + O(s^(k+1))
 * then D^k f(k-1) = k! c + O(s) (continuity in y of the frozen-direction
 * derivative) and f1^k = s^k + O(s^(k+1)), so fk = s + O(s^(k+1)).  D^k is
 * computed exactly: D^k g = sum_{|alpha| = k} (k!/alpha!) nu^alpha
 * d^alpha g, with every factor a truncated Taylor polynomial.
 *
 * Degrees: to know fm to degree n at a point, f(k-1) is needed to degree
 * N(k-1) = N(k) + k, so f1 to n + m(m+1)/2 - 1 and f to one more (A.1 has
 * grad f).  Cost grows like that degree^(2 dim): use m <= 6 for grids;
 * DFL_RFUNC_NORM_MAX bounds m.
 *
 * Where grad f = 0 (e.g. the ellipse's centre) nu is undefined and so is fm
 * for m >= 2 (its limit depends on the direction of approach); eval then
 * returns f1 there (gradient 0) and the jet fails with DFL_E_NUMERIC.
 */
#ifndef DFL_RFUNC_NORMALIZE_H
#define DFL_RFUNC_NORMALIZE_H

#include <stddef.h>

#include "core/status.h"
#include "field/field.h"
#include "rfunc/mtaylor.h"

#define DFL_RFUNC_NORM_MAX 8

/* Taylor expansion of f at x to degree out->deg (out->dim set). */
typedef dfl_status (*dfl_rfunc_taylor_fn)(const void *ctx, const double *x, dfl_mt *out,
                                          dfl_err *err);

/* Doubles of workspace dfl_rfunc_normalize_at needs. */
size_t dfl_rfunc_normalize_work(int dim, int m, int nout);

/* Taylor expansion of fm at x to degree out->deg (>= 0), 1 <= m <=
 * DFL_RFUNC_NORM_MAX.  work: dfl_rfunc_normalize_work(dim, m, out->deg)
 * doubles.  DFL_E_NUMERIC where grad f vanishes (m >= 2) or f1's radicand
 * is not positive; errors of src are passed on. */
dfl_status dfl_rfunc_normalize_at(dfl_rfunc_taylor_fn src, const void *ctx, int m,
                                  const double *x, dfl_mt *out, double *work, dfl_err *err);

/* A polynomial sum_t coef[t] x^exps[t] in dim variables (owned copies). */
typedef struct dfl_rfunc_poly {
    int dim;
    int nterms;
    double *coef;
    int *exps;       /* nterms * dim exponents >= 0 */
} dfl_rfunc_poly;

/* Copies the terms.  DFL_E_INPUT for a bad dim, no terms, negative
 * exponents or non-finite coefficients; DFL_E_NOMEM. */
dfl_status dfl_rfunc_poly_init(int dim, int nterms, const double *coef, const int *exps,
                               dfl_rfunc_poly *out, dfl_err *err);
/* x^2/a^2 + y^2/b^2 - 1 (a, b > 0). */
dfl_status dfl_rfunc_poly_ellipse(double a, double b, dfl_rfunc_poly *out, dfl_err *err);
void dfl_rfunc_poly_free(dfl_rfunc_poly *p);
/* The polynomial as a dfl_rfunc_taylor_fn (ctx = const dfl_rfunc_poly *). */
dfl_status dfl_rfunc_poly_taylor(const void *ctx, const double *x, dfl_mt *out, dfl_err *err);

/* fm of the polynomial as a dfl_field (the polynomial is copied).  eval
 * allocates one workspace per batch (not per point); jets allocate one. */
dfl_status dfl_rfunc_normalized_field(const dfl_rfunc_poly *f, int m, dfl_field *out,
                                      dfl_err *err);

#endif
