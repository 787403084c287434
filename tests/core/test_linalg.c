/* core/linalg: LU against exact small systems (integer matrices whose
 * solutions are exact in double), residuals of random systems, pivoting,
 * singular input; the symmetric 2x2 eigen-decomposition against its
 * definition. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "core/linalg.h"
#include "core/rng.h"
#include "core/vec.h"

Test(linalg, lu_solves_an_exact_system)
{
    /* A x = b with x = (1, -2, 3, 0.5); A needs pivoting (A00 = 0) */
    const double A0[16] = {0, 2, 1, 4, 1, 1, 0, 2, 3, -1, 2, 0, 2, 0, 1, 3};
    const double x[4] = {1, -2, 3, 0.5};
    double A[16], b[4];
    memcpy(A, A0, sizeof A);
    for (int i = 0; i < 4; i++) {
        b[i] = 0;
        for (int j = 0; j < 4; j++) b[i] += A0[4 * i + j] * x[j];
    }
    int piv[4];
    cr_assert_eq(dfl_lu_factor(4, A, piv, 1e-13, NULL), DFL_OK);
    cr_assert_neq(piv[0], 0); /* the zero pivot was swapped away */
    dfl_lu_solve(4, A, piv, b);
    for (int i = 0; i < 4; i++) cr_assert(fabs(b[i] - x[i]) < 1e-14, "x%d = %.17g", i, b[i]);
}

Test(linalg, lu_residuals_of_random_systems)
{
    uint64_t s = 42;
    for (int n = 1; n <= 6; n++)
        for (int it = 0; it < 50; it++) {
            double A0[36], A[36], b[6], x[6];
            for (int i = 0; i < n * n; i++) A0[i] = dfl_rng_splitmix(&s, -1, 1);
            for (int i = 0; i < n; i++) A0[n * i + i] += 2.0; /* well conditioned */
            for (int i = 0; i < n; i++) b[i] = x[i] = dfl_rng_splitmix(&s, -1, 1);
            memcpy(A, A0, sizeof A);
            int piv[6];
            cr_assert_eq(dfl_lu_factor(n, A, piv, 1e-13, NULL), DFL_OK);
            dfl_lu_solve(n, A, piv, x);
            for (int i = 0; i < n; i++) {
                double r = -b[i];
                for (int j = 0; j < n; j++) r += A0[n * i + j] * x[j];
                cr_assert(fabs(r) < 1e-14, "n %d it %d row %d: residual %g", n, it, i, r);
            }
        }
}

Test(linalg, lu_rejects_singular_matrices)
{
    double Z[4] = {0, 0, 0, 0}, S[9] = {1, 2, 3, 2, 4, 6, 1, 0, 1}, N[4] = {NAN, 1, 1, 1};
    int piv[3];
    dfl_err err;
    cr_assert_eq(dfl_lu_factor(2, Z, piv, 1e-13, &err), DFL_E_NUMERIC);
    cr_assert(strstr(err.msg, "singular"), "%s", err.msg);
    cr_assert_eq(dfl_lu_factor(3, S, piv, 1e-13, &err), DFL_E_NUMERIC);
    cr_assert_eq(dfl_lu_factor(2, N, piv, 1e-13, NULL), DFL_E_NUMERIC);
    /* a tiny but regular pivot passes a tolerance of 0 */
    double T[4] = {1, 0, 0, 1e-300};
    cr_assert_eq(dfl_lu_factor(2, T, piv, 0.0, NULL), DFL_OK);
    cr_assert_eq(dfl_lu_factor(2, (double[]){1, 0, 0, 1e-300}, piv, 1e-13, NULL), DFL_E_NUMERIC);
}

Test(linalg, sym2_eigen_is_a_decomposition)
{
    uint64_t s = 7;
    for (int it = 0; it < 200; it++) {
        double a = dfl_rng_splitmix(&s, -3, 3), b = dfl_rng_splitmix(&s, -3, 3);
        double c = it % 10 == 0 ? a : dfl_rng_splitmix(&s, -3, 3);
        if (it % 20 == 0) b = 0;
        double lo, hi, th;
        dfl_sym2_eigen(a, b, c, &lo, &hi, &th);
        cr_assert(lo <= hi);
        cr_assert(fabs(th) <= 0.5 * DFL_PI + 1e-15);
        const double v[2][2] = {{cos(th), sin(th)}, {-sin(th), cos(th)}}, lam[2] = {hi, lo};
        for (int k = 0; k < 2; k++) {
            /* M v = lambda v */
            double r0 = a * v[k][0] + b * v[k][1] - lam[k] * v[k][0];
            double r1 = b * v[k][0] + c * v[k][1] - lam[k] * v[k][1];
            cr_assert(hypot(r0, r1) < 1e-14 * (1 + fabs(a) + fabs(b) + fabs(c)), "it %d k %d", it, k);
        }
        cr_assert(fabs(lo + hi - (a + c)) < 1e-14 * (1 + fabs(a) + fabs(c)));
    }
    /* closed form: [[2, 1], [1, 2]] has eigenvalues 1 and 3, th = pi/4 */
    double lo, hi, th;
    dfl_sym2_eigen(2, 1, 2, &lo, &hi, &th);
    cr_assert_float_eq(lo, 1.0, 1e-15);
    cr_assert_float_eq(hi, 3.0, 1e-15);
    cr_assert_float_eq(th, 0.25 * DFL_PI, 1e-15);
}

/* A pivot is accepted only if |pivot| > tol * max |A_ij| (linalg.h): the
 * test is relative to the matrix, so a well-conditioned matrix scaled by
 * 1e-20 factors with tol = 1e-13, and it is strict, so a pivot exactly at
 * tol * max (and a zero pivot with tol = 0) is refused. */
Test(linalg, pivot_tolerance_is_relative_and_strict)
{
    int piv[2];
    double A[4] = {1e-20, 0, 0, 2e-20}, b[2] = {1e-20, 4e-20};
    cr_assert_eq(dfl_lu_factor(2, A, piv, 1e-13, NULL), DFL_OK);
    dfl_lu_solve(2, A, piv, b);
    cr_assert(b[0] == 1.0 && b[1] == 2.0, "x = %.17g %.17g", b[0], b[1]);
    /* max |A_ij| = 1, pivot 0.5: refused at tol 0.5, accepted just below */
    cr_assert_eq(dfl_lu_factor(2, (double[]){1, 0, 0, 0.5}, piv, 0.5, NULL), DFL_E_NUMERIC);
    cr_assert_eq(dfl_lu_factor(2, (double[]){1, 0, 0, 0.5}, piv, 0.25, NULL), DFL_OK);
    /* max |A_ij| = 4: pivot 1 is exactly 0.25 * 4 */
    cr_assert_eq(dfl_lu_factor(2, (double[]){4, 0, 0, 1}, piv, 0.25, NULL), DFL_E_NUMERIC);
    cr_assert_eq(dfl_lu_factor(2, (double[]){1, 0, 0, 0}, piv, 0.0, NULL), DFL_E_NUMERIC);
}

/* Partial pivoting: step k swaps in the row i >= k with the largest |A_ik|,
 * and piv[k] names it.  Column 0 of A is (1, 3, -7): piv[0] = 2.  After the
 * swap and elimination, column 1 below the diagonal holds 1 (row 1, from
 * 1 - (3/-7) 0) and 2 (row 2, the old row 0: 2 - (1/-7) 0): piv[1] = 2. */
Test(linalg, partial_pivoting_takes_the_largest)
{
    double A[9] = {1, 2, 0, 3, 1, 1, -7, 0, 2};
    int piv[3];
    cr_assert_eq(dfl_lu_factor(3, A, piv, 1e-13, NULL), DFL_OK);
    cr_assert_eq(piv[0], 2);
    cr_assert_eq(piv[1], 2);
    cr_assert_eq(piv[2], 2);
    cr_assert_eq(A[0], -7.0); /* U's first row is the old row 2 */
}
