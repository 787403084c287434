/* bs04 appendix A: recursive normalization, and the multivariate Taylor
 * arithmetic it runs on. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

#include "rfunc/mtaylor.h"
#include "rfunc/normalize.h"
#include "rfunc_util.h"

/* Multivariate arithmetic against the independent univariate jets: the
 * restriction to a ray commutes with products, powers and derivatives
 * (d/ds a(x + s dir) = grad a . dir). */
Test(rfunc_normalize, mtaylor_matches_univariate_jets)
{
    for (int dim = 2; dim <= 3; dim++) {
        const int deg = 9;
        const size_t n = dfl_mt_size(dim, deg);
        double *buf = calloc(6 * n, sizeof *buf);
        dfl_mt a = {dim, deg, buf}, b = {dim, deg, buf + n}, c = {dim, deg, buf + 2 * n};
        dfl_mt d = {dim, deg, buf + 3 * n}, e = {dim, deg - 1, buf + 4 * n};
        uint64_t rng = 42 + dim;
        for (size_t i = 0; i < n; i++) {
            a.c[i] = tu_uniform(&rng, -1, 1) / (1 + i);
            b.c[i] = tu_uniform(&rng, -1, 1) / (1 + i);
        }
        a.c[0] = 1.5;
        const double dir[3] = {0.7, -0.4, 0.5};
        dfl_jet ja, jb, jc, jd, je, t;
        dfl_mt_ray(&a, dir, deg, &ja);
        dfl_mt_ray(&b, dir, deg, &jb);
        dfl_mt_mul(&a, &b, &c);
        dfl_mt_ray(&c, dir, deg, &jc);
        dfl_jet_mul(&ja, &jb, &t);
        for (int k = 0; k <= deg; k++)
            cr_assert_float_eq(dfl_jet_coeff(&jc, k), dfl_jet_coeff(&t, k), 1e-13);
        cr_assert_eq(dfl_mt_pow(&a, -0.37, &d, NULL), DFL_OK);
        dfl_mt_ray(&d, dir, deg, &jd);
        cr_assert_eq(dfl_jet_pow(&ja, -0.37, &t, NULL), DFL_OK);
        for (int k = 0; k <= deg; k++)
            cr_assert_float_eq(dfl_jet_coeff(&jd, k), dfl_jet_coeff(&t, k), 1e-12);
        /* directional derivative: sum_i dir_i d a / d x_i */
        dfl_mt_const(0.0, &e);
        dfl_mt tmp = {dim, deg - 1, buf + 5 * n};
        for (int i = 0; i < dim; i++) {
            dfl_mt_deriv(&a, i, &tmp);
            dfl_mt_axpy(&e, dir[i], &tmp, &e);
        }
        dfl_mt_ray(&e, dir, deg - 1, &je);
        for (int k = 0; k < deg; k++)
            cr_assert_float_eq(dfl_jet_coeff(&je, k), (k + 1) * dfl_jet_coeff(&ja, k + 1), 1e-13);
        /* polynomial expansion at a point: the ray of the expansion is the
         * polynomial on the ray, (x0 + s d0)^2 (y0 + s d1) - 3 (x0 + s d0). */
        const double coef[2] = {1.0, -3.0};
        const int exps3[6] = {2, 1, 0, 1, 0, 0}, exps2[4] = {2, 1, 1, 0};
        const double x[3] = {0.3, -1.2, 0.8};
        dfl_mt_poly_expand(2, coef, dim == 2 ? exps2 : exps3, x, &c);
        dfl_mt_ray(&c, dir, deg, &jc);
        const double p0 = x[0], p1 = dir[0], q0 = x[1], q1 = dir[1];
        const double want[4] = {p0 * p0 * q0 - 3 * p0, 2 * p0 * p1 * q0 + p0 * p0 * q1 - 3 * p1,
                                p1 * p1 * q0 + 2 * p0 * p1 * q1, p1 * p1 * q1};
        for (int k = 0; k <= deg; k++)
            cr_assert_float_eq(dfl_jet_coeff(&jc, k), k < 4 ? want[k] : 0.0, 1e-14);
        free(buf);
    }
}

/* Order m measured by jets for the ellipse x^2/a^2 + y^2/b^2 - 1, m = 1..6,
 * at several boundary points along the outward normal: d1 = 1, d2..dm = 0
 * (to 1e-9 relative), d(m+1) != 0 (the construction only cancels up to m;
 * for m = 1 the second derivative of f/sqrt(f^2+|grad f|^2) along the
 * normal is generically non-zero). */
Test(rfunc_normalize, ellipse_orders)
{
    const double A = 2.0, B = 1.0;
    dfl_rfunc_poly e;
    cr_assert_eq(dfl_rfunc_poly_ellipse(A, B, &e, NULL), DFL_OK);
    for (int m = 1; m <= 6; m++) {
        dfl_field f;
        cr_assert_eq(dfl_rfunc_normalized_field(&e, m, &f, NULL), DFL_OK);
        for (int i = 0; i < 7; i++) {
            const double th = 0.3 + 0.8 * i;
            const double x[2] = {A * cos(th), B * sin(th)};
            double nu[2] = {2 * x[0] / (A * A), 2 * x[1] / (B * B)};
            const double nn = hypot(nu[0], nu[1]);
            nu[0] /= nn;
            nu[1] /= nn;
            dfl_jet j;
            dfl_err err;
            const int K = m + 2;
            cr_assert_eq(dfl_field_jet(&f, x, nu, K, &j, &err), DFL_OK, "%s", err.msg);
            const double cm1 = dfl_jet_coeff(&j, m + 1);
            cr_assert(fabs(dfl_jet_coeff(&j, 0)) < 1e-14);
            cr_assert(fabs(dfl_jet_deriv(&j, 1) - 1) < 1e-12, "m=%d d1=%.17g", m,
                      dfl_jet_deriv(&j, 1));
            for (int k = 2; k <= m; k++)
                cr_assert(fabs(dfl_jet_coeff(&j, k)) <= 1e-9 * (1 + fabs(cm1)),
                          "m=%d th=%g: coefficient %d = %g", m, th, k, dfl_jet_coeff(&j, k));
            cr_assert(fabs(cm1) > 1e-4, "m=%d th=%g: coefficient %d = %g should not vanish", m,
                      th, m + 1, cm1);
            /* Inward too (signed field: d1 = 1 along -nu means slope -1). */
            const double mnu[2] = {-nu[0], -nu[1]};
            cr_assert_eq(dfl_field_jet(&f, x, mnu, K, &j, &err), DFL_OK);
            cr_assert(fabs(dfl_jet_deriv(&j, 1) + 1) < 1e-12);
            for (int k = 2; k <= m; k++) cr_assert(fabs(dfl_jet_coeff(&j, k)) <= 1e-9 * (1 + fabs(cm1)));
        }
        dfl_field_destroy(&f);
    }
    dfl_rfunc_poly_free(&e);
}

/* Values against an independent implementation: f1 by its closed form and
 * f2 = f1 - f1^2/2 D^2 f1 with D^2 by central differences of the closed
 * form along nu(y) (step 1e-3: error ~ 1e-6 |f1''''| h^2 / 12). */
static double ell_f1(double A, double B, double x, double y, double *nu)
{
    const double f = x * x / (A * A) + y * y / (B * B) - 1;
    const double gx = 2 * x / (A * A), gy = 2 * y / (B * B);
    if (nu) {
        nu[0] = gx / hypot(gx, gy);
        nu[1] = gy / hypot(gx, gy);
    }
    return f / sqrt(f * f + gx * gx + gy * gy);
}

Test(rfunc_normalize, values_match_closed_forms)
{
    const double A = 1.5, B = 0.8;
    dfl_rfunc_poly e;
    cr_assert_eq(dfl_rfunc_poly_ellipse(A, B, &e, NULL), DFL_OK);
    dfl_field f1, f2;
    cr_assert_eq(dfl_rfunc_normalized_field(&e, 1, &f1, NULL), DFL_OK);
    cr_assert_eq(dfl_rfunc_normalized_field(&e, 2, &f2, NULL), DFL_OK);
    uint64_t rng = 8;
    for (int i = 0; i < 100; i++) {
        const double x[2] = {tu_uniform(&rng, -2.5, 2.5), tu_uniform(&rng, -2, 2)};
        if (hypot(x[0], x[1]) < 0.1) continue;
        double nu[2];
        const double v1 = ell_f1(A, B, x[0], x[1], nu);
        cr_assert_float_eq(dfl_field_eval1(&f1, x, NULL), v1, 1e-14);
        const double h = 1e-3;
        const double fp = ell_f1(A, B, x[0] + h * nu[0], x[1] + h * nu[1], NULL);
        const double fm = ell_f1(A, B, x[0] - h * nu[0], x[1] - h * nu[1], NULL);
        const double d2 = (fp - 2 * v1 + fm) / (h * h);
        const double v2 = v1 - 0.5 * v1 * v1 * d2;
        cr_assert(fabs(dfl_field_eval1(&f2, x, NULL) - v2) <= 1e-5 * (1 + fabs(d2)),
                  "x=(%g %g): %.12g vs %.12g", x[0], x[1], dfl_field_eval1(&f2, x, NULL), v2);
    }
    dfl_field_destroy(&f1);
    dfl_field_destroy(&f2);
    dfl_rfunc_poly_free(&e);
}

/* Gradients vs central differences (2D ellipse m = 1..6, 3D ellipsoid
 * m = 1..3), finite at the critical point (documented fallback). */
Test(rfunc_normalize, gradients_and_critical_point)
{
    dfl_rfunc_poly e2, e3;
    cr_assert_eq(dfl_rfunc_poly_ellipse(2.0, 1.0, &e2, NULL), DFL_OK);
    const double c3[4] = {1.0, 1.0 / 4, 1.0 / 2.25, -1.0};
    const int x3[12] = {2, 0, 0, 0, 2, 0, 0, 0, 2, 0, 0, 0};
    cr_assert_eq(dfl_rfunc_poly_init(3, 4, c3, x3, &e3, NULL), DFL_OK);
    for (int dim = 2; dim <= 3; dim++)
        for (int m = 1; m <= (dim == 2 ? 6 : 3); m++) {
            dfl_field f;
            cr_assert_eq(dfl_rfunc_normalized_field(dim == 2 ? &e2 : &e3, m, &f, NULL), DFL_OK);
            uint64_t rng = 100 + m;
            for (int i = 0; i < 30; i++) {
                double x[3];
                for (int j = 0; j < dim; j++) x[j] = tu_uniform(&rng, -2.2, 2.2);
                if (tu_norm(dim, x) < 0.3) continue;
                double g[3], gf[3];
                const double u = dfl_field_eval1(&f, x, g);
                cr_assert(isfinite(u));
                tu_fd_grad(&f, x, 1e-6, gf);
                for (int j = 0; j < dim; j++)
                    cr_assert(fabs(g[j] - gf[j]) <= 1e-6 * (1 + tu_norm(dim, g)),
                              "dim %d m %d: %g vs %g", dim, m, g[j], gf[j]);
            }
            const double o[3] = {0, 0, 0};
            double g[3];
            const double u = dfl_field_eval1(&f, o, g);
            cr_assert(isfinite(u) && u < 0, "at the centre: %g", u);
            dfl_field_destroy(&f);
        }
    dfl_rfunc_poly_free(&e2);
    dfl_rfunc_poly_free(&e3);
}

/* dfl_rfunc_poly_ellipse needs both semi-axes > 0 and finite (header
 * a, b > 0): each one zero, negative or not finite is DFL_E_INPUT. */
Test(rfunc_normalize, ellipse_semi_axes_must_be_positive)
{
    const double bad[4] = {0.0, -1.0, INFINITY, NAN};
    dfl_rfunc_poly e;
    dfl_err err;
    for (int i = 0; i < 4; i++) {
        cr_expect_eq(dfl_rfunc_poly_ellipse(bad[i], 1.0, &e, &err), DFL_E_INPUT, "a = %g", bad[i]);
        cr_expect_eq(dfl_rfunc_poly_ellipse(1.0, bad[i], &e, &err), DFL_E_INPUT, "b = %g", bad[i]);
    }
    cr_assert_eq(dfl_rfunc_poly_ellipse(2.0, 0.5, &e, &err), DFL_OK);
    dfl_rfunc_poly_free(&e);
}
