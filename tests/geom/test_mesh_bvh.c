/* geom/mesh_bvh.h against brute force: the Embree distance equals
 * field/meshdist.h's minimum bit for bit (random points in and around the
 * box, points just off vertices, far points on the brute-force path); the
 * clustered winding number is within its stated bound of the exact sum,
 * and the inside test agrees with the exact sum everywhere sampled. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>

#include "core/rng.h"
#include "field/meshdist.h"
#include "geom/mesh_bvh.h"
#include "geom/trimesh.h"
#include "geom/tridist.h"
#include "geom/winding.h"
#include "mesh_fixtures.h"

static void wuson(dfl_trimesh *m)
{
    dfl_err err;
    cr_assert_eq(dfl_trimesh_read(WUSON, m, &err), DFL_OK, "%s", err.msg);
    const double c[3] = {0, 0, 0};
    dfl_trimesh_fit(m, c, 1.6);
}

Test(mesh_bvh, distance_equals_brute_force_bit_for_bit)
{
    dfl_trimesh m;
    wuson(&m);
    dfl_mesh_bvh *b;
    dfl_err err;
    cr_assert_eq(dfl_mesh_bvh_new(m.verts, m.nverts, m.tris, m.ntris, &b, &err), DFL_OK, "%s",
                 err.msg);
    uint64_t s = 11;
    for (int it = 0; it < 3000; it++) {
        double x[3];
        if (it % 3 == 0) { /* just off a vertex: where ties and pruning are tight */
            size_t v = (size_t)dfl_rng_splitmix(&s, 0, (double)m.nverts);
            for (int j = 0; j < 3; j++) x[j] = m.verts[3 * v + j] + dfl_rng_splitmix(&s, -1e-3, 1e-3);
        } else {
            for (int j = 0; j < 3; j++) x[j] = dfl_rng_splitmix(&s, -1.5, 1.5);
        }
        dfl_mesh_hit h;
        dfl_mesh_bvh_closest(b, x, &h);
        double bf = dfl_meshdist_eval(&m, x);
        cr_assert_eq(h.d, bf, "at (%.17g %.17g %.17g): %.17g vs brute %.17g", x[0], x[1], x[2],
                     h.d, bf);
        cr_assert_lt(h.tri, m.ntris);
        double e = 0;
        for (int j = 0; j < 3; j++) e += (x[j] - h.q[j]) * (x[j] - h.q[j]);
        cr_assert_eq(sqrt(e), h.d, "q is the closest point");
    }
    const double far[3] = {3e30, -1, 2}; /* beyond float range after widening: brute force */
    dfl_mesh_hit h;
    dfl_mesh_bvh_closest(b, far, &h);
    cr_expect_eq(h.d, dfl_meshdist_eval(&m, far));
    const double nan[3] = {NAN, 0, 0};
    dfl_mesh_bvh_closest(b, nan, &h);
    cr_expect(isnan(h.d));
    dfl_mesh_bvh_free(b);
    dfl_trimesh_free(&m);
}

Test(mesh_bvh, winding_within_its_bound_and_inside_exact)
{
    dfl_trimesh m;
    wuson(&m);
    dfl_mesh_bvh *b;
    dfl_err err;
    cr_assert_eq(dfl_mesh_bvh_new(m.verts, m.nverts, m.tris, m.ntris, &b, &err), DFL_OK);
    uint64_t s = 5;
    int accepted_far = 0;
    for (int it = 0; it < 2000; it++) {
        double x[3], B;
        for (int j = 0; j < 3; j++) x[j] = dfl_rng_splitmix(&s, -1.2, 1.2);
        const double w = dfl_mesh_bvh_winding(b, x, DFL_MESH_WINDING_BETA, &B);
        const double wx = dfl_winding_brute(m.verts, m.tris, m.ntris, x);
        cr_assert(fabs(w - wx) <= B + 1e-12, "|%.17g - %.17g| > bound %g", w, wx, B);
        accepted_far += B > 0;
        cr_assert_eq(dfl_mesh_bvh_inside(b, x), wx > 0.5, "inside at (%g %g %g): w = %.17g", x[0],
                     x[1], x[2], wx);
    }
    cr_expect(accepted_far > 1000, "clusters are used: %d", accepted_far);
    /* beta = infinity: nothing is accepted, the sum is exact */
    const double x[3] = {0.1, 0.2, 0.3};
    double B;
    const double w = dfl_mesh_bvh_winding(b, x, INFINITY, &B);
    cr_expect_eq(B, 0.0);
    cr_expect_float_eq(w, dfl_winding_brute(m.verts, m.tris, m.ntris, x), 1e-12);
    dfl_mesh_bvh_free(b);
    dfl_trimesh_free(&m);
}

Test(mesh_bvh, closed_mesh_winds_one_inside)
{
    dfl_trimesh m;
    mf_octahedron(&m);
    dfl_mesh_bvh *b;
    dfl_err err;
    cr_assert_eq(dfl_mesh_bvh_new(m.verts, m.nverts, m.tris, m.ntris, &b, &err), DFL_OK);
    uint64_t s = 9;
    for (int it = 0; it < 1000; it++) {
        double x[3], B;
        for (int j = 0; j < 3; j++) x[j] = dfl_rng_splitmix(&s, -3, 3);
        const double in = 1 - (fabs(x[0]) + fabs(x[1]) + fabs(x[2]));
        if (fabs(in) < 1e-9) continue;
        const double w = dfl_mesh_bvh_winding(b, x, DFL_MESH_WINDING_BETA, &B);
        cr_expect(fabs(w - (in > 0)) <= B + 1e-13, "w %.17g bound %g", w, B);
        cr_expect_eq(dfl_mesh_bvh_inside(b, x), in > 0);
    }
    dfl_mesh_bvh_free(b);
    dfl_trimesh_free(&m);
}

Test(mesh_bvh, refuses_empty)
{
    dfl_mesh_bvh *b = NULL;
    dfl_err err;
    const double v[3] = {0, 0, 0};
    cr_expect_eq(dfl_mesh_bvh_new(v, 1, NULL, 0, &b, &err), DFL_E_INPUT);
    cr_expect_null(b);
}

/* Ties of the closest triangle keep the smallest index (header).  Points
 * beyond the vertices and edge midpoints of the cube and the octahedron are
 * equally far from every triangle sharing that vertex or edge (the vertex
 * region's q is the vertex itself, bit for bit, so the distances are equal
 * exactly); the expected triangle is the first minimum of the brute force
 * in index order. */
Test(mesh_bvh, ties_go_to_the_smallest_triangle_index)
{
    for (int mesh = 0; mesh < 2; mesh++) {
        dfl_trimesh m;
        if (mesh) mf_cube(&m);
        else mf_octahedron(&m);
        dfl_mesh_bvh *b;
        cr_assert_eq(dfl_mesh_bvh_new(m.verts, m.nverts, m.tris, m.ntris, &b, NULL), DFL_OK);
        int tied = 0;
        for (size_t v = 0; v < m.nverts; v++)
            for (size_t w = v; w < m.nverts; w++) {
                /* beyond vertex v (w == v) or beyond the midpoint of v-w */
                double x[3];
                for (int j = 0; j < 3; j++)
                    x[j] = 1.5 * (m.verts[3 * v + j] + m.verts[3 * w + j]);
                size_t best = SIZE_MAX;
                double bd = INFINITY;
                int nties = 0;
                for (size_t t = 0; t < m.ntris; t++) {
                    const size_t *T = m.tris + 3 * t;
                    const double d = dfl_tridist_closest(x, m.verts + 3 * T[0], m.verts + 3 * T[1],
                                                         m.verts + 3 * T[2], NULL, NULL);
                    if (d < bd) bd = d, best = t, nties = 1;
                    else if (d == bd) nties++;
                }
                if (!(bd > 0.0)) continue; /* the midpoint of opposite vertices */
                tied += nties > 1;
                dfl_mesh_hit h;
                dfl_mesh_bvh_closest(b, x, &h);
                cr_assert_eq(h.d, bd);
                cr_expect_eq(h.tri, best, "mesh %d, vertices %zu %zu: triangle %zu, want %zu (of %d)",
                             mesh, v, w, h.tri, best, nties);
            }
        cr_expect(tied > 10, "mesh %d: %d tied points", mesh, tied);
        dfl_mesh_bvh_free(b);
        dfl_trimesh_free(&m);
    }
}

/* inside is w(x) > 1/2 by the exact sum where the clustered bounds cannot
 * decide (|w - 1/2| <= bound + 1e-9 on every rung).  A single triangle seen
 * from just behind its normal side at height z subtends nearly a half
 * sphere: w = 1/2 - O(z), and x just above its front side gives w close to
 * -1/2.  The answer is the exact sum's, decided against 1/2 (not 0). */
Test(mesh_bvh, inside_near_one_half_is_the_exact_sum_against_one_half)
{
    const double V[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const size_t T[3] = {0, 1, 2};
    dfl_mesh_bvh *b;
    cr_assert_eq(dfl_mesh_bvh_new(V, 3, T, 1, &b, NULL), DFL_OK);
    const double zs[] = {1e-12, 1e-11, 3e-11, -1e-12, -3e-11};
    for (size_t i = 0; i < sizeof zs / sizeof *zs; i++) {
        /* the normal (b - a) x (c - a) is +z: x below sees it counter-clockwise */
        const double x[3] = {0.25, 0.3, -zs[i]};
        const double w = dfl_winding_brute(V, T, 1, x);
        cr_assert(fabs(fabs(w) - 0.5) < 1e-9, "z %g: w %.17g", zs[i], w);
        cr_assert(zs[i] > 0 ? (w > 0.0 && w < 0.5) : w < 0.0, "z %g: w %.17g", zs[i], w);
        cr_expect_eq(dfl_mesh_bvh_inside(b, x), w > 0.5, "z %g: w %.17g", zs[i], w);
    }
    dfl_mesh_bvh_free(b);
}
