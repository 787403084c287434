/* Order-2 grids on dflab's real inputs (proxy/input_*.h): sphere,
 * cylinder and plane proxies are exact near the surface for every input
 * the shape has (SDF with analytic curvature; the sphere also parametric
 * and implicit); a torus is exact at its equators through every input. */
#include <criterion/criterion.h>
#include <math.h>

#include "core/rng.h"
#include "geom/implicit.h"
#include "geom/shape.h"
#include "proxy/filter.h"
#include "proxy/input_implicit.h"
#include "proxy/input_param.h"
#include "proxy/input_sdf.h"

static const double C[3] = {0.01, -0.02, 0.03};

/* max |D - sdf| of each near-surface cell's proxy at points within h/2 */
static double near_err(dfl_proxy_input *in, double (*sdf)(const double *), int res)
{
    dfl_proxy_build_opts o;
    dfl_proxy_build_opts_default(&o);
    o.order = 2;
    o.res = res;
    dfl_proxy_grid g;
    dfl_err err;
    cr_assert_eq(dfl_proxy_grid_build(in, &o, &g, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(g.stats.uncertified + g.stats.failed, 0, "%s", in->name);
    const double h = dfl_proxy_cell_size(&g);
    uint64_t seed = 5;
    double worst = 0;
    for (size_t c = 0; c < g.ncells; c++) {
        double xc[3], x[3];
        dfl_proxy_cell_centre(&g, c, xc);
        if (fabs(sdf(xc)) > h) continue;
        for (int q = 0; q < 4; q++) {
            for (int j = 0; j < 3; j++) x[j] = xc[j] + dfl_rng_splitmix(&seed, -h / 2, h / 2);
            const double e = fabs(dfl_proxy_proxy_dist(&g, c, DFL_PROXY_CLIP_BOUND, 0, x, NULL) - sdf(x));
            if (e > worst) worst = e;
        }
    }
    dfl_proxy_grid_free(&g);
    dfl_proxy_input_free(in);
    return worst;
}

static double sphere_sdf(const double *x)
{
    return sqrt((x[0] - C[0]) * (x[0] - C[0]) + (x[1] - C[1]) * (x[1] - C[1]) +
                (x[2] - C[2]) * (x[2] - C[2])) - 0.5;
}

static const double AX[3] = {0.6, 0, 0.8};
static double cylinder_sdf(const double *x)
{
    const double w[3] = {x[0] - C[0], x[1] - C[1], x[2] - C[2]};
    const double z = w[0] * AX[0] + w[1] * AX[1] + w[2] * AX[2];
    return sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2] - z * z) - 0.4;
}

static const double NP[3] = {0.48, 0.6, 0.64};
static double plane_sdf(const double *x)
{
    return (x[0] - C[0]) * NP[0] + (x[1] - C[1]) * NP[1] + (x[2] - C[2]) * NP[2];
}

Test(proxy_inputs, order2_exact_for_every_input)
{
    dfl_proxy_input in;
    dfl_shape s;
    cr_assert_eq(dfl_shape_sphere(C, 0.5, &s, NULL), DFL_OK);
    cr_assert_eq(dfl_proxy_input_sdf(&s, DFL_PROXY_CURV_ANALYTIC, NULL, &in, NULL), DFL_OK);
    cr_expect_lt(near_err(&in, sphere_sdf, 12), 1e-10, "sphere sdf");
    cr_assert_eq(dfl_proxy_input_param_sphere(C, 0.5, NULL, &in, NULL), DFL_OK);
    cr_expect_lt(near_err(&in, sphere_sdf, 12), 1e-10, "sphere parametric");
    dfl_implicit *imp;
    cr_assert_eq(dfl_implicit_sphere(C, 0.5, NULL, &imp, NULL), DFL_OK);
    cr_assert_eq(dfl_proxy_input_implicit(&imp, DFL_IMPLICIT_FOOT_ROBUST, &in, NULL), DFL_OK);
    cr_expect_lt(near_err(&in, sphere_sdf, 12), 1e-10, "sphere implicit");
    cr_assert_eq(dfl_shape_cylinder(C, AX, 0.4, &s, NULL), DFL_OK);
    cr_assert_eq(dfl_proxy_input_sdf(&s, DFL_PROXY_CURV_ANALYTIC, NULL, &in, NULL), DFL_OK);
    cr_expect_lt(near_err(&in, cylinder_sdf, 12), 1e-10, "cylinder sdf");
    cr_assert_eq(dfl_shape_plane(3, C, NP, &s, NULL), DFL_OK);
    cr_assert_eq(dfl_proxy_input_sdf(&s, DFL_PROXY_CURV_ANALYTIC, NULL, &in, NULL), DFL_OK);
    cr_expect_lt(near_err(&in, plane_sdf, 12), 1e-10, "plane sdf");
}
