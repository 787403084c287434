#include "core/series.h"

#include <assert.h>
#include <math.h>
#include <string.h>

static void check_order(int K) { assert(K >= 0 && K <= DFL_SERIES_MAX); }

void dfl_series_zero(dfl_series *out) { memset(out, 0, sizeof *out); }

void dfl_series_add(const dfl_series *a, const dfl_series *b, int K, dfl_series *out)
{
    check_order(K);
    for (int k = 0; k <= K; k++) out->c[k] = a->c[k] + b->c[k];
}

void dfl_series_axpy(double k, const dfl_series *x, int K, dfl_series *y)
{
    check_order(K);
    for (int m = 0; m <= K; m++) y->c[m] += k * x->c[m];
}

void dfl_series_mul(const dfl_series *a, const dfl_series *b, int K, dfl_series *out)
{
    check_order(K);
    dfl_series r; /* out may alias a or b */
    for (int k = 0; k <= K; k++) {
        double s = 0.0;
        for (int i = 0; i <= k; i++) s += a->c[i] * b->c[k - i];
        r.c[k] = s;
    }
    memcpy(out->c, r.c, (size_t)(K + 1) * sizeof r.c[0]);
}

dfl_status dfl_series_sqrt(const dfl_series *a, int K, dfl_series *out, dfl_err *err)
{
    check_order(K);
    if (!(a->c[0] > 0.0))
        return dfl_err_set(err, DFL_E_NUMERIC, "square root of a series with c0 = %g (need > 0)",
                           a->c[0]);
    dfl_series r;
    r.c[0] = sqrt(a->c[0]);
    for (int k = 1; k <= K; k++) {
        double s = a->c[k];
        for (int i = 1; i < k; i++) s -= r.c[i] * r.c[k - i];
        r.c[k] = s / (2.0 * r.c[0]);
    }
    memcpy(out->c, r.c, (size_t)(K + 1) * sizeof r.c[0]);
    return DFL_OK;
}
