/* Implicit footpoints (implicit_foot.c): the torus quartic against the
 * closed-form torus SDF of geom/shape (itself checked against brute force
 * in test_shape_analytic.c), Newton against Ceres on hard points, and the
 * deterministic medial-axis choice. */
#include <string.h>

#include "geom/shape.h"
#include "geom/implicit_fixtures.h"

/* The implicit torus' footpoint SDF equals the closed-form torus SDF. */
Test(implicit_foot, torus_footpoint_sdf_is_exact)
{
    dfl_implicit *s = make_torus(DFL_FOOT_NEWTON);
    dfl_shape ex;
    cr_assert_eq(dfl_shape_torus(TC, TAX, TR, Tr, &ex, NULL), DFL_OK);
    double worst = 0;
    for (int t = 0; t < 400; t++) {
        double x[3];
        if (t < 300)
            for (int j = 0; j < 3; j++) x[j] = TC[j] + urand(-1, 1);
        else /* far away */
            for (int j = 0; j < 3; j++) x[j] = TC[j] + urand(-50, 50);
        dfl_footpoint f;
        dfl_err err;
        cr_assert_eq(dfl_implicit_footpoint(s, x, &f, &err), DFL_OK, "%s", err.msg);
        double g[3], d = dfl_shape_eval1(&ex, x, g);
        worst = fmax(worst, fabs(f.d - d));
        cr_assert(fabs(f.d - d) <= 1e-10 * (1 + fabs(d)), "x = (%g %g %g): %.17g vs exact %.17g",
                  x[0], x[1], x[2], f.d, d);
        if (!f.medial)
            for (int j = 0; j < 3; j++) cr_assert(fabs(f.n[j] - g[j]) < 1e-8);
    }
    cr_log_info("implicit torus vs exact: max |error| %.3g", worst);
    dfl_shape_free(&ex);
    dfl_implicit_free(s);
}

/* Hard points: near the axis (the medial axis outside the tube's ring and
 * the centres of the major curvature), near the centre circle (centres of
 * the minor curvature, medial axis of the solid), far away.  Both backends
 * must agree with each other and with the exact SDF to 1e-10. */
Test(implicit_foot, newton_and_ceres_agree_on_hard_points)
{
    dfl_implicit *s = make_torus(DFL_FOOT_NEWTON);
    dfl_shape ex;
    cr_assert_eq(dfl_shape_torus(TC, TAX, TR, Tr, &ex, NULL), DFL_OK);
    double pts[][3] = {
        {1e-3, 0.3, 0.0},  {1e-6, 1.0, 0.1},  {1e-4, 2.0, -0.3}, {2e-3, 4.0, 0.5},  /* near axis */
        {TR + 1e-3, 0.2, 0.0}, {TR - 1e-4, 1.3, 1e-4}, {TR, 2.5, 1e-3},           /* centre circle */
        {TR + 1e-6, 5.0, -1e-6},
        {80.0, 0.7, 30.0}, {3.0, 2.0, -60.0}, {0.01, 0.0, 100.0},                 /* far away */
        {TR + Tr - 1e-9, 0.4, 0.0}, {TR - Tr + 1e-9, 0.4, 0.0}};                  /* on surface */
    int np = sizeof pts / sizeof pts[0];
    double worst = 0;
    for (int i = 0; i < np; i++) {
        double x[3];
        torus_point(pts[i][0], pts[i][1], pts[i][2], x);
        dfl_footpoint fn, fc;
        dfl_err err;
        cr_assert_eq(dfl_implicit_footpoint_with(s, DFL_FOOT_NEWTON, x, &fn, &err), DFL_OK, "%s",
                     err.msg);
        cr_assert_eq(dfl_implicit_footpoint_with(s, DFL_FOOT_CERES, x, &fc, &err), DFL_OK, "%s",
                     err.msg);
        double d = dfl_shape_eval1(&ex, x, NULL);
        worst = fmax(worst, fabs(fn.d - fc.d));
        cr_assert(fabs(fn.d - fc.d) <= 1e-10, "point %d: newton %.17g ceres %.17g", i, fn.d, fc.d);
        cr_assert(fabs(fn.d - d) <= 1e-10, "point %d: newton %.17g exact %.17g", i, fn.d, d);
        cr_assert(fabs(fc.d - d) <= 1e-10, "point %d: ceres %.17g exact %.17g", i, fc.d, d);
    }
    cr_log_info("newton vs ceres on %d hard points: max |diff| %.3g", np, worst);
    dfl_shape_free(&ex);
    dfl_implicit_free(s);
}

Test(implicit_foot, medial_axis_is_flagged_and_deterministic)
{
    dfl_implicit *s = make_torus(DFL_FOOT_NEWTON);
    double x[3];
    torus_point(0.0, 0.0, 0.1, x); /* on the axis: a whole circle of footpoints */
    dfl_footpoint a, b;
    cr_assert_eq(dfl_implicit_footpoint(s, x, &a, NULL), DFL_OK);
    cr_assert_eq(dfl_implicit_footpoint(s, x, &b, NULL), DFL_OK);
    cr_assert(a.medial == 1);
    cr_assert(memcmp(a.p, b.p, sizeof a.p) == 0);
    double want = sqrt(TR * TR + 0.1 * 0.1) - Tr;
    cr_assert(fabs(a.d - want) < 1e-10);
    torus_point(0.3, 1.0, 0.05, x);
    cr_assert_eq(dfl_implicit_footpoint(s, x, &a, NULL), DFL_OK);
    cr_assert(a.medial == 0);
    dfl_implicit_free(s);
}


/* implicit.h: a point with a NaN or infinite coordinate has no footpoint
 * (DFL_E_NUMERIC, nothing read: a NaN cast to a bucket index read far
 * outside the buckets) and the shape gives it NaN value and gradient, with
 * either backend, while the other points of a batch get what they get
 * alone. */
Test(implicit_foot, nan_and_infinite_points_have_no_footpoint)
{
    static const double odd[3] = {NAN, INFINITY, -INFINITY};
    for (int b = 0; b < 2; b++) {
        dfl_implicit *s = make_torus(b ? DFL_FOOT_CERES : DFL_FOOT_NEWTON);
        for (int a = 0; a < 3; a++)
            for (int q = 0; q < 3; q++) {
                double x[3] = {0.3, 0.2, 0.1};
                x[a] = odd[q];
                dfl_footpoint f;
                dfl_err err;
                cr_expect_eq(dfl_implicit_footpoint(s, x, &f, &err), DFL_E_NUMERIC,
                             "backend %d axis %d: %g", b, a, odd[q]);
            }
        dfl_shape sh;
        cr_assert_eq(dfl_implicit_shape(&s, &sh, NULL), DFL_OK);
        enum { M = 6 };
        double x[3 * M], v[M], g[3 * M];
        for (int i = 0; i < 3 * M; i++) x[i] = urand(-0.8, 0.8);
        x[3 * 1 + 0] = NAN, x[3 * 2 + 1] = INFINITY, x[3 * 4 + 2] = -INFINITY;
        dfl_shape_eval(&sh, M, x, v, g);
        for (int i = 0; i < M; i++) {
            if (i == 1 || i == 2 || i == 4) {
                cr_expect(isnan(v[i]) && isnan(g[3 * i]) && isnan(g[3 * i + 1]) &&
                              isnan(g[3 * i + 2]),
                          "backend %d point %d: %g", b, i, v[i]);
                continue;
            }
            double g1[3];
            const double v1 = dfl_shape_eval1(&sh, x + 3 * i, g1);
            cr_expect(memcmp(&v1, v + i, sizeof v1) == 0 && memcmp(g1, g + 3 * i, sizeof g1) == 0,
                      "backend %d point %d", b, i);
        }
        dfl_shape_free(&sh);
    }
}
