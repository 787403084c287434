/* geom/mesh_bvh.h against brute force: the Embree distance equals
 * field/meshdist.h's minimum bit for bit (random points in and around the
 * box, points just off vertices, far points on the brute-force path); the
 * clustered winding number is within its stated bound of the exact sum,
 * and the inside test agrees with the exact sum everywhere sampled, with
 * the anchors (geom/mesh_anchor.h) and by the traversal alone. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "core/rng.h"
#include "core/vec.h"
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
        dfl_mesh_hit h, hh;
        dfl_mesh_bvh_closest(b, x, &h);
        /* any start gives the same hit, bit for bit: a random triangle,
         * the hit's own, or none (SIZE_MAX, ntris: not a triangle) */
        const size_t starts[4] = {(size_t)dfl_rng_splitmix(&s, 0, (double)m.ntris), h.tri, SIZE_MAX,
                                  m.ntris};
        for (int k = 0; k < 4; k++) {
            dfl_mesh_bvh_closest_hint(b, x, starts[k], &hh);
            cr_assert(hh.d == h.d && hh.tri == h.tri && hh.feat == h.feat &&
                          memcmp(hh.q, h.q, sizeof h.q) == 0,
                      "start %zu at (%.17g %.17g %.17g): %.17g (triangle %zu) vs %.17g (%zu)",
                      starts[k], x[0], x[1], x[2], hh.d, hh.tri, h.d, h.tri);
        }
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
        cr_assert_eq(dfl_mesh_bvh_inside_traversal(b, x), wx > 0.5, "inside at (%g %g %g): w = %.17g", x[0],
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
        cr_expect_eq(dfl_mesh_bvh_inside_traversal(b, x), in > 0);
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
                /* started from the last triangle (a tied one considered
                 * first), the smallest index still wins */
                dfl_mesh_bvh_closest_hint(b, x, m.ntris - 1, &h);
                cr_assert_eq(h.d, bd);
                cr_expect_eq(h.tri, best, "hint: mesh %d, vertices %zu %zu: triangle %zu, want %zu",
                             mesh, v, w, h.tri, best);
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
        cr_expect_eq(dfl_mesh_bvh_inside_traversal(b, x), w > 0.5, "z %g: w %.17g", zs[i], w);
    }
    dfl_mesh_bvh_free(b);
}

/* The far-field bound 3 A r^2 / (4 pi (R - r)^4) (header) holds and is
 * nearly attained.  Two tiny triangles of area a with normal +x at
 * (+-rho, 0, 0) seen from x = (R, 0, 0): their first moment vanishes, so
 * the clustered value is the monopole 2 a / (4 pi R^2) and the error is
 * the second-order term, a / (4 pi) |2 / R^2 - 1 / (R - rho)^2 -
 * 1 / (R + rho)^2| -> 6 a rho^2 / (4 pi R^4) for R >> rho, i.e. the
 * bound's 3 (2 a) rho^2 / (4 pi R^4) up to (R - r)^4 / R^4.  At R = 20 rho
 * the error is about 0.8 of the bound: the test fails if the bound were
 * taken at half its value, and of course if it were exceeded. */
/* The two-triangle cluster above seen from R = 3 rho .. 40 rho along x:
 * asserts |w - exact| <= bound at every R and returns the largest
 * |w - exact| / bound; wind is one of the two clustered sums, param its
 * beta or tol. */
typedef double (*wind_fn)(const dfl_mesh_bvh *, const double *, double, double *);
static double two_triangle_worst_ratio(wind_fn wind, double param)
{
    const double s = 1e-4, rho = 0.05;
    const double V[18] = {-rho, 0, 0, -rho, s, 0, -rho, 0, s, rho, 0, 0, rho, s, 0, rho, 0, s};
    const size_t T[6] = {0, 1, 2, 3, 4, 5};
    dfl_mesh_bvh *b;
    cr_assert_eq(dfl_mesh_bvh_new(V, 6, T, 2, &b, NULL), DFL_OK);
    double worst = 0.0;
    for (double R = 3 * rho; R <= 40 * rho; R *= 1.25) {
        const double x[3] = {R, s / 3, s / 3};
        double B;
        const double w = wind(b, x, param, &B);
        const double wx = dfl_winding_brute(V, T, 2, x);
        cr_assert_gt(B, 0.0, "R %g: the cluster is used", R);
        cr_assert(fabs(w - wx) <= B, "R %g: |%.17g - %.17g| > bound %g", R, w, wx, B);
        worst = fmax(worst, fabs(w - wx) / B);
    }
    dfl_mesh_bvh_free(b);
    return worst;
}

Test(mesh_bvh, far_field_bound_holds_and_is_nearly_attained)
{
    const double worst = two_triangle_worst_ratio(dfl_mesh_bvh_winding, 2.0);
    cr_expect_gt(worst, 0.5, "largest error / bound %g", worst);
}

/* The same two-triangle cluster against dfl_mesh_bvh_winding_within's
 * sharper bound 3 I2 / (4 pi g^4) (header): here I2 = A rho^2 (+ the
 * triangles' own O(s^2) moments) and g = R - rho, so it is as tight as the
 * ladder's; tol = 1 stops at the root cluster. */
Test(mesh_bvh, sharper_bound_holds_and_is_nearly_attained)
{
    const double worst = two_triangle_worst_ratio(dfl_mesh_bvh_winding_within, 1.0);
    cr_expect_gt(worst, 0.5, "largest error / bound %g", worst);
}

/* The far field's terms (area vector and first moment, built leaf by leaf
 * and moved up the tree) are right: a soup of 40 random triangles in
 * [-1, 1]^3 without any symmetry, seen from 3 to 300 units away, where the
 * bound (3 I2 / (4 pi g^4), about R^-4) is far below the first-order term
 * itself (about R^-3): a wrong term would exceed it. */
Test(mesh_bvh, sharper_bound_holds_far_from_a_random_soup)
{
    enum { NT = 40 };
    double V[9 * NT];
    size_t T[3 * NT];
    uint64_t s = 21;
    for (int i = 0; i < 9 * NT; i++) V[i] = dfl_rng_splitmix(&s, -1, 1);
    for (int i = 0; i < 3 * NT; i++) T[i] = (size_t)i;
    dfl_mesh_bvh *b;
    cr_assert_eq(dfl_mesh_bvh_new(V, 3 * NT, T, NT, &b, NULL), DFL_OK);
    int used = 0;
    for (int it = 0; it < 400; it++) {
        double u[3], l = 0.0;
        for (int j = 0; j < 3; j++) {
            u[j] = dfl_rng_splitmix(&s, -1, 1);
            l += u[j] * u[j];
        }
        const double R = 3.0 * pow(100.0, (it % 20) / 19.0);
        double x[3];
        for (int j = 0; j < 3; j++) x[j] = R * u[j] / sqrt(l);
        double B;
        const double w = dfl_mesh_bvh_winding_within(b, x, 1.0, &B);
        const double wx = dfl_winding_brute(V, T, NT, x);
        cr_assert(fabs(w - wx) <= B + 1e-15, "R %g: |%.17g - %.17g| > bound %g", R, w, wx, B);
        used += B > 0.0;
    }
    cr_expect_gt(used, 300);
    dfl_mesh_bvh_free(b);
}

/* The sharper bound holds on Wuson: random points in and around the box
 * and points within 1e-2 of vertices, at tolerances from coarse to fine;
 * the returned bound is <= tol, and tol = 0 gives the exact sum. */
Test(mesh_bvh, winding_within_its_bound_on_wuson)
{
    dfl_trimesh m;
    wuson(&m);
    dfl_mesh_bvh *b;
    cr_assert_eq(dfl_mesh_bvh_new(m.verts, m.nverts, m.tris, m.ntris, &b, NULL), DFL_OK);
    uint64_t s = 13;
    const double tols[] = {0.5, 0.05, 1e-3, 0.0};
    int used = 0;
    for (int it = 0; it < 1200; it++) {
        double x[3];
        if (it % 2) {
            const size_t v = (size_t)dfl_rng_splitmix(&s, 0, (double)m.nverts);
            for (int j = 0; j < 3; j++) x[j] = m.verts[3 * v + j] + dfl_rng_splitmix(&s, -1e-2, 1e-2);
        } else {
            for (int j = 0; j < 3; j++) x[j] = dfl_rng_splitmix(&s, -1.2, 1.2);
        }
        const double wx = dfl_winding_brute(m.verts, m.tris, m.ntris, x);
        const double tol = tols[it % 4];
        double B;
        const double w = dfl_mesh_bvh_winding_within(b, x, tol, &B);
        cr_assert_leq(B, tol);
        cr_assert(fabs(w - wx) <= B + 1e-12, "tol %g: |%.17g - %.17g| > bound %g", tol, w, wx, B);
        used += B > 0;
    }
    cr_expect(used > 300, "clusters are used: %d", used);
    dfl_mesh_bvh_free(b);
    dfl_trimesh_free(&m);
}

/* The boundary edges of m (used by exactly one triangle), as vertex pairs
 * into e (2 per edge, capacity 2 * 3 * ntris); returns their count. */
static size_t boundary_edges(const dfl_trimesh *m, size_t *e)
{
    size_t n = 0;
    for (size_t t = 0; t < m->ntris; t++)
        for (int k = 0; k < 3; k++) {
            size_t a = m->tris[3 * t + k], c = m->tris[3 * t + (k + 1) % 3];
            int uses = 0;
            for (size_t u = 0; u < m->ntris && uses < 2; u++)
                for (int l = 0; l < 3; l++) {
                    size_t p = m->tris[3 * u + l], q = m->tris[3 * u + (l + 1) % 3];
                    uses += (p == a && q == c) || (p == c && q == a);
                }
            if (uses == 1) {
                e[2 * n] = a;
                e[2 * n + 1] = c;
                n++;
            }
        }
    return n;
}

/* The inside test is the exact sum's decision w > 1/2 (header) on points
 * where it is hardest: uniform in and around the box, within 1e-3 and
 * 1e-7 of random points of random triangles (both sides of the surface),
 * and within 1e-3 and 1e-7 of random points of Wuson's boundary edges (it
 * is not closed: there w passes through 1/2 on the film across a hole). */
Test(mesh_bvh, inside_equals_the_exact_sum_near_surface_and_boundary)
{
    dfl_trimesh m;
    wuson(&m);
    dfl_mesh_bvh *b;
    cr_assert_eq(dfl_mesh_bvh_new(m.verts, m.nverts, m.tris, m.ntris, &b, NULL), DFL_OK);
    size_t *e = malloc(6 * m.ntris * sizeof *e);
    const size_t ne = boundary_edges(&m, e);
    cr_assert_gt(ne, 0, "Wuson has holes");
    uint64_t s = 77;
    int inside = 0, near_half = 0;
    const int n = 6000;
    for (int it = 0; it < n; it++) {
        double x[3], y[3];
        const int kind = it % 5;
        const double eps = it % 2 ? 1e-3 : 1e-7;
        if (kind == 0) {
            for (int j = 0; j < 3; j++) x[j] = dfl_rng_splitmix(&s, -1, 1);
        } else if (kind <= 2) { /* a random point of a random triangle */
            const size_t t = (size_t)dfl_rng_splitmix(&s, 0, (double)m.ntris);
            double u = dfl_rng_splitmix(&s, 0, 1), v = dfl_rng_splitmix(&s, 0, 1);
            if (u + v > 1) u = 1 - u, v = 1 - v;
            const double *A = m.verts + 3 * m.tris[3 * t], *B = m.verts + 3 * m.tris[3 * t + 1],
                         *C = m.verts + 3 * m.tris[3 * t + 2];
            for (int j = 0; j < 3; j++) y[j] = A[j] + u * (B[j] - A[j]) + v * (C[j] - A[j]);
            for (int j = 0; j < 3; j++) x[j] = y[j] + dfl_rng_splitmix(&s, -eps, eps);
        } else { /* a random point of a boundary edge */
            const size_t k = (size_t)dfl_rng_splitmix(&s, 0, (double)ne);
            const double *A = m.verts + 3 * e[2 * k], *B = m.verts + 3 * e[2 * k + 1];
            const double u = dfl_rng_splitmix(&s, 0, 1);
            for (int j = 0; j < 3; j++) x[j] = A[j] + u * (B[j] - A[j]) + dfl_rng_splitmix(&s, -eps, eps);
        }
        const double wx = dfl_winding_brute(m.verts, m.tris, m.ntris, x);
        inside += wx > 0.5;
        near_half += fabs(wx - 0.5) < 0.1;
        cr_assert_eq(dfl_mesh_bvh_inside(b, x), wx > 0.5, "kind %d at (%.17g %.17g %.17g): w = %.17g",
                     kind, x[0], x[1], x[2], wx);
        cr_assert_eq(dfl_mesh_bvh_inside_traversal(b, x), wx > 0.5, "kind %d at (%.17g %.17g %.17g): w = %.17g",
                     kind, x[0], x[1], x[2], wx);
    }
    cr_expect(inside > n / 10 && inside < n - n / 10, "both sides sampled: %d inside", inside);
    cr_expect(near_half > 50, "points near the film w = 1/2: %d", near_half);
    free(e);
    dfl_mesh_bvh_free(b);
    dfl_trimesh_free(&m);
}

/* The one-pass budget: its bound is at most tol and holds against the
 * exact sum, uniform in and around Wuson and near its triangles. */
Test(mesh_bvh, winding_budget_within_its_bound)
{
    dfl_trimesh m;
    wuson(&m);
    dfl_mesh_bvh *b;
    cr_assert_eq(dfl_mesh_bvh_new(m.verts, m.nverts, m.tris, m.ntris, &b, NULL), DFL_OK);
    uint64_t s = 91;
    const double tols[] = {0.1, 1e-2, 1e-4};
    int used = 0;
    for (int it = 0; it < 1500; it++) {
        double x[3];
        if (it % 2) {
            const size_t v = (size_t)dfl_rng_splitmix(&s, 0, (double)m.nverts);
            for (int j = 0; j < 3; j++) x[j] = m.verts[3 * v + j] + dfl_rng_splitmix(&s, -0.02, 0.02);
        } else {
            for (int j = 0; j < 3; j++) x[j] = dfl_rng_splitmix(&s, -1.2, 1.2);
        }
        const double tol = tols[it % 3];
        double B;
        const double w = dfl_mesh_bvh_winding_budget(b, x, tol, &B);
        const double wb = dfl_winding_brute(m.verts, m.tris, m.ntris, x);
        cr_assert_leq(B, tol * (1 + 1e-12), "bound %g above tol %g", B, tol);
        cr_assert_leq(fabs(w - wb), B + 1e-12, "at (%.17g %.17g %.17g): %.17g vs %.17g, bound %g", x[0],
                      x[1], x[2], w, wb, B);
        used += B > 0;
    }
    cr_expect_gt(used, 1000, "far fields used: %d", used);
    dfl_mesh_bvh_free(b);
    dfl_trimesh_free(&m);
}

/* The traversal decides only past its bound: |W - 1/2| > B + 1e-9.  Built
 * so that a cluster's far-field error is most of its bound while w is just
 * above 1/2: the two-triangle cluster of the far-field tests (normals -x,
 * so that x sees them counter-clockwise and their error W_P - w_P is
 * negative) at x = (R, s/3, s/3), R = 20 rho, behind a 12-triangle fan of
 * radius 1/2 in the plane X = R + eps (normal +x, x behind it: w_fan just
 * below 1/2).  eps is set by bisection so that the exact sum is
 * w = 1/2 + 0.2 |e|, e the cluster's error, so that the clustered sum is
 * W = w + e = 1/2 - 0.8 |e|: on the wrong side, by 0.8 |e| <= 0.8 B, more
 * than half the bound.  The premises are checked (the cluster is one BVH
 * leaf whose bound and value are the pair's alone, the fan is summed
 * exactly, |e| > 0.65 B); then the traversal must not stop at W, and its
 * answer is the exact sum's, inside.  A rule at B / 2 would answer outside. */
Test(mesh_bvh, a_sum_within_its_bound_of_one_half_does_not_decide)
{
    const double s = 1e-2, rho = 0.05, R = 20 * rho, L = 0.5;
    enum { NF = 12 };
    double V[3 * (6 + NF + 1)];
    size_t T[3 * (2 + NF)];
    const double P[18] = {-rho, 0, 0, -rho, 0, s, -rho, s, 0, rho, 0, 0, rho, 0, s, rho, s, 0};
    for (int i = 0; i < 18; i++) V[i] = P[i];
    for (int i = 0; i < 6; i++) T[i] = (size_t)i;
    const double x[3] = {R, s / 3, s / 3};
    /* the pair alone: its clustered value and bound at x, and its error */
    dfl_mesh_bvh *bp;
    cr_assert_eq(dfl_mesh_bvh_new(V, 6, T, 2, &bp, NULL), DFL_OK);
    double Bp;
    const double Wp = dfl_mesh_bvh_winding_within(bp, x, 1.0, &Bp);
    dfl_mesh_bvh_free(bp);
    const double e = Wp - dfl_winding_brute(V, T, 2, x);
    cr_assert(Bp > 0 && e < 0 && -e > 0.65 * Bp, "premise: error %g of bound %g", e, Bp);
    /* the fan: centre vertex 6, rim 7..18, counter-clockwise in (y, z) */
    for (int k = 0; k < NF; k++) {
        T[6 + 3 * k] = 6;
        T[6 + 3 * k + 1] = 7 + (size_t)k;
        T[6 + 3 * k + 2] = 7 + (size_t)((k + 1) % NF);
    }
    double lo = 1e-9, hi = L;
    const double target = 0.5 - 0.2 * e;
    for (int it = 0; it < 200; it++) {
        const double eps = 0.5 * (lo + hi);
        for (int k = 0; k <= NF; k++) {
            const double a = 2 * DFL_PI * (k - 1) / NF, r = k ? L : 0.0;
            V[18 + 3 * k] = R + eps;
            V[18 + 3 * k + 1] = x[1] + r * cos(a);
            V[18 + 3 * k + 2] = x[2] + r * sin(a);
        }
        if (dfl_winding_brute(V, T, 2 + NF, x) > target) lo = eps;
        else hi = eps;
    }
    const double w = dfl_winding_brute(V, T, 2 + NF, x);
    cr_assert(w > 0.5 && fabs(w - target) < 1e-3 * (-e), "w %.17g, target %.17g", w, target);
    dfl_mesh_bvh *b;
    cr_assert_eq(dfl_mesh_bvh_new(V, 6 + NF + 1, T, 2 + NF, &b, NULL), DFL_OK);
    /* premise: stopped at the pair's bound, the traversal holds the pair's
     * far field and the fan's exact sum, on the wrong side of 1/2 */
    double B;
    const double W = dfl_mesh_bvh_winding_within(b, x, 1.0001 * Bp, &B);
    cr_assert(fabs(B - Bp) <= 1e-9 * Bp, "premise: bound %g, the pair's %g", B, Bp);
    const double wfan = dfl_winding_brute(V, T + 6, NF, x);
    cr_assert(fabs(W - (wfan + Wp)) <= 1e-3 * (-e), "premise: W %.17g", W);
    cr_assert(W < 0.5 && 0.5 - W > 0.5 * B && 0.5 - W <= B, "premise: 1/2 - W = %g, B = %g",
              0.5 - W, B);
    cr_expect_eq(dfl_mesh_bvh_inside_traversal(b, x), 1, "w = 1/2 + %g: inside", w - 0.5);
    cr_expect_eq(dfl_mesh_bvh_inside(b, x), 1);
    dfl_mesh_bvh_free(b);
}
