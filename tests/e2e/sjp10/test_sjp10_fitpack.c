/* End-to-end: the FITPACK peer script on the circle with small grids.
 * Expected values are derived from FITPACK's interpolation rule: with
 * s = 0 on an n x n grid RectBivariateSpline interpolates with not-a-knot
 * cubic knots, n + 4 knots per axis and n^2 coefficients, so the stored
 * scalars are n^2 + 2 (n + 4); the validation points are the val_n^2 nodes
 * plus (val_n - 1)^2 midpoints; a coarser grid errs more. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/e2e_util.h"

Test(e2e_sjp10_fitpack, s0_counts_on_the_circle, .timeout = 120)
{
    char dir[256], csv[700];
    e2e_tmpdir(dir, sizeof dir);
    const char *dflab = getenv("DFL_DFLAB") ? getenv("DFL_DFLAB") : "build/dflab";
    const int rc = e2e_python_run(dir, NULL,
                                  "scripts/peers/sjp10_fitpack.py --results %s --dflab %s --cases circle"
                                  " --val-n 21 --s0-n 9,17 --rms 1e-3",
                                  dir, dflab);
    cr_assert_eq(rc, 0);
    snprintf(csv, sizeof csv, "%s/sjp10_peers/sjp10_fitpack.csv", dir);
    cr_assert_eq(e2e_csv_rows(csv), 3);
    double err[2] = {0};
    for (long r = 0; r < 2; r++) {
        char *m = e2e_csv_cell(csv, r, "method");
        cr_assert_str_eq(m, "fitpack_s0");
        free(m);
        const double n = r == 0 ? 9 : 17;
        cr_expect_eq(e2e_csv_get(csv, (size_t)r, "coeffs"), n * n);
        cr_expect_eq(e2e_csv_get(csv, (size_t)r, "knots_x"), n + 4);
        cr_expect_eq(e2e_csv_get(csv, (size_t)r, "scalars"), n * n + 2 * (n + 4));
        cr_expect_eq(e2e_csv_get(csv, (size_t)r, "val_points"), 21 * 21 + 20 * 20);
        err[r] = e2e_csv_get(csv, (size_t)r, "val_max");
    }
    cr_expect_gt(err[0], err[1]);
    char *m = e2e_csv_cell(csv, 2, "method");
    cr_expect_str_eq(m, "fitpack_adaptive");
    free(m);
    e2e_rmtree(dir);
}

/* Bad arguments exit 2 and write nothing. */
Test(e2e_sjp10_fitpack, bad_arguments, .timeout = 30)
{
    char dir[256];
    e2e_tmpdir(dir, sizeof dir);
    cr_expect_eq(e2e_python_run(dir, NULL, "scripts/peers/sjp10_fitpack.py --results %s --cases nope", dir), 2);
    cr_expect_eq(e2e_python_run(dir, NULL, "scripts/peers/sjp10_fitpack.py --results %s --rms 0", dir), 2);
    cr_expect_eq(e2e_count_entries(dir), 1); /* py.txt only */
    e2e_rmtree(dir);
}
