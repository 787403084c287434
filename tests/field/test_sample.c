/* sample: grids (volumes, 2D, section planes) and the parallel sampler. */
#include <criterion/criterion.h>
#include <math.h>

#include "field/sample.h"

static void lin_eval(const void *ctx, size_t m, const double *p, double *v, double *g)
{
    (void)ctx;
    for (size_t i = 0; i < m; i++) {
        v[i] = p[3 * i] + 2 * p[3 * i + 1] + 3 * p[3 * i + 2];
        if (g) g[3 * i] = 1, g[3 * i + 1] = 2, g[3 * i + 2] = 3;
    }
}
static const dfl_field_ops lin_ops = {"linear", lin_eval, NULL, NULL};

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
