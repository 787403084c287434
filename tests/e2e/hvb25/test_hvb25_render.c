/* End-to-end: the hvb25_render study on a 33^2 frame.  Expected numbers:
 * an order-2 proxy grid of a sphere (SDF input, analytic curvature,
 * double) is the sphere, so the centre pixel's ray (eye on the z axis,
 * looking at the centre) hits at t = |eye| - r within the hit threshold,
 * under every filter; the EXR holds the frame the row describes. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/exr.h"
#include "util/e2e_util.h"

Test(e2e_hvb25_render, sphere_depth_per_filter, .timeout = 60)
{
    char dir[256], cfg[512], out[512], csv[700];
    e2e_tmpdir(dir, sizeof dir);
    e2e_write(dir, "t.ini",
              "[study]\nname = hvb25_render\nfilters = nearest trilinear hermite\nreps = 1\n"
              "[shape]\nkind = sphere\ncenter = 0 0 0\nradius = 0.5\n"
              "[field]\nkind = proxy\norder = 2\nres = 8\ninput = sdf\nstorage = double\n"
              "[camera]\neye = 0 0 3\ntarget = 0 0 0\nup = 0 1 0\nfov = 30\nwidth = 33\n"
              "height = 33\n[trace]\neps = 1e-6\n",
              cfg, sizeof cfg);
    e2e_run_table(cfg, NULL, "hvb25_render", 3, out, sizeof out, csv, sizeof csv);
    for (long r = 0; r < 3; r++) {
        char *name = e2e_csv_cell(csv, r, "frame_exr"), path[1024];
        cr_assert_not_null(name);
        snprintf(path, sizeof path, "%s/%s", out, name);
        free(name);
        int w, h;
        float *depth;
        dfl_err err;
        cr_assert_eq(dfl_exr_read_channel(path, "depth", &w, &h, &depth, &err), DFL_OK, "%s",
                     err.msg);
        cr_assert(w == 33 && h == 33);
        const float t = depth[16 * 33 + 16];
        cr_expect(fabs(t - 2.5) < 2e-6, "row %ld: centre depth %g", r, t);
        cr_expect(isinf(depth[0]), "a corner pixel misses");
        long hits = 0;
        for (int i = 0; i < w * h; i++) hits += isfinite(depth[i]);
        cr_expect_eq((double)hits, e2e_csv_get(csv, r, "hits"));
        cr_expect_eq(e2e_csv_get(csv, r, "exhausted"), 0);
        free(depth);
    }
}

/* [field] clip_radius with [study] filters: every frame's clip is
 * clip_radius cell sizes (0.5 * h, h = 0.25), not the filter's default. */
Test(e2e_hvb25_render, clip_radius_with_filters, .timeout = 60)
{
    char dir[256], cfg[512], out[512], csv[700];
    e2e_tmpdir(dir, sizeof dir);
    e2e_write(dir, "t.ini",
              "[study]\nname = hvb25_render\nfilters = nearest hermite\nreps = 1\n"
              "[shape]\nkind = sphere\ncenter = 0 0 0\nradius = 0.5\n"
              "[field]\nkind = proxy\norder = 1\nres = 8\ninput = sdf\nstorage = double\n"
              "clip_radius = 0.5\n"
              "[camera]\neye = 0 0 3\ntarget = 0 0 0\nup = 0 1 0\nfov = 30\nwidth = 9\n"
              "height = 9\n",
              cfg, sizeof cfg);
    e2e_run_table(cfg, NULL, "hvb25_render", 2, out, sizeof out, csv, sizeof csv);
    for (long r = 0; r < 2; r++)
        cr_expect_eq(e2e_csv_get(csv, r, "clip"), 0.125, "row %ld: clip %g", r,
                     e2e_csv_get(csv, r, "clip"));
}

/* False hits (hits farther than false_hit_tol cells from the true surface)
 * of a sphere's order-2 SDF-input proxies, which are the sphere itself: no
 * clip gives |phi| = |d| exactly, and the bound clip max(|phi|, |x-p|-rho)
 * is zero only where phi is, so neither frame has a false hit, whatever the
 * tolerance; every row names its clip kind. */
Test(e2e_hvb25_render, exact_proxies_have_no_false_hits, .timeout = 60)
{
    char dir[256], cfg[512], out[512], csv[700];
    e2e_tmpdir(dir, sizeof dir);
    e2e_write(dir, "t.ini",
              "[study]\nname = hvb25_render\nfilters = nearest\nreps = 1\nfalse_hit_tol = 1e-3\n"
              "[shape]\nkind = sphere\ncenter = 0 0 0\nradius = 0.5\n"
              "[field]\nkind = proxy\norder = 2\nres = 8\ninput = sdf\nstorage = double\n"
              "clip = off, bound\n"
              "[camera]\neye = 0 0 3\ntarget = 0 0 0\nup = 0 1 0\nfov = 30\nwidth = 17\n"
              "height = 17\n[trace]\neps = 1e-7\nbox = false\n",
              cfg, sizeof cfg);
    e2e_run_table(cfg, NULL, "hvb25_render", 2, out, sizeof out, csv, sizeof csv);
    static const char *const kind[2] = {"off", "bound"};
    for (long r = 0; r < 2; r++) {
        cr_expect_eq(e2e_csv_get(csv, r, "false_hits"), 0, "row %ld", r);
        cr_expect_gt(e2e_csv_get(csv, r, "hits"), 0, "row %ld", r);
        char *k = e2e_csv_cell(csv, r, "clip_kind");
        cr_assert_not_null(k);
        cr_expect_str_eq(k, kind[r]);
        free(k);
    }
}
