/* Grid building: layout, counts, options, thread-count independence, and
 * exactness of order-2 sphere grids through the stored scalars. */
#include <criterion/criterion.h>
#include <math.h>
#include <omp.h>
#include <string.h>

#include "core/rng.h"
#include "proxy/analytic_inputs.h"
#include "proxy/filter.h"
#include "proxy/proxy.h"

static const ta_shape sphere = {TA_SPHERE, {0.02, -0.03, 0.01}, {0, 0, 1}, 0.5, 0};

Test(proxy_grid, layout_and_centres)
{
    dfl_proxy_build_opts o;
    dfl_proxy_build_opts_default(&o);
    o.res = 4;
    o.lo[0] = 0;
    o.hi[2] = 3;
    dfl_proxy_input in;
    ta_input(&sphere, &in);
    dfl_proxy_grid g;
    cr_assert_eq(dfl_proxy_grid_build(&in, &o, &g, NULL), DFL_OK);
    cr_expect_eq(g.ncells, 64);
    cr_expect_eq(g.nscalar, 3);
    cr_expect_not_null(g.side);
    double x[3];
    dfl_proxy_cell_centre(&g, 1 + 4 * (2 + 4 * 3), x);
    cr_expect_float_eq(x[0], 0.375, 1e-15);
    cr_expect_float_eq(x[1], 0.25, 1e-15);
    cr_expect_float_eq(x[2], 2.5, 1e-15);
    cr_expect_float_eq(dfl_proxy_cell_size(&g), 1.0, 1e-15);
    cr_expect_eq(g.stats.uncertified + g.stats.failed + g.stats.moved, 0);
    /* stored displacement = footpoint - centre */
    dfl_surfpoint sp;
    ta_answer(&sphere, x, &sp);
    const double *d = (const double *)g.data + 3 * (1 + 4 * (2 + 4 * 3));
    for (int j = 0; j < 3; j++) cr_expect_float_eq(d[j], sp.p[j] - x[j], 1e-15);
    dfl_proxy_grid_free(&g);
    dfl_proxy_grid_free(&g);
}

Test(proxy_grid, bad_options)
{
    dfl_proxy_input in;
    ta_input(&sphere, &in);
    dfl_proxy_build_opts o;
    dfl_proxy_grid g;
    dfl_err err;
    dfl_proxy_build_opts_default(&o);
    o.res = 0;
    cr_expect_eq(dfl_proxy_grid_build(&in, &o, &g, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "res") != NULL);
    dfl_proxy_build_opts_default(&o);
    o.order = 3;
    cr_expect_eq(dfl_proxy_grid_build(&in, &o, &g, &err), DFL_E_INPUT);
    dfl_proxy_build_opts_default(&o);
    o.lo[1] = 2;
    cr_expect_eq(dfl_proxy_grid_build(&in, &o, &g, &err), DFL_E_INPUT);
    dfl_proxy_build_opts_default(&o);
    o.noise = -1;
    cr_expect_eq(dfl_proxy_grid_build(&in, &o, &g, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_proxy_grid_build(NULL, &o, &g, &err), DFL_E_INPUT);
    cr_expect_null(g.data);
}

static void build_with_threads(int nt, const dfl_proxy_build_opts *o, dfl_proxy_grid *g)
{
    dfl_proxy_input in;
    ta_input(&sphere, &in);
    const int save = omp_get_max_threads();
    omp_set_num_threads(nt);
    cr_assert_eq(dfl_proxy_grid_build(&in, o, g, NULL), DFL_OK);
    omp_set_num_threads(save);
}

Test(proxy_grid, same_at_any_thread_count_with_noise)
{
    dfl_proxy_build_opts o;
    dfl_proxy_build_opts_default(&o);
    o.order = 2;
    o.res = 13;
    o.storage = DFL_PROXY_HALF;
    o.noise = 0.01;
    o.seed = 5;
    dfl_proxy_grid a, b;
    build_with_threads(1, &o, &a);
    build_with_threads(2, &o, &b);
    cr_expect_eq(memcmp(a.data, b.data, dfl_proxy_grid_scalars(&a) * 2), 0);
    /* the noise moved every footpoint by 0.01 (up to half rounding): each
     * cell's decoded footpoint lies 0.01 from the true one */
    size_t off = 0;
    for (size_t c = 0; c < (size_t)13 * 13 * 13; c++) {
        dfl_proxy_geom pg;
        double x[3];
        dfl_proxy_cell_decode(&a, c, &pg);
        dfl_proxy_cell_centre(&a, c, x);
        dfl_surfpoint sp;
        ta_answer(&sphere, x, &sp);
        double v[3] = {pg.p[0] - sp.p[0], pg.p[1] - sp.p[1], pg.p[2] - sp.p[2]};
        off += !(fabs(sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) - 0.01) <= 1e-3);
    }
    cr_expect_eq(off, 0, "%zu of 2197 footpoints not moved by 0.01", off);
    dfl_proxy_grid_free(&a);
    dfl_proxy_grid_free(&b);
}

/* Order 2 in double: every proxy near the surface is the sphere itself. */
Test(proxy_grid, order2_sphere_exact_through_storage)
{
    dfl_proxy_input in;
    ta_input(&sphere, &in);
    for (int pos = 0; pos < 2; pos++) {
        dfl_proxy_build_opts o;
        dfl_proxy_build_opts_default(&o);
        o.order = 2;
        o.position = (dfl_proxy_position)pos;
        dfl_proxy_grid g;
        cr_assert_eq(dfl_proxy_grid_build(&in, &o, &g, NULL), DFL_OK);
        const double h = dfl_proxy_cell_size(&g);
        uint64_t seed = 3;
        double worst = 0;
        for (size_t c = 0; c < g.ncells; c++) {
            double xc[3], x[3];
            dfl_proxy_cell_centre(&g, c, xc);
            if (fabs(ta_sdf(&sphere, xc)) > h) continue;
            for (int j = 0; j < 3; j++) x[j] = xc[j] + dfl_rng_splitmix(&seed, -h / 2, h / 2);
            double e = fabs(dfl_proxy_proxy_dist(&g, c, DFL_PROXY_CLIP_BOUND, 0, x, NULL) - ta_sdf(&sphere, x));
            if (e > worst) worst = e;
        }
        cr_expect_lt(worst, 1e-10, "position %d", pos);
        dfl_proxy_grid_free(&g);
    }
}

static dfl_status failing_query(const void *ctx, size_t m, const double *x, int need_curv,
                                dfl_surfpoint *out, dfl_err *err)
{
    (void)ctx;
    (void)need_curv;
    for (size_t i = 0; i < m; i++) {
        ta_answer(&sphere, x + 3 * i, &out[i]);
        out[i].certified = x[3 * i] > 0;
        if (x[3 * i + 1] > 0.9) return dfl_err_set(err, DFL_E_NUMERIC, "query failed");
        if (x[3 * i + 1] < -0.8) out[i].p[0] = NAN;
    }
    return DFL_OK;
}

Test(proxy_grid, counts_and_errors)
{
    dfl_proxy_input in = {"t", failing_query, NULL, NULL, 1};
    dfl_proxy_build_opts o;
    dfl_proxy_build_opts_default(&o);
    o.res = 8;
    o.hi[1] = 0.8; /* keeps y <= 0.9: no query error */
    dfl_proxy_grid g;
    cr_assert_eq(dfl_proxy_grid_build(&in, &o, &g, NULL), DFL_OK);
    cr_expect_eq(g.stats.uncertified, 256);
    cr_expect_eq(g.stats.failed, 64); /* the first row, y = -0.8875 */
    dfl_proxy_grid_free(&g);
    dfl_proxy_build_opts_default(&o);
    dfl_err err;
    cr_expect_eq(dfl_proxy_grid_build(&in, &o, &g, &err), DFL_E_NUMERIC);
    cr_expect_str_eq(err.msg, "query failed");
    cr_expect_null(g.data);
}

/* Cell centres on the surface (a plane through a layer of centres), with
 * the footpoint stored absolutely in half precision, where a footpoint
 * moved by delta alone would round back onto the centre: every such cell
 * is moved until its normal survives, and decodes to the plane within the
 * documented offset. */
Test(proxy_grid, centres_on_surface_half_absolute)
{
    static const ta_shape plane = {TA_PLANE, {0.3, -0.2, -0.125}, {0, 0, 1}, 0, 0};
    dfl_proxy_input in;
    ta_input(&plane, &in);
    for (int order = 1; order <= 2; order++)
        for (int pos = 0; pos < 2; pos++) {
            dfl_proxy_build_opts o;
            dfl_proxy_build_opts_default(&o);
            o.order = order;
            o.res = 8;
            o.storage = DFL_PROXY_HALF;
            o.position = (dfl_proxy_position)pos;
            dfl_proxy_grid g;
            cr_assert_eq(dfl_proxy_grid_build(&in, &o, &g, NULL), DFL_OK);
            cr_expect_eq(g.stats.moved, 64, "order %d %s", order, dfl_proxy_position_name(pos));
            for (size_t c = 3 * 64; c < 4 * 64; c++) {
                dfl_proxy_geom pg;
                dfl_proxy_cell_decode(&g, c, &pg);
                cr_expect_float_eq(pg.n[2], 1.0, 1e-3, "cell %zu", c);
                double xc[3];
                dfl_proxy_cell_centre(&g, c, xc);
                xc[2] += 0.1;
                /* moved by at most 8 delta = 8 h 2^-10 (|x_c| < 2), plus rounding */
                cr_expect_lt(fabs(dfl_proxy_proxy_dist(&g, c, DFL_PROXY_CLIP_BOUND, 0, xc, NULL) - 0.1), 3e-3);
            }
            dfl_proxy_grid_free(&g);
        }
}

/* noise_cell: only that cell's stored scalars differ from the noiseless
 * grid (the paper's variant, one footpoint moved); -1 moves every cell's.
 * Out-of-range cells are refused. */
Test(proxy_grid, noise_on_one_cell_only)
{
    dfl_proxy_build_opts o;
    dfl_proxy_build_opts_default(&o);
    cr_expect_eq(o.noise_cell, -1, "the default moves every footpoint");
    o.res = 6;
    dfl_proxy_grid clean, one, all;
    build_with_threads(1, &o, &clean);
    o.noise = 0.01;
    o.noise_cell = 3 + 6 * (2 + 6 * 4);
    build_with_threads(1, &o, &one);
    o.noise_cell = -1;
    build_with_threads(1, &o, &all);
    size_t differ_one = 0, differ_all = 0, which = 0;
    const size_t ns = (size_t)clean.nscalar;
    for (size_t c = 0; c < clean.ncells; c++) {
        const double *a = (const double *)clean.data + ns * c;
        if (memcmp(a, (const double *)one.data + ns * c, ns * sizeof(double)) != 0)
            differ_one++, which = c;
        if (memcmp(a, (const double *)all.data + ns * c, ns * sizeof(double)) != 0) differ_all++;
    }
    cr_expect_eq(differ_one, 1);
    cr_expect_eq(which, (size_t)(3 + 6 * (2 + 6 * 4)));
    cr_expect_eq(differ_all, clean.ncells, "every footpoint moves without noise_cell");
    dfl_proxy_grid_free(&clean);
    dfl_proxy_grid_free(&one);
    dfl_proxy_grid_free(&all);
    dfl_proxy_input in;
    ta_input(&sphere, &in);
    dfl_proxy_grid g;
    dfl_err err;
    o.noise_cell = 216;
    cr_expect_eq(dfl_proxy_grid_build(&in, &o, &g, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "noise cell 216") != NULL, "%s", err.msg);
    o.noise_cell = -2;
    cr_expect_eq(dfl_proxy_grid_build(&in, &o, &g, &err), DFL_E_INPUT);
    o.noise_cell = 215;
    cr_expect_eq(dfl_proxy_grid_build(&in, &o, &g, &err), DFL_OK, "%s", err.msg);
    dfl_proxy_grid_free(&g);
}
