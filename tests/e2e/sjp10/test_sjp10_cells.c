/* End-to-end: the sjp10_cells study on a small config.  Expected values
 * are derived, not recorded:
 *   - uniform level k: 4^k cells, (2^k + 1)^2 base vertices (every vertex of
 *     a uniform grid is a crossing or boundary vertex), 4 dofs each;
 *   - a plane's SDF is linear, a bicubic polynomial: the PHT spline
 *     reproduces it exactly on every T-mesh, so the adaptive fit stops at
 *     the one-cell mesh (4 base vertices, 16 dofs) and every validation
 *     error is rounding;
 *   - the smooth case (distance to a circle centred outside the square) is
 *     C-infinity in the box: bicubic Hermite interpolation errs by
 *     O(h^4), so halving h divides the max error by ~16 and the slope of
 *     log cells vs log 1/error on the uniform grid is log 4 / log 16 = 1/2
 *     (sjp10's C4 slope);
 *   - dofs = 4 x base vertices in every row. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/e2e_util.h"

static const char *CELLS_INI =
    "[study]\n"
    "name = sjp10_cells\n"
    "cases = smooth plane\n"
    "fit = fit\n"
    "eps = 1e-3 1e-5\n"
    "uniform_levels = 2 3 4 5\n"
    "val_n = 41\n"
    "band = 0.02\n"
    "[fit]\n"
    "max_level = 6\n"
    "samples = 4\n"
    "lo = 0 0\n"
    "hi = 1 1\n"
    "[smooth]\n"
    "kind = circle\n"
    "center = -0.4 0.5\n"
    "radius = 0.1\n"
    "[plane]\n"
    "kind = plane\n"
    "dim = 2\n"
    "point = 0.5 0.5\n"
    "normal = 1 2\n";

Test(e2e_sjp10_cells, uniform_counts_plane_exact_smooth_rate, .timeout = 120)
{
    e2e_table t = {0};
    /* 2 cases x (2 eps + 4 levels) */
    e2e_ini_table(&t, "cells.ini", CELLS_INI, "sjp10_cells", 12);
    const char *csv = t.csv;
    double smooth_err[6] = {0};
    for (long r = 0; r < 12; r++) {
        char *cs = e2e_csv_cell(csv, r, "case"), *m = e2e_csv_cell(csv, r, "method");
        cr_assert(cs && m);
        const double cells = e2e_csv_get(csv, (size_t)r, "cells");
        const double dofs = e2e_csv_get(csv, (size_t)r, "dofs");
        const double vmax = e2e_csv_get(csv, (size_t)r, "val_max");
        cr_expect_eq(e2e_csv_get(csv, (size_t)r, "val_points"), 41 * 41 + 40 * 40);
        const int k = e2e_sjp10_counts(csv, r, 2);
        if (k >= 0 && strcmp(cs, "smooth") == 0) smooth_err[k] = vmax;
        if (strcmp(cs, "plane") == 0) {
            cr_expect_lt(vmax, 1e-13, "row %ld: a linear SDF is reproduced", r);
            if (strcmp(m, "pht") == 0) {
                cr_expect_eq(cells, 1);
                cr_expect_eq(dofs, 16);
                cr_expect_eq(e2e_csv_get(csv, (size_t)r, "converged"), 1);
            }
        }
        if (strcmp(cs, "smooth") == 0 && strcmp(m, "pht") == 0) {
            cr_expect_eq(e2e_csv_get(csv, (size_t)r, "converged"), 1, "row %ld", r);
            cr_expect_leq(e2e_csv_get(csv, (size_t)r, "est_max"), e2e_csv_get(csv, (size_t)r, "eps"));
        }
        free(cs);
        free(m);
    }
    /* O(h^4): ratios near 16, slope log(4^k) / log(1/err) near 1/2 */
    for (int k = 3; k < 5; k++) {
        const double ratio = smooth_err[k] / smooth_err[k + 1];
        cr_expect(ratio > 12 && ratio < 20, "level %d -> %d: error ratio %g, expected ~16", k, k + 1,
                  ratio);
    }
    const double slope = log(4.0 * 4.0) / log(smooth_err[3] / smooth_err[5]);
    cr_expect(fabs(slope - 0.5) < 0.05, "uniform slope %g, expected 1/2", slope);
    e2e_rmtree(t.dir);
}

/* Bad input: a threshold <= 0, a uniform level out of range, an unknown or
 * repeated fit rule, an open curve as a case: exit 2 naming the key. */
Test(e2e_sjp10_cells, bad_input, .timeout = 60)
{
    static const char *const rows[][2] = {
        {"--set 'study.eps=1e-3 0'", "eps"},
        {"--set 'study.uniform_levels=2 13'", "uniform_levels"},
        {"--set fit.max_level=99", "max_level"},
        {"--set 'study.rules=dflab foo'", "rules"},
        {"--set 'study.rules=paper paper'", "rules"},
    };
    char dir[256], cfg[512];
    e2e_tmpdir(dir, sizeof dir);
    e2e_write(dir, "cells.ini", CELLS_INI, cfg, sizeof cfg);
    e2e_expect_bad_runs(cfg, NULL, rows, sizeof rows / sizeof rows[0]);
    e2e_expect_bad_config("[study]\nname = sjp10_cells\ncases = open\nfit = fit\neps = 1e-3\n"
                          "uniform_levels = 2\n[fit]\nmax_level = 4\n[open]\nkind = bspline_curve\norder = 4\n"
                          "control = 0.1 0.1; 0.5 0.9; 0.9 0.1; 0.9 0.9\n",
                          "[open]", NULL);
    e2e_rmtree(dir);
}
