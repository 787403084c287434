/* isoline: marching squares and marching cubes against closed forms
 * (circles, spheres, a torus), topology invariants (closed lines,
 * watertight surfaces, Euler characteristics) and the saddle rule. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "field/isoline.h"

/* |x - c| - r in 2D or 3D (ctx = {dim, cx, cy, cz, r}). */
static void ball_eval(const void *ctx, size_t m, const double *p, double *v, double *g)
{
    const double *c = ctx;
    const int dim = (int)c[0];
    for (size_t i = 0; i < m; i++) {
        double s = 0;
        for (int j = 0; j < dim; j++) s += (p[i * dim + j] - c[1 + j]) * (p[i * dim + j] - c[1 + j]);
        v[i] = sqrt(s) - c[4];
        (void)g;
    }
}
static const dfl_field_ops ball_ops = {"ball", ball_eval, NULL, NULL, NULL};

/* torus R = 0.6, r = 0.25, axis z */
static void torus_eval(const void *ctx, size_t m, const double *p, double *v, double *g)
{
    (void)ctx, (void)g;
    for (size_t i = 0; i < m; i++) {
        const double q = hypot(p[3 * i], p[3 * i + 1]) - 0.6;
        v[i] = hypot(q, p[3 * i + 2]) - 0.25;
    }
}
static const dfl_field_ops torus_ops = {"torus", torus_eval, NULL, NULL, NULL};

static double *sample(const dfl_field *f, const dfl_grid *g)
{
    double *v = malloc(dfl_grid_size(g) * sizeof *v);
    dfl_err err;
    cr_assert_eq(dfl_field_sample(f, g, 1, v, NULL, &err), DFL_OK);
    return v;
}

/* A circle inside the grid: one closed line; linear vertices within the
 * interpolation error h^2 / (8 r) (chord sagitta of the secant through two
 * nodes) and, after refinement, on the circle to rounding. */
Test(isoline, circle_closed_and_refined)
{
    double c[5] = {2, 0.5, 0.4, 0, 0.3};
    dfl_field f = {2, &ball_ops, c};
    dfl_grid g = {2, {41, 37, 1}, {0, 0, 0}, {1, 0.9, 0}};
    double *v = sample(&f, &g);
    dfl_iso iso;
    dfl_err err;
    cr_assert_eq(dfl_iso_lines(&g, v, 0.0, &iso, &err), DFL_OK);
    cr_assert_eq(iso.nlines, 1);
    cr_assert_eq(iso.nclosed, 1);
    const size_t n = iso.line_offsets[1];
    cr_assert_eq(iso.line_conn[0], iso.line_conn[n - 1]);
    cr_assert_eq(n, iso.npoints + 1);
    const double h = 1.0 / 40;
    for (size_t i = 0; i < iso.npoints; i++) {
        const double *p = iso.points + 3 * i;
        cr_expect_lt(fabs(hypot(p[0] - 0.5, p[1] - 0.4) - 0.3), h * h / (8 * (0.3 - h)));
        cr_expect_eq(p[2], 0.0);
    }
    cr_assert_eq(dfl_iso_refine(&iso, &f, 0.0, 40, &err), DFL_OK);
    for (size_t i = 0; i < iso.npoints; i++) {
        const double *p = iso.points + 3 * i;
        cr_expect_lt(fabs(hypot(p[0] - 0.5, p[1] - 0.4) - 0.3), 1e-14);
    }
    /* consecutive points are neighbours on the circle (no jumps across) */
    for (size_t k = 0; k + 1 < n; k++) {
        const double *a = iso.points + 3 * iso.line_conn[k], *b = iso.points + 3 * iso.line_conn[k + 1];
        cr_expect_lt(hypot(a[0] - b[0], a[1] - b[1]), 1.5 * h);
    }
    dfl_vtp_data d;
    dfl_iso_vtp(&iso, &d);
    cr_expect_eq(d.nlines, 1);
    cr_expect_eq(d.npoints, iso.npoints);
    dfl_iso_free(&iso);
    free(v);
}

/* A circle cut by the grid boundary gives open lines ending on it. */
Test(isoline, cut_circle_open)
{
    double c[5] = {2, 0.0, 0.0, 0, 0.5};
    dfl_field f = {2, &ball_ops, c};
    dfl_grid g = {2, {21, 21, 1}, {-0.2, -1, 0}, {1, 1, 0}};
    double *v = sample(&f, &g);
    dfl_iso iso;
    dfl_err err;
    cr_assert_eq(dfl_iso_lines(&g, v, 0.0, &iso, &err), DFL_OK);
    cr_assert_eq(iso.nlines, 1);
    cr_expect_eq(iso.nclosed, 0);
    const size_t n = iso.line_offsets[1];
    cr_expect_eq(n, iso.npoints);
    const double *a = iso.points + 3 * iso.line_conn[0], *b = iso.points + 3 * iso.line_conn[n - 1];
    /* the circle leaves through the edge x = -0.2 at y = +-sqrt(0.21) */
    cr_expect_eq(a[0], -0.2);
    cr_expect_eq(b[0], -0.2);
    cr_expect_lt(fabs(fabs(a[1]) - sqrt(0.21)), 2e-3);
    dfl_iso_free(&iso);
    free(v);
}

/* The saddle: corners 0 and 2 above.  Centre mean above: the above corners
 * connect (the two segments cut off corners 1 and 3), else corners 0, 2. */
Test(isoline, saddle_rule)
{
    dfl_grid g = {2, {2, 2, 1}, {0, 0, 0}, {1, 1, 0}};
    dfl_err err;
    dfl_iso iso;
    const double hi[4] = {1.0, -0.5, -0.5, 1.0};  /* grid order; mean 0.25 >= 0 */
    cr_assert_eq(dfl_iso_lines(&g, hi, 0.0, &iso, &err), DFL_OK);
    cr_assert_eq(iso.nlines, 2);
    for (size_t l = 0; l < 2; l++) {
        const double *a = iso.points + 3 * iso.line_conn[iso.line_offsets[l]];
        const double *b = iso.points + 3 * iso.line_conn[iso.line_offsets[l] + 1];
        const double mx = 0.5 * (a[0] + b[0]), my = 0.5 * (a[1] + b[1]);
        /* cut-off corner is (1,0) or (0,1): the segment midpoint is near it */
        cr_expect(fabs(mx - my) > 0.5, "segment %zu cuts corner 0 or 2", l);
    }
    dfl_iso_free(&iso);
    const double lo[4] = {0.5, -1.0, -1.0, 0.5};  /* mean -0.25 < 0 */
    cr_assert_eq(dfl_iso_lines(&g, lo, 0.0, &iso, &err), DFL_OK);
    cr_assert_eq(iso.nlines, 2);
    for (size_t l = 0; l < 2; l++) {
        const double *a = iso.points + 3 * iso.line_conn[iso.line_offsets[l]];
        const double *b = iso.points + 3 * iso.line_conn[iso.line_offsets[l] + 1];
        const double mx = 0.5 * (a[0] + b[0]), my = 0.5 * (a[1] + b[1]);
        cr_expect(fabs(mx - my) < 0.5, "segment %zu cuts corner 1 or 3", l);
    }
    dfl_iso_free(&iso);
}

/* A section plane z = 0.3 of a sphere of radius 0.5: the circle of radius
 * sqrt(0.25 - 0.09) = 0.4 at height 0.3 (points in 3D). */
Test(isoline, plane_section_of_sphere)
{
    double c[5] = {3, 0, 0, 0, 0.5};
    dfl_field f = {3, &ball_ops, c};
    dfl_grid g;
    const int n[2] = {33, 33};
    const double lo[2] = {-1, -1}, hi[2] = {1, 1};
    dfl_grid_plane(2, 0.3, n, lo, hi, &g);
    double *v = sample(&f, &g);
    dfl_iso iso;
    dfl_err err;
    cr_assert_eq(dfl_iso_lines(&g, v, 0.0, &iso, &err), DFL_OK);
    cr_assert_eq(iso.nclosed, 1);
    cr_assert_eq(dfl_iso_refine(&iso, &f, 0.0, 40, &err), DFL_OK);
    for (size_t i = 0; i < iso.npoints; i++) {
        const double *p = iso.points + 3 * i;
        cr_expect_eq(p[2], 0.3);
        cr_expect_lt(fabs(hypot(p[0], p[1]) - 0.4), 1e-14);
    }
    dfl_iso_free(&iso);
    free(v);
}

/* Watertight closed surface: every directed edge used once and its
 * reverse once (two triangles per edge, consistent orientation); returns
 * V - E + F. */
static int cmp_pair(const void *x, const void *y)
{
    const size_t *a = x, *b = y;
    return a[0] != b[0] ? (a[0] < b[0] ? -1 : 1) : (a[1] < b[1] ? -1 : a[1] > b[1]);
}

static long euler_closed(const dfl_iso *iso)
{
    const size_t nt = iso->ntris, m = 3 * nt;
    size_t *e = malloc(2 * m * sizeof *e);
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++) {
            e[6 * t + 2 * k] = iso->tris[3 * t + k];
            e[6 * t + 2 * k + 1] = iso->tris[3 * t + (k + 1) % 3];
        }
    qsort(e, m, 2 * sizeof *e, cmp_pair);
    size_t bad = 0;
    long ne = 0;
    for (size_t i = 0; i < m; i++) {
        if (i + 1 < m && e[2 * i] == e[2 * i + 2] && e[2 * i + 1] == e[2 * i + 3]) bad++;
        const size_t key[2] = {e[2 * i + 1], e[2 * i]};
        if (!bsearch(key, e, m, 2 * sizeof *e, cmp_pair)) bad++;
        if (e[2 * i] < e[2 * i + 1]) ne++;
    }
    free(e);
    cr_expect_eq(bad, 0, "%zu directed edges repeated or without a reverse", bad);
    return (long)iso->npoints - ne + (long)nt;
}

/* Sphere: vertices on the sphere after refinement, outward normals,
 * Euler characteristic 2. */
Test(isoline, sphere_surface)
{
    double c[5] = {3, 0.05, -0.02, 0.01, 0.5};
    dfl_field f = {3, &ball_ops, c};
    dfl_grid g = {3, {11, 12, 13}, {-1, -1, -1}, {1, 1, 1}};
    double *v = sample(&f, &g);
    dfl_iso iso;
    dfl_err err;
    cr_assert_eq(dfl_iso_surface(&g, v, 0.0, &iso, &err), DFL_OK);
    cr_assert_gt(iso.ntris, 50);
    cr_expect_eq(euler_closed(&iso), 2);
    cr_assert_eq(dfl_iso_refine(&iso, &f, 0.0, 40, &err), DFL_OK);
    for (size_t i = 0; i < iso.npoints; i++) {
        const double *p = iso.points + 3 * i;
        cr_expect_lt(fabs(sqrt((p[0] - 0.05) * (p[0] - 0.05) + (p[1] + 0.02) * (p[1] + 0.02) +
                               (p[2] - 0.01) * (p[2] - 0.01)) - 0.5), 1e-14);
    }
    for (size_t t = 0; t < iso.ntris; t++) {
        const double *a = iso.points + 3 * iso.tris[3 * t], *b = iso.points + 3 * iso.tris[3 * t + 1],
                     *q = iso.points + 3 * iso.tris[3 * t + 2];
        double u[3], w[3], m[3];
        for (int j = 0; j < 3; j++) u[j] = b[j] - a[j], w[j] = q[j] - a[j], m[j] = (a[j] + b[j] + q[j]) / 3 - c[1 + j];
        const double nx = u[1] * w[2] - u[2] * w[1], ny = u[2] * w[0] - u[0] * w[2], nz = u[0] * w[1] - u[1] * w[0];
        cr_expect_geq(nx * m[0] + ny * m[1] + nz * m[2], 0.0, "triangle %zu faces inwards", t);
    }
    dfl_iso_free(&iso);
    free(v);
}

/* Torus: Euler characteristic 0; vertices within the linear-interpolation
 * error before refinement (|d| <= h^2 max|d''| / 8 with d'' <= 1/(dist to
 * the tube's axis) on the edge; generous bound h^2 / (8 * 0.1)). */
Test(isoline, torus_surface)
{
    dfl_field f = {3, &torus_ops, NULL};
    dfl_grid g = {3, {25, 25, 11}, {-1, -1, -0.4}, {1, 1, 0.4}};
    double *v = sample(&f, &g);
    dfl_iso iso;
    dfl_err err;
    cr_assert_eq(dfl_iso_surface(&g, v, 0.0, &iso, &err), DFL_OK);
    cr_expect_eq(euler_closed(&iso), 0);
    const double h = 2.0 / 24 * sqrt(3.0);
    for (size_t i = 0; i < iso.npoints; i++) {
        double val;
        torus_eval(NULL, 1, iso.points + 3 * i, &val, NULL);
        cr_expect_lt(fabs(val), h * h / (8 * 0.1));
    }
    dfl_iso_free(&iso);
    free(v);
}

/* Bad input: a 3D volume for marching squares, a 2D grid for marching
 * cubes, NaN values, a 2D field refining a plane grid. */
Test(isoline, bad_input)
{
    dfl_err err;
    dfl_iso iso;
    dfl_grid g3 = {3, {2, 2, 2}, {0, 0, 0}, {1, 1, 1}};
    double v8[8] = {0};
    cr_expect_eq(dfl_iso_lines(&g3, v8, 0.0, &iso, &err), DFL_E_INPUT);
    dfl_grid g2 = {2, {2, 2, 1}, {0, 0, 0}, {1, 1, 0}};
    cr_expect_eq(dfl_iso_surface(&g2, v8, 0.0, &iso, &err), DFL_E_INPUT);
    double vn[4] = {0, NAN, 1, 1};
    cr_expect_eq(dfl_iso_lines(&g2, vn, 0.0, &iso, &err), DFL_E_INPUT);
    cr_expect_eq(iso.npoints, 0);
    dfl_grid gp;
    const int n[2] = {3, 3};
    const double lo[2] = {0, 0}, hi[2] = {1, 1};
    dfl_grid_plane(2, 0.5, n, lo, hi, &gp);
    double vp[9] = {-1, -1, -1, -1, 1, 1, 1, 1, 1};
    cr_assert_eq(dfl_iso_lines(&gp, vp, 0.0, &iso, &err), DFL_OK);
    double c[5] = {2, 0, 0, 0, 0.5};
    dfl_field f2 = {2, &ball_ops, c};
    cr_expect_eq(dfl_iso_refine(&iso, &f2, 0.0, 5, &err), DFL_E_INPUT);
    dfl_iso_free(&iso);
}

/* isoline.h: a node is "above" when val >= level, so a node exactly at the
 * level with every other node above is no crossing (no line), and with
 * every other node below it is the above corner of one segment. */
Test(isoline, node_at_the_level_is_above)
{
    dfl_grid g = {2, {2, 2, 1}, {0, 0, 0}, {1, 1, 0}};
    dfl_err err;
    dfl_iso iso;
    const double up[4] = {0.0, 1.0, 1.0, 1.0};
    cr_assert_eq(dfl_iso_lines(&g, up, 0.0, &iso, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(iso.nlines, 0);
    dfl_iso_free(&iso);
    const double down[4] = {0.0, -1.0, -1.0, -1.0};
    cr_assert_eq(dfl_iso_lines(&g, down, 0.0, &iso, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(iso.nlines, 1);
    dfl_iso_free(&iso);
}
