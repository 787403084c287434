/* experiments/normorder: orders of jets with known expansions. */
#include <criterion/criterion.h>
#include <math.h>

#include "core/jet.h"
#include "geom/shape.h"
#include "field/normorder.h"

static dfl_normorder measure(const double *a, int m, int K, double sigma, double L)
{
    dfl_jet j;
    dfl_jet_poly(a, m, K, &j);
    dfl_normorder r;
    dfl_err err;
    cr_assert_eq(dfl_normorder_measure(&j, sigma, L, 1e-9, &r, &err), DFL_OK, "%s", err.msg);
    return r;
}

/* u = s + c s^k is normalized to order k - 1 exactly; d_k = k! c. */
Test(normorder, first_nonzero_coefficient)
{
    for (int k = 2; k <= 14; k++) {
        double a[16] = {0};
        a[1] = 1.0;
        a[k] = -0.37;
        const dfl_normorder r = measure(a, k + 1, 15, 1.0, 1.0);
        cr_assert_eq(r.order, k - 1);
        cr_assert_eq(r.k, k);
        cr_assert_eq(r.capped, 0);
        cr_assert_float_eq(r.coef, -0.37, 0);
        cr_assert_float_eq(r.deriv, -0.37 * tgamma(k + 1.0), 1e-15 * tgamma(k + 1.0));
        cr_assert_eq(r.d1, 1.0);
    }
}

Test(normorder, capped_sign_and_defects)
{
    const double s[2] = {0.0, 1.0};
    dfl_normorder r = measure(s, 2, 12, 1.0, 1.0);
    cr_assert(r.capped && r.order == 12 && r.k == 13 && isnan(r.coef));
    /* inward along a signed field: slope -1 */
    const double ms[3] = {0.0, -1.0, 0.25};
    r = measure(ms, 3, 6, -1.0, 1.0);
    cr_assert_eq(r.order, 1);
    cr_assert_float_eq(r.deriv, 0.5, 1e-15);
    r = measure(ms, 3, 6, 1.0, 1.0); /* d1 = -1 is not +1 */
    cr_assert_eq(r.order, 0);
    cr_assert_eq(r.k, 1);
    cr_assert_eq(r.deriv, -1.0);
    /* bulging: d1 = 2^(-1/2) */
    const double b[2] = {0.0, sqrt(0.5)};
    r = measure(b, 2, 6, 1.0, 1.0);
    cr_assert(r.order == 0 && r.k == 1 && r.d1 == sqrt(0.5));
    /* off the zero set */
    const double off[2] = {1e-3, 1.0};
    r = measure(off, 2, 6, 1.0, 1.0);
    cr_assert(r.order == -1 && r.k == 0 && r.coef == 1e-3);
}

/* The zero test is |a_k| L^(k-1) <= tol: a small coefficient is zero on a
 * small scale and not on a large one. */
Test(normorder, length_scale)
{
    const double a[4] = {0.0, 1.0, 0.0, 1e-10};
    cr_assert(measure(a, 4, 8, 1.0, 1.0).capped);
    const dfl_normorder r = measure(a, 4, 8, 1.0, 100.0); /* 1e-10 * 1e4 */
    cr_assert(r.order == 2 && r.k == 3 && r.coef == 1e-10);
    /* d1 is compared without the scale */
    const double d[2] = {0.0, 1.0 + 2e-9};
    cr_assert_eq(measure(d, 2, 8, 1.0, 1e-6).order, 0);
}

/* The exact SDF of a circle along its normal is s: normalized to every
 * order the jet knows; along an oblique ray from a boundary point it is
 * not even normalized to first order (d1 = cos of the angle). */
Test(normorder, circle_sdf)
{
    const double c[2] = {0.3, -0.2};
    dfl_shape sh;
    cr_assert_eq(dfl_shape_circle(c, 0.7, &sh, NULL), DFL_OK);
    const double th = 0.9, x[2] = {c[0] + 0.7 * cos(th), c[1] + 0.7 * sin(th)};
    const double nu[2] = {cos(th), sin(th)}, obl[2] = {cos(th + 0.5), sin(th + 0.5)};
    dfl_jet j;
    dfl_normorder r;
    cr_assert_eq(sh.ops->jet(sh.impl, x, nu, 16, &j, NULL), DFL_OK);
    cr_assert_eq(dfl_normorder_measure(&j, 1.0, 0.7, 1e-9, &r, NULL), DFL_OK);
    cr_assert(r.capped && r.order == 16, "order %d", r.order);
    cr_assert_eq(sh.ops->jet(sh.impl, x, obl, 8, &j, NULL), DFL_OK);
    cr_assert_eq(dfl_normorder_measure(&j, 1.0, 0.7, 1e-9, &r, NULL), DFL_OK);
    cr_assert_eq(r.order, 0);
    cr_assert_float_eq(r.d1, cos(0.5), 1e-14);
    dfl_shape_free(&sh);
}

Test(normorder, bad_input)
{
    dfl_jet j;
    dfl_jet_linear(0.0, 1.0, 5, &j);
    dfl_normorder r;
    dfl_err err;
    cr_assert_eq(dfl_normorder_measure(&j, 0.5, 1.0, 1e-9, &r, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_normorder_measure(&j, 1.0, 0.0, 1e-9, &r, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_normorder_measure(&j, 1.0, 1.0, 0.0, &r, &err), DFL_E_INPUT);
    dfl_jet_const(0.0, 0, &j);
    cr_assert_eq(dfl_normorder_measure(&j, 1.0, 1.0, 1e-9, &r, &err), DFL_E_INPUT);
    dfl_jet_linear(2.0, 1.0, 5, &j);
    dfl_jet_recip(&(dfl_jet){.v = 1, .n = 6, .c = {1.0}}, &j, NULL);
    cr_assert_eq(dfl_normorder_measure(&j, 1.0, 1.0, 1e-9, &r, &err), DFL_E_NUMERIC);
}

/* The series scale: u = s + c s^k gives R = |c|^(-1/(k-1)); the smallest
 * over several terms wins; no term: infinity. */
Test(normorder, series_scale)
{
    dfl_jet j;
    const double a[5] = {0.0, 1.0, 0.0, 0.0, -64.0};
    dfl_jet_poly(a, 5, 8, &j);
    cr_assert_float_eq(dfl_normorder_scale(&j), 0.25, 1e-15);
    const double b[5] = {0.0, 1.0, 2.0, 0.0, -64.0};
    dfl_jet_poly(b, 5, 8, &j);
    cr_assert_float_eq(dfl_normorder_scale(&j), 0.25, 1e-15); /* 64^(-1/3) < 2^(-1) */
    const double c[3] = {0.0, 1.0, 100.0};
    dfl_jet_poly(c, 3, 8, &j);
    cr_assert_float_eq(dfl_normorder_scale(&j), 0.01, 1e-17);
    dfl_jet_linear(0.0, 1.0, 8, &j);
    cr_assert(isinf(dfl_normorder_scale(&j)));
    /* residue 1e-6 below a huge leading term is zero on the series scale */
    const double d[7] = {0.0, 1.0, 0.0, 0.0, 0.0, 1e-6, -1e20};
    dfl_jet_poly(d, 7, 8, &j);
    const double R = dfl_normorder_scale(&j);
    dfl_normorder r;
    cr_assert_eq(dfl_normorder_measure(&j, 1.0, fmin(1.0, R), 1e-9, &r, NULL), DFL_OK);
    cr_assert_eq(r.order, 5);
    cr_assert_eq(dfl_normorder_measure(&j, 1.0, 1.0, 1e-9, &r, NULL), DFL_OK);
    cr_assert_eq(r.order, 4);
}

/* normorder.h: u(p) counts as zero when |a_0| <= tol L, a_k (k >= 2) when
 * |a_k| L^(k-1) <= tol: the exponent is k - 1, not k, so on L = 100 with
 * tol = 1e-9 a_0 = 1e-8 (<= 1e-7) and a_2 = 1e-12 (1e-10 <= 1e-9) are
 * zero, while a_2 = 1e-10 (1e-8) is not. */
Test(normorder, scale_exponent_is_k_minus_one)
{
    const double a0[3] = {1e-8, 1.0, 0.0};
    cr_expect(measure(a0, 3, 4, 1.0, 100.0).capped, "u(p) = 1e-8 <= tol L");
    const double a2[3] = {0.0, 1.0, 1e-12};
    cr_expect(measure(a2, 3, 4, 1.0, 100.0).capped, "a_2 L = 1e-10 <= tol");
    const double b2[3] = {0.0, 1.0, 1e-10};
    const dfl_normorder r = measure(b2, 3, 4, 1.0, 100.0);
    cr_expect(r.order == 1 && r.k == 2 && r.coef == 1e-10, "a_2 L = 1e-8 > tol");
}
