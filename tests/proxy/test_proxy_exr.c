/* EXR round trip: every storage, order and position; the loaded grid has
 * the same bits and decodes to the same values and gradients. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

#include "core/rng.h"
#include "io/exr.h"
#include "proxy/analytic_inputs.h"
#include "proxy/filter.h"
#include "proxy/proxy_exr.h"
#include "util/tmpdir.h"

static const ta_shape torus = {TA_TORUS, {0.05, -0.02, 0.03}, {0, 0.6, 0.8}, 0.6, 0.25};

Test(proxy_exr, round_trip_bit_identical)
{
    char dir[256], path[512];
    tmpdir_new(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/g.exr", dir);
    dfl_proxy_input in;
    ta_input(&torus, &in);
    for (int s = 0; s < DFL_PROXY_STORAGE_COUNT; s++)
        for (int order = 1; order <= 2; order++)
            for (int pos = 0; pos < 2; pos++) {
                dfl_proxy_build_opts o;
                dfl_proxy_build_opts_default(&o);
                o.order = order;
                o.res = 5; /* 25 scanlines: two ZIP chunks */
                o.storage = (dfl_proxy_storage)s;
                o.position = (dfl_proxy_position)pos;
                o.lo[2] = -1.5;
                o.noise = 1e-3;
                dfl_proxy_grid a, b;
                cr_assert_eq(dfl_proxy_grid_build(&in, &o, &a, NULL), DFL_OK);
                a.stats.uncertified = 3; /* counts travel too */
                dfl_err err;
                cr_assert_eq(dfl_proxy_exr_save(&a, path, &err), DFL_OK, "%s", err.msg);
                cr_assert_eq(dfl_proxy_exr_load(path, &b, &err), DFL_OK, "%s", err.msg);
                cr_expect_eq(b.order, order);
                cr_expect_eq(b.res, 5);
                cr_expect_eq(b.storage, a.storage);
                cr_expect_eq(b.position, a.position);
                cr_expect_eq(b.has_inside, 1);
                cr_expect_eq(b.stats.uncertified, 3);
                cr_expect_eq(memcmp(a.lo, b.lo, sizeof a.lo), 0);
                cr_expect_eq(memcmp(a.h, b.h, sizeof a.h), 0);
                cr_expect_eq(memcmp(a.data, b.data,
                                    dfl_proxy_grid_scalars(&a) * dfl_proxy_storage_size(a.storage)),
                             0, "%s order %d", dfl_proxy_storage_name(a.storage), order);
                cr_expect_eq(a.side == NULL, b.side == NULL);
                if (a.side) cr_expect_eq(memcmp(a.side, b.side, a.ncells), 0);
                uint64_t seed = 1;
                for (int f = 0; f < DFL_PROXY_FILTER_COUNT; f++) {
                    dfl_proxy_filter_opts fo;
                    dfl_proxy_filter_opts_default((dfl_proxy_filter)f, &a, &fo);
                    fo.is_signed = 1;
                    for (int k = 0; k < 50; k++) {
                        double x[3], va, vb, ga[3], gb[3];
                        for (int j = 0; j < 3; j++) x[j] = dfl_rng_splitmix(&seed, -1.2, 1.2);
                        dfl_proxy_filter_eval(&a, &fo, 1, x, &va, ga);
                        dfl_proxy_filter_eval(&b, &fo, 1, x, &vb, gb);
                        cr_expect_eq(memcmp(&va, &vb, sizeof va), 0);
                        cr_expect_eq(memcmp(ga, gb, sizeof ga), 0);
                    }
                }
                dfl_proxy_grid_free(&a);
                dfl_proxy_grid_free(&b);
            }
    tmpdir_remove(dir);
}

Test(proxy_exr, not_a_grid)
{
    char dir[256], path[512];
    tmpdir_new(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/missing.exr", dir);
    dfl_proxy_grid g;
    dfl_err err;
    cr_expect_eq(dfl_proxy_exr_load(path, &g, &err), DFL_E_IO);
    cr_expect(strstr(err.msg, "missing.exr") != NULL);
    snprintf(path, sizeof path, "%s/img.exr", dir);
    const float v[4] = {1, 2, 3, 4};
    dfl_exr_channel ch = {"px", v};
    cr_assert_eq(dfl_exr_write(path, 2, 2, &ch, 1, 0, NULL), DFL_OK);
    cr_expect_eq(dfl_proxy_exr_load(path, &g, &err), DFL_E_IO);
    cr_expect(strstr(err.msg, "not a dflab proxy grid") != NULL, "%s", err.msg);
    cr_expect_null(g.data);
    tmpdir_remove(dir);
}
