/* The dfl_field adapter: the filter's values and gradients, ownership. */
#include <criterion/criterion.h>

#include "proxy/analytic_inputs.h"
#include "proxy/proxy_field.h"

static const ta_shape sphere = {TA_SPHERE, {0.02, -0.03, 0.01}, {0, 0, 1}, 0.5, 0};

Test(proxy_field, adapter)
{
    dfl_proxy_input in;
    ta_input(&sphere, &in);
    dfl_proxy_build_opts bo;
    dfl_proxy_build_opts_default(&bo);
    bo.order = 2;
    bo.res = 8;
    dfl_proxy_grid g, copy;
    cr_assert_eq(dfl_proxy_grid_build(&in, &bo, &g, NULL), DFL_OK);
    cr_assert_eq(dfl_proxy_grid_build(&in, &bo, &copy, NULL), DFL_OK);
    dfl_proxy_filter_opts o;
    dfl_proxy_filter_opts_default(DFL_PROXY_HERMITE, &g, &o);
    o.is_signed = 1;
    dfl_field f;
    dfl_err err;
    o.clip = -1;
    cr_expect_eq(dfl_proxy_field_new(&g, &o, &f, &err), DFL_E_INPUT);
    cr_expect_not_null(g.data);
    o.clip = 0;
    cr_assert_eq(dfl_proxy_field_new(&g, &o, &f, &err), DFL_OK);
    cr_expect_null(g.data);
    cr_expect_eq(f.dim, 3);
    cr_expect_eq(dfl_proxy_field_grid(&f)->res, 8);
    cr_expect_eq(dfl_proxy_field_opts(&f)->filter, DFL_PROXY_HERMITE);
    const double x[3] = {0.3, 0.2, -0.1};
    double gr[3], gw[3], v;
    const double u = dfl_field_eval1(&f, x, gr);
    dfl_proxy_filter_eval(&copy, &o, 1, x, &v, gw);
    cr_expect_eq(u, v);
    for (int j = 0; j < 3; j++) cr_expect_eq(gr[j], gw[j]);
    cr_expect_lt(u, 0);
    dfl_jet jet;
    const double dir[3] = {1, 0, 0};
    cr_expect_eq(dfl_field_jet(&f, x, dir, 2, &jet, NULL), DFL_E_INPUT);
    dfl_field_destroy(&f);
    dfl_proxy_grid_free(&copy);
    cr_expect_null(dfl_proxy_field_grid(&f));
}
