/* Plain truncated power series a(s) = c[0] + c[1] s + ... + c[K] s^K.
 *
 *   dfl_series_zero(out)              all coefficients 0
 *   dfl_series_add(a, b, K, out)      a + b
 *   dfl_series_axpy(k, x, K, y)       y += k x
 *   dfl_series_mul(a, b, K, out)      Cauchy product truncated at s^K
 *   dfl_series_sqrt(a, K, out, err)   square root, needs c[0] > 0
 *
 * Unlike core/jet.h there is no valuation and no precision bookkeeping:
 * every coefficient 0..K is carried and the caller knows which ones are
 * exact.  This is what Newton iterations in series arithmetic want (the
 * implicit-surface jets: one more exact order per step, coefficient 0
 * pinned), where a jet's stripping of cancelled leading terms would change
 * the numbers.  K is the caller's order, 0 <= K <= DFL_SERIES_MAX
 * (asserted); coefficients above K are neither read nor written.  All
 * functions allow aliasing of inputs and output and allocate nothing. */
#ifndef DFL_CORE_SERIES_H
#define DFL_CORE_SERIES_H

#include "core/jet.h"
#include "core/status.h"

#define DFL_SERIES_MAX DFL_JET_MAX

typedef struct dfl_series {
    double c[DFL_SERIES_MAX + 1];
} dfl_series;

/* Sets every coefficient (0..DFL_SERIES_MAX) to 0. */
void dfl_series_zero(dfl_series *out);
void dfl_series_add(const dfl_series *a, const dfl_series *b, int K, dfl_series *out);
/* y->c[k] += k * x->c[k], k = 0..K. */
void dfl_series_axpy(double k, const dfl_series *x, int K, dfl_series *y);
/* out->c[k] = sum_{i=0..k} a->c[i] b->c[k-i], summed from 0.0 in i order. */
void dfl_series_mul(const dfl_series *a, const dfl_series *b, int K, dfl_series *out);
/* sqrt(a) with the Cauchy product solved term by term:
 * r0 = sqrt(a0), r_k = (a_k - sum_{i=1..k-1} r_i r_{k-i}) / (2 r0).
 * DFL_E_NUMERIC if !(a->c[0] > 0) (out untouched); err may be NULL. */
dfl_status dfl_series_sqrt(const dfl_series *a, int K, dfl_series *out, dfl_err *err);

#endif
