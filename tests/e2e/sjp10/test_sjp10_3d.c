/* End-to-end: the sjp10_3d study on a small config.  Expected values are
 * derived:
 *   - uniform level k: 8^k cells, (2^k + 1)^3 base vertices (all vertices
 *     of a uniform grid are base vertices), 8 dofs each;
 *   - a plane's SDF is linear, a tricubic polynomial: reproduced exactly,
 *     the adaptive fit stops at the one-cell mesh (8 base vertices, 64
 *     dofs), every validation error is rounding;
 *   - the sphere's SDF is smooth off its centre: the uniform grid's L1
 *     falls by more than 8 (the h^4 rate is 16) from level 2 to 3. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/e2e_util.h"

static const char *INI3 =
    "[study]\n"
    "name = sjp10_3d\n"
    "cases = sphere_case plane_case\n"
    "fit = fit\n"
    "eps = 1e-2\n"
    "uniform_levels = 2 3\n"
    "[fit]\n"
    "max_level = 3\n"
    "samples = 4\n"
    "lo = -1 -1 -1\n"
    "hi = 1 1 1\n"
    "[sphere_case]\n"
    "shape = sphere\n"
    "lo = -1 -1 -1\n"
    "hi = 1 1 1\n"
    "val_n = 17\n"
    "[plane_case]\n"
    "shape = plane\n"
    "lo = -1 -1 -1\n"
    "hi = 1 1 1\n"
    "val_n = 9\n"
    "midpoints = true\n"
    "cache = true\n"
    "[sphere]\n"
    "kind = sphere\n"
    "center = 0.1 0 0\n"
    "radius = 0.5\n"
    "[plane]\n"
    "kind = plane\n"
    "point = 0 0 0.1\n"
    "normal = 1 2 3\n";

Test(e2e_sjp10_3d, uniform_counts_plane_exact, .timeout = 120)
{
    char dir[256], cfg[512], out[512], csv[700];
    e2e_tmpdir(dir, sizeof dir);
    e2e_write(dir, "t3.ini", INI3, cfg, sizeof cfg);
    e2e_run_table(cfg, NULL, "sjp10_3d", 6, out, sizeof out, csv, sizeof csv);
    double l1[4] = {0};
    for (long r = 0; r < 6; r++) {
        char *cs = e2e_csv_cell(csv, r, "case"), *m = e2e_csv_cell(csv, r, "method");
        cr_assert(cs && m);
        const double cells = e2e_csv_get(csv, (size_t)r, "cells");
        const double base = e2e_csv_get(csv, (size_t)r, "base_vertices");
        cr_expect_eq(e2e_csv_get(csv, (size_t)r, "dofs"), 8 * base, "row %ld", r);
        if (strcmp(m, "uniform") == 0) {
            const int k = (int)e2e_csv_get(csv, (size_t)r, "uniform_level");
            const double s = ldexp(1.0, k);
            cr_expect_eq(cells, s * s * s, "row %ld", r);
            cr_expect_eq(base, (s + 1) * (s + 1) * (s + 1), "row %ld", r);
            if (strcmp(cs, "sphere_case") == 0) l1[k] = e2e_csv_get(csv, (size_t)r, "val_mean");
        }
        if (strcmp(cs, "plane_case") == 0) {
            cr_expect_lt(e2e_csv_get(csv, (size_t)r, "val_max"), 1e-13, "row %ld", r);
            cr_expect_eq(e2e_csv_get(csv, (size_t)r, "val_points"), 9 * 9 * 9 + 8 * 8 * 8);
            if (strcmp(m, "pht") == 0) {
                cr_expect_eq(cells, 1);
                cr_expect_eq(base, 8);
            }
        } else {
            cr_expect_eq(e2e_csv_get(csv, (size_t)r, "val_points"), 17 * 17 * 17);
        }
        free(cs);
        free(m);
    }
    cr_expect_gt(l1[2] / l1[3], 8.0, "sphere L1 %g -> %g", l1[2], l1[3]);
    e2e_rmtree(dir);
}
