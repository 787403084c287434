/* B-spline curves against independent formulas: the naive Cox-de Boor
 * recursion, Bernstein polynomials, finite differences and periodicity. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "geom/bspline_ref.h"
#include "geom/bspline.h"

static void naive_eval(const dfl_bspline *c, double t, double *out)
{
    for (int j = 0; j < c->dim; j++) out[j] = 0.0;
    for (size_t i = 0; i < c->n; i++) {
        double N = ref_cox_de_boor(c->knots, i, c->order, t);
        for (int j = 0; j < c->dim; j++) out[j] += N * c->cp[i * (size_t)c->dim + (size_t)j];
    }
}

static void random_cp(unsigned *seed, size_t n, int dim, double *cp)
{
    for (size_t i = 0; i < n * (size_t)dim; i++) cp[i] = 2.0 * dfl_rng_lcg(seed) - 1.0;
}

Test(bspline, matches_cox_de_boor_clamped_and_nonuniform)
{
    unsigned seed = 7;
    for (int order = 2; order <= 6; order++) {
        for (int dim = 1; dim <= 3; dim++) {
            size_t n = (size_t)order + 4;
            double cp[64 * 3], knots[64];
            random_cp(&seed, n, dim, cp);
            /* non-uniform clamped knots with one double interior knot */
            size_t nk = n + (size_t)order;
            for (size_t i = 0; i < nk; i++) knots[i] = 0.0;
            double v = 0.0;
            for (size_t i = (size_t)order; i < n; i++) {
                if (!(i == (size_t)order + 2 && order > 2)) v += 0.3 + dfl_rng_lcg(&seed);
                knots[i] = v;
            }
            v += 0.5;
            for (size_t i = n; i < nk; i++) knots[i] = v;
            dfl_bspline c;
            dfl_err err;
            cr_assert_eq(dfl_bspline_init(dim, order, n, cp, knots, nk, &c, &err), DFL_OK, "%s",
                         err.msg);
            for (int s = 0; s < 200; s++) {
                double t = c.t0 + (c.t1 - c.t0) * dfl_rng_lcg(&seed) * 0.999999;
                double a[3], b[3];
                dfl_bspline_eval(&c, t, 0, a);
                naive_eval(&c, t, b);
                for (int j = 0; j < dim; j++)
                    cr_assert(fabs(a[j] - b[j]) < 1e-13, "order %d t %g: %g vs %g", order, t, a[j],
                              b[j]);
            }
            /* clamped curves interpolate the end control points */
            double e0[3], e1[3];
            dfl_bspline_eval(&c, c.t0, 0, e0);
            dfl_bspline_eval(&c, c.t1, 0, e1);
            for (int j = 0; j < dim; j++) {
                cr_assert(fabs(e0[j] - cp[j]) < 1e-14);
                cr_assert(fabs(e1[j] - cp[(n - 1) * (size_t)dim + (size_t)j]) < 1e-14);
            }
            dfl_bspline_free(&c);
        }
    }
}

Test(bspline, unclamped_knots_match_cox_de_boor)
{
    unsigned seed = 11;
    const int order = 4, dim = 2;
    const size_t n = 7;
    double cp[14], knots[11];
    random_cp(&seed, n, dim, cp);
    for (int i = 0; i < 11; i++) knots[i] = 0.1 * i * i;
    dfl_bspline c;
    cr_assert_eq(dfl_bspline_init(dim, order, n, cp, knots, 11, &c, NULL), DFL_OK);
    cr_assert_float_eq(c.t0, knots[3], 0.0);
    cr_assert_float_eq(c.t1, knots[7], 0.0);
    for (int s = 0; s < 100; s++) {
        double t = c.t0 + (c.t1 - c.t0) * dfl_rng_lcg(&seed) * 0.999999;
        double a[2], b[2];
        dfl_bspline_eval(&c, t, 0, a);
        naive_eval(&c, t, b);
        cr_assert(fabs(a[0] - b[0]) < 1e-13 && fabs(a[1] - b[1]) < 1e-13);
    }
    dfl_bspline_free(&c);
}

Test(bspline, derivatives_match_finite_differences)
{
    unsigned seed = 3;
    for (int order = 2; order <= 7; order++) {
        const int dim = 3;
        size_t n = (size_t)order + 3;
        double cp[64 * 3];
        random_cp(&seed, n, dim, cp);
        dfl_bspline c;
        cr_assert_eq(dfl_bspline_init(dim, order, n, cp, NULL, 0, &c, NULL), DFL_OK);
        const double h = 1e-5;
        for (int s = 0; s < 50; s++) {
            double t = c.t0 + (c.t1 - c.t0) * dfl_rng_lcg(&seed);
            /* stay away from knots (integers for the clamped uniform vector) */
            if (fabs(t - round(t)) < 1e-3) continue;
            double d[5 * 3], dp[5 * 3], dm[5 * 3];
            dfl_bspline_eval(&c, t, 4, d);
            dfl_bspline_eval(&c, t + h, 4, dp);
            dfl_bspline_eval(&c, t - h, 4, dm);
            for (int r = 1; r <= 4; r++)
                for (int j = 0; j < dim; j++) {
                    double fd = (dp[(r - 1) * dim + j] - dm[(r - 1) * dim + j]) / (2 * h);
                    double scale = 1.0 + fabs(d[r * dim + j]) + fabs(d[(r - 1) * dim + j]);
                    if (r >= order) {
                        cr_assert_eq(d[r * dim + j], 0.0, "order %d r %d", order, r);
                        continue;
                    }
                    cr_assert(fabs(fd - d[r * dim + j]) < 1e-6 * scale * (r + 1) * order,
                              "order %d r %d: %g vs %g", order, r, d[r * dim + j], fd);
                }
        }
        dfl_bspline_free(&c);
    }
}

static double binom(int n, int k)
{
    double r = 1.0;
    for (int i = 1; i <= k; i++) r = r * (n - k + i) / i;
    return r;
}

Test(bspline, bezier_equals_clamped_bspline_and_bernstein)
{
    unsigned seed = 5;
    for (int np = 2; np <= 8; np++) {
        double cp[8 * 2];
        random_cp(&seed, (size_t)np, 2, cp);
        dfl_bspline b;
        cr_assert_eq(dfl_bspline_init_bezier(2, (size_t)np, cp, &b, NULL), DFL_OK);
        double knots[16];
        for (int i = 0; i < 2 * np; i++) knots[i] = i < np ? 0.0 : 1.0;
        dfl_bspline c;
        cr_assert_eq(dfl_bspline_init(2, np, (size_t)np, cp, knots, (size_t)(2 * np), &c, NULL),
                     DFL_OK);
        for (int s = 0; s <= 20; s++) {
            double t = s / 20.0, x[2], y[2], z[2] = {0, 0}, w[2];
            dfl_bspline_eval(&b, t, 0, x);
            dfl_bspline_eval(&c, t, 0, y);
            dfl_bezier_eval(cp, np, 2, t, w);
            int p = np - 1;
            for (int i = 0; i <= p; i++) {
                double B = binom(p, i) * pow(t, i) * pow(1 - t, p - i);
                z[0] += B * cp[2 * i];
                z[1] += B * cp[2 * i + 1];
            }
            for (int j = 0; j < 2; j++) {
                cr_assert(fabs(x[j] - z[j]) < 1e-14, "np %d t %g", np, t);
                cr_assert(fabs(y[j] - z[j]) < 1e-14);
                cr_assert(fabs(w[j] - z[j]) < 1e-14);
            }
        }
        dfl_bspline_free(&b);
        dfl_bspline_free(&c);
    }
}

Test(bspline, blossom_bezier_of_subinterval_reproduces_curve)
{
    unsigned seed = 9;
    const int order = 5, dim = 2;
    const size_t n = 9;
    double cp[18];
    random_cp(&seed, n, dim, cp);
    dfl_bspline c;
    cr_assert_eq(dfl_bspline_init(dim, order, n, cp, NULL, 0, &c, NULL), DFL_OK);
    size_t ns = dfl_bspline_span_count(&c);
    cr_assert_eq(ns, n - (size_t)order + 1);
    for (size_t s = 0; s < ns; s++) {
        size_t j = dfl_bspline_span_index(&c, s);
        double a = c.knots[j] + 0.2 * (c.knots[j + 1] - c.knots[j]);
        double b = c.knots[j] + 0.7 * (c.knots[j + 1] - c.knots[j]);
        double bez[5 * 2], L[10], R[10];
        dfl_bspline_span_bezier(&c, j, a, b, bez);
        dfl_bezier_split(bez, order, dim, 0.25, L, R);
        for (int q = 0; q <= 10; q++) {
            double sq = q / 10.0, x[2], y[2], z[2];
            dfl_bezier_eval(bez, order, dim, sq, x);
            dfl_bspline_eval(&c, a + sq * (b - a), 0, y);
            if (sq <= 0.25) dfl_bezier_eval(L, order, dim, sq / 0.25, z);
            else dfl_bezier_eval(R, order, dim, (sq - 0.25) / 0.75, z);
            for (int d = 0; d < dim; d++) {
                cr_assert(fabs(x[d] - y[d]) < 1e-13);
                cr_assert(fabs(z[d] - y[d]) < 1e-13);
            }
        }
    }
    dfl_bspline_free(&c);
}

Test(bspline, periodic_curve_is_periodic_and_smooth)
{
    unsigned seed = 13;
    for (int order = 2; order <= 6; order++) {
        const size_t m = 7;
        double cp[7 * 2], br[8];
        random_cp(&seed, m, 2, cp);
        br[0] = -1.0;
        for (size_t i = 1; i <= m; i++) br[i] = br[i - 1] + 0.5 + dfl_rng_lcg(&seed);
        dfl_bspline c;
        dfl_err err;
        cr_assert_eq(dfl_bspline_init_periodic(2, order, m, cp, br, m + 1, &c, &err), DFL_OK, "%s",
                     err.msg);
        cr_assert_eq(c.t0, br[0]);
        cr_assert_eq(c.t1, br[m]);
        double T = c.t1 - c.t0;
        for (int s = 0; s < 30; s++) {
            double t = c.t0 + T * dfl_rng_lcg(&seed), a[2], b[2], y[2];
            dfl_bspline_eval(&c, t, 0, a);
            dfl_bspline_eval(&c, t + 3 * T, 0, b);
            naive_eval(&c, t, y);
            for (int j = 0; j < 2; j++) {
                cr_assert(fabs(a[j] - b[j]) < 1e-12);
                cr_assert(fabs(a[j] - y[j]) < 1e-13);
            }
        }
        /* C^(p-1) across the seam: left and right derivatives agree */
        double L[8 * 2], R[8 * 2];
        dfl_bspline_eval_side(&c, c.t0, -1, order - 1, L);
        dfl_bspline_eval_side(&c, c.t0, +1, order - 1, R);
        for (int r = 0; r < order - 1; r++)
            for (int j = 0; j < 2; j++)
                cr_assert(fabs(L[r * 2 + j] - R[r * 2 + j]) < 1e-9 * (1 + fabs(R[r * 2 + j])),
                          "order %d r %d: %g vs %g", order, r, L[r * 2 + j], R[r * 2 + j]);
        cr_assert(dfl_bspline_is_closed(&c, 0.0));
        dfl_bspline_free(&c);
    }
}

Test(bspline, rejects_bad_input)
{
    double cp[] = {0, 0, 1, 0, 1, 1, 0, 1};
    double k_short[] = {0, 0, 0, 1, 1, 1, 1};
    double k_dec[] = {0, 0, 0, 0, 1, 0.5, 1, 1};
    double k_mult[] = {0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1}; /* order 3, 6 cp: interior mult 3 */
    double cp6[] = {0, 0, 1, 0, 1, 1, 0, 1, 2, 2, 3, 3};
    double same[] = {1, 1, 1, 1, 1, 1, 1, 1};
    dfl_bspline c;
    dfl_err err;
    cr_assert_eq(dfl_bspline_init(2, 4, 4, cp, k_short, 7, &c, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "expected 8"), "%s", err.msg);
    cr_assert_eq(dfl_bspline_init(2, 4, 4, cp, k_dec, 8, &c, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "non-decreasing"), "%s", err.msg);
    cr_assert_eq(dfl_bspline_init(2, 3, 6, cp6, k_mult, 9, &c, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "multiplicity"), "%s", err.msg);
    cr_assert_eq(dfl_bspline_init(2, 1, 4, cp, NULL, 0, &c, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "order"), "%s", err.msg);
    cr_assert_eq(dfl_bspline_init(2, 5, 4, cp, NULL, 0, &c, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_bspline_init(2, 4, 4, same, NULL, 0, &c, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "degenerate"), "%s", err.msg);
    double br_bad[] = {0, 1, 1, 1, 2}; /* order 3: mult 3 > 2 */
    cr_assert_eq(dfl_bspline_init_periodic(2, 3, 4, cp, br_bad, 5, &c, &err), DFL_E_INPUT);
    double br_zero[] = {0, 0, 0, 0, 0};
    cr_assert_eq(dfl_bspline_init_periodic(2, 2, 4, cp, br_zero, 5, &c, &err), DFL_E_INPUT);
}

/* dfl_bspline_is_closed(c, tol): the end points' gap (largest coordinate
 * difference) at most tol (1 + extent), the extent the largest side of the
 * control points' bounding box: relative for large curves.  Extent 1000,
 * tol 1e-12: a gap of 1e-10 is closed, 2e-9 (> 1.001e-9) is not. */
Test(bspline, closed_tolerance_is_relative_to_the_extent)
{
    const double gaps[2] = {1e-10, 2e-9};
    for (int i = 0; i < 2; i++) {
        const double cp[5 * 2] = {0, 0, 1000, 0, 1000, 1000, 0, 1000, gaps[i], 0};
        dfl_bspline c;
        cr_assert_eq(dfl_bspline_init(2, 4, 5, cp, NULL, 0, &c, NULL), DFL_OK);
        cr_expect_eq(dfl_bspline_is_closed(&c, 1e-12), i == 0, "gap %g", gaps[i]);
        dfl_bspline_free(&c);
    }
}

/* dfl_knot_span at a knot: side < 0 is the non-empty span to the left
 * (U[j] < t <= U[j+1]), side >= 0 the one to the right (U[j] <= t <
 * U[j+1]); a double knot is skipped (spans are non-empty), t0 has no left
 * span and t1 of an open curve is in the last span (header).  Order 4,
 * n = 8 control points: U = 0 0 0 0 1 2 2 3 4 4 4 4, the spans j = 3..7. */
Test(bspline, knot_span_sides_at_knots)
{
    const double U[12] = {0, 0, 0, 0, 1, 2, 2, 3, 4, 4, 4, 4};
    const struct {
        double t;
        size_t left, right;
    } cs[] = {{0.0, 3, 3}, {0.5, 3, 3}, {1.0, 3, 4}, {1.5, 4, 4}, {2.0, 4, 6},
              {2.5, 6, 6}, {3.0, 6, 7}, {4.0, 7, 7}, {-1.0, 3, 3}, {5.0, 7, 7}};
    for (size_t i = 0; i < sizeof cs / sizeof *cs; i++) {
        cr_expect_eq(dfl_knot_span(U, 4, 8, cs[i].t, -1), cs[i].left, "t %g left", cs[i].t);
        cr_expect_eq(dfl_knot_span(U, 4, 8, cs[i].t, 1), cs[i].right, "t %g right", cs[i].t);
    }
}

/* A closed curve's parameter wraps into [t0, t1) by whole periods
 * T = t1 - t0 (below t0 as well as above t1); an open one is clamped. */
Test(bspline, wrap_by_whole_periods_on_both_sides)
{
    double cp[6 * 2];
    for (int i = 0; i < 6; i++) {
        cp[2 * i] = cos(i * 1.047);
        cp[2 * i + 1] = sin(i * 1.047);
    }
    dfl_bspline c;
    cr_assert_eq(dfl_bspline_init_periodic(2, 4, 6, cp, NULL, 0, &c, NULL), DFL_OK);
    const double T = c.t1 - c.t0;
    for (int k = -3; k <= 3; k++)
        for (int i = 0; i < 8; i++) {
            const double t = c.t0 + T * (i + 0.5) / 8, w = dfl_bspline_wrap(&c, t + k * T);
            cr_expect(w >= c.t0 && w < c.t1, "k %d i %d: %g", k, i, w);
            cr_expect(fabs(w - t) <= 1e-13 * (1 + abs(k)) * T, "k %d i %d: %.17g vs %.17g", k, i,
                      w, t);
        }
    dfl_bspline_free(&c);
    cr_assert_eq(dfl_bspline_init(2, 4, 6, cp, NULL, 0, &c, NULL), DFL_OK);
    cr_expect_eq(dfl_bspline_wrap(&c, c.t0 - 0.25 * (c.t1 - c.t0)), c.t0);
    cr_expect_eq(dfl_bspline_wrap(&c, c.t1 + 0.25 * (c.t1 - c.t0)), c.t1);
    dfl_bspline_free(&c);
}
