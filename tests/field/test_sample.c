/* sample: grids (volumes, 2D, section planes) and the parallel sampler. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "field/sample.h"

static void lin_eval(const void *ctx, size_t m, const double *p, double *v, double *g)
{
    (void)ctx;
    for (size_t i = 0; i < m; i++) {
        v[i] = p[3 * i] + 2 * p[3 * i + 1] + 3 * p[3 * i + 2];
        if (g) g[3 * i] = 1, g[3 * i + 1] = 2, g[3 * i + 2] = 3;
    }
}
static const dfl_field_ops lin_ops = {"linear", lin_eval, NULL, NULL, NULL};

/* Sampling visits every node once at the right coordinates, x fastest,
 * whatever the thread count. */
Test(sample, grid_order_and_threads)
{
    dfl_grid g = {3, {5, 4, 3}, {-1, 0, 2}, {1, 3, 3}};
    dfl_field f = {3, &lin_ops, NULL};
    size_t m = dfl_grid_size(&g);
    cr_assert_eq(m, 60);
    double v1[60], v2[60], gr[180];
    dfl_err err;
    cr_assert_eq(dfl_field_sample(&f, &g, 1, v1, gr, &err), DFL_OK);
    cr_assert_eq(dfl_field_sample(&f, &g, 2, v2, NULL, &err), DFL_OK);
    for (size_t idx = 0; idx < m; idx++) {
        size_t i = idx % 5, j = (idx / 5) % 4, k = idx / 20;
        double x = -1 + 0.5 * i, y = 0 + 1.0 * j, z = 2 + 0.5 * k;
        cr_expect_float_eq(v1[idx], x + 2 * y + 3 * z, 1e-14);
        cr_expect_eq(v1[idx], v2[idx]);
        cr_expect_eq(gr[3 * idx + 2], 3);
    }
    dfl_grid bad = {2, {1, 4, 1}, {0, 0, 0}, {1, 1, 0}};
    cr_expect_eq(dfl_field_sample(&f, &bad, 1, v1, NULL, &err), DFL_E_INPUT);
}

/* The in-plane axes of a section plane, as the planes always had them. */
static void plane_axes(int axis, int *a0, int *a1)
{
    *a0 = axis == 0 ? 1 : 0;
    *a1 = axis == 2 ? 1 : 2;
}

/* A plane x[axis] = at is a 3D grid with one flat axis: its nodes are
 * those of the plane sampler it replaces, bit for bit (the same
 * interpolation (1 - t) lo + t hi, t = i/(n-1)), in-plane node (i, j) at
 * index i + n0 j. */
Test(sample, plane_nodes)
{
    const int n[2] = {7, 5};
    const double lo[2] = {-0.3, 0.1}, hi[2] = {1.7, 0.9};
    for (int axis = 0; axis < 3; axis++) {
        dfl_grid g;
        dfl_grid_plane(axis, 0.35, n, lo, hi, &g);
        dfl_err err;
        cr_assert_eq(dfl_grid_check(&g, &err), DFL_OK, "%s", err.msg);
        cr_expect_eq(dfl_grid_flat_axis(&g), axis);
        cr_assert_eq(dfl_grid_size(&g), 35);
        cr_expect_eq(dfl_grid_spacing(&g, axis), 0.0);
        int a0, a1;
        plane_axes(axis, &a0, &a1);
        for (size_t idx = 0; idx < 35; idx++) {
            const size_t i = idx % 7, j = idx / 7;
            const double t0 = (double)i / (double)(n[0] - 1), t1 = (double)j / (double)(n[1] - 1);
            double want[3], x[3];
            want[axis] = 0.35;
            want[a0] = (1.0 - t0) * lo[0] + t0 * hi[0];
            want[a1] = (1.0 - t1) * lo[1] + t1 * hi[1];
            dfl_grid_node(&g, idx, x);
            for (int d = 0; d < 3; d++)
                cr_assert_eq(x[d], want[d], "axis %d node %zu coordinate %d", axis, idx, d);
        }
        int dims[3];
        double origin[3], sp[3];
        dfl_grid_frame(&g, dims, origin, sp);
        cr_expect(dims[axis] == 1 && dims[a0] == 7 && dims[a1] == 5);
        cr_expect(origin[axis] == 0.35 && origin[a0] == lo[0] && origin[a1] == lo[1]);
        cr_expect(sp[axis] == 1.0 && sp[a0] == (hi[0] - lo[0]) / 6);
        cr_expect(sp[a1] == (hi[1] - lo[1]) / 4);
    }
    /* volumes and 2D grids have no flat axis */
    const dfl_grid v = {3, {2, 2, 2}, {0, 0, 0}, {1, 1, 1}};
    const dfl_grid s = {2, {2, 3, 1}, {0, 0, 0}, {1, 1, 0}};
    cr_expect_eq(dfl_grid_flat_axis(&v), -1);
    cr_expect_eq(dfl_grid_flat_axis(&s), -1);
    int dims[3];
    double origin[3], sp[3];
    dfl_grid_frame(&s, dims, origin, sp);
    cr_expect(dims[0] == 2 && dims[1] == 3 && dims[2] == 1);
    cr_expect(origin[2] == 0.0 && sp[0] == 1.0 && sp[1] == 0.5 && sp[2] == 1.0);
}

Test(sample, grid_check)
{
    dfl_err err;
    const dfl_grid two_flat = {3, {1, 1, 4}, {0.5, 0.5, 0}, {0.5, 0.5, 1}};
    cr_expect_eq(dfl_grid_check(&two_flat, &err), DFL_E_INPUT);
    const dfl_grid flat_range = {3, {4, 1, 4}, {0, 0, 0}, {1, 1, 1}};
    cr_expect_eq(dfl_grid_check(&flat_range, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "axis 1") != NULL, "%s", err.msg);
    const dfl_grid flat_nan = {3, {4, 1, 4}, {0, NAN, 0}, {1, NAN, 1}};
    cr_expect_eq(dfl_grid_check(&flat_nan, &err), DFL_E_INPUT);
    /* a 2D grid has no flat axis of its own */
    const dfl_grid flat2d = {2, {4, 1, 1}, {0, 0.5, 0}, {1, 0.5, 0}};
    cr_expect_eq(dfl_grid_check(&flat2d, &err), DFL_E_INPUT);
    const dfl_grid empty = {3, {4, 4, 4}, {0, 0, 1}, {1, 1, 1}};
    cr_expect_eq(dfl_grid_check(&empty, &err), DFL_E_INPUT);
    const dfl_grid plane = {3, {4, 4, 1}, {0, 0, 0.5}, {1, 1, 0.5}};
    cr_expect_eq(dfl_grid_check(&plane, &err), DFL_OK, "%s", err.msg);
    /* sample.h: n >= 2 on every axis of a 2D grid, even with a non-empty
     * range (one node cannot span [lo, hi]) */
    const dfl_grid one2d = {2, {4, 1, 1}, {0, 0, 0}, {1, 1, 0}};
    cr_expect_eq(dfl_grid_check(&one2d, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "axis 1") != NULL, "%s", err.msg);
}

/* Records the size of every eval call and the points it was given. */
typedef struct recorder {
    size_t calls, sizes[64];
    double pts[3 * 700];
    size_t npts;
} recorder;

static void record_eval(const void *ctx, size_t m, const double *p, double *v, double *g)
{
    recorder *r = (recorder *)ctx; /* one thread in this test */
    r->sizes[r->calls++] = m;
    for (size_t i = 0; i < m; i++) {
        for (int d = 0; d < 3; d++) r->pts[3 * r->npts + (size_t)d] = p[3 * i + (size_t)d];
        r->npts++;
        v[i] = p[3 * i] - p[3 * i + 2];
        if (g) g[3 * i] = 1, g[3 * i + 1] = 0, g[3 * i + 2] = -1;
    }
}
static const dfl_field_ops record_ops = {"record", record_eval, NULL, NULL, NULL};

/* A plane is sampled in chunks of 256 nodes in index order, one eval call
 * per chunk, at the grid's nodes; the values land at their node. */
Test(sample, plane_chunks)
{
    dfl_grid g;
    dfl_grid_plane(1, -0.25, (const int[2]){29, 23}, (const double[2]){0, 0},
                   (const double[2]){1, 2}, &g);
    static recorder r;
    memset(&r, 0, sizeof r);
    dfl_field f = {3, &record_ops, &r};
    double v[667], gr[3 * 667];
    dfl_err err;
    cr_assert_eq(dfl_field_sample(&f, &g, 1, v, gr, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(r.calls, 3);
    cr_expect(r.sizes[0] == 256 && r.sizes[1] == 256 && r.sizes[2] == 155);
    for (size_t idx = 0; idx < 667; idx++) {
        double x[3];
        dfl_grid_node(&g, idx, x);
        for (int d = 0; d < 3; d++) cr_assert_eq(r.pts[3 * idx + (size_t)d], x[d]);
        cr_assert_eq(v[idx], x[0] - x[2]);
        cr_assert_eq(gr[3 * idx + 2], -1);
    }
    /* a 2D field on a plane: DFL_E_INPUT */
    dfl_field f2 = {2, &record_ops, &r};
    cr_expect_eq(dfl_field_sample(&f2, &g, 1, v, NULL, &err), DFL_E_INPUT);
}
