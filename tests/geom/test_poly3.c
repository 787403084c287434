/* geom/poly3: building (merging, zero terms, table overflow), products and
 * derivatives against polynomials expanded by hand, evaluation and its
 * partials against the direct formula and finite differences, and the
 * series evaluation against the Taylor coefficients of the partials. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "core/rng.h"
#include "geom/poly3.h"

/* g = 2 u^2 v - w^3 + 0.5 u v w + 3 */
static void make_g(dfl_poly3 *P)
{
    memset(P, 0, sizeof *P);
    cr_assert(dfl_poly3_term(P, 2, 2, 1, 0));
    cr_assert(dfl_poly3_term(P, -1, 0, 0, 3));
    cr_assert(dfl_poly3_term(P, 0.5, 1, 1, 1));
    cr_assert(dfl_poly3_term(P, 3, 0, 0, 0));
}

static double g_direct(const double q[3])
{
    return 2 * q[0] * q[0] * q[1] - q[2] * q[2] * q[2] + 0.5 * q[0] * q[1] * q[2] + 3;
}

Test(poly3, building_merges_and_overflows)
{
    dfl_poly3 P;
    make_g(&P);
    cr_assert_eq(P.n, 4);
    cr_assert_eq(P.deg, 3);
    cr_assert(dfl_poly3_term(&P, 1, 2, 1, 0)); /* merges: 3 u^2 v */
    cr_assert(dfl_poly3_term(&P, 0, 5, 5, 0)); /* zero: not stored */
    cr_assert_eq(P.n, 4);
    cr_assert_eq(P.c[0], 3.0);
    dfl_poly3 F;
    memset(&F, 0, sizeof F);
    int ok = 1;
    for (int k = 0; k <= DFL_POLY3_MAX_TERMS && ok; k++)
        ok = dfl_poly3_term(&F, 1, k % 5, (k / 5) % 5, k / 25); /* distinct, degree <= 11 */
    cr_assert(!ok, "the table must overflow");
    cr_assert_eq(F.n, DFL_POLY3_MAX_TERMS);
    dfl_poly3 E;
    memset(&E, 0, sizeof E);
    cr_assert(!dfl_poly3_term(&E, 1, DFL_POLY3_MAX_DEGREE + 1, 0, 0), "degree too high");
    cr_assert_eq(E.n, 0);
}

Test(poly3, products_axpy_and_derivatives)
{
    /* (u + v)(u - v) = u^2 - v^2 */
    dfl_poly3 A, B, C;
    memset(&A, 0, sizeof A);
    memset(&B, 0, sizeof B);
    dfl_poly3_term(&A, 1, 1, 0, 0);
    dfl_poly3_term(&A, 1, 0, 1, 0);
    dfl_poly3_term(&B, 1, 1, 0, 0);
    dfl_poly3_term(&B, -1, 0, 1, 0);
    cr_assert(dfl_poly3_mul(&A, &B, &C));
    const double q[3] = {0.7, -0.4, 1.3};
    cr_assert_eq(C.n, 3); /* the u v terms cancel to 0 but stay merged in one term */
    cr_assert_float_eq(dfl_poly3_eval(&C, q, 0, NULL, NULL, NULL), 0.49 - 0.16, 1e-15);
    cr_assert(dfl_poly3_axpy(2.0, &A, &C)); /* + 2u + 2v */
    cr_assert_float_eq(dfl_poly3_eval(&C, q, 0, NULL, NULL, NULL), 0.33 + 0.6, 1e-15);
    dfl_poly3 G, D;
    make_g(&G);
    dfl_poly3_deriv(&G, 0, &D); /* 4 u v + 0.5 v w */
    cr_assert_float_eq(dfl_poly3_eval(&D, q, 0, NULL, NULL, NULL),
                       4 * q[0] * q[1] + 0.5 * q[1] * q[2], 1e-15);
    dfl_poly3_deriv(&G, 2, &D); /* -3 w^2 + 0.5 u v */
    cr_assert_float_eq(dfl_poly3_eval(&D, q, 0, NULL, NULL, NULL),
                       -3 * q[2] * q[2] + 0.5 * q[0] * q[1], 1e-15);
}

Test(poly3, partials_match_finite_differences)
{
    dfl_poly3 P;
    make_g(&P);
    uint64_t s = 5;
    for (int it = 0; it < 30; it++) {
        double q[3], gr[3], H[9], T[27];
        for (int j = 0; j < 3; j++) q[j] = dfl_rng_splitmix(&s, -1.5, 1.5);
        double g = dfl_poly3_eval(&P, q, 3, gr, H, T);
        cr_assert(fabs(g - g_direct(q)) < 1e-14);
        const double h = 1e-5;
        for (int a = 0; a < 3; a++) {
            double qp[3] = {q[0], q[1], q[2]}, qm[3] = {q[0], q[1], q[2]};
            qp[a] += h;
            qm[a] -= h;
            double gp[3], gm[3], Hp[9], Hm[9];
            double fd = (dfl_poly3_eval(&P, qp, 2, gp, Hp, NULL) - dfl_poly3_eval(&P, qm, 2, gm, Hm, NULL)) / (2 * h);
            cr_assert(fabs(fd - gr[a]) < 1e-8, "d/dq%d", a);
            for (int i = 0; i < 3; i++) {
                cr_assert(fabs((gp[i] - gm[i]) / (2 * h) - H[3 * i + a]) < 1e-8);
                for (int j = 0; j < 3; j++)
                    cr_assert(fabs((Hp[3 * i + j] - Hm[3 * i + j]) / (2 * h) - T[9 * i + 3 * j + a]) <
                              1e-8);
            }
        }
    }
}

Test(poly3, series_evaluation_is_the_taylor_expansion)
{
    dfl_poly3 P;
    make_g(&P);
    const double q[3] = {0.3, -0.8, 0.6}, d[3] = {0.5, 0.25, -1.0};
    dfl_series X[3], out;
    for (int a = 0; a < 3; a++) {
        dfl_series_zero(&X[a]);
        X[a].c[0] = q[a];
        X[a].c[1] = d[a];
    }
    dfl_poly3_eval_series(&P, X, 5, &out);
    double gr[3], H[9], T[27];
    double g = dfl_poly3_eval(&P, q, 3, gr, H, T);
    double d1 = 0, d2 = 0, d3 = 0;
    for (int i = 0; i < 3; i++) {
        d1 += gr[i] * d[i];
        for (int j = 0; j < 3; j++) {
            d2 += H[3 * i + j] * d[i] * d[j];
            for (int k = 0; k < 3; k++) d3 += T[9 * i + 3 * j + k] * d[i] * d[j] * d[k];
        }
    }
    cr_assert(fabs(out.c[0] - g) < 1e-15);
    cr_assert(fabs(out.c[1] - d1) < 1e-14);
    cr_assert(fabs(out.c[2] - d2 / 2) < 1e-14);
    cr_assert(fabs(out.c[3] - d3 / 6) < 1e-14);
    /* degree 3: nothing beyond */
    cr_assert(fabs(out.c[4]) < 1e-15 && fabs(out.c[5]) < 1e-15);
}

/* Orders 0, 1 and 2 (their own written-out loop) give the value, gradient
 * and Hessian bit for bit as order 3 (the general loop) does, for random
 * polynomials up to the largest degree and points with zero, negative zero,
 * subnormal, huge (overflowing powers), infinite and NaN coordinates; a NaN
 * where order 3 has a NaN (C leaves a NaN's sign and payload to the
 * compiler's choice of operand order). */
static int same(const double *a, const double *b, int n)
{
    for (int i = 0; i < n; i++)
        if (!(isnan(a[i]) && isnan(b[i])) && memcmp(a + i, b + i, sizeof *a) != 0) return 0;
    return 1;
}

Test(poly3, low_orders_equal_the_general_loop_bit_for_bit)
{
    const double special[] = {0.0, -0.0, 1.0, -1.0, 0x1p-1060, 1e30, -1e200, INFINITY,
                              -INFINITY, NAN, 0.7, -2.5};
    const int ns = (int)(sizeof special / sizeof special[0]);
    uint64_t s = 19;
    for (int it = 0; it < 400; it++) {
        dfl_poly3 P;
        memset(&P, 0, sizeof P);
        int nt = 1 + (int)dfl_rng_splitmix(&s, 0, 40);
        for (int t = 0; t < nt; t++) {
            int e[3], left = DFL_POLY3_MAX_DEGREE;
            for (int a = 0; a < 3; a++) {
                e[a] = (int)dfl_rng_splitmix(&s, 0, left + 0.999);
                left -= e[a];
            }
            double c = dfl_rng_splitmix(&s, -3, 3);
            if (t % 7 == 3) c *= 1e300;
            cr_assert(dfl_poly3_term(&P, c, e[0], e[1], e[2]));
        }
        for (int k = 0; k < 20; k++) {
            double q[3];
            for (int a = 0; a < 3; a++)
                q[a] = dfl_rng_splitmix(&s, 0, 1) < 0.3
                           ? special[(int)dfl_rng_splitmix(&s, 0, ns - 0.001)]
                           : dfl_rng_splitmix(&s, -1.6, 1.6);
            double g3, gr3[3], H3[9], T3[27];
            g3 = dfl_poly3_eval(&P, q, 3, gr3, H3, T3);
            for (int order = 0; order <= 2; order++) {
                double gr[3] = {7, 7, 7}, H[9] = {7, 7, 7, 7, 7, 7, 7, 7, 7};
                double g = dfl_poly3_eval(&P, q, order, gr, H, NULL);
                cr_assert(same(&g, &g3, 1), "order %d value at (%g %g %g)", order,
                          q[0], q[1], q[2]);
                if (order >= 1)
                    cr_assert(same(gr, gr3, 3), "order %d gradient at (%g %g %g)", order, q[0],
                              q[1], q[2]);
                else
                    cr_assert(gr[0] == 7 && gr[1] == 7 && gr[2] == 7, "order 0 writes no gradient");
                if (order >= 2)
                    cr_assert(same(H, H3, 9), "order %d Hessian at (%g %g %g)",
                              order, q[0], q[1], q[2]);
                else
                    for (int i = 0; i < 9; i++) cr_assert(H[i] == 7, "order %d writes no Hessian", order);
            }
        }
    }
}
