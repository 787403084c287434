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

/* Every frame here: the sphere seen from the z axis, looking at its centre. */
#define SPHERE "[shape]\nkind = sphere\ncenter = 0 0 0\nradius = 0.5\n"
#define CAMERA "[camera]\neye = 0 0 3\ntarget = 0 0 0\nup = 0 1 0\nfov = 30\n"

Test(e2e_hvb25_render, sphere_depth_per_filter, .timeout = 60)
{
    e2e_table t = {0};
    e2e_ini_table(&t, "t.ini",
                  "[study]\nname = hvb25_render\nfilters = nearest trilinear hermite\nreps = 1\n"
                  SPHERE "[field]\nkind = proxy\norder = 2\nres = 8\ninput = sdf\n"
                  "storage = double\n" CAMERA "width = 33\nheight = 33\n[trace]\neps = 1e-6\n",
                  "hvb25_render", 3);
    const char *out = t.out, *csv = t.csv;
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
    e2e_table t = {0};
    e2e_ini_table(&t, "t.ini",
                  "[study]\nname = hvb25_render\nfilters = nearest hermite\nreps = 1\n" SPHERE
                  "[field]\nkind = proxy\norder = 1\nres = 8\ninput = sdf\nstorage = double\n"
                  "clip_radius = 0.5\n" CAMERA "width = 9\nheight = 9\n",
                  "hvb25_render", 2);
    const char *csv = t.csv;
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
    e2e_table t = {0};
    e2e_ini_table(&t, "t.ini",
                  "[study]\nname = hvb25_render\nfilters = nearest\nreps = 1\n"
                  "false_hit_tol = 1e-3\n" SPHERE
                  "[field]\nkind = proxy\norder = 2\nres = 8\ninput = sdf\nstorage = double\n"
                  "clip = off, bound\n" CAMERA "width = 17\nheight = 17\n[trace]\neps = 1e-7\n"
                  "box = false\n",
                  "hvb25_render", 2);
    const char *csv = t.csv;
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

/* The report's section renders both paper configs of Table 4's frames
 * (scripts/sections/hvb25/hvb25_render.py): the frames figure passes the
 * figure rules (report.py refuses one with a label over a neighbouring
 * panel), so `make reproduce` ends with no failed section. */
Test(e2e_hvb25_render, report_section_of_the_paper_configs, .timeout = 300)
{
    static const char *const cfgs[2] = {"hvb25_table4_render_sphere", "hvb25_table4_render_torus"};
    char dir[256], args[1024];
    e2e_tmpdir(dir, sizeof dir);
    cr_assert(dir[0], "no temporary directory");
    for (int k = 0; k < 2; k++) {
        snprintf(args, sizeof args, "run configs/paper/hvb25/%s.ini --out %s/results/%s --quiet",
                 cfgs[k], dir, cfgs[k]);
        cr_assert_eq(e2e_dflab(dir, args), 0, "%s", cfgs[k]);
    }
    char *py;
    const int rc = e2e_python_run(dir, &py, "scripts/report.py --results %s/results --out %s/REPORT.md",
                                  dir, dir);
    cr_expect_eq(rc, 0, "%s", py);
    cr_expect(strstr(py, "(2 runs, 0 failed sections)") != NULL, "%s", py);
    free(py);
    cr_expect_eq(e2e_rmtree(dir), 0);
}
