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

#include "util/e2e_util.h"
#include "geom/polygonize.h"

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
    /* 2 orders x (5 + 5 + 4 offsets) */
    e2e_run_table(CFG, args, "bs04_bulging", 28, out, sizeof out, path, sizeof path);
    /* per point 3 u images (vti + exr), 3 exact images once, csv, config, manifest,
     * and a collection (.pvd) of each u image over the 2 points */
    cr_expect_eq(e2e_count_entries(out), 2 * 6 + 6 + 3 + 3);

    dfl_bspline W;
    e2e_load_curve("configs/shapes/W.ini", "shape", &W);
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
    e2e_vti ex, u;
    const char *ex_arrays[] = {"value"}, *u_arrays[] = {"value", "reference", "error"};
    snprintf(path, sizeof path, "%s/collinear_disk_exact_pt000.vti", out);
    e2e_vti_read(dir, path, ex_arrays, 1, &ex);
    snprintf(path, sizeof path, "%s/collinear_strip_u_pt000.vti", out);
    e2e_vti_read(dir, path, u_arrays, 3, &u);
    cr_assert_eq(u.npoints, ex.npoints, "both images on the collinear grid");
    int nc = 0;
    double e1 = 0, e2 = 0, e3 = 0, e4 = 0;
    for (size_t i = 0; i < ex.npoints; i++) {
        const double x = ex.pts[3 * i], y = ex.pts[3 * i + 1];
        const double d = fabs(x) <= 1 ? fabs(y) : hypot(fabs(x) - 1, y);
        const double uv = u.val[3 * i], ref = u.val[3 * i + 1], er = u.val[3 * i + 2];
        e1 = e2e_max(e1, fabs(ex.val[i] - d));
        e2 = e2e_max(e2, fabs(ref - d));
        e3 = e2e_max(e3, fabs(er - (uv - ref)));
        if (fabs(x) < 1e-12) {
            nc++;
            e4 = e2e_max(e4, fabs(uv - fabs(y) / sqrt(2)));
        }
    }
    cr_expect(ex.dims[0] == 41 && ex.dims[1] == 41 && nc == 41);
    cr_expect(e1 < 1e-12 && e2 < 1e-12, "exact image off by %g / %g", e1, e2);
    cr_expect(e3 < 1e-15, "error != value - reference");
    cr_expect(e4 < 1e-14, "u on the joint normal off by %g", e4);
    e2e_vti_free(&ex);
    e2e_vti_free(&u);
    dfl_polyline_free(&wp);
    dfl_bspline_free(&W);
}

Test(e2e_bs04_bulging, bad_input_exits_2_without_files)
{
    static const char *const sets[][2] = {
        {"--set study.p=0", "study.p: expected an integer in [1, 64]"},
        {"--set study.cases=nope", "no section [nope]"},
        {"--set 'W_fig2.levels=0.1 -0.1'", "W_fig2.levels: expected offsets > 0"},
        {"--set W_fig2.grid=grid_X", "no section [grid_X]"},
        {"--set collinear.order=1", "collinear.order"},
        {"--set W_fig2.trim=round", "W_fig2.trim"},
        {"--set study.steps=0", "study.steps"},
        {"--set collinear.colour=red", "collinear.colour: unknown key"},
    };
    e2e_expect_bad_runs(CFG, NULL, sets, sizeof sets / sizeof sets[0]);
}
