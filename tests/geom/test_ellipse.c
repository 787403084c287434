/* geom/ellipse: the distance against brute force, closed forms and finite
 * differences, and the ellipse shape kind against the shape checks of
 * shape_check.h (boundary brute force, FD gradients, no jets). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>

#include <string.h>

#include "core/rng.h"
#include "core/vec.h"
#include "geom/ellipse.h"
#include "geom/shape_check.h"

/* Unsigned distance by dense sampling of the parameter and golden-section
 * refinement around every sampled local minimum. */
static double brute(double a, double b, const double *x)
{
    const int N = 4000;
    const double tp = 2 * DFL_PI;
    double best = INFINITY;
    double prev2 = 0, prev1 = 0;
    for (int i = 0; i <= N + 1; i++) {
        const double t = tp * i / N;
        const double d = hypot(a * cos(t) - x[0], b * sin(t) - x[1]);
        if (i >= 2 && prev1 <= prev2 && prev1 <= d) {
            double lo = tp * (i - 2) / N, hi = t;
            const double gr = 0.5 * (sqrt(5.0) - 1.0);
            for (int it = 0; it < 200; it++) {
                const double m1 = hi - gr * (hi - lo), m2 = lo + gr * (hi - lo);
                const double d1 = hypot(a * cos(m1) - x[0], b * sin(m1) - x[1]);
                const double d2 = hypot(a * cos(m2) - x[0], b * sin(m2) - x[1]);
                if (d1 < d2) hi = m2;
                else lo = m1;
            }
            const double tm = 0.5 * (lo + hi);
            const double dm = hypot(a * cos(tm) - x[0], b * sin(tm) - x[1]);
            if (dm < best) best = dm;
        }
        prev2 = prev1;
        prev1 = d;
    }
    return best;
}

Test(ellipse_dist, brute_force_both_orientations)
{
    const double ab[3][2] = {{1.0, 0.5}, {0.3, 1.1}, {2.0, 0.25}};
    uint64_t st = 7;
    for (int s = 0; s < 3; s++) {
        const double a = ab[s][0], b = ab[s][1];
        for (int i = 0; i < 300; i++) {
            const double x[2] = {dfl_rng_splitmix(&st, -1.6 * a, 1.6 * a), dfl_rng_splitmix(&st, -1.6 * b, 1.6 * b)};
            double foot[2], g[2];
            const double d = dfl_ellipse_sdist(a, b, x, foot, g);
            const double inside = x[0] * x[0] / (a * a) + x[1] * x[1] / (b * b) < 1;
            cr_assert(inside ? d <= 0 : d >= 0, "sign at (%g %g): %g", x[0], x[1], d);
            cr_assert(fabs(fabs(d) - brute(a, b, x)) <= 1e-12 * (a + b), "(%g, %g) a %g b %g: %.17g vs %.17g",
                      x[0], x[1], a, b, fabs(d), brute(a, b, x));
            /* the footpoint is on the ellipse, x - foot along the normal */
            const double on = foot[0] * foot[0] / (a * a) + foot[1] * foot[1] / (b * b) - 1;
            /* rounding of x0 = r0 y0 / (s + r0): a few ulps times r0 = (e0/e1)^2 */
            cr_assert(fabs(on) < 1e-15 * (a * a / (b * b) + b * b / (a * a)) + 1e-14, "(%g %g) a %g b %g: foot off by %g", x[0], x[1], a, b, on);
            cr_assert(fabs(hypot(g[0], g[1]) - 1) < 1e-15);
            cr_assert(fabs(x[0] - foot[0] - d * g[0]) < 1e-12 && fabs(x[1] - foot[1] - d * g[1]) < 1e-12);
        }
    }
}

/* Circle: |x| - r.  Axes: closed forms (the centre of an ellipse is at
 * distance b; on the major axis inside the cusp, b sqrt(1 - x^2 /
 * (a^2 - b^2))). */
Test(ellipse_dist, closed_forms)
{
    uint64_t st = 3;
    for (int i = 0; i < 100; i++) {
        const double x[2] = {dfl_rng_splitmix(&st, -2, 2), dfl_rng_splitmix(&st, -2, 2)};
        cr_assert_float_eq(dfl_ellipse_sdist(0.8, 0.8, x, NULL, NULL), hypot(x[0], x[1]) - 0.8,
                           1e-15);
    }
    const double a = 1.0, b = 0.5, o[2] = {0, 0};
    cr_assert_float_eq(dfl_ellipse_sdist(a, b, o, NULL, NULL), -b, 1e-16);
    const double c = (a * a - b * b) / a;
    for (int i = 0; i < 20; i++) {
        const double x[2] = {dfl_rng_splitmix(&st, -c, c), 0.0};
        cr_assert_float_eq(dfl_ellipse_sdist(a, b, x, NULL, NULL),
                           -b * sqrt(1 - x[0] * x[0] / (a * a - b * b)), 1e-15);
        const double y[2] = {dfl_rng_splitmix(&st, 0, 1), dfl_rng_splitmix(&st, -2, 2)};
        const double xy[2] = {0.0, y[1]}, xx[2] = {c + y[0], 0.0};
        cr_assert_float_eq(dfl_ellipse_sdist(a, b, xy, NULL, NULL), fabs(y[1]) - b, 1e-15);
        cr_assert_float_eq(dfl_ellipse_sdist(a, b, xx, NULL, NULL), c + y[0] - a, 1e-15);
    }
}

/* Gradient vs central differences away from the medial axis. */
Test(ellipse_dist, gradient)
{
    uint64_t st = 11;
    const double a = 1.3, b = 0.6, c = (a * a - b * b) / a;
    for (int i = 0; i < 200; i++) {
        const double x[2] = {dfl_rng_splitmix(&st, -2, 2), dfl_rng_splitmix(&st, -1.2, 1.2)};
        if (fabs(x[1]) < 0.05 && fabs(x[0]) < c + 0.05) continue;
        double g[2];
        dfl_ellipse_sdist(a, b, x, NULL, g);
        const double h = 1e-6;
        for (int k = 0; k < 2; k++) {
            double xp[2] = {x[0], x[1]}, xm[2] = {x[0], x[1]};
            xp[k] += h;
            xm[k] -= h;
            const double fd = (dfl_ellipse_sdist(a, b, xp, NULL, NULL) -
                               dfl_ellipse_sdist(a, b, xm, NULL, NULL)) / (xp[k] - xm[k]);
            cr_assert(fabs(fd - g[k]) < 1e-6, "(%g %g) %d: %g vs %g", x[0], x[1], k, fd, g[k]);
        }
    }
}

/* ---- the shape kind ---- */

static const double EC[2] = {0.3, -0.2}, EA = 1.1, EB = 0.45;

static void ellipse_pt(const void *ctx, const double *prm, double *p)
{
    (void)ctx;
    p[0] = EC[0] + EA * cos(prm[0]);
    p[1] = EC[1] + EB * sin(prm[0]);
}

static int ellipse_in(const double *x)
{
    const double u = (x[0] - EC[0]) / EA, v = (x[1] - EC[1]) / EB;
    return u * u + v * v < 1;
}

Test(ellipse_shape, matches_brute_force_and_the_distance)
{
    dfl_shape s;
    dfl_err err;
    cr_assert_eq(dfl_shape_ellipse(EC, EA, EB, &s, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(s.dim, 2);
    sc_patch P = {1, {0, 0}, {2 * DFL_PI, 0}, ellipse_pt, NULL};
    sc_check_shape(&s, &P, 1, ellipse_in, 1, -1.5, 1.5, 40, 1, 1, 0);
    /* the shape is the distance function moved to the centre, bit for bit,
     * in batches too */
    double pts[2 * 64], val[64], grad[2 * 64];
    for (int i = 0; i < 64; i++) {
        pts[2 * i] = sc_urand(-2, 2);
        pts[2 * i + 1] = sc_urand(-2, 2);
    }
    pts[0] = EC[0], pts[1] = EC[1]; /* the centre: one-sided gradient, |g| = 1 */
    dfl_shape_eval(&s, 64, pts, val, grad);
    for (int i = 0; i < 64; i++) {
        const double u[2] = {pts[2 * i] - EC[0], pts[2 * i + 1] - EC[1]};
        double g[2];
        cr_assert_eq(val[i], dfl_ellipse_sdist(EA, EB, u, NULL, g));
        cr_assert_eq(grad[2 * i], g[0]);
        cr_assert_eq(grad[2 * i + 1], g[1]);
        cr_assert(fabs(hypot(g[0], g[1]) - 1) < 1e-15);
    }
    cr_assert_float_eq(val[0], -EB, 1e-16);
    dfl_shape_derivs D;
    cr_assert_eq(dfl_shape_derivs_at(&s, pts, &D, &err), DFL_E_INPUT); /* no jets */
    dfl_shape_free(&s);
    /* a == b is the circle */
    cr_assert_eq(dfl_shape_ellipse(EC, 0.7, 0.7, &s, NULL), DFL_OK);
    dfl_shape c;
    cr_assert_eq(dfl_shape_circle(EC, 0.7, &c, NULL), DFL_OK);
    for (int i = 0; i < 100; i++) {
        double x[2] = {sc_urand(-2, 2), sc_urand(-2, 2)};
        cr_assert_float_eq(dfl_shape_eval1(&s, x, NULL), dfl_shape_eval1(&c, x, NULL), 1e-15);
    }
    dfl_shape_free(&s);
    dfl_shape_free(&c);
}

Test(ellipse_shape, rejects_degenerate_input)
{
    dfl_shape s = {0};
    dfl_err err;
    const double c[2] = {0, 0}, bad[2] = {NAN, 0};
    cr_assert_eq(dfl_shape_ellipse(c, 0.0, 1.0, &s, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "semi-axes"), "%s", err.msg);
    cr_assert_eq(dfl_shape_ellipse(c, 1.0, -1.0, &s, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_shape_ellipse(c, INFINITY, 1.0, &s, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_shape_ellipse(bad, 1.0, 1.0, &s, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "centre"), "%s", err.msg);
    cr_assert_null(s.impl);
}
