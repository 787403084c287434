/* Tensor-product surfaces against the naive Cox-de Boor double sum,
 * Bernstein polynomials, finite differences, and join classification on
 * patches built to be G1, C0 only, or apart. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "core/rng.h"
#include "geom/bspline_ref.h"
#include "geom/surface.h"

static void make_patch(unsigned *seed, int ku, int kv, size_t nu, size_t nv, dfl_surface *s)
{
    double cp[20 * 20 * 3];
    for (size_t j = 0; j < nv; j++)
        for (size_t i = 0; i < nu; i++) {
            double *P = cp + (i + nu * j) * 3;
            P[0] = (double)i + 0.3 * dfl_rng_lcg(seed);
            P[1] = (double)j + 0.3 * dfl_rng_lcg(seed);
            P[2] = dfl_rng_lcg(seed) - 0.5;
        }
    dfl_err err;
    cr_assert_eq(dfl_surface_init(ku, kv, nu, nv, cp, NULL, 0, NULL, 0, s, &err), DFL_OK, "%s",
                 err.msg);
}

Test(surface, matches_naive_double_sum)
{
    unsigned seed = 1;
    dfl_surface s;
    make_patch(&seed, 4, 3, 6, 5, &s);
    for (int q = 0; q < 100; q++) {
        double u = s.u0 + (s.u1 - s.u0) * dfl_rng_lcg(&seed) * 0.99999;
        double v = s.v0 + (s.v1 - s.v0) * dfl_rng_lcg(&seed) * 0.99999;
        double d[3], r[3] = {0, 0, 0};
        dfl_surface_eval(&s, u, v, 0, d);
        for (size_t j = 0; j < s.nv; j++)
            for (size_t i = 0; i < s.nu; i++) {
                double w = ref_cox_de_boor(s.knots_u, i, s.ku, u) * ref_cox_de_boor(s.knots_v, j, s.kv, v);
                for (int c = 0; c < 3; c++) r[c] += w * s.cp[(i + s.nu * j) * 3 + (size_t)c];
            }
        for (int c = 0; c < 3; c++) cr_assert(fabs(d[c] - r[c]) < 1e-13);
    }
    dfl_surface_free(&s);
}

Test(surface, derivatives_match_finite_differences)
{
    unsigned seed = 2;
    dfl_surface s;
    make_patch(&seed, 4, 5, 7, 6, &s);
    const double h = 1e-5;
    for (int q = 0; q < 40; q++) {
        double u = s.u0 + (s.u1 - s.u0) * dfl_rng_lcg(&seed);
        double v = s.v0 + (s.v1 - s.v0) * dfl_rng_lcg(&seed);
        if (fabs(u - round(u)) < 1e-3 || fabs(v - round(v)) < 1e-3) continue;
        double d[30], pu[30], mu[30], pv[30], mv[30];
        dfl_surface_eval(&s, u, v, 3, d);
        dfl_surface_eval(&s, u + h, v, 3, pu);
        dfl_surface_eval(&s, u - h, v, 3, mu);
        dfl_surface_eval(&s, u, v + h, 3, pv);
        dfl_surface_eval(&s, u, v - h, 3, mv);
        for (int tot = 1; tot <= 3; tot++)
            for (int b = 0; b <= tot; b++) {
                int a = tot - b;
                /* differentiate a lower derivative along u (if a > 0) or v */
                int lo = a > 0 ? DFL_SURF_IDX(a - 1, b) : DFL_SURF_IDX(a, b - 1);
                const double *P = a > 0 ? pu : pv, *M = a > 0 ? mu : mv;
                for (int c = 0; c < 3; c++) {
                    double fd = (P[lo * 3 + c] - M[lo * 3 + c]) / (2 * h);
                    double ex = d[DFL_SURF_IDX(a, b) * 3 + c];
                    cr_assert(fabs(fd - ex) < 1e-5 * (1 + fabs(ex)), "(%d,%d): %g vs %g", a, b,
                              ex, fd);
                }
            }
    }
    dfl_surface_free(&s);
}

static double bern(int n, int i, double t)
{
    double c = 1.0;
    for (int k = 1; k <= i; k++) c = c * (n - i + k) / k;
    return c * pow(t, i) * pow(1 - t, n - i);
}

Test(surface, bezier_patch_is_bernstein_and_cells_reproduce)
{
    unsigned seed = 3;
    const int ku = 4, kv = 3;
    double cp[12 * 3];
    for (int i = 0; i < 36; i++) cp[i] = dfl_rng_lcg(&seed);
    dfl_surface s;
    cr_assert_eq(dfl_surface_init_bezier(ku, kv, cp, &s, NULL), DFL_OK);
    double bez[12 * 3];
    dfl_surface_cell_bezier(&s, (size_t)ku - 1, (size_t)kv - 1, 0.2, 0.6, 0.1, 0.9, bez);
    for (int q = 0; q < 50; q++) {
        double u = dfl_rng_lcg(&seed), v = dfl_rng_lcg(&seed), d[3], r[3] = {0, 0, 0};
        dfl_surface_eval(&s, u, v, 0, d);
        for (int j = 0; j < kv; j++)
            for (int i = 0; i < ku; i++)
                for (int c = 0; c < 3; c++)
                    r[c] += bern(ku - 1, i, u) * bern(kv - 1, j, v) * cp[(i + ku * j) * 3 + c];
        for (int c = 0; c < 3; c++) cr_assert(fabs(d[c] - r[c]) < 1e-14);
        /* the cell's Bezier net evaluated at local (a, b) */
        double a = dfl_rng_lcg(&seed), b = dfl_rng_lcg(&seed), e[3] = {0, 0, 0}, f[3];
        for (int j = 0; j < kv; j++)
            for (int i = 0; i < ku; i++)
                for (int c = 0; c < 3; c++)
                    e[c] += bern(ku - 1, i, a) * bern(kv - 1, j, b) * bez[(i + ku * j) * 3 + c];
        dfl_surface_eval(&s, 0.2 + 0.4 * a, 0.1 + 0.8 * b, 0, f);
        for (int c = 0; c < 3; c++) cr_assert(fabs(e[c] - f[c]) < 1e-14);
    }
    dfl_surface_free(&s);
}

/* Two bicubic Bezier patches over [0,1]x[0,1] and [1,2]x[0,1] in the plane
 * z = h(x, y); the second patch's first control column is the first's last
 * column; G1 when the columns next to the seam are collinear with it. */
static void two_patches(double kink, int reverse_b, dfl_surface *a, dfl_surface *b)
{
    double ca[48], cb[48];
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            double x = i / 3.0, y = j / 3.0;
            double *P = ca + (i + 4 * j) * 3;
            P[0] = x;
            P[1] = y;
            P[2] = 0.3 * x * (1 - y) + 0.1 * y * y; /* linear in x near the seam */
            double *Q = cb + ((reverse_b ? 3 - i : i) + 4 * (reverse_b ? 3 - j : j)) * 3;
            Q[0] = 1.0 + x;
            Q[1] = y;
            /* slope along x continues 0.3 (1 - y) for G1; kink changes it */
            Q[2] = 0.3 * (1 - y) + (0.3 * (1 - y) + kink) * x + 0.1 * y * y;
        }
    cr_assert_eq(dfl_surface_init_bezier(4, 4, ca, a, NULL), DFL_OK);
    cr_assert_eq(dfl_surface_init_bezier(4, 4, cb, b, NULL), DFL_OK);
}

Test(surface, join_classification)
{
    dfl_surface a, b;
    int rev = -1;
    two_patches(0.0, 0, &a, &b);
    cr_assert_eq(dfl_surface_join(&a, 1, &b, 3, 1e-12, 1e-9, 9, &rev), DFL_JOIN_G1);
    cr_assert_eq(rev, 0);
    cr_assert_eq(dfl_surface_join(&a, 0, &b, 3, 1e-12, 1e-9, 9, &rev), DFL_JOIN_NONE);
    dfl_surface_free(&a);
    dfl_surface_free(&b);

    two_patches(0.0, 1, &a, &b); /* b's parameters run backwards: seam is b's edge 1 */
    cr_assert_eq(dfl_surface_join(&a, 1, &b, 1, 1e-12, 1e-9, 9, &rev), DFL_JOIN_G1);
    cr_assert_eq(rev, 1);
    dfl_surface_free(&a);
    dfl_surface_free(&b);

    two_patches(0.5, 0, &a, &b);
    cr_assert_eq(dfl_surface_join(&a, 1, &b, 3, 1e-12, 1e-9, 9, &rev), DFL_JOIN_C0);
    dfl_surface arr[2] = {a, b};
    dfl_surface_set set;
    cr_assert_eq(dfl_surface_set_init(2, arr, &set, NULL), DFL_OK);
    size_t nshared, iso;
    cr_assert_eq(dfl_surface_set_joins(&set, 1e-12, 1e-9, &nshared, &iso), DFL_JOIN_C0);
    cr_assert_eq(nshared, 1);
    cr_assert_eq(iso, 2);
    dfl_surface_set_free(&set);
}

Test(surface, rejects_bad_input)
{
    double cp[16 * 3];
    for (int i = 0; i < 48; i++) cp[i] = 1.0;
    dfl_surface s;
    dfl_err err;
    cr_assert_eq(dfl_surface_init_bezier(4, 4, cp, &s, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "degenerate"), "%s", err.msg);
    cp[0] = 0.0;
    cr_assert_eq(dfl_surface_init(4, 4, 3, 4, cp, NULL, 0, NULL, 0, &s, &err), DFL_E_INPUT);
    double U[] = {0, 0, 0, 0, 1, 1, 1}; /* 7 knots for 4 + 4 */
    cr_assert_eq(dfl_surface_init(4, 4, 4, 4, cp, U, 7, NULL, 0, &s, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "u knots"), "%s", err.msg);
    cr_assert_eq(dfl_surface_init(1, 4, 4, 4, cp, NULL, 0, NULL, 0, &s, &err), DFL_E_INPUT);
}
