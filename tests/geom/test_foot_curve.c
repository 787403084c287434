/* Curve footpoints (foot_curve.c) against brute force, Newton against
 * Ceres on hard cases (medial axis, centre of curvature, far away), open
 * curve ends. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/curve_fixtures.h"
#include "geom/footpoint.h"

static void check_vs_brute(dfl_bspline *c, unsigned seed, int npts, double lo, double hi)
{
    dfl_curve_locator *L;
    dfl_err err;
    cr_assert_eq(dfl_curve_locator_new(c, NULL, &L, &err), DFL_OK, "%s", err.msg);
    for (int q = 0; q < npts; q++) {
        double x[3];
        for (int j = 0; j < c->dim; j++) x[j] = lo + (hi - lo) * dfl_rng_lcg(&seed);
        dfl_curve_foot f;
        cr_assert_eq(dfl_curve_footpoint(L, x, &f, &err), DFL_OK);
        double bf = cf_brute_curve(c, x, NULL);
        /* brute force is an upper bound of the minimum; Newton must not be
         * worse, and both agree to rounding + golden-section accuracy */
        cr_assert(f.dist <= bf + 1e-12, "newton %.17g > brute %.17g", f.dist, bf);
        cr_assert(bf - f.dist < 1e-10, "newton %.17g brute %.17g at (%g %g)", f.dist, bf, x[0],
                  x[1]);
        double p[3];
        dfl_bspline_eval(c, f.t, 0, p);
        for (int j = 0; j < c->dim; j++) cr_assert(fabs(p[j] - f.p[j]) < 1e-15);
    }
    dfl_curve_locator_free(L);
}

Test(foot_curve, curve_matches_brute_force)
{
    dfl_bspline c;
    cf_make_S(&c);
    check_vs_brute(&c, 1, 40, -0.5, 1.5);
    dfl_bspline_free(&c);
    cf_make_blob(&c);
    check_vs_brute(&c, 2, 40, -3.0, 3.0);
    dfl_bspline_free(&c);
    cf_make_space(&c);
    check_vs_brute(&c, 3, 40, -0.5, 1.5);
    dfl_bspline_free(&c);
}

/* Newton and Ceres agree on hard cases */
static void agree(const dfl_curve_locator *A, const dfl_curve_locator *B, const double *x,
                  int dim, int expect_flags)
{
    dfl_curve_foot fa, fb;
    dfl_err err;
    cr_assert_eq(dfl_curve_footpoint(A, x, &fa, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_curve_footpoint(B, x, &fb, &err), DFL_OK, "%s", err.msg);
    cr_assert(fabs(fa.dist - fb.dist) <= 1e-10, "newton %.17g ceres %.17g at (%g %g)", fa.dist,
              fb.dist, x[0], x[1]);
    if (expect_flags) {
        cr_assert(fa.flags & expect_flags, "flags %d at (%g, %g)", fa.flags, x[0], x[1]);
        cr_assert(fb.flags & expect_flags);
    }
    /* the footpoints coincide unless the position is ill-conditioned
     * (medial / focal); then both are on the same circle of radius dist */
    if (!((fa.flags | fb.flags) & (DFL_FOOT_MEDIAL | DFL_FOOT_FOCAL))) {
        double e = 0;
        for (int j = 0; j < dim; j++) e += (fa.p[j] - fb.p[j]) * (fa.p[j] - fb.p[j]);
        cr_assert(sqrt(e) < 1e-9, "footpoints differ by %g", sqrt(e));
    }
}

Test(foot_curve, newton_and_ceres_agree_on_hard_cases)
{
    dfl_bspline c;
    cf_make_blob(&c);
    dfl_foot_opts on, oc;
    dfl_foot_opts_default(&on);
    dfl_foot_opts_default(&oc);
    oc.backend = DFL_FOOT_CERES;
    dfl_curve_locator *A, *B;
    dfl_err err;
    cr_assert_eq(dfl_curve_locator_new(&c, &on, &A, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_curve_locator_new(&c, &oc, &B, &err), DFL_OK, "%s", err.msg);
    /* on the medial axis (the x axis inside) and next to it */
    for (int k = -5; k <= 5; k++) {
        double x[2] = {0.2 * k, 0.0};
        agree(A, B, x, 2, DFL_FOOT_MEDIAL);
        double y[2] = {0.2 * k, 1e-7};
        agree(A, B, y, 2, 0);
    }
    /* deterministic choice on the medial axis: the smaller parameter */
    {
        double x[2] = {0.3, 0.0};
        dfl_curve_foot f[4];
        int n = dfl_curve_footpoints(A, x, f, 4, &err);
        cr_assert(n >= 2);
        cr_assert(f[0].flags & DFL_FOOT_MEDIAL);
        cr_assert(f[0].t < f[1].t);
        cr_assert(fabs(f[0].p[1] + f[1].p[1]) < 1e-9, "mirror footpoints");
    }
    /* at and near the centre of curvature of the vertex of maximal
     * curvature, found by a dense scan + golden section on kappa(t): there
     * the distance has a degenerate (quartic) minimum.  kappa =
     * (C' x C'') / |C'|^3 is geom/curvature.h's curvature for the right
     * normal, the outward one of this counter-clockwise curve (> 0 here) */
    {
        double best = 0, tb = 0;
        for (int q = 0; q < 8000; q++) {
            double t = 8.0 * q / 8000, D[3 * 2];
            dfl_bspline_eval(&c, t, 2, D);
            double v = hypot(D[2], D[3]), k = (D[2] * D[5] - D[3] * D[4]) / (v * v * v);
            if (k > best) {
                best = k;
                tb = t;
            }
        }
        double lo = tb - 1e-3, hi = tb + 1e-3;
        for (int it = 0; it < 100; it++) {
            double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3, k1, k2, D[6];
            dfl_bspline_eval(&c, m1, 2, D);
            k1 = (D[2] * D[5] - D[3] * D[4]) / pow(hypot(D[2], D[3]), 3);
            dfl_bspline_eval(&c, m2, 2, D);
            k2 = (D[2] * D[5] - D[3] * D[4]) / pow(hypot(D[2], D[3]), 3);
            if (k1 > k2) hi = m2;
            else lo = m1;
        }
        double D[6];
        dfl_bspline_eval(&c, 0.5 * (lo + hi), 2, D);
        double v = hypot(D[2], D[3]);
        double k = (D[2] * D[5] - D[3] * D[4]) / (v * v * v), rho = 1.0 / k;
        /* inward (left) normal of the counter-clockwise curve */
        double cx[2] = {D[0] - rho * D[3] / v, D[1] + rho * D[2] / v};
        agree(A, B, cx, 2, DFL_FOOT_FOCAL);
        dfl_curve_foot f;
        dfl_curve_footpoint(A, cx, &f, &err);
        cr_assert(fabs(f.dist - rho) < 1e-9, "focal distance %.17g vs radius %.17g", f.dist, rho);
        cr_assert(!(f.flags & DFL_FOOT_MEDIAL));
        for (int q = 1; q <= 4; q++) {
            double y[2] = {cx[0] + q * 1e-4, cx[1] - q * 3e-5};
            agree(A, B, y, 2, 0);
        }
    }
    /* far away */
    unsigned seed = 5;
    for (int q = 0; q < 20; q++) {
        double a = 6.283185307179586 * dfl_rng_lcg(&seed), x[2] = {300 * cos(a), 300 * sin(a)};
        agree(A, B, x, 2, 0);
    }
    /* random points */
    for (int q = 0; q < 40; q++) {
        double x[2] = {-3 + 6 * dfl_rng_lcg(&seed), -2 + 4 * dfl_rng_lcg(&seed)};
        agree(A, B, x, 2, 0);
    }
    dfl_curve_locator_free(A);
    dfl_curve_locator_free(B);
    dfl_bspline_free(&c);
}

Test(foot_curve, open_curve_ends_and_ceres)
{
    dfl_bspline c;
    cf_make_S(&c);
    dfl_foot_opts oc;
    dfl_foot_opts_default(&oc);
    oc.backend = DFL_FOOT_CERES;
    dfl_curve_locator *A, *B;
    cr_assert_eq(dfl_curve_locator_new(&c, NULL, &A, NULL), DFL_OK);
    cr_assert_eq(dfl_curve_locator_new(&c, &oc, &B, NULL), DFL_OK);
    /* beyond the ends: footpoint is the end point */
    double x[2] = {1.2, 0.9}, y[2] = {0.0, 0.1};
    agree(A, B, x, 2, DFL_FOOT_END);
    agree(A, B, y, 2, DFL_FOOT_END);
    dfl_curve_foot f;
    dfl_curve_footpoint(A, x, &f, NULL);
    cr_assert_eq(f.t, c.t0);
    cr_assert(fabs(f.dist - hypot(1.2 - 0.85, 0.9 - 0.85)) < 1e-15);
    dfl_curve_locator_free(A);
    dfl_curve_locator_free(B);
    dfl_bspline_free(&c);
}


/* The option ranges of footpoint.h, bounds included: samples_per_span
 * 2..10000, candidates 1..DFL_FOOT_MAX_CAND, max_iter 1..100000, tie_rel in
 * [0, 1); one step outside each is DFL_E_INPUT. */
Test(foot_curve, option_ranges_are_inclusive)
{
    dfl_foot_opts o;
    dfl_err err;
    dfl_foot_opts_default(&o);
    cr_assert_eq(dfl_foot_opts_check(&o, &err), DFL_OK);
    struct {
        int *field;
        int lo, hi;
    } ints[] = {{&o.samples_per_span, 2, 10000},
                {&o.candidates, 1, DFL_FOOT_MAX_CAND},
                {&o.max_iter, 1, 100000}};
    for (size_t i = 0; i < sizeof ints / sizeof *ints; i++) {
        const int keep = *ints[i].field;
        *ints[i].field = ints[i].lo;
        cr_expect_eq(dfl_foot_opts_check(&o, &err), DFL_OK, "field %zu = %d", i, ints[i].lo);
        *ints[i].field = ints[i].hi;
        cr_expect_eq(dfl_foot_opts_check(&o, &err), DFL_OK, "field %zu = %d", i, ints[i].hi);
        *ints[i].field = ints[i].lo - 1;
        cr_expect_eq(dfl_foot_opts_check(&o, &err), DFL_E_INPUT, "field %zu = %d", i,
                     ints[i].lo - 1);
        *ints[i].field = ints[i].hi + 1;
        cr_expect_eq(dfl_foot_opts_check(&o, &err), DFL_E_INPUT, "field %zu = %d", i,
                     ints[i].hi + 1);
        *ints[i].field = keep;
    }
    o.tie_rel = 0.0;
    cr_expect_eq(dfl_foot_opts_check(&o, &err), DFL_OK);
    o.tie_rel = nextafter(1.0, 0.0);
    cr_expect_eq(dfl_foot_opts_check(&o, &err), DFL_OK);
    o.tie_rel = 1.0;
    cr_expect_eq(dfl_foot_opts_check(&o, &err), DFL_E_INPUT);
    o.tie_rel = -1e-300;
    cr_expect_eq(dfl_foot_opts_check(&o, &err), DFL_E_INPUT);
    o.tie_rel = NAN;
    cr_expect_eq(dfl_foot_opts_check(&o, &err), DFL_E_INPUT);
}
