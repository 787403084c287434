/* End-to-end: the FITPACK peer script with small grids.  Expected values
 * are derived from the methods' rules, never copied from a run:
 *  - s = 0 on an n x n grid (RectBivariateSpline) interpolates with
 *    not-a-knot cubic ends: n + 4 knots per axis, n^2 coefficients, and its
 *    error at its own samples is rounding (SDF values <= sqrt 2, so far
 *    below 1e-12);
 *  - every tensor spline has (nx - 4)(ny - 4) coefficients, bytes = 8 (coefficients + knots);
 *  - s > 0: FITPACK stops when its residual sum of squares fp is within
 *    0.001 s of s (or below it), so fp <= 1.001 s; fp is the sum over the
 *    N = data_n samples of the squared residual, so fp = N data_rms^2, and
 *    the max residual is >= the RMS residual;
 *  - the least-squares spline on user knots solves the same problem as
 *    LSQBivariateSpline on the same data and knots: one solution when the
 *    knots are well-posed (rank_deficiency 0), equal to rounding;
 *  - the validation maxima: whole = max(in band, off band) >= near-medial;
 *    points = val_n^2 + medial + surface points;
 *  - the circle's medial axis is its centre (0.5, 0.5), the teardrop's
 *    interior one lies on its symmetry line y = 0.5 and spans x: the knots
 *    grade towards 0.5 on both axes of the circle, on y only for the tip. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/e2e_util.h"

static const char *dflab_path(void)
{
    return getenv("DFL_DFLAB") ? getenv("DFL_DFLAB") : "build/dflab";
}

static int method_is(const char *csv, long r, const char *want)
{
    char *m = e2e_csv_cell(csv, r, "method");
    const int same = m && strcmp(m, want) == 0;
    free(m);
    return same;
}

static int cell_empty(const char *csv, long r, const char *col)
{
    char *c = e2e_csv_cell(csv, r, col);
    const int empty = c && c[0] == '\0';
    free(c);
    return empty;
}

/* The rules every row obeys (sizes, validation maxima, point counts). */
static void expect_row_rules(const char *csv, long r, double val_n)
{
    const double nx = e2e_csv_get(csv, (size_t)r, "knots_x"), ny = e2e_csv_get(csv, (size_t)r, "knots_y");
    const double c = e2e_csv_get(csv, (size_t)r, "coefficients");
    cr_expect_eq(c, (nx - 4) * (ny - 4), "row %ld", r);
    cr_expect_eq(e2e_csv_get(csv, (size_t)r, "knots"), nx + ny);
    cr_expect_eq(e2e_csv_get(csv, (size_t)r, "bytes"), 8 * (c + nx + ny));
    const double whole = e2e_csv_get(csv, (size_t)r, "max_whole");
    const double band = e2e_csv_get(csv, (size_t)r, "max_band"), off = e2e_csv_get(csv, (size_t)r, "max_off");
    cr_expect(isfinite(whole) && whole > 0, "row %ld", r);
    cr_expect_eq(whole, e2e_max(band, off), "row %ld", r);
    cr_expect_leq(e2e_csv_get(csv, (size_t)r, "near_medial_max"), whole);
    cr_expect_leq(e2e_csv_get(csv, (size_t)r, "near_surface_max"), whole);
    const double share = e2e_csv_get(csv, (size_t)r, "share_above_eps");
    cr_expect(share >= 0 && share <= 1);
    cr_expect_eq(e2e_csv_get(csv, (size_t)r, "val_points"),
                 val_n * val_n + e2e_csv_get(csv, (size_t)r, "medial_points") +
                     e2e_csv_get(csv, (size_t)r, "surface_points"));
    cr_expect_gt(e2e_csv_get(csv, (size_t)r, "medial_points"), 0);
    cr_expect_gt(e2e_csv_get(csv, (size_t)r, "surface_points"), 0);
    cr_expect_gt(e2e_csv_get(csv, (size_t)r, "sample_s"), 0);
}

Test(e2e_sjp10_fitpack, circle_rows, .timeout = 600)
{
    char dir[256], csv[700];
    e2e_tmpdir(dir, sizeof dir);
    const int rc = e2e_python_run(dir, NULL,
                                  "scripts/peers/sjp10_fitpack.py --results %s --dflab %s --cases circle"
                                  " --data-n 101 --s0-n 11,26 --rms 1e-3,1e-4 --lsq-m 7 --lsq-p 1,3"
                                  " --val-n 41 --seed-n 41 --lsq-check",
                                  dir, dflab_path());
    cr_assert_eq(rc, 0);
    snprintf(csv, sizeof csv, "%s/sjp10_peers/sjp10_fitpack.csv", dir);
    cr_assert_eq(e2e_csv_rows(csv), 6);
    double err[2] = {0};
    for (long r = 0; r < 2; r++) {
        cr_assert(method_is(csv, r, "fitpack_s0"));
        const double n = r == 0 ? 11 : 26;
        cr_expect_eq(e2e_csv_get(csv, (size_t)r, "coefficients"), n * n);
        cr_expect_eq(e2e_csv_get(csv, (size_t)r, "knots_x"), n + 4);
        cr_expect_eq(e2e_csv_get(csv, (size_t)r, "data_n"), n * n);
        cr_expect_lt(e2e_csv_get(csv, (size_t)r, "data_max"), 1e-12);
        expect_row_rules(csv, r, 41);
        err[r] = e2e_csv_get(csv, (size_t)r, "max_off");
    }
    cr_expect_gt(err[0], err[1]); /* off the kink a finer grid errs less */
    for (long r = 2; r < 4; r++) {
        cr_assert(method_is(csv, r, "fitpack_smooth"));
        const double rms = r == 2 ? 1e-3 : 1e-4, n = e2e_csv_get(csv, (size_t)r, "data_n");
        cr_expect_eq(n, 101.0 * 101.0);
        cr_expect_eq(e2e_csv_get(csv, (size_t)r, "s"), n * rms * rms);
        const double fp = e2e_csv_get(csv, (size_t)r, "fp"), drms = e2e_csv_get(csv, (size_t)r, "data_rms");
        cr_expect_leq(fp, 1.001 * n * rms * rms, "row %ld: fp %g", r, fp);
        cr_expect(fabs(fp - n * drms * drms) <= 1e-9 * fp + 1e-300, "row %ld", r);
        cr_expect_geq(e2e_csv_get(csv, (size_t)r, "data_max"), drms);
        expect_row_rules(csv, r, 41);
    }
    for (long r = 4; r < 6; r++) {
        cr_assert(method_is(csv, r, "lsq_graded"));
        cr_expect_eq(e2e_csv_get(csv, (size_t)r, "rank_deficiency"), 0);
        cr_expect_leq(e2e_csv_get(csv, (size_t)r, "cond"), 1e3);
        cr_expect_lt(e2e_csv_get(csv, (size_t)r, "lsq_check_diff"), 1e-10);
        cr_expect(fabs(e2e_csv_get(csv, (size_t)r, "grade_cx") - 0.5) < 1e-9);
        cr_expect(fabs(e2e_csv_get(csv, (size_t)r, "grade_cy") - 0.5) < 1e-9);
        /* m = 7 interior knots per axis, none dropped: 11 x 11 coefficients */
        cr_expect_eq(e2e_csv_get(csv, (size_t)r, "knots_dropped"), 0);
        cr_expect_eq(e2e_csv_get(csv, (size_t)r, "coefficients"), 121);
        expect_row_rules(csv, r, 41);
    }
    /* the kink of the cone at the centre: knots graded towards it err less
     * there than uniform knots of the same count */
    cr_expect_lt(e2e_csv_get(csv, 5, "near_medial_max"), e2e_csv_get(csv, 4, "near_medial_max"));
    e2e_rmtree(dir);
}

Test(e2e_sjp10_fitpack, teardrop_grades_y_only, .timeout = 600)
{
    char dir[256], csv[700];
    e2e_tmpdir(dir, sizeof dir);
    const int rc = e2e_python_run(dir, NULL,
                                  "scripts/peers/sjp10_fitpack.py --results %s --dflab %s --cases tip"
                                  " --data-n 101 --s0-n 101 --rms 3e-4 --lsq-m 15 --lsq-p 2"
                                  " --val-n 41 --seed-n 61",
                                  dir, dflab_path());
    cr_assert_eq(rc, 0);
    snprintf(csv, sizeof csv, "%s/sjp10_peers/sjp10_fitpack.csv", dir);
    cr_assert_eq(e2e_csv_rows(csv), 3);
    for (long r = 0; r < 3; r++) {
        cr_expect(cell_empty(csv, r, "grade_cx"), "row %ld", r);
        cr_expect(fabs(e2e_csv_get(csv, (size_t)r, "grade_cy") - 0.5) < 1e-6, "row %ld", r);
        expect_row_rules(csv, r, 41);
    }
    cr_assert(method_is(csv, 0, "fitpack_s0"));
    cr_expect_lt(e2e_csv_get(csv, 0, "data_max"), 1e-12);
    cr_assert(method_is(csv, 1, "fitpack_smooth"));
    const double n = e2e_csv_get(csv, 1, "data_n");
    cr_expect_leq(e2e_csv_get(csv, 1, "fp"), 1.001 * n * 3e-4 * 3e-4);
    cr_assert(method_is(csv, 2, "lsq_graded"));
    e2e_rmtree(dir);
}

/* Bad arguments exit 2 and write nothing. */
Test(e2e_sjp10_fitpack, bad_arguments, .timeout = 180)
{
    char dir[256];
    e2e_tmpdir(dir, sizeof dir);
    cr_expect_eq(e2e_python_run(dir, NULL, "scripts/peers/sjp10_fitpack.py --results %s --cases nope", dir), 2);
    cr_expect_eq(e2e_python_run(dir, NULL, "scripts/peers/sjp10_fitpack.py --results %s --rms 0", dir), 2);
    /* 14 - 1 does not divide 1201 - 1 */
    cr_expect_eq(e2e_python_run(dir, NULL, "scripts/peers/sjp10_fitpack.py --results %s --s0-n 14", dir), 2);
    cr_expect_eq(e2e_python_run(dir, NULL, "scripts/peers/sjp10_fitpack.py --results %s --lsq-p 0.5", dir), 2);
    cr_expect_eq(e2e_count_entries(dir), 1); /* py.txt only */
    e2e_rmtree(dir);
}
