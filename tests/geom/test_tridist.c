/* geom/tridist.h: the closest point of a triangle.  Expected values: a
 * dense barycentric scan (brute force), the Voronoi regions written out
 * for a right triangle, and the bit-for-bit identity with
 * dfl_point_triangle_dist. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>

#include "core/rng.h"
#include "geom/polygonize.h"
#include "geom/tridist.h"

static double scan(const double *x, const double *a, const double *b, const double *c)
{
    double best = INFINITY;
    const int N = 400;
    for (int i = 0; i <= N; i++)
        for (int j = 0; i + j <= N; j++) {
            double u = (double)i / N, v = (double)j / N, s = 0;
            for (int k = 0; k < 3; k++) {
                double p = a[k] + u * (b[k] - a[k]) + v * (c[k] - a[k]) - x[k];
                s += p * p;
            }
            best = fmin(best, s);
        }
    return sqrt(best);
}

Test(tridist, regions_of_a_right_triangle)
{
    const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
    struct {
        double x[3];
        dfl_tri_feature f;
        double q[3], d;
    } cs[] = {
        {{0.2, 0.2, 0.5}, DFL_TRI_FACE, {0.2, 0.2, 0}, 0.5},
        {{-1, -1, 0}, DFL_TRI_VERT_A, {0, 0, 0}, sqrt(2.0)},
        {{2, -1, 0}, DFL_TRI_VERT_B, {1, 0, 0}, sqrt(2.0)},
        {{-1, 3, 0}, DFL_TRI_VERT_C, {0, 1, 0}, sqrt(5.0)},
        {{0.5, -2, 0}, DFL_TRI_EDGE_AB, {0.5, 0, 0}, 2.0},
        {{-3, 0.25, 4}, DFL_TRI_EDGE_AC, {0, 0.25, 0}, 5.0},
        {{1, 1, 0}, DFL_TRI_EDGE_BC, {0.5, 0.5, 0}, sqrt(0.5)},
    };
    for (size_t i = 0; i < sizeof cs / sizeof *cs; i++) {
        double q[3];
        dfl_tri_feature f;
        double d = dfl_tridist_closest(cs[i].x, a, b, c, q, &f);
        cr_expect_eq(f, cs[i].f, "case %zu: feature %d", i, (int)f);
        cr_expect_float_eq(d, cs[i].d, 1e-15, "case %zu", i);
        for (int k = 0; k < 3; k++) cr_expect_float_eq(q[k], cs[i].q[k], 1e-15, "case %zu", i);
    }
}

Test(tridist, brute_force_and_the_polygonize_distance)
{
    uint64_t s = 7;
    for (int it = 0; it < 200; it++) {
        double a[3], b[3], c[3], x[3], q[3];
        for (int k = 0; k < 3; k++) {
            a[k] = dfl_rng_splitmix(&s, -1, 1);
            b[k] = dfl_rng_splitmix(&s, -1, 1);
            c[k] = dfl_rng_splitmix(&s, -1, 1);
            x[k] = dfl_rng_splitmix(&s, -2, 2);
        }
        dfl_tri_feature f;
        double d = dfl_tridist_closest(x, a, b, c, q, &f);
        double e = 0;
        for (int k = 0; k < 3; k++) e += (x[k] - q[k]) * (x[k] - q[k]);
        cr_assert_eq(d, sqrt(e), "d is |x - q| summed in coordinate order");
        cr_assert_eq(d, dfl_point_triangle_dist(x, a, b, c), "bit for bit");
        double bf = scan(x, a, b, c);
        cr_expect(d <= bf + 1e-14, "closest: %g > scan %g", d, bf);
        cr_expect(bf - d < 5e-3, "the scan reaches the minimum: %g vs %g", bf, d);
        if (f == DFL_TRI_VERT_A) cr_expect(q[0] == a[0] && q[1] == a[1] && q[2] == a[2]);
        if (f == DFL_TRI_VERT_B) cr_expect(q[0] == b[0] && q[1] == b[1] && q[2] == b[2]);
        if (f == DFL_TRI_VERT_C) cr_expect(q[0] == c[0] && q[1] == c[1] && q[2] == c[2]);
    }
}

/* The regions are tested in the order of dfl_tri_feature with exact sign
 * tests, so a point on the boundary of vertex c's region (x - c).(c - b)
 * = 0 against edge BC, (x - c).(c - a) = 0 against edge AC) belongs to the
 * vertex: feature DFL_TRI_VERT_C and q = c bit for bit (header).  Right
 * triangle a = 0, b = e1, c = e2: x = c + s (1, 1, 0) + z e3 has
 * (x - c).(b - a) = (x - c).(c - a) = s; x = c + (-s, 0, z) has
 * (x - c).(c - a) = 0.  The same for vertex b (before edge AB and BC). */
Test(tridist, region_boundaries_go_to_the_vertex)
{
    const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
    const double xs[][3] = {{1, 2, 0.5}, {-2, 1, 0.25}, {0.5, 1.5, 0}};
    for (size_t i = 0; i < sizeof xs / sizeof *xs; i++) {
        double q[3];
        dfl_tri_feature f;
        const double d = dfl_tridist_closest(xs[i], a, b, c, q, &f);
        cr_expect_eq(f, DFL_TRI_VERT_C, "case %zu: feature %d", i, (int)f);
        for (int k = 0; k < 3; k++) cr_expect_eq(q[k], c[k], "case %zu", i);
        const double w[3] = {xs[i][0] - c[0], xs[i][1] - c[1], xs[i][2] - c[2]};
        cr_expect_eq(d, sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]), "case %zu", i);
    }
    /* vertex b: (x - b).(b - a) = 0 and (x - b).(c - b) <= 0, or
     * (x - b).(b - c) = (x - b).(b - a) > 0 */
    const double ys[][3] = {{1, -2, 0.5}, {2, 1, 0}};
    for (size_t i = 0; i < sizeof ys / sizeof *ys; i++) {
        double q[3];
        dfl_tri_feature f;
        dfl_tridist_closest(ys[i], a, b, c, q, &f);
        cr_expect_eq(f, DFL_TRI_VERT_B, "case %zu: feature %d", i, (int)f);
        for (int k = 0; k < 3; k++) cr_expect_eq(q[k], b[k], "case %zu", i);
    }
}
