/* geom/mesh.h: the mesh shape.  Expected values: the octahedron's closed
 * form (inside, the distance to the nearest face plane, (1 - |x|_1)/sqrt 3;
 * outside, brute force), the unsigned mode, gradients against central
 * differences where the closest feature does not change, jets against the
 * gradient and second differences, and Wuson: every value finite. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "field/meshdist.h"
#include "geom/mesh.h"
#include "geom/mesh_bvh.h"
#include "geom/trimesh.h"
#include "mesh_fixtures.h"

static void make(dfl_trimesh *m, dfl_mesh_distance dist, dfl_shape *s)
{
    dfl_err err;
    cr_assert_eq(dfl_shape_mesh(m, dist, s, &err), DFL_OK, "%s", err.msg);
    cr_assert_null(m->verts, "taken over");
}

static void wuson_shape(dfl_shape *s)
{
    dfl_trimesh m;
    dfl_err err;
    cr_assert_eq(dfl_trimesh_read(WUSON, &m, &err), DFL_OK, "%s", err.msg);
    const double c[3] = {0, 0, 0};
    dfl_trimesh_fit(&m, c, 1.6);
    make(&m, DFL_MESH_SIGNED, s);
}

Test(mesh, octahedron_closed_form_and_sign)
{
    dfl_trimesh m;
    mf_octahedron(&m);
    dfl_shape s, u;
    make(&m, DFL_MESH_SIGNED, &s);
    mf_octahedron(&m);
    make(&m, DFL_MESH_UNSIGNED, &u);
    cr_expect_eq(s.dim, 3);
    const dfl_trimesh *T = dfl_shape_mesh_trimesh(&s);
    cr_assert_not_null(T);
    cr_expect_eq(T->ntris, 8);
    uint64_t r = 1;
    for (int it = 0; it < 2000; it++) {
        double x[3], g[3];
        for (int j = 0; j < 3; j++) x[j] = dfl_rng_splitmix(&r, -2, 2);
        const double l1 = fabs(x[0]) + fabs(x[1]) + fabs(x[2]);
        const double d = dfl_shape_eval1(&s, x, g), du = dfl_shape_eval1(&u, x, NULL);
        cr_assert_eq(du, dfl_meshdist_eval(T, x), "unsigned: the brute-force distance");
        cr_assert_eq(fabs(d), du);
        if (l1 < 1) {
            cr_expect(d < 0, "inside is negative");
            cr_expect_float_eq(d, -(1 - l1) / sqrt(3.0), 1e-14, "at (%g %g %g)", x[0], x[1], x[2]);
            /* gradient: the outward normal of the face of sign(x) */
            for (int j = 0; j < 3; j++)
                if (x[j] != 0) cr_expect_float_eq(g[j], copysign(1 / sqrt(3.0), x[j]), 1e-12);
        } else if (l1 > 1) {
            cr_expect(d > 0);
        }
        cr_expect_float_eq(g[0] * g[0] + g[1] * g[1] + g[2] * g[2], 1.0, 1e-13);
    }
    /* on the surface: +0 and the face normal */
    const double on[3] = {0.25, 0.25, 0.5};
    double g[3];
    cr_expect_eq(dfl_shape_eval1(&s, on, g), 0.0);
    cr_expect_float_eq(g[2], 1 / sqrt(3.0), 1e-15);
    dfl_shape_free(&s);
    dfl_shape_free(&u);
}

/* Closest triangle and feature at x (the branch of d at x). */
static void branch(const dfl_shape *s, const double *x, size_t *tri, int *feat, double *d)
{
    const dfl_trimesh *T = dfl_shape_mesh_trimesh(s);
    *d = INFINITY;
    for (size_t t = 0; t < T->ntris; t++) {
        dfl_tri_feature f;
        double e = dfl_tridist_closest(x, T->verts + 3 * T->tris[3 * t], T->verts + 3 * T->tris[3 * t + 1],
                                       T->verts + 3 * T->tris[3 * t + 2], NULL, &f);
        if (e < *d) *d = e, *tri = t, *feat = (int)f;
    }
}

Test(mesh, wuson_gradient_and_jets_off_the_medial_axis, .timeout = 120)
{
    dfl_shape s;
    wuson_shape(&s);
    uint64_t r = 21;
    const double h = 1e-6;
    int checked = 0, feats[3] = {0, 0, 0};
    for (int it = 0; it < 400; it++) {
        double x[3], g[3], dir[3];
        for (int j = 0; j < 3; j++) {
            x[j] = dfl_rng_splitmix(&r, -1, 1);
            dir[j] = dfl_rng_splitmix(&r, -1, 1);
        }
        const double d = dfl_shape_eval1(&s, x, g);
        size_t t0;
        int f0;
        double e0;
        branch(&s, x, &t0, &f0, &e0);
        /* the same branch (triangle, feature, side) at the 6 stencil points
         * and along +-h dir: off the medial axis and off region boundaries */
        int same = 1;
        double fd[3];
        for (int j = 0; j < 3 && same; j++) {
            double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]};
            xp[j] += h;
            xm[j] -= h;
            size_t tp, tm;
            int fp, fm;
            double ep, em;
            branch(&s, xp, &tp, &fp, &ep);
            branch(&s, xm, &tm, &fm, &em);
            const double dp = dfl_shape_eval1(&s, xp, NULL), dm = dfl_shape_eval1(&s, xm, NULL);
            same = tp == t0 && tm == t0 && fp == f0 && fm == f0 && (dp > 0) == (d > 0) &&
                   (dm > 0) == (d > 0);
            fd[j] = (dp - dm) / (2 * h);
        }
        if (!same) continue;
        checked++;
        feats[f0 == DFL_TRI_FACE ? 0 : (f0 == DFL_TRI_VERT_A || f0 == DFL_TRI_VERT_B || f0 == DFL_TRI_VERT_C) ? 2 : 1]++;
        for (int j = 0; j < 3; j++)
            cr_expect(fabs(g[j] - fd[j]) < 1e-6, "grad %d: %.12g vs fd %.12g (feature %d)", j, g[j],
                      fd[j], f0);
        dfl_jet J;
        dfl_err err;
        cr_assert_eq(dfl_shape_jet(&s, x, dir, 3, &J, &err), DFL_OK, "%s", err.msg);
        cr_expect_float_eq(dfl_jet_deriv(&J, 0), d, 1e-15);
        const double gd = g[0] * dir[0] + g[1] * dir[1] + g[2] * dir[2];
        cr_expect_float_eq(dfl_jet_deriv(&J, 1), gd, 1e-12);
        const double k = 1e-4;
        double xp[3], xm[3];
        for (int j = 0; j < 3; j++) xp[j] = x[j] + k * dir[j], xm[j] = x[j] - k * dir[j];
        size_t tp, tm;
        int fp, fm;
        double ep, em;
        branch(&s, xp, &tp, &fp, &ep);
        branch(&s, xm, &tm, &fm, &em);
        if (tp == t0 && tm == t0 && fp == f0 && fm == f0) {
            const double d2 = (dfl_shape_eval1(&s, xp, NULL) - 2 * d + dfl_shape_eval1(&s, xm, NULL)) / (k * k);
            cr_expect(fabs(dfl_jet_deriv(&J, 2) - d2) < 1e-4 * (1 + fabs(d2)), "d2 %.12g vs %.12g (feature %d)",
                      dfl_jet_deriv(&J, 2), d2, f0);
        }
    }
    cr_expect(checked > 300, "most random points are off the medial axis: %d", checked);
    cr_expect(feats[0] > 0 && feats[1] > 0 && feats[2] > 0, "faces %d, edges %d, vertices %d",
              feats[0], feats[1], feats[2]);
    dfl_shape_free(&s);
}

Test(mesh, face_jet_is_linear_and_hessian_vanishes)
{
    dfl_trimesh m;
    mf_octahedron(&m);
    dfl_shape s;
    make(&m, DFL_MESH_SIGNED, &s);
    const double x[3] = {0.1, 0.2, 0.3}; /* inside, closest to face (+,+,+) */
    dfl_shape_derivs D;
    dfl_err err;
    cr_assert_eq(dfl_shape_derivs_at(&s, x, &D, &err), DFL_OK, "%s", err.msg);
    cr_expect_float_eq(D.d, -(1 - 0.6) / sqrt(3.0), 1e-15);
    for (int j = 0; j < 9; j++) cr_expect(fabs(D.H[j]) < 1e-12, "H[%d] = %g", j, D.H[j]);
    cr_expect(fabs(D.dxyz) < 1e-10);
    /* outside next to a vertex: d = |x - v|, H = (I - u u^T) / d */
    const double y[3] = {1.5, 0.1, -0.05};
    cr_assert_eq(dfl_shape_derivs_at(&s, y, &D, &err), DFL_OK, "%s", err.msg);
    const double p[3] = {0.5, 0.1, -0.05}, dd = sqrt(0.25 + 0.01 + 0.0025);
    cr_expect_float_eq(D.d, dd, 1e-15);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double want = ((i == j) - p[i] * p[j] / (dd * dd)) / dd;
            cr_expect_float_eq(D.H[3 * i + j], want, 1e-9, "H[%d][%d]", i, j);
        }
    dfl_shape_free(&s);
}

Test(mesh, wuson_every_value_finite_and_batched)
{
    dfl_shape s;
    wuson_shape(&s);
    const int n = 24;
    const size_t N = (size_t)n * n * n;
    double *p = malloc(3 * N * sizeof *p), *v = malloc(N * sizeof *v), *g = malloc(3 * N * sizeof *g);
    for (size_t i = 0; i < N; i++) {
        p[3 * i] = -1 + 2.0 * (i % n) / (n - 1);
        p[3 * i + 1] = -1 + 2.0 * (i / n % n) / (n - 1);
        p[3 * i + 2] = -1 + 2.0 * (i / n / n) / (n - 1);
    }
    dfl_shape_eval(&s, N, p, v, g);
    int inside = 0;
    for (size_t i = 0; i < N; i++) {
        cr_assert(isfinite(v[i]) && isfinite(g[3 * i]) && isfinite(g[3 * i + 1]) && isfinite(g[3 * i + 2]));
        inside += v[i] < 0;
        double one = dfl_shape_eval1(&s, p + 3 * i, NULL);
        cr_assert_eq(one, v[i], "batch = single");
    }
    cr_expect(inside > 100 && inside < (int)N / 2, "Wuson has an inside: %d of %zu", inside, N);
    free(p), free(v), free(g);
    dfl_shape_free(&s);
}

Test(mesh, accessor_and_refusal)
{
    dfl_shape c;
    dfl_err err;
    const double o[3] = {0, 0, 0};
    cr_assert_eq(dfl_shape_sphere(o, 1, &c, &err), DFL_OK);
    cr_expect_null(dfl_shape_mesh_trimesh(&c));
    cr_expect(isnan(dfl_shape_mesh_winding(&c, o, NULL)));
    dfl_shape_free(&c);
    dfl_trimesh m;
    mf_octahedron(&m);
    m.tris[2] = m.tris[1];
    dfl_shape s = {0};
    cr_expect_eq(dfl_shape_mesh(&m, DFL_MESH_SIGNED, &s, &err), DFL_E_INPUT);
    cr_expect_not_null(m.verts, "left with the caller on failure");
    cr_expect_null(s.impl);
    dfl_trimesh_free(&m);
}

/* mesh_bvh.h: a point with a NaN or infinite coordinate gets distance NaN
 * (signed and unsigned, gradient NaN too) without a crash or a read outside
 * the mesh's arrays, and its winding number NaN; the other points of a
 * batch get what they get alone.  The anchors locate no leaf for it
 * (mesh_anchor.h: not finite, no estimate, no decision, no hint). */
Test(mesh, nan_and_infinite_points_are_nan)
{
    for (int dist = 0; dist < 2; dist++) {
        dfl_shape s;
        dfl_trimesh m;
        cr_assert_eq(dfl_trimesh_read(WUSON, &m, NULL), DFL_OK);
        const double c[3] = {0, 0, 0};
        dfl_trimesh_fit(&m, c, 1.6);
        make(&m, dist ? DFL_MESH_UNSIGNED : DFL_MESH_SIGNED, &s);
        enum { M = 12 };
        double x[3 * M], v[M], g[3 * M];
        uint64_t seed = 41;
        for (int i = 0; i < 3 * M; i++) x[i] = dfl_rng_splitmix(&seed, -1, 1);
        static const double odd[3] = {NAN, INFINITY, -INFINITY};
        for (int a = 0; a < 3; a++)
            for (int q = 0; q < 3; q++) x[3 * (1 + q + 3 * (a % 3)) + a] = odd[q];
        dfl_shape_eval(&s, M, x, v, g);
        for (int i = 0; i < M; i++) {
            const int fin = isfinite(x[3 * i]) && isfinite(x[3 * i + 1]) && isfinite(x[3 * i + 2]);
            if (!fin) {
                cr_expect(isnan(v[i]) && isnan(g[3 * i]) && isnan(g[3 * i + 1]) &&
                              isnan(g[3 * i + 2]),
                          "dist %d point %d: %g", dist, i, v[i]);
                cr_expect(isnan(dfl_shape_mesh_winding(&s, x + 3 * i, NULL)), "point %d", i);
                continue;
            }
            double g1[3];
            const double v1 = dfl_shape_eval1(&s, x + 3 * i, g1);
            cr_expect(v1 == v[i] && g1[0] == g[3 * i] && g1[1] == g[3 * i + 1] &&
                          g1[2] == g[3 * i + 2],
                      "dist %d point %d: batch = single", dist, i);
        }
        dfl_shape_free(&s);
    }
}

/* The fold of d and its gradient (shape.h's dfl_shape_eval_unsigned rule):
 * values < 0 and their gradients negated, everything else as given. */
static void fold(size_t m, double *v, double *g)
{
    for (size_t i = 0; i < m; i++)
        if (v[i] < 0) {
            v[i] = -v[i];
            for (int j = 0; j < 3; j++) g[3 * i + j] = -g[3 * i + j];
        }
}

/* geom/shape.h: dfl_shape_eval_unsigned is eval with values < 0 and their
 * gradients negated, bit for bit.  A mesh computes it without the winding
 * number (its own op): on Wuson (open rims, so the sign is the winding
 * number's) at points of the box, near its vertices (where the sign test
 * is hardest), on the surface (d = 0: the face normal, not negated) and
 * at a NaN point; signed and unsigned modes, with and without gradient;
 * and the same through the fold for a shape without the op (a sphere). */
Test(mesh, eval_unsigned_is_the_folded_signed_eval_bit_for_bit, .timeout = 120)
{
    dfl_shape s;
    wuson_shape(&s);
    cr_assert_not_null(s.ops->eval_unsigned, "a mesh has its own unsigned evaluation");
    const dfl_trimesh *T = dfl_shape_mesh_trimesh(&s);
    enum { N = 6000 };
    double *p = malloc(3 * N * sizeof *p), *v = malloc(N * sizeof *v), *g = malloc(3 * N * sizeof *g),
           *u = malloc(N * sizeof *u), *gu = malloc(3 * N * sizeof *gu), *u2 = malloc(N * sizeof *u2);
    cr_assert(p && v && g && u && gu && u2);
    uint64_t r = 11;
    for (size_t i = 0; i < N; i++) {
        if (i % 2) {
            for (int j = 0; j < 3; j++) p[3 * i + j] = dfl_rng_splitmix(&r, -1, 1);
        } else {
            const size_t k = (size_t)dfl_rng_splitmix(&r, 0, (double)T->nverts);
            for (int j = 0; j < 3; j++)
                p[3 * i + j] = T->verts[3 * k + j] + dfl_rng_splitmix(&r, -0.02, 0.02);
        }
    }
    /* a vertex (d = 0) and a NaN point */
    for (int j = 0; j < 3; j++) p[j] = T->verts[j], p[3 + j] = NAN;
    dfl_shape_eval(&s, N, p, v, g);
    dfl_shape_eval_unsigned(&s, N, p, u, gu);
    dfl_shape_eval_unsigned(&s, N, p, u2, NULL);
    int neg = 0;
    for (size_t i = 0; i < N; i++) neg += v[i] < 0;
    cr_expect(neg > N / 20, "points inside: %d", neg);
    cr_expect_eq(v[0], 0.0, "a vertex is on the surface");
    fold(N, v, g);
    cr_expect(memcmp(v, u, N * sizeof *v) == 0, "values: |d| bit for bit");
    cr_expect(memcmp(g, gu, 3 * N * sizeof *g) == 0, "gradients: sgn(d) grad d bit for bit");
    cr_expect(memcmp(v, u2, N * sizeof *v) == 0, "values without gradient");
    cr_expect(isnan(u[1]));
    dfl_shape_free(&s);
    /* unsigned mode: eval is already |d| */
    dfl_trimesh m;
    dfl_err err;
    cr_assert_eq(dfl_trimesh_read(WUSON, &m, &err), DFL_OK, "%s", err.msg);
    const double c[3] = {0, 0, 0};
    dfl_trimesh_fit(&m, c, 1.6);
    make(&m, DFL_MESH_UNSIGNED, &s);
    dfl_shape_eval(&s, N, p, v, g);
    dfl_shape_eval_unsigned(&s, N, p, u, gu);
    cr_expect(memcmp(v, u, N * sizeof *v) == 0 && memcmp(g, gu, 3 * N * sizeof *g) == 0);
    dfl_shape_free(&s);
    /* a shape without the op: eval and the fold */
    const double ctr[3] = {0.1, -0.2, 0.05};
    cr_assert_eq(dfl_shape_sphere(ctr, 0.5, &s, &err), DFL_OK);
    cr_assert_null(s.ops->eval_unsigned);
    dfl_shape_eval(&s, N, p, v, g);
    dfl_shape_eval_unsigned(&s, N, p, u, gu);
    neg = 0;
    for (size_t i = 0; i < N; i++) neg += v[i] < 0;
    cr_expect(neg > N / 20, "points inside the sphere: %d", neg);
    fold(N, v, g);
    cr_expect(memcmp(v, u, N * sizeof *v) == 0 && memcmp(g, gu, 3 * N * sizeof *g) == 0);
    dfl_shape_free(&s);
    free(p), free(v), free(g), free(u), free(gu), free(u2);
}
