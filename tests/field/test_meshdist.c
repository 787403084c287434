/* field/meshdist: the distance to a two-triangle mesh in closed form, the
 * minimum over the triangles, the empty mesh, and grid sampling equal to
 * point evaluation for any thread count. */
#include <criterion/criterion.h>
#include <math.h>

#include "field/meshdist.h"
#include "geom/polygonize.h"

/* The unit square in z = 0 as two triangles, and a far triangle at z = 10. */
static double verts[15] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 10};
static size_t tris[9] = {0, 1, 2, 0, 2, 3, 0, 1, 4};

static dfl_trimesh mesh(size_t ntris)
{
    dfl_trimesh M = {0};
    M.nverts = 5;
    M.verts = verts;
    M.ntris = ntris;
    M.tris = tris;
    return M;
}

Test(meshdist, closed_forms)
{
    const dfl_trimesh M = mesh(2);
    const double above[3] = {0.25, 0.75, 2.0}, side[3] = {4, 0.5, 0}, corner[3] = {2, 3, 2};
    const double on[3] = {0.5, 0.5, 0};
    cr_expect_float_eq(dfl_meshdist_eval(&M, above), 2.0, 1e-15);
    cr_expect_float_eq(dfl_meshdist_eval(&M, side), 3.0, 1e-15);
    cr_expect_float_eq(dfl_meshdist_eval(&M, corner), 3.0, 1e-15); /* (1, 2, 2) from (1, 1, 0) */
    cr_expect_eq(dfl_meshdist_eval(&M, on), 0.0);
}

/* The minimum over all triangles, not the first or the last. */
Test(meshdist, least_over_triangles)
{
    const dfl_trimesh M = mesh(3);
    const double x[3] = {0.9, 0.1, -1.0}; /* in triangle 0's footprint */
    const double d0 = dfl_point_triangle_dist(x, verts, verts + 3, verts + 6);
    const double d1 = dfl_point_triangle_dist(x, verts, verts + 6, verts + 9);
    const double d2 = dfl_point_triangle_dist(x, verts, verts + 3, verts + 12);
    cr_expect_eq(dfl_meshdist_eval(&M, x), fmin(d0, fmin(d1, d2)));
    cr_expect_float_eq(dfl_meshdist_eval(&M, x), 1.0, 1e-15);
    const double y[3] = {0.1, 1.0, 5.0}; /* above the far triangle's face (plane y = 0) */
    cr_expect_float_eq(dfl_meshdist_eval(&M, y), 1.0, 1e-15);
    const dfl_trimesh E = mesh(0);
    cr_expect(isinf(dfl_meshdist_eval(&E, x)));
}

Test(meshdist, sample_is_eval_at_every_node)
{
    const dfl_trimesh M = mesh(3);
    dfl_grid g = {3, {7, 5, 4}, {-1, -1, -1}, {2, 2, 3}};
    const size_t m = dfl_grid_size(&g);
    double out1[140], out2[140];
    cr_assert_eq(m, 140);
    dfl_meshdist_sample(&M, &g, 1, out1);
    dfl_meshdist_sample(&M, &g, 3, out2);
    for (size_t i = 0; i < m; i++) {
        double x[3];
        dfl_grid_node(&g, i, x);
        cr_assert_eq(out1[i], dfl_meshdist_eval(&M, x), "node %zu", i);
        cr_assert_eq(out2[i], out1[i], "node %zu", i);
    }
    /* a plane grid over the square (without the far triangle) */
    const dfl_trimesh S = mesh(2);
    const int n[2] = {4, 3};
    const double lo[2] = {0, 0}, hi[2] = {1, 1};
    dfl_grid_plane(2, 0.5, n, lo, hi, &g);
    dfl_meshdist_sample(&S, &g, 2, out1);
    for (size_t i = 0; i < 12; i++) cr_assert_float_eq(out1[i], 0.5, 1e-15, "node %zu", i);
}
