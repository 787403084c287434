/* geom/polygon: orientation of both windings and of degenerate polygons,
 * the convex region's distance against closed forms and a brute force
 * over the edges and the inside test. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>

#include "core/rng.h"
#include "core/vec.h"
#include "geom/polygon.h"
#include "geom/segdist.h"

static const double square_ccw[8] = {0, 0, 2, 0, 2, 2, 0, 2};
static const double square_cw[8] = {0, 0, 0, 2, 2, 2, 2, 0};

Test(polygon, orientation_of_both_windings)
{
    cr_expect_eq(dfl_polygon_orientation(square_ccw, 4), 1.0);
    cr_expect_eq(dfl_polygon_orientation(square_cw, 4), -1.0);
    const double tri[6] = {0, 0, 1, 0, 0, 1};
    const double tri_cw[6] = {0, 0, 0, 1, 1, 0};
    cr_expect_eq(dfl_polygon_orientation(tri, 3), 1.0);
    cr_expect_eq(dfl_polygon_orientation(tri_cw, 3), -1.0);
    /* zero area (collinear, or a single point) is documented as -1 */
    const double line[6] = {0, 0, 1, 1, 2, 2};
    cr_expect_eq(dfl_polygon_orientation(line, 3), -1.0);
    cr_expect_eq(dfl_polygon_orientation(square_ccw, 1), -1.0);
}

Test(polygon, convex_distance_closed_forms)
{
    for (int w = 0; w < 2; w++) {
        const double *v = w ? square_cw : square_ccw;
        const double o = dfl_polygon_orientation(v, 4);
        const double in[2] = {0.5, 1.5}, edge[2] = {2, 1}, corner[2] = {0, 0};
        cr_expect_eq(dfl_convex_polygon_dist(v, 4, o, in), 0.0);
        cr_expect_eq(dfl_convex_polygon_dist(v, 4, o, edge), 0.0);
        cr_expect_eq(dfl_convex_polygon_dist(v, 4, o, corner), 0.0);
        const double right[2] = {5, 1}, below[2] = {1, -0.25}, diag[2] = {5, 6};
        cr_expect_eq(dfl_convex_polygon_dist(v, 4, o, right), 3.0);
        cr_expect_eq(dfl_convex_polygon_dist(v, 4, o, below), 0.25);
        cr_expect_eq(dfl_convex_polygon_dist(v, 4, o, diag), 5.0); /* (3, 4) from (2, 2) */
    }
    /* the wrong orientation turns the inside test around: nothing is inside */
    const double in[2] = {1, 1};
    cr_expect_eq(dfl_convex_polygon_dist(square_ccw, 4, -1.0, in), 1.0);
}

/* Random points against a hexagon: the distance is the least edge distance
 * (by its own projection formula) outside, 0 inside (inside when the point
 * is a convex combination of the vertices; here: of the centre and one
 * edge's end points). */
Test(polygon, convex_distance_matches_brute_force)
{
    double hex[12];
    for (int i = 0; i < 6; i++) {
        hex[2 * i] = 1.0 + 2.0 * cos(i * DFL_PI / 3);
        hex[2 * i + 1] = -0.5 + 1.5 * sin(i * DFL_PI / 3);
    }
    const double o = dfl_polygon_orientation(hex, 6);
    cr_assert_eq(o, 1.0);
    uint64_t seed = 5;
    int inside = 0;
    for (int it = 0; it < 3000; it++) {
        const double x[2] = {dfl_rng_splitmix(&seed, -3, 5), dfl_rng_splitmix(&seed, -3, 2)};
        double best = INFINITY;
        int in = 0;
        for (int i = 0; i < 6; i++) {
            const double *a = hex + 2 * i, *b = hex + 2 * ((i + 1) % 6);
            const double ex = b[0] - a[0], ey = b[1] - a[1];
            double t = ((x[0] - a[0]) * ex + (x[1] - a[1]) * ey) / (ex * ex + ey * ey);
            t = fmin(1.0, fmax(0.0, t));
            best = fmin(best, hypot(x[0] - a[0] - t * ex, x[1] - a[1] - t * ey));
            /* triangle (centre, a, b): barycentric coordinates >= 0 */
            const double c[2] = {1.0, -0.5};
            const double d = (a[0] - c[0]) * (b[1] - c[1]) - (b[0] - c[0]) * (a[1] - c[1]);
            const double l1 = ((a[0] - x[0]) * (b[1] - x[1]) - (b[0] - x[0]) * (a[1] - x[1])) / d;
            const double l2 = ((b[0] - x[0]) * (c[1] - x[1]) - (c[0] - x[0]) * (b[1] - x[1])) / d;
            const double l3 = 1.0 - l1 - l2;
            if (l1 > 1e-9 && l2 > 1e-9 && l3 > 1e-9) in = 1;
        }
        const double got = dfl_convex_polygon_dist(hex, 6, o, x);
        if (in) {
            cr_assert_eq(got, 0.0, "it %d: inside but %g", it, got);
            inside++;
        } else if (best > 1e-9) {
            cr_assert_float_eq(got, best, 1e-14, "it %d: %.17g vs %.17g", it, got, best);
        }
    }
    cr_expect(inside > 100 && inside < 2900, "inside %d", inside);
}

/* The inside test is o (b - a) x (x - a) >= 0 evaluated as written, with
 * no tolerance: a point for which that cross product is exactly 0 (on an
 * edge up to rounding) and positive for the other edges is inside, so its
 * distance is 0.0 even where the rounded projection onto the edge leaves a
 * residual of an ulp or so.  Points along an edge whose end points are
 * not on a coarse grid give both cases. */
Test(polygon, a_zero_cross_product_counts_as_inside)
{
    for (int w = 0; w < 2; w++) {
        const double ccw[6] = {0.1, 0.2, 1.7, 0.3, 0.4, 1.9};
        const double cw[6] = {0.1, 0.2, 0.4, 1.9, 1.7, 0.3};
        const double *v = w ? cw : ccw;
        const double o = dfl_polygon_orientation(v, 3);
        cr_assert_eq(o, w ? -1.0 : 1.0);
        int zero = 0, residual = 0;
        for (int k = 1; k < 2000; k++) {
            const double t = k / 2000.0;
            const double *a = v, *b = v + 2;
            const double x[2] = {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])};
            int in = 1, on = 0;
            for (int i = 0; i < 3; i++) {
                const double *p = v + 2 * i, *q = v + 2 * ((i + 1) % 3);
                const double cr = o * ((q[0] - p[0]) * (x[1] - p[1]) - (q[1] - p[1]) * (x[0] - p[0]));
                if (cr < 0) in = 0;
                if (cr == 0) on = 1;
            }
            if (!in || !on) continue;
            zero++;
            residual += dfl_point_segment_dist_hypot(x, a, b) > 0.0;
            cr_assert_eq(dfl_convex_polygon_dist(v, 3, o, x), 0.0, "w %d t %g", w, t);
        }
        /* both kinds occurred, so the rule was exercised */
        cr_expect(zero > 100 && residual > 0, "w %d: %d zero, %d with a residual", w, zero,
                  residual);
    }
}
