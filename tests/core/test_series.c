/* core/series against closed forms: polynomial products computed by hand,
 * the binomial series of sqrt(1 + s) and of sqrt(4 + 4 s + s^2) = 2 + s,
 * aliasing, and the failure of sqrt at c0 <= 0. */
#include <criterion/criterion.h>
#include <math.h>

#include "core/series.h"

static dfl_series poly(const double *c, int n)
{
    dfl_series s;
    dfl_series_zero(&s);
    for (int k = 0; k < n; k++) s.c[k] = c[k];
    return s;
}

Test(series, products_and_sums)
{
    /* (1 + 2s - s^2)(3 - s + 4s^3) = 3 + 5s - 5s^2 + 5s^3 + 8s^4 - 4s^5 */
    dfl_series a = poly((double[]){1, 2, -1}, 3), b = poly((double[]){3, -1, 0, 4}, 4), r;
    dfl_series_mul(&a, &b, 6, &r);
    const double want[7] = {3, 5, -5, 5, 8, -4, 0};
    for (int k = 0; k <= 6; k++) cr_assert_eq(r.c[k], want[k], "c%d = %g", k, r.c[k]);
    /* truncation: order 2 only */
    dfl_series t;
    dfl_series_zero(&t);
    t.c[3] = 99.0;
    dfl_series_mul(&a, &b, 2, &t);
    cr_assert_eq(t.c[2], -5.0);
    cr_assert_eq(t.c[3], 99.0); /* above K: untouched */
    /* aliasing: a = a * a */
    dfl_series_mul(&a, &a, 4, &a);
    const double sq[5] = {1, 4, 2, -4, 1};
    for (int k = 0; k <= 4; k++) cr_assert_eq(a.c[k], sq[k]);
    dfl_series_add(&a, &b, 4, &r);
    cr_assert_eq(r.c[0], 4.0);
    cr_assert_eq(r.c[3], 0.0);
    /* coefficient K itself is summed (0..K inclusive): a4 + b4 = 1 + 0 */
    cr_assert_eq(r.c[4], 1.0);
    dfl_series_axpy(-2.0, &b, 3, &r);
    cr_assert_eq(r.c[0], -2.0);
    cr_assert_eq(r.c[3], -8.0);
}

Test(series, square_roots)
{
    /* sqrt(1 + s) = sum C(1/2, k) s^k */
    dfl_series a = poly((double[]){1, 1}, 2), r;
    cr_assert_eq(dfl_series_sqrt(&a, 12, &r, NULL), DFL_OK);
    double bin = 1.0;
    for (int k = 0; k <= 12; k++) {
        cr_assert(fabs(r.c[k] - bin) <= 1e-15 * fabs(bin), "c%d = %.17g vs %.17g", k, r.c[k], bin);
        bin *= (0.5 - k) / (k + 1);
    }
    /* a perfect square: sqrt(4 + 4s + s^2) = 2 + s exactly */
    dfl_series q = poly((double[]){4, 4, 1}, 3);
    cr_assert_eq(dfl_series_sqrt(&q, 8, &q, NULL), DFL_OK);
    cr_assert_eq(q.c[0], 2.0);
    cr_assert_eq(q.c[1], 1.0);
    for (int k = 2; k <= 8; k++) cr_assert_eq(q.c[k], 0.0);
    /* c0 <= 0 fails and leaves out alone */
    dfl_series z = poly((double[]){0, 1}, 2), o = poly((double[]){7}, 1);
    dfl_err err;
    cr_assert_eq(dfl_series_sqrt(&z, 3, &o, &err), DFL_E_NUMERIC);
    cr_assert_eq(o.c[0], 7.0);
}
