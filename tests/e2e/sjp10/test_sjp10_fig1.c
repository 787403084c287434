/* End-to-end: the sjp10_fig1 study on the circle with a small fit.
 * Expected values are derived:
 *   - the leaf cells of a T-mesh partition the box: their areas sum to 1,
 *     and their count is the row's cells; every level <= max_level;
 *   - dofs = 4 x base vertices;
 *   - the image's reference is the exact SDF |x - c| - r at every node,
 *     and error = value - reference;
 *   - the circle's medial axis is its centre c: the normal line of an
 *     inside point x (at distance r_x from c) away from the curve runs
 *     through c, so the band criterion |d(x)| + w - |d(x - w n)| =
 *     2 (w - r_x) > 0 flags exactly the validation points with r_x < w
 *     (outside points are never flagged);
 *   - eps honestly: the estimator's points are points of the square, so
 *     the true max is >= est_max, and the per-cell protocol is within 10 %
 *     of the true max: cv_max >= 0.9 est_max.  At max_level 6 the centre's
 *     kink keeps est_max above eps = 1e-3, so the row must say converged =
 *     0, reason level_cap, capped_cells > 0; the whole max is the larger of
 *     the band and off-band maxima;
 *   - rules = dflab paper: a second row with grade = peaks = 0 and its own
 *     files <case>_paper_*. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/e2e_util.h"

static const char *FIG1_INI =
    "[study]\n"
    "name = sjp10_fig1\n"
    "cases = circle\n"
    "fit = fit\n"
    "val_n = 41\n"
    "band = 0.05\n"
    "image_n = 21\n"
    "graph_n = 11\n"
    "rules = dflab paper\n"
    "[fit]\n"
    "eps = 1e-3\n"
    "max_level = 6\n"
    "samples = 8\n"
    "[circle]\n"
    "kind = circle\n"
    "center = 0.5 0.5\n"
    "radius = 0.3\n"
    "[output]\n"
    "vti = true\n"
    "exr = false\n";

Test(e2e_sjp10_fig1, circle_mesh_tiles_image_reference, .timeout = 120)
{
    char dir[256], cfg[512], out[512], csv[700], path[800];
    e2e_tmpdir(dir, sizeof dir);
    e2e_write(dir, "fig1.ini", FIG1_INI, cfg, sizeof cfg);
    e2e_run_table(cfg, NULL, "sjp10_fig1", 2, out, sizeof out, csv, sizeof csv);
    const double cells = e2e_csv_get(csv, 0, "cells");
    cr_expect_eq(e2e_csv_get(csv, 0, "dofs"), 4 * e2e_csv_get(csv, 0, "base_vertices"));
    cr_expect_gt(cells, 4);
    snprintf(path, sizeof path, "%s/circle_mesh.csv", out);
    const long n = e2e_csv_rows(path);
    cr_assert_eq(n, (long)cells);
    double area = 0;
    int maxlev = 0;
    for (long i = 0; i < n; i++) {
        const double w = e2e_csv_get(path, (size_t)i, "hi_x") - e2e_csv_get(path, (size_t)i, "lo_x");
        const double h = e2e_csv_get(path, (size_t)i, "hi_y") - e2e_csv_get(path, (size_t)i, "lo_y");
        cr_expect_gt(w, 0);
        cr_expect_gt(h, 0);
        area += w * h;
        const int l = (int)e2e_csv_get(path, (size_t)i, "level");
        if (l > maxlev) maxlev = l;
    }
    cr_expect_float_eq(area, 1.0, 1e-12);
    cr_expect_leq(maxlev, 6);
    cr_expect_eq(maxlev, e2e_csv_get(csv, 0, "max_cell_level"));
    const double est = e2e_csv_get(csv, 0, "est_max"), cv = e2e_csv_get(csv, 0, "cv_max");
    cr_expect_gt(est, 1e-3);
    cr_expect_geq(cv, 0.9 * est, "cell protocol max %g vs estimator max %g", cv, est);
    cr_expect_gt(cv, e2e_csv_get(csv, 0, "val_max"), "the grid misses the centre's kink");
    cr_expect_eq(e2e_csv_get(csv, 0, "converged"), 0);
    cr_expect_gt(e2e_csv_get(csv, 0, "capped_cells"), 0);
    char *reason = e2e_csv_cell(csv, 0, "reason");
    cr_expect_str_eq(reason, "level_cap");
    free(reason);
    cr_expect_eq(cv, fmax(e2e_csv_get(csv, 0, "cv_band_max"), e2e_csv_get(csv, 0, "cv_off_max")));
    cr_expect_gt(e2e_csv_get(csv, 0, "cv_medial_points"), 0);
    char *rule = e2e_csv_cell(csv, 1, "rule");
    cr_expect_str_eq(rule, "paper");
    free(rule);
    cr_expect_eq(e2e_csv_get(csv, 0, "grade"), 1);
    cr_expect_eq(e2e_csv_get(csv, 1, "grade"), 0);
    cr_expect_eq(e2e_csv_get(csv, 1, "peaks"), 0);
    long inband = 0;
    for (int mid = 0; mid < 2; mid++)
        for (int j = 0; j < 41 - mid; j++)
            for (int i = 0; i < 41 - mid; i++) {
                const double x = (i + 0.5 * mid) / 40.0, y = (j + 0.5 * mid) / 40.0;
                inband += hypot(x - 0.5, y - 0.5) < 0.05 - 1e-9;
            }
    cr_expect_eq(e2e_csv_get(csv, 0, "val_band_points"), inband);
    cr_expect_eq(e2e_csv_get(csv, 0, "val_points"), 41 * 41 + 40 * 40);
    snprintf(path, sizeof path, "%s/circle.vti", out);
    const char *names[3] = {"value", "reference", "error"};
    e2e_vti v;
    e2e_vti_read(dir, path, names, 3, &v);
    cr_assert_eq(v.npoints, 21 * 21);
    for (size_t i = 0; i < v.npoints; i++) {
        const double *p = v.pts + 3 * i;
        const double d = hypot(p[0] - 0.5, p[1] - 0.5) - 0.3;
        cr_expect_float_eq(v.val[3 * i + 1], d, 1e-15, "node %zu", i);
        cr_expect_float_eq(v.val[3 * i + 2], v.val[3 * i] - v.val[3 * i + 1], 1e-15);
    }
    e2e_vti_free(&v);
    snprintf(path, sizeof path, "%s/circle_mesh.vtp", out);
    cr_expect_gt(e2e_count_entries(out), 0);
    FILE *fp = fopen(path, "rb");
    cr_expect_not_null(fp, "%s", path);
    if (fp) fclose(fp);
    snprintf(path, sizeof path, "%s/circle_graph.vtp", out);
    fp = fopen(path, "rb");
    cr_expect_not_null(fp, "%s", path);
    if (fp) fclose(fp);
    snprintf(path, sizeof path, "%s/circle_paper_mesh.csv", out);
    cr_expect_eq(e2e_csv_rows(path), (long)e2e_csv_get(csv, 1, "cells"));
    e2e_rmtree(dir);
}
