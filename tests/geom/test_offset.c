/* offset: untrimmed offsets of closed curves (invariants |o - C| = |delta|,
 * o - C normal to C'), cusp and swallow-tail counts on an elongated curve
 * where they are known, and the crossing sweep against brute force. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

#include "core/rng.h"
#include "core/vec.h"
#include "geom/offset.h"

/* Periodic cubic B-spline through m control points on the ellipse with
 * semi-axes a, b (counter-clockwise, or clockwise when cw). */
static void ellipse_spline(double a, double b, int m, int cw, dfl_bspline *c)
{
    double *cp = malloc(2 * (size_t)m * sizeof *cp);
    for (int i = 0; i < m; i++) {
        const double t = 2 * DFL_PI * i / m * (cw ? -1 : 1);
        cp[2 * i] = 0.5 + a * cos(t);
        cp[2 * i + 1] = 0.5 + b * sin(t);
    }
    dfl_err err;
    cr_assert_eq(dfl_bspline_init_periodic(2, 4, (size_t)m, cp, NULL, 0, c, &err), DFL_OK);
    free(cp);
}

/* |o - C| = |delta| exactly (to rounding), o - C is normal to C', and the
 * offset points outwards (delta > 0: away from the centre) for both
 * orientations. */
Test(offset, invariants_both_orientations)
{
    for (int cw = 0; cw < 2; cw++) {
        dfl_bspline c;
        ellipse_spline(0.3, 0.2, 24, cw, &c);
        dfl_offset o;
        dfl_err err;
        cr_assert_eq(dfl_offset_curve(&c, cw ? -1 : 1, 0.05, 400, &o, &err), DFL_OK);
        for (size_t i = 0; i < o.n; i++) {
            const double dx = o.pts[2 * i] - o.foot[2 * i], dy = o.pts[2 * i + 1] - o.foot[2 * i + 1];
            cr_expect_float_eq(hypot(dx, dy), 0.05, 1e-15);
            double d[4];
            dfl_bspline_eval(&c, o.t[i], 1, d);
            cr_expect_lt(fabs(dx * d[2] + dy * d[3]) / hypot(d[2], d[3]), 1e-15);
            const double rx = o.foot[2 * i] - 0.5, ry = o.foot[2 * i + 1] - 0.5;
            cr_expect_gt(dx * rx + dy * ry, 0.0, "outward at sample %zu", i);
            cr_expect_gt(o.speed[i], 1.0);
        }
        dfl_offset_counts k;
        cr_assert_eq(dfl_offset_count(&o, &k, &err), DFL_OK);
        cr_expect_eq(k.cusps, 0);
        cr_expect_eq(k.swallow_tails, 0);
        cr_expect_eq(k.self_intersections, 0);
        dfl_offset_free(&o);
        dfl_bspline_free(&c);
    }
}

/* Near-circle (64 control points on a circle of radius 0.3): the speed
 * factor is 1 + delta / R (R ~ 0.3 within 1e-4 for this spline: its points
 * lie at radius 0.3 (4 + 2 cos(2 pi/64)) / 6 at the knots), so inner
 * offsets with |delta| < R have no cusp, and past the centre (delta < -R)
 * the whole offset runs backwards: no cusp, no tail, no crossing. */
Test(offset, circle_is_a_circle)
{
    dfl_bspline c;
    ellipse_spline(0.3, 0.3, 64, 0, &c);
    const double R = 0.3 * (4 + 2 * cos(2 * DFL_PI / 64)) / 6;
    const double deltas[3] = {-0.2, 0.1, -0.35};
    for (int k = 0; k < 3; k++) {
        dfl_offset o;
        dfl_err err;
        cr_assert_eq(dfl_offset_curve(&c, 1, deltas[k], 256, &o, &err), DFL_OK);
        for (size_t i = 0; i < o.n; i++) {
            const double r = hypot(o.pts[2 * i] - 0.5, o.pts[2 * i + 1] - 0.5);
            cr_expect_lt(fabs(r - fabs(R + deltas[k])), 2e-5);
            cr_expect_lt(fabs(o.speed[i] - (1 + deltas[k] / R)), 1e-3);
        }
        dfl_offset_counts n;
        cr_assert_eq(dfl_offset_count(&o, &n, &err), DFL_OK);
        cr_expect_eq(n.cusps, 0);
        cr_expect_eq(n.swallow_tails, 0);
        cr_expect_eq(n.self_intersections, 0);
        cr_expect_float_eq(n.reversed_fraction, deltas[k] < -R ? 1.0 : 0.0, 0);
        dfl_offset_free(&o);
    }
    dfl_bspline_free(&c);
}

/* An elongated convex curve (semi-axes 0.4, 0.2; curvature about
 * a / b^2 = 10 at the ends of the long axis, b / a^2 = 1.25 at the short
 * one's): inner offsets with 1/kappa_max < |delta| < b have a swallow-tail
 * at each end of the long axis: 4 cusps, 2 tails, 2 crossings.  At
 * |delta| = 0.05 < 1/kappa_max none. */
Test(offset, ellipse_swallow_tails)
{
    dfl_bspline c;
    ellipse_spline(0.4, 0.2, 32, 0, &c);
    dfl_offset o;
    dfl_offset_counts n;
    dfl_err err;
    cr_assert_eq(dfl_offset_curve(&c, 1, -0.15, 2000, &o, &err), DFL_OK);
    cr_assert_eq(dfl_offset_count(&o, &n, &err), DFL_OK);
    cr_expect_eq(n.cusps, 4);
    cr_expect_eq(n.swallow_tails, 2);
    cr_expect_eq(n.self_intersections, 2);
    cr_expect_gt(n.reversed_fraction, 0.0);
    dfl_offset_free(&o);
    cr_assert_eq(dfl_offset_curve(&c, 1, -0.05, 2000, &o, &err), DFL_OK);
    cr_assert_eq(dfl_offset_count(&o, &n, &err), DFL_OK);
    cr_expect_eq(n.cusps, 0);
    cr_expect_eq(n.self_intersections, 0);
    dfl_offset_free(&o);
    dfl_bspline_free(&c);
}

static size_t brute_crossings(const double *p, size_t n)
{
    size_t c = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + 2; j < n; j++) {
            if (i == 0 && j == n - 1) continue;
            const double *a = p + 2 * i, *b = p + 2 * ((i + 1) % n), *q = p + 2 * j,
                         *d = p + 2 * ((j + 1) % n);
            const double o1 = (b[0] - a[0]) * (q[1] - a[1]) - (b[1] - a[1]) * (q[0] - a[0]);
            const double o2 = (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]);
            const double o3 = (d[0] - q[0]) * (a[1] - q[1]) - (d[1] - q[1]) * (a[0] - q[0]);
            const double o4 = (d[0] - q[0]) * (b[1] - q[1]) - (d[1] - q[1]) * (b[0] - q[0]);
            c += o1 * o2 < 0 && o3 * o4 < 0;
        }
    return c;
}

/* The x sweep counts what all pairs count, on random closed polylines. */
Test(offset, crossings_match_brute_force)
{
    uint64_t r = 7;
    for (int trial = 0; trial < 20; trial++) {
        const size_t n = 4 + (size_t)(trial * 3);
        double p[2 * 64];
        for (size_t i = 0; i < 2 * n; i++) p[i] = dfl_rng_splitmix(&r, 0.0, 1.0);
        size_t got;
        dfl_err err;
        cr_assert_eq(dfl_polyline_crossings(p, n, &got, &err), DFL_OK);
        cr_expect_eq(got, brute_crossings(p, n), "trial %d", trial);
    }
    /* a figure eight: one crossing */
    const double eight[8] = {0, 0, 1, 1, 1, 0, 0, 1};
    size_t got;
    dfl_err err;
    cr_assert_eq(dfl_polyline_crossings(eight, 4, &got, &err), DFL_OK);
    cr_expect_eq(got, 1);
}

/* Bad input: an open curve, too few samples, a bad orientation. */
Test(offset, bad_input)
{
    dfl_bspline c;
    dfl_err err;
    const double cp[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    cr_assert_eq(dfl_bspline_init(2, 4, 4, cp, NULL, 0, &c, &err), DFL_OK);
    dfl_offset o;
    cr_expect_eq(dfl_offset_curve(&c, 1, 0.1, 100, &o, &err), DFL_E_INPUT);
    dfl_bspline_free(&c);
    ellipse_spline(0.3, 0.2, 12, 0, &c);
    cr_expect_eq(dfl_offset_curve(&c, 1, 0.1, 4, &o, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_offset_curve(&c, 0, 0.1, 100, &o, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_offset_curve(&c, 1, NAN, 100, &o, &err), DFL_E_INPUT);
    cr_expect_eq(o.n, 0);
    dfl_bspline_free(&c);
}
