/* Ground-truth fields: exact SDFs pass through; the brute-force-seeded
 * parametric truth agrees with geom's independent surface locator; the
 * implicit truth of the torus quartic is the torus' exact SDF; the config
 * glue picks the truth of the representation. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>

#include "cfg/proxy_input_cfg.h"
#include "core/rng.h"
#include "geom/footpoint.h"
#include "geom/surface_random.h"
#include "io/config.h"
#include "proxy/truth.h"

Test(truth, exact_sphere)
{
    const double c[3] = {0, 0, 0};
    dfl_shape s;
    cr_assert_eq(dfl_shape_sphere(c, 0.5, &s, NULL), DFL_OK);
    dfl_field f;
    cr_assert_eq(dfl_proxy_truth_exact(&s, &f, NULL), DFL_OK);
    double x[3] = {0.3, 0.4, 0}, g[3];
    cr_assert(fabs(dfl_field_eval1(&f, x, g)) < 1e-16 && fabs(g[0] - 0.6) < 1e-15);
    dfl_field_destroy(&f);
}

Test(truth, param_agrees_with_the_locator)
{
    dfl_surface_set set, copy;
    cr_assert_eq(dfl_surface_random_bezier(5, 4, 0.8, 0.4, &set, NULL), DFL_OK);
    cr_assert_eq(dfl_surface_random_bezier(5, 4, 0.8, 0.4, &copy, NULL), DFL_OK);
    dfl_foot_opts fo;
    dfl_foot_opts_default(&fo);
    fo.samples_per_span = 64;
    fo.candidates = 8;
    dfl_surface_locator *L;
    cr_assert_eq(dfl_surface_locator_new(&copy, &fo, &L, NULL), DFL_OK);
    dfl_field f;
    cr_assert_eq(dfl_proxy_truth_param(&set, 0, &f, NULL), DFL_OK);
    uint64_t seed = 77;
    enum { M = 100 };
    double x[3 * M], v[M];
    for (int i = 0; i < 3 * M; i++) x[i] = dfl_rng_splitmix(&seed, -1, 1);
    f.ops->eval(f.ctx, M, x, v, NULL);
    for (int i = 0; i < M; i++) {
        dfl_surface_foot sf;
        cr_assert_eq(dfl_surface_footpoint(L, x + 3 * i, &sf, NULL), DFL_OK);
        cr_assert(fabs(sf.dist - v[i]) < 1e-10, "%g vs %g", v[i], sf.dist);
    }
    dfl_surface_locator_free(L);
    dfl_surface_set_free(&copy);
    dfl_field_destroy(&f);
}

Test(truth, implicit_torus_is_the_exact_sdf)
{
    const double c[3] = {0, 0, 0}, ax[3] = {0, 0, 1};
    dfl_implicit *imp;
    cr_assert_eq(dfl_implicit_torus(c, ax, 0.6, 0.25, NULL, &imp, NULL), DFL_OK);
    dfl_field f;
    cr_assert_eq(dfl_proxy_truth_implicit(&imp, &f, NULL), DFL_OK);
    cr_assert_null(imp);
    const int N = 8;
    for (int k = 0; k < N; k++)
        for (int j = 0; j < N; j++)
            for (int i = 0; i < N; i++) {
                double x[3] = {-1 + (i + 0.5) * 2.0 / N, -1 + (j + 0.5) * 2.0 / N,
                               -1 + (k + 0.5) * 2.0 / N};
                double want = hypot(hypot(x[0], x[1]) - 0.6, x[2]) - 0.25;
                double got = dfl_field_eval1(&f, x, NULL);
                cr_assert(fabs(got - want) < 1e-9, "%g vs %g", got, want);
            }
    dfl_field_destroy(&f);
}

static double truth_at(const char *text, const double x[3])
{
    dfl_cfg *cfg;
    dfl_err err;
    cr_assert_eq(dfl_cfg_parse_string("t.ini", text, &cfg, &err), DFL_OK, "%s", err.msg);
    dfl_field f;
    cr_assert_eq(dfl_proxy_truth_from_cfg(cfg, "field", "shape", &f, &err), DFL_OK, "%s", err.msg);
    double v = dfl_field_eval1(&f, x, NULL);
    dfl_field_destroy(&f);
    dfl_cfg_free(cfg);
    return v;
}

Test(truth, cfg_picks_the_representation)
{
    /* cone frustum a = 0, b = z, ra 0.5, rb 0.1: below the base disc the
     * capped solid is 0.2 away, the open lateral surface sqrt(0.2^2 + 0.5^2) */
    const char *cone = "[shape]\nkind = cone\na = 0 0 0\nb = 0 0 1\nra = 0.5\nrb = 0.1\n";
    char text[512];
    double x[3] = {0, 0, -0.2};
    snprintf(text, sizeof text, "[field]\ninput = sdf\n%s", cone);
    cr_assert(fabs(truth_at(text, x) - 0.2) < 1e-12);
    snprintf(text, sizeof text, "[field]\ninput = parametric\n%s", cone);
    cr_assert(fabs(truth_at(text, x) - hypot(0.2, 0.5)) < 1e-12, "%g", truth_at(text, x));
    double y[3] = {0.9, 0.1, 0.05};
    double want = hypot(hypot(0.9, 0.1) - 0.6, 0.05) - 0.25;
    cr_assert(fabs(truth_at("[field]\ninput = implicit\n[shape]\nkind = torus\ncenter = 0 0 0\n"
                            "axis = 0 0 1\nmajor = 0.6\nminor = 0.25\n",
                            y) -
                   want) < 1e-15);
    cr_assert(fabs(truth_at("[field]\ninput = implicit\n[shape]\nkind = implicit\n"
                            "surface = torus\ncenter = 0 0 0\naxis = 0 0 1\nmajor = 0.6\n"
                            "minor = 0.25\n",
                            y) -
                   want) < 1e-12);
}
