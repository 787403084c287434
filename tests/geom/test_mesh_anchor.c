/* geom/mesh_anchor.h against brute force: the crossing count equals an
 * independent parametric count (Cramer's rule) and refuses segments
 * through a shared edge, a vertex or with an end on a triangle; the
 * estimate w(c) + J is within its margin of the exact sum; and the sign it
 * decides is the exact sum's w > 1/2 on Wuson and on small open meshes,
 * with most points decided by the anchors (not by the traversal). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "core/rng.h"
#include "geom/mesh_anchor.h"
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

/* One triangle (normal +z), an open box (the cube without its two
 * triangles of z = 1) and two triangles that run their shared edge the
 * same way (inconsistent orientation: net count 2 on it). */
static void single(dfl_trimesh *m)
{
    static const double v[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const size_t t[] = {0, 1, 2};
    mf_take(v, 3, t, 1, m);
}

static void open_box(dfl_trimesh *m)
{
    mf_cube(m);
    for (size_t i = 6; i < 30; i++) m->tris[i] = m->tris[i + 6]; /* drop z = 1 */
    m->ntris = 10;
}

static void inconsistent(dfl_trimesh *m)
{
    static const double v[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0.3};
    static const size_t t[] = {0, 1, 2, 1, 2, 3};
    mf_take(v, 4, t, 2, m);
}

/* The crossings by Cramer's rule on c + s (x - c) = A + u e1 + v e2:
 * +1 when 0 < s < 1, u, v > 0, u + v < 1 and x - c points against the
 * normal e1 x e2 (from the normal side to the back), -1 along it; *hits
 * counts the triangles crossed. */
static int brute_crossings(const dfl_trimesh *m, const double *c, const double *x, int *hits)
{
    int J = 0;
    *hits = 0;
    for (size_t t = 0; t < m->ntris; t++) {
        const double *A = m->verts + 3 * m->tris[3 * t], *B = m->verts + 3 * m->tris[3 * t + 1],
                     *C = m->verts + 3 * m->tris[3 * t + 2];
        double e1[3], e2[3], d[3], r[3];
        for (int j = 0; j < 3; j++) {
            e1[j] = B[j] - A[j];
            e2[j] = C[j] - A[j];
            d[j] = c[j] - x[j]; /* -(x - c) */
            r[j] = c[j] - A[j];
        }
        /* [e1 e2 d] (u v s)^T = r */
        const double det = e1[0] * (e2[1] * d[2] - e2[2] * d[1]) - e2[0] * (e1[1] * d[2] - e1[2] * d[1]) +
                           d[0] * (e1[1] * e2[2] - e1[2] * e2[1]);
        if (det == 0.0) continue;
        const double u = (r[0] * (e2[1] * d[2] - e2[2] * d[1]) - e2[0] * (r[1] * d[2] - r[2] * d[1]) +
                          d[0] * (r[1] * e2[2] - r[2] * e2[1])) / det;
        const double v = (e1[0] * (r[1] * d[2] - r[2] * d[1]) - r[0] * (e1[1] * d[2] - e1[2] * d[1]) +
                          d[0] * (e1[1] * r[2] - e1[2] * r[1])) / det;
        const double s = (e1[0] * (e2[1] * r[2] - e2[2] * r[1]) - e2[0] * (e1[1] * r[2] - e1[2] * r[1]) +
                          r[0] * (e1[1] * e2[2] - e1[2] * e2[1])) / det;
        if (s > 0 && s < 1 && u > 0 && v > 0 && u + v < 1) {
            double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                           e1[0] * e2[1] - e1[1] * e2[0]};
            J += n[0] * d[0] + n[1] * d[1] + n[2] * d[2] > 0 ? 1 : -1;
            ++*hits;
        }
    }
    return J;
}

Test(mesh_anchor, crossings_of_constructed_segments)
{
    dfl_trimesh m;
    single(&m);
    int J = 99;
    const double tol = 1e-9;
    const double up[3] = {0.2, 0.2, 1}, down[3] = {0.2, 0.2, -1};
    cr_assert_eq(dfl_mesh_anchor_crossings(m.verts, m.tris, NULL, 1, up, down, tol, &J), 0);
    cr_expect_eq(J, 1, "normal side to back: +1");
    cr_assert_eq(dfl_mesh_anchor_crossings(m.verts, m.tris, NULL, 1, down, up, tol, &J), 0);
    cr_expect_eq(J, -1, "back to normal side: -1");
    const double miss0[3] = {0.6, 0.6, 1}, miss1[3] = {0.6, 0.6, -1};
    cr_assert_eq(dfl_mesh_anchor_crossings(m.verts, m.tris, NULL, 1, miss0, miss1, tol, &J), 0);
    cr_expect_eq(J, 0, "beyond the hypotenuse");
    const double e0[3] = {0.5, 0, 1}, e1[3] = {0.5, 0, -1};
    cr_expect_eq(dfl_mesh_anchor_crossings(m.verts, m.tris, NULL, 1, e0, e1, tol, &J), -1,
                 "through an edge: refused");
    const double v0[3] = {0, 0, 1}, v1[3] = {0, 0, -1};
    cr_expect_eq(dfl_mesh_anchor_crossings(m.verts, m.tris, NULL, 1, v0, v1, tol, &J), -1,
                 "through a vertex: refused");
    const double on[3] = {0.2, 0.2, 0};
    cr_expect_eq(dfl_mesh_anchor_crossings(m.verts, m.tris, NULL, 1, on, up, tol, &J), -1,
                 "an end on the triangle: refused");
    const double near_plane[3] = {0.2, 0.2, 1e-10};
    cr_expect_eq(dfl_mesh_anchor_crossings(m.verts, m.tris, NULL, 1, near_plane, up, tol, &J), -1,
                 "an end within tol of the triangle: refused");
    const double off_side[3] = {2, 2, 0};
    cr_assert_eq(dfl_mesh_anchor_crossings(m.verts, m.tris, NULL, 1, off_side, up, tol, &J), 0,
                 "an end in the plane beside the triangle is clear");
    cr_expect_eq(J, 0);
    dfl_trimesh_free(&m);

    /* the cube: the diagonal edge of face z = -1 is shared by two triangles */
    mf_cube(&m);
    const double a[3] = {0.3, 0.3, 0}, b[3] = {0.3, 0.3, -2}; /* on the diagonal x = y */
    cr_expect_eq(dfl_mesh_anchor_crossings(m.verts, m.tris, NULL, m.ntris, a, b, tol, &J), -1,
                 "through a shared edge: refused, not counted once or twice");
    const double a2[3] = {0.3, -0.4, 0}, b2[3] = {0.3, -0.4, -2};
    cr_assert_eq(dfl_mesh_anchor_crossings(m.verts, m.tris, NULL, m.ntris, a2, b2, tol, &J), 0);
    cr_expect_eq(J, -1, "out through the bottom face: from its back (inside) to its normal side");
    dfl_trimesh_free(&m);
}

/* Random segments through and around the cube, the octahedron and Wuson:
 * every count that is not refused equals the parametric count, and the
 * refusals are rare (generic segments meet no edge). */
Test(mesh_anchor, crossings_equal_the_parametric_count)
{
    dfl_trimesh ms[3];
    mf_cube(&ms[0]);
    mf_octahedron(&ms[1]);
    wuson(&ms[2]);
    uint64_t s = 5;
    for (int k = 0; k < 3; k++) {
        int refused = 0, crossed = 0;
        const int n = k == 2 ? 2000 : 5000;
        for (int it = 0; it < n; it++) {
            double c[3], x[3];
            for (int j = 0; j < 3; j++) {
                c[j] = dfl_rng_splitmix(&s, -1.5, 1.5);
                x[j] = dfl_rng_splitmix(&s, -1.5, 1.5);
            }
            int J;
            if (dfl_mesh_anchor_crossings(ms[k].verts, ms[k].tris, NULL, ms[k].ntris, c, x, 1e-9, &J)) {
                refused++;
                continue;
            }
            int hits;
            const int Jb = brute_crossings(&ms[k], c, x, &hits);
            cr_assert_eq(J, Jb, "mesh %d, (%g %g %g) -> (%g %g %g): %d vs %d", k, c[0], c[1], c[2],
                         x[0], x[1], x[2], J, Jb);
            crossed += hits > 0;
        }
        cr_expect_lt(refused, n / 100, "mesh %d: %d refused", k, refused);
        cr_expect_gt(crossed, n / 20, "mesh %d: segments that cross: %d", k, crossed);
        /* closed meshes: w jumps by the count and is constant between */
        if (k < 2)
            for (int it = 0; it < 200; it++) {
                double c[3], x[3];
                for (int j = 0; j < 3; j++) {
                    c[j] = dfl_rng_splitmix(&s, -1.5, 1.5);
                    x[j] = dfl_rng_splitmix(&s, -1.5, 1.5);
                }
                int J;
                if (dfl_mesh_anchor_crossings(ms[k].verts, ms[k].tris, NULL, ms[k].ntris, c, x, 1e-9, &J))
                    continue;
                const double dw = dfl_winding_brute(ms[k].verts, ms[k].tris, ms[k].ntris, x) -
                                  dfl_winding_brute(ms[k].verts, ms[k].tris, ms[k].ntris, c);
                cr_assert_lt(fabs(dw - J), 1e-9, "closed mesh %d: w(x) - w(c) = %g, J = %d", k, dw, J);
            }
        dfl_trimesh_free(&ms[k]);
    }
}

/* Points where the sign is hard: uniform in and around the box, near
 * random points of random triangles, near vertices, near random points of
 * the edges of nonzero net count (the holes' rims, the inconsistent edge)
 * at 1e-3 and 1e-7. */
static void sample(const dfl_trimesh *m, const size_t *be, size_t nbe, uint64_t *s, int it, double *x)
{
    const int kind = it % 4;
    const double eps = it % 8 < 4 ? 1e-3 : 1e-7;
    if (kind == 0 || (kind == 3 && nbe == 0)) {
        for (int j = 0; j < 3; j++) x[j] = dfl_rng_splitmix(s, -1.6, 1.6);
    } else if (kind == 1) {
        const size_t t = (size_t)dfl_rng_splitmix(s, 0, (double)m->ntris);
        double u = dfl_rng_splitmix(s, 0, 1), v = dfl_rng_splitmix(s, 0, 1);
        if (u + v > 1) u = 1 - u, v = 1 - v;
        const double *A = m->verts + 3 * m->tris[3 * t], *B = m->verts + 3 * m->tris[3 * t + 1],
                     *C = m->verts + 3 * m->tris[3 * t + 2];
        for (int j = 0; j < 3; j++)
            x[j] = A[j] + u * (B[j] - A[j]) + v * (C[j] - A[j]) + dfl_rng_splitmix(s, -eps, eps);
    } else if (kind == 2) {
        const size_t v = (size_t)dfl_rng_splitmix(s, 0, (double)m->nverts);
        for (int j = 0; j < 3; j++) x[j] = m->verts[3 * v + j] + dfl_rng_splitmix(s, -0.02, 0.02);
    } else {
        const size_t k = (size_t)dfl_rng_splitmix(s, 0, (double)nbe);
        const double *A = m->verts + 3 * be[2 * k], *B = m->verts + 3 * be[2 * k + 1];
        const double u = dfl_rng_splitmix(s, 0, 1);
        for (int j = 0; j < 3; j++) x[j] = A[j] + u * (B[j] - A[j]) + dfl_rng_splitmix(s, -eps, eps);
    }
}

/* The edges {a, b} whose net count (+1 per triangle running a -> b,
 * -1 per triangle running b -> a) is not 0, by a quadratic search. */
static size_t net_edges(const dfl_trimesh *m, size_t *e)
{
    size_t n = 0;
    for (size_t t = 0; t < m->ntris; t++)
        for (int k = 0; k < 3; k++) {
            const size_t a = m->tris[3 * t + k], c = m->tris[3 * t + (k + 1) % 3];
            int net = 0, first = 1;
            for (size_t u = 0; u < m->ntris; u++)
                for (int l = 0; l < 3; l++) {
                    const size_t p = m->tris[3 * u + l], q = m->tris[3 * u + (l + 1) % 3];
                    net += (p == a && q == c) - (p == c && q == a);
                    if ((u < t || (u == t && l < k)) && ((p == a && q == c) || (p == c && q == a)))
                        first = 0;
                }
            if (net != 0 && first) {
                e[2 * n] = a;
                e[2 * n + 1] = c;
                n++;
            }
        }
    return n;
}

/* min_decided: the least fraction the anchors must decide; tight: the
 * largest |w - est| / margin must exceed it (a margin that small would
 * fail the bound check); sheet: w < 1 everywhere (one triangle). */
static void check_mesh(dfl_trimesh *m, int n, uint64_t seed, double min_decided, double tight,
                       int sheet, const char *name)
{
    dfl_mesh_bvh *b;
    cr_assert_eq(dfl_mesh_bvh_new(m->verts, m->nverts, m->tris, m->ntris, &b, NULL), DFL_OK);
    const dfl_mesh_anchor *a = dfl_mesh_bvh_anchors(b);
    cr_assert_not_null(a);
    size_t *be = malloc(6 * m->ntris * sizeof *be);
    const size_t nbe = net_edges(m, be);
    uint64_t s = seed;
    int decided = 0, inside = 0, estimated = 0;
    double worst = 0.0; /* the largest |w - est| / margin */
    double worst_near[2] = {0.0, 0.0};
    int near_estimated = 0;
    for (int it = 0; it < n; it++) {
        double x[3];
        sample(m, be, nbe, &s, it, x);
        const double w = dfl_winding_brute(m->verts, m->tris, m->ntris, x);
        int in;
        if (dfl_mesh_anchor_decide(a, x, &in)) {
            decided++;
            cr_assert_eq(in, w > 0.5, "%s: anchor at (%.17g %.17g %.17g): w = %.17g", name, x[0], x[1],
                         x[2], w);
        }
        cr_assert_eq(dfl_mesh_bvh_inside(b, x), w > 0.5, "%s: at (%.17g %.17g %.17g): w = %.17g", name,
                     x[0], x[1], x[2], w);
        inside += w > 0.5;
        double est, margin;
        if (dfl_mesh_anchor_estimate(a, x, &est, &margin)) {
            estimated++;
            cr_assert_leq(fabs(w - est), margin + 1e-12, "%s: at (%.17g %.17g %.17g): w = %.17g, est %.17g "
                          "margin %.3g", name, x[0], x[1], x[2], w, est, margin);
            if (margin > 0) worst = fmax(worst, fabs(w - est) / margin);
        }
        /* the second chance, as decide stops it and with every near edge */
        const double stops[2] = {1e-9, INFINITY};
        for (int k = 0; k < 2; k++)
            if (dfl_mesh_anchor_estimate_near(a, x, stops[k], &est, &margin)) {
                near_estimated++;
                cr_assert_leq(fabs(w - est), margin + 1e-12, "%s near (stop %g): at (%.17g %.17g %.17g): "
                              "w = %.17g, est %.17g margin %.3g", name, stops[k], x[0], x[1], x[2], w,
                              est, margin);
                if (margin > 0) worst_near[k] = fmax(worst_near[k], fabs(w - est) / margin);
            }
    }
    if (sheet)
        cr_expect_eq(inside, 0, "%s: a single triangle's w is at most 1/2", name);
    else
        cr_expect(inside > 0 && inside < n, "%s: both sides sampled: %d inside", name, inside);
    cr_expect_gt(worst, tight, "%s: the margin is attained within %g: %g", name, tight, worst);
    cr_expect_geq(decided, (int)(min_decided * n), "%s: the anchors decided %d of %d", name, decided, n);
    cr_expect_gt(estimated, n / 2, "%s: %d estimated", name, estimated);
    cr_expect_gt(near_estimated, n, "%s: %d estimated with near edges exact", name, near_estimated);
    cr_expect_gt(worst_near[0], tight, "%s: the second chance's margin is attained within %g: %g",
                 name, tight, worst_near[0]);
    cr_log_info("%s: second chance worst |w - est| / margin %.3g (stop 1e-9), %.3g (all exact)", name,
                worst_near[0], worst_near[1]);
    cr_log_info("%s: decided %d / %d, worst |w - est| / margin %.3f", name, decided, n, worst);
    free(be);
    dfl_mesh_bvh_free(b);
    dfl_trimesh_free(m);
}

Test(mesh_anchor, sign_is_the_exact_sums_on_wuson)
{
    dfl_trimesh m;
    wuson(&m);
    check_mesh(&m, 6000, 77, 0.6, 0.1, 0, "wuson");
}

Test(mesh_anchor, sign_is_the_exact_sums_on_small_open_meshes)
{
    dfl_trimesh m;
    /* Half of the points of a single sheet lie within 1e-3 of it or of its
     * rim, where w is near 1/2 behind it or passes through 1/2: the
     * anchors can decide only the rest.  Near the middle of a long edge
     * with a short segment along the field the margin is nearly the true
     * change (|grad w| -> 1/(2 pi rho)): more than half of it is
     * reached, so a margin half as large would fail the bound check. */
    single(&m);
    check_mesh(&m, 4000, 3, 0.3, 0.5, 1, "single triangle");
    open_box(&m);
    check_mesh(&m, 4000, 4, 0.6, 0.5, 0, "open box");
    inconsistent(&m);
    check_mesh(&m, 4000, 5, 0.3, 0.5, 0, "inconsistent pair");
}

/* A soup of small random triangles (every edge on a rim) would need more
 * cells than the cap of 64 per triangle and 2^18 (header): it gets no anchors, and
 * the inside test is still the exact sum's. */
Test(mesh_anchor, a_soup_beyond_the_caps_gets_no_anchors)
{
    const size_t n = 3000;
    double *v = malloc(9 * n * sizeof *v);
    size_t *t = malloc(3 * n * sizeof *t);
    uint64_t s = 8;
    for (size_t i = 0; i < n; i++) {
        double c[3];
        for (int j = 0; j < 3; j++) c[j] = dfl_rng_splitmix(&s, -1, 1);
        for (int k = 0; k < 3; k++) {
            for (int j = 0; j < 3; j++) v[9 * i + 3 * k + j] = c[j] + dfl_rng_splitmix(&s, -0.1, 0.1);
            t[3 * i + k] = 3 * i + (size_t)k;
        }
    }
    dfl_mesh_bvh *b;
    cr_assert_eq(dfl_mesh_bvh_new(v, 3 * n, t, n, &b, NULL), DFL_OK);
    cr_expect_null(dfl_mesh_bvh_anchors(b));
    for (int it = 0; it < 200; it++) {
        double x[3];
        for (int j = 0; j < 3; j++) x[j] = dfl_rng_splitmix(&s, -1.2, 1.2);
        cr_assert_eq(dfl_mesh_bvh_inside(b, x), dfl_winding_brute(v, t, n, x) > 0.5);
    }
    dfl_mesh_bvh_free(b);
    free(v);
    free(t);
}

/* The hint is a triangle near x (the closest to x's leaf anchor): within
 * 1e-3 of a Wuson vertex most leaves are small, so on average its distance
 * from x exceeds x's own by less than 0.01 (a triangle chosen at random is
 * about 0.5 away; leaves over flat parts with few triangles are larger);
 * outside the root cube or not finite: none (and no estimate or decision:
 * a NaN coordinate must locate no leaf). */
Test(mesh_anchor, hint_is_a_triangle_near_x_or_none)
{
    dfl_trimesh m;
    wuson(&m);
    dfl_mesh_bvh *b;
    cr_assert_eq(dfl_mesh_bvh_new(m.verts, m.nverts, m.tris, m.ntris, &b, NULL), DFL_OK);
    const dfl_mesh_anchor *a = dfl_mesh_bvh_anchors(b);
    cr_assert_not_null(a);
    uint64_t s = 19;
    double excess = 0.0;
    for (int it = 0; it < 500; it++) {
        const size_t v = (size_t)dfl_rng_splitmix(&s, 0, (double)m.nverts);
        double x[3];
        for (int j = 0; j < 3; j++) x[j] = m.verts[3 * v + j] + dfl_rng_splitmix(&s, -1e-3, 1e-3);
        const size_t t = dfl_mesh_anchor_hint(a, x);
        cr_assert_lt(t, m.ntris);
        const size_t *T = m.tris + 3 * t;
        const double dt = dfl_tridist_closest(x, m.verts + 3 * T[0], m.verts + 3 * T[1],
                                              m.verts + 3 * T[2], NULL, NULL);
        dfl_mesh_hit h;
        dfl_mesh_bvh_closest(b, x, &h);
        cr_assert_geq(dt, h.d);
        excess += dt - h.d;
    }
    cr_expect_lt(excess / 500, 0.01, "mean excess distance of the hint %g", excess / 500);
    cr_log_info("hint: mean excess distance %g", excess / 500);
    const double out[3] = {10.0, 0.0, 0.0}, nan[3] = {0.0, NAN, 0.0};
    cr_expect_eq(dfl_mesh_anchor_hint(a, out), SIZE_MAX);
    cr_expect_eq(dfl_mesh_anchor_hint(a, nan), SIZE_MAX);
    /* not finite: no leaf, so no estimate and no decision either (on every
     * axis, NaN and both infinities) */
    static const double odd[3] = {NAN, INFINITY, -INFINITY};
    for (int j = 0; j < 3; j++)
        for (int q = 0; q < 3; q++) {
            double x[3] = {0.01, 0.02, 0.03}, est = 7, margin = 7;
            int inside = 7;
            x[j] = odd[q];
            cr_expect_eq(dfl_mesh_anchor_hint(a, x), SIZE_MAX, "axis %d %g", j, odd[q]);
            cr_expect_eq(dfl_mesh_anchor_estimate(a, x, &est, &margin), 0, "axis %d %g", j, odd[q]);
            cr_expect_eq(dfl_mesh_anchor_estimate_near(a, x, INFINITY, &est, &margin), 0);
            cr_expect_eq(dfl_mesh_anchor_decide(a, x, &inside), 0, "axis %d %g", j, odd[q]);
            cr_expect(est == 7 && margin == 7 && inside == 7, "untouched");
        }
    dfl_mesh_bvh_free(b);
    dfl_trimesh_free(&m);
}
