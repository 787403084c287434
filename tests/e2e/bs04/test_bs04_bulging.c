/* End-to-end: the bs04 bulging study on a shrunk copy of its paper config.
 * Expected values are derived, not recorded:
 *   - collinear unit segments, strip trims: on the joint's normal both
 *     parts' fields equal the distance |y| (the joint lies on both strips'
 *     boundaries, t = 0), so u = 2^(-1/p) |y| and the joint bulge is
 *     2^(1/p) - 1 for every offset;
 *   - disk trims: on the joint's normal t = -y^2 for both unit segments
 *     (t = -((x - a).(x - b)) / d), h = y sqrt(1 + y^2), so u = delta at
 *     y^2 = (sqrt(1 + 4 4^(1/p) delta^2) - 1) / 2;
 *   - every row (R-equivalence, disk or strip trims): h_i >= the distance to
 *     part i, so u >= h_min N^(-1/p) >= (d - bound) N^(-1/p) on a ray that
 *     still follows the true gradient; the first crossing is then at most
 *     N^(1/p) delta + bound plus one bracketing step:
 *     bulge_max <= N^(1/p) - 1 + (bound + smax delta / steps) / delta;
 *   - the sets are convex for the collinear cases, so every ray is valid;
 *   - the exact image is the distance to the segment [-1, 1] x {0}. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cfg/curve_cfg.h"
#include "util/e2e_util.h"
#include "geom/polygonize.h"
#include "io/config.h"

#define CFG "configs/paper/bs04/bs04_bulging.ini"

#define NSIDE 101
#define NCAP 8
#define STEPS 128
#define SMAX 8.0

Test(e2e_bs04_bulging, collinear_closed_forms_and_bounds, .timeout = 120)
{
    char dir[256], out[512], args[2048], path[700];
    e2e_tmpdir(dir, sizeof dir);
    snprintf(args, sizeof args,
             "--set 'study.p=2, 12' --set study.rounds=10"
             " --set study.steps=%d --set study.smax=%g"
             " --set collinear_disk.rays=%d --set collinear_strip.rays=%d --set W_fig2.rays=201"
             " --set collinear_disk.cap_rays=%d --set collinear_strip.cap_rays=%d"
             " --set W_fig2.cap_rays=8 --set grid_collinear.n=41 --set grid_W.n=41",
             STEPS, SMAX, NSIDE, NSIDE, NCAP, NCAP);
    e2e_run_ok(CFG, args, out, sizeof out);
    /* 2 orders x (5 + 5 + 4 offsets) */
    snprintf(path, sizeof path, "%s/bs04_bulging.csv", out);
    cr_assert_eq(e2e_csv_rows(path), 28);
    /* per point 3 u images (vti + exr), 3 exact images once, csv, config, manifest */
    cr_expect_eq(e2e_count_entries(out), 2 * 6 + 6 + 3);

    dfl_cfg *wc;
    dfl_bspline W;
    dfl_err err;
    cr_assert_eq(dfl_cfg_load("configs/shapes/W.ini", &wc, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_curve_from_cfg(wc, "shape", &W, &err), DFL_OK, "%s", err.msg);
    dfl_polyline wp;
    cr_assert_eq(dfl_polygonize_curve(&W, 1e-3, 0, &wp, NULL), DFL_OK);

    double joint_by_p[2][2] = {{0}};  /* [strip?][p index] at delta = 0.1 */
    for (long r = 0; r < 28; r++) {
        char *cs = e2e_csv_cell(path, r, "case");
        cr_assert_not_null(cs);
        const double p = e2e_csv_get(path, (size_t)r, "p");
        const double delta = e2e_csv_get(path, (size_t)r, "delta");
        const double seg = e2e_csv_get(path, (size_t)r, "segments");
        const double bmax = e2e_csv_get(path, (size_t)r, "bulge_max");
        const double bj = e2e_csv_get(path, (size_t)r, "bulge_joint_max");
        const double rays = e2e_csv_get(path, (size_t)r, "rays");
        const double valid = e2e_csv_get(path, (size_t)r, "rays_valid");
        const int strip = strcmp(cs, "collinear_strip") == 0;
        const int disk = strcmp(cs, "collinear_disk") == 0;
        cr_expect_float_eq(e2e_csv_get(path, (size_t)r, "joint_limit"), pow(2, 1 / p) - 1, 1e-15);
        cr_expect(bmax >= bj - 1e-12, "row %ld: max %g < joint %g", r, bmax, bj);
        double bound = 0;
        if (strip || disk) {
            cr_expect_eq(seg, 2);
            cr_expect_eq(rays, 2 * NSIDE + 2 * NCAP + 2, "row %ld", r);
            cr_expect_eq(valid, rays, "row %ld: convex set, every ray valid", r);
            cr_expect_eq(e2e_csv_get(path, (size_t)r, "unresolved"), 0);
            cr_expect_eq(e2e_csv_get(path, (size_t)r, "beyond"), 0);
            double want;
            if (strip) {
                want = pow(2, 1 / p) - 1;
            } else {
                const double y2 = (sqrt(1 + 4 * pow(4, 1 / p) * delta * delta) - 1) / 2;
                want = sqrt(y2) / delta - 1;
            }
            /* final bracket 8 delta / 128 / 16^10: interpolation error far below */
            cr_expect(fabs(bj - want) <= 1e-9, "%s p %g delta %g: joint bulge %.12g, theory %.12g",
                      cs, p, delta, bj, want);
            if (delta == 0.1) joint_by_p[strip][p == 12] = bj;
        } else {
            cr_expect_str_eq(cs, "W_fig2");
            cr_expect_eq(seg, (double)(wp.n - 1), "W segments");
            cr_expect_eq(rays, 2 * 201 + 2 * 8 + 2 * (double)(wp.n - 2));
            bound = wp.bound;
        }
        const double ub = pow(seg, 1 / p) - 1 + (bound + SMAX * delta / STEPS) / delta;
        cr_expect(bmax <= ub, "%s p %g delta %g: bulge %g above the bound %g", cs, p, delta, bmax,
                  ub);
        free(cs);
    }
    /* the joint bulge falls with p (2^(1/p) - 1) */
    cr_expect(joint_by_p[0][1] < joint_by_p[0][0] && joint_by_p[1][1] < joint_by_p[1][0]);

    /* images through VTK: the exact distance to [-1, 1] x {0}; u on the
     * joint's normal x = 0 for strips and p = 2 (point 0) is |y| / sqrt 2 */
    char cmd[4096], pyout[700];
    snprintf(pyout, sizeof pyout, "%s/py.txt", dir);
    snprintf(cmd, sizeof cmd,
             "%s -c \"import sys, numpy as np, vtk\n"
             "from vtk.util.numpy_support import vtk_to_numpy as v\n"
             "def rd(f):\n"
             "  r = vtk.vtkXMLImageDataReader(); r.SetFileName(f); r.Update(); return r.GetOutput()\n"
             "e = rd(sys.argv[1]); n = e.GetDimensions()\n"
             "P = np.array([e.GetPoint(i) for i in range(e.GetNumberOfPoints())])\n"
             "x, y = P[:,0], P[:,1]\n"
             "d = np.where(np.abs(x) <= 1, np.abs(y), np.hypot(np.abs(x) - 1, y))\n"
             "ev = v(e.GetPointData().GetArray('value'))\n"
             "u = rd(sys.argv[2]); uv = v(u.GetPointData().GetArray('value'))\n"
             "ref = v(u.GetPointData().GetArray('reference'))\n"
             "er = v(u.GetPointData().GetArray('error'))\n"
             "c = np.abs(x) < 1e-12\n"
             "print(n[0], n[1], np.abs(ev - d).max(), np.abs(ref - d).max(), "
             "np.abs(er - (uv - ref)).max(), np.abs(uv[c] - np.abs(y[c]) / np.sqrt(2)).max(), c.sum())\" "
             "%s/collinear_disk_exact_pt000.vti %s/collinear_strip_u_pt000.vti >%s 2>&1",
             e2e_python(), out, out, pyout);
    int prc = system(cmd);
    char *py = e2e_slurp(pyout);
    cr_assert_eq(prc, 0, "VTK check failed: %s", py);
    int nx = 0, ny = 0, nc = 0;
    double e1 = 1, e2 = 1, e3 = 1, e4 = 1;
    cr_assert_eq(sscanf(py, "%d %d %lf %lf %lf %lf %d", &nx, &ny, &e1, &e2, &e3, &e4, &nc), 7, "%s",
                 py);
    cr_expect(nx == 41 && ny == 41 && nc == 41);
    cr_expect(e1 < 1e-12 && e2 < 1e-12, "exact image off by %g / %g", e1, e2);
    cr_expect(e3 < 1e-15, "error != value - reference");
    cr_expect(e4 < 1e-14, "u on the joint normal off by %g", e4);
    free(py);
    dfl_polyline_free(&wp);
    dfl_bspline_free(&W);
    dfl_cfg_free(wc);
}

Test(e2e_bs04_bulging, bad_input_exits_2_without_files)
{
    const char *sets[][2] = {
        {"study.p=0", "study.p: expected an integer in [1, 64]"},
        {"study.cases=nope", "no section [nope]"},
        {"W_fig2.levels=0.1 -0.1", "W_fig2.levels: expected offsets > 0"},
        {"W_fig2.grid=grid_X", "no section [grid_X]"},
        {"collinear.order=1", "collinear.order"},
        {"W_fig2.trim=round", "W_fig2.trim"},
        {"study.steps=0", "study.steps"},
        {"collinear.colour=red", "collinear.colour: unknown key"},
    };
    for (size_t i = 0; i < sizeof sets / sizeof sets[0]; i++) {
        char extra[512];
        snprintf(extra, sizeof extra, "--set '%s'", sets[i][0]);
        e2e_run_expect_fail(CFG, extra, sets[i][1]);
    }
}
