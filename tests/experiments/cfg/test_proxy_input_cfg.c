/* [field] input keys -> proxy inputs: each representation a shape offers
 * builds, one it lacks exits 2 (DFL_E_INPUT) naming the key. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cfg_util.h"
#include "cfg/proxy_input_cfg.h"

static dfl_status build(const char *text, dfl_proxy_input *in, dfl_err *err)
{
    dfl_cfg *cfg = tu_cfg("t.ini", text);
    dfl_status st = dfl_proxy_input_from_cfg(cfg, "field", "shape", in, err);
    if (st == DFL_OK) cr_assert_eq(dfl_cfg_check_used(cfg, err), DFL_OK, "%s", err->msg);
    dfl_cfg_free(cfg);
    return st;
}

Test(proxy_input_cfg, sdf_sphere_default_keys)
{
    dfl_proxy_input in;
    dfl_err err;
    cr_assert_eq(build("[field]\n[shape]\nkind = sphere\ncenter = 0 0 0\n"
                       "radius = 0.5\n",
                       &in, &err),
                 DFL_OK, "%s", err.msg);
    cr_assert_str_eq(in.name, "sdf");
    double x[3] = {0.9, 0, 0};
    dfl_surfpoint o;
    cr_assert_eq(dfl_proxy_input_query(&in, 1, x, 1, &o, NULL), DFL_OK);
    cr_assert(fabs(o.d - 0.4) < 1e-15 && fabs(o.curv.k1 - 2) < 1e-9);
    dfl_proxy_input_free(&in);
}

Test(proxy_input_cfg, sdf_fit_keys)
{
    dfl_proxy_input in;
    dfl_err err;
    cr_assert_eq(build("[field]\ninput = sdf\ncurvature = fit\nfit_grid = 7\nfit_spacing = 0.005\n"
                       "footpoint = paper\nparam_grid = 8\nparam_starts = 1\n"
                       "[shape]\nkind = sphere\ncenter = 0 0 0\nradius = 0.5\n",
                       &in, &err),
                 DFL_OK, "%s", err.msg);
    double x[3] = {0.3, 0.4, 0.5};
    dfl_surfpoint o;
    cr_assert_eq(dfl_proxy_input_query(&in, 1, x, 1, &o, NULL), DFL_OK);
    /* the fit's quartic aliasing, ~ (3 h)^2 / r^3 = 1.8e-3 (proxy/curvfit.h) */
    cr_assert(fabs(o.curv.k1 - 2) < 2e-3 && fabs(o.curv.k2 - 2) < 2e-3, "%g %g", o.curv.k1,
              o.curv.k2);
    dfl_proxy_input_free(&in);
}

static void expect_reject(const char *text, const char *key, const char *what)
{
    dfl_proxy_input in = {0};
    dfl_err err;
    cr_assert_eq(build(text, &in, &err), DFL_E_INPUT, "%s", text);
    cr_assert(strstr(err.msg, "t.ini") && strstr(err.msg, key), "%s", err.msg);
    if (what) cr_assert(strstr(err.msg, what), "%s", err.msg);
    cr_assert_null(in.ctx);
}

Test(proxy_input_cfg, bad_keys_name_the_key)
{
    expect_reject("[field]\ninput = implicit\n[shape]\nkind = box\ncenter = 0 0 0\nhalf = 1 1 1\n",
                  "input", "offers: sdf");
    expect_reject("[field]\ninput = sdf\n[shape]\nkind = bezier_surface\n", "input", "no sdf");
    expect_reject("[field]\ninput = parametric\n[shape]\nkind = implicit\n", "input",
                  "offers: implicit");
    expect_reject("[field]\ninput = mesh\n[shape]\nkind = sphere\n", "input", NULL);
    expect_reject("[field]\ncurvature = fit\nfit_spacing = 0\n[shape]\nkind = sphere\n",
                  "fit_spacing", NULL);
    expect_reject("[field]\nfit_grid = 2\n[shape]\nkind = sphere\n", "fit_grid", NULL);
    expect_reject("[field]\nfootpoint = fast\n[shape]\nkind = sphere\n", "footpoint", NULL);
    expect_reject("[field]\nparam_starts = 4\n[shape]\nkind = sphere\n", "param_starts", NULL);
    expect_reject("[field]\nimplicit_resolution = 4\n[shape]\nkind = sphere\n",
                  "implicit_resolution", NULL);
}

/* Every hvb25 shape file builds every representation the table says it
 * offers (and the random Bezier patch is the seed's). */
Test(proxy_input_cfg, implicit_footpoint_methods)
{
    const char *m[2] = {"paper", "robust"};
    for (int k = 0; k < 2; k++) {
        char text[256];
        snprintf(text, sizeof text,
                 "[field]\ninput = implicit\nfootpoint = %s\nimplicit_resolution = 24\n"
                 "[shape]\nkind = torus\n"
                 "center = 0 0 0\naxis = 0 0 1\nmajor = 0.6\nminor = 0.25\n", m[k]);
        dfl_proxy_input in;
        dfl_err err;
        cr_assert_eq(build(text, &in, &err), DFL_OK, "%s", err.msg);
        double x[3] = {0.9, 0.1, 0.05};
        dfl_surfpoint o;
        cr_assert_eq(dfl_proxy_input_query(&in, 1, x, 1, &o, NULL), DFL_OK);
        double want = hypot(hypot(0.9, 0.1) - 0.6, 0.05) - 0.25;
        cr_assert(o.certified && fabs(o.d - want) < 1e-12, "%s: %g vs %g", m[k], o.d, want);
        dfl_proxy_input_free(&in);
    }
}

Test(proxy_input_cfg, hvb25_shape_files)
{
    static const struct { const char *file, *inputs[3]; } files[] = {
        {"hvb25_sphere.ini", {"sdf", "parametric", "implicit"}},
        {"hvb25_torus.ini", {"sdf", "parametric", "implicit"}},
        {"hvb25_goursat.ini", {"implicit", NULL, NULL}},
        {"hvb25_ellipsoid.ini", {"implicit", NULL, NULL}},
        {"hvb25_cone.ini", {"sdf", "parametric", NULL}},
        {"hvb25_bezier_single.ini", {"parametric", NULL, NULL}},
        {"hvb25_bezier_multi.ini", {"parametric", NULL, NULL}},
        {"hvb25_bezier_random.ini", {"parametric", NULL, NULL}},
    };
    for (size_t f = 0; f < sizeof files / sizeof *files; f++)
        for (int i = 0; i < 3 && files[f].inputs[i]; i++) {
            char text[512];
            snprintf(text, sizeof text, "[field]\ninput = %s\n[shape]\ninclude = configs/shapes/%s\n",
                     files[f].inputs[i], files[f].file);
            dfl_proxy_input in;
            dfl_err err;
            cr_assert_eq(build(text, &in, &err), DFL_OK, "%s %s: %s", files[f].file,
                         files[f].inputs[i], err.msg);
            cr_assert_str_eq(in.name, files[f].inputs[i]);
            double x[3] = {0.1, 0.2, 0.3};
            dfl_surfpoint o;
            cr_assert_eq(dfl_proxy_input_query(&in, 1, x, 1, &o, NULL), DFL_OK);
            cr_assert(isfinite(o.d) && o.certified, "%s %s", files[f].file, files[f].inputs[i]);
            dfl_proxy_input_free(&in);
        }
}

/* The CSG scenes: every section from its own shape file, input = sdf with
 * both curvatures; a point next to a known part gets that part's distance. */
Test(proxy_input_cfg, hvb25_csg_scenes)
{
    static const char *const scene2 =
        "[field]\ninput = sdf\ncurvature = %s\n"
        "[shape]\ninclude = configs/shapes/hvb25_scene2.ini\n"
        "[scene2_body]\ninclude = configs/shapes/hvb25_scene2_body.ini\n"
        "[scene2_box]\ninclude = configs/shapes/hvb25_scene2_box.ini\n"
        "[scene2_hole]\ninclude = configs/shapes/hvb25_scene2_hole.ini\n"
        "[scene2_ring]\ninclude = configs/shapes/hvb25_scene2_ring.ini\n";
    static const char *const details =
        "[field]\ninput = sdf\ncurvature = %s\n"
        "[shape]\ninclude = configs/shapes/hvb25_details.ini\n"
        "[det_bumpy]\ninclude = configs/shapes/hvb25_details_bumpy.ini\n"
        "[det_core]\ninclude = configs/shapes/hvb25_details_core.ini\n"
        "[det_adds]\ninclude = configs/shapes/hvb25_details_adds.ini\n"
        "[det_pin]\ninclude = configs/shapes/hvb25_details_pin.ini\n"
        "[det_bump]\ninclude = configs/shapes/hvb25_details_bump.ini\n"
        "[det_groove]\ninclude = configs/shapes/hvb25_details_groove.ini\n";
    const char *curv[2] = {"analytic", "fit"};
    for (int k = 0; k < 2; k++) {
        char text[1024];
        dfl_proxy_input in;
        dfl_err err;
        dfl_surfpoint o;
        /* scene2: below the box bottom (z = -0.6), 0.2 away */
        snprintf(text, sizeof text, scene2, curv[k]);
        cr_assert_eq(build(text, &in, &err), DFL_OK, "%s", err.msg);
        double x[3] = {0.1, 0.1, -0.8};
        cr_assert_eq(dfl_proxy_input_query(&in, 1, x, 1, &o, NULL), DFL_OK);
        cr_assert(fabs(o.d - 0.2) < 1e-14 && fabs(o.curv.k1) < 1e-6 && fabs(o.curv.k2) < 1e-6,
                  "%s: d %g k %g %g", curv[k], o.d, o.curv.k1, o.curv.k2);
        dfl_proxy_input_free(&in);
        /* details: beside the pin, 0.05 from its axis at height 0.55 */
        snprintf(text, sizeof text, details, curv[k]);
        cr_assert_eq(build(text, &in, &err), DFL_OK, "%s", err.msg);
        double y[3] = {0.05, 0, 0.55};
        cr_assert_eq(dfl_proxy_input_query(&in, 1, y, 1, &o, NULL), DFL_OK);
        cr_assert(fabs(o.d - 0.02) < 1e-14, "d %g", o.d);
        if (k == 0) cr_assert(fabs(o.curv.k2 - 1 / 0.03) < 1e-8, "k %g", o.curv.k2);
        dfl_proxy_input_free(&in);
    }
}
