/* End-to-end: the bs04_gradbounds study (Fig. 4-5, eq. 13-14) on a small
 * sweep.  Expected values are derived here, not copied from a run:
 *   - |grad u| of exact segment distances around the vertex by brute force
 *     (u from first principles in this file, central differences, a dense
 *     scan of the circle refined by a fine scan);
 *   - the band: 0 violations everywhere, and for exact parts none of the
 *     paper's unwidened band either;
 *   - trimmed parts: the excess over the paper's band is at most the parts'
 *     own gradient defect (|grad u| <= F1 g1 + F2 g2 <= F1 + F2 + max|g-1|
 *     since F1 + F2 <= 1), and that defect is O(r) (the trim's quadratic
 *     term): 10x the radius, ~10x the defect;
 *   - Fig. 5 claims: min of F1 + F2 at 45 degrees, equal to 2^(-1/p)
 *     (R-equivalence) and 2 - 2^(1/p) (R-conjunction), F1 - F2 = 0 there. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/vec.h"
#include "util/e2e_util.h"

#define CFG "configs/paper/bs04/bs04_gradbounds.ini"

/* u from first principles: exact distances to the segments from O along
 * (1, 0) and (cos a, sin a) (length 1), joined with pow(). */
static double segd(double ex, double ey, double x, double y)
{
    double t = fmin(fmax(x * ex + y * ey, 0.0), 1.0);
    return hypot(x - t * ex, y - t * ey);
}

static double u_at(int rconj, int p, double a, double x, double y)
{
    double h1 = segd(1, 0, x, y), h2 = segd(cos(a), sin(a), x, y);
    if (rconj) return h1 + h2 - pow(pow(h1, p) + pow(h2, p), 1.0 / p);
    return pow(pow(h1, -p) + pow(h2, -p), -1.0 / p);
}

static double g_at(int rconj, int p, double a, double r, double t)
{
    double x = r * cos(t), y = r * sin(t), e = 1e-6 * r;
    double gx = (u_at(rconj, p, a, x + e, y) - u_at(rconj, p, a, x - e, y)) / (2 * e);
    double gy = (u_at(rconj, p, a, x, y + e) - u_at(rconj, p, a, x, y - e)) / (2 * e);
    return hypot(gx, gy);
}

static double brute_min(int rconj, int p, double a, double r, double *tmin)
{
    double best = INFINITY, tb = 0;
    for (int k = 0; k < 3600; k++) {
        double t = 2 * DFL_PI * (k + 0.25) / 3600, g = g_at(rconj, p, a, r, t);
        if (g < best) best = g, tb = t;
    }
    double t0 = tb;
    for (int k = -500; k <= 500; k++) {
        double t = t0 + k * (2 * DFL_PI / 3600) / 500, g = g_at(rconj, p, a, r, t);
        if (g < best) best = g, tb = t;
    }
    *tmin = tb;
    return best;
}

Test(e2e_bs04_gradbounds, bounds_minimum_and_fig5, .timeout = 60)
{
    char out[512], csv[700];
    /* 3 alpha x 2 p x 2 joins x 2 parts, 2 radii each */
    e2e_run_table(CFG,
                  "--set 'study.alpha=60, 180, 270' --set 'study.p=2, 12'"
                  " --set 'study.parts=exact, disk' --set study.samples=720"
                  " --set study.profile_alpha=60 --set study.profile_samples=72",
                  "bs04_gradbounds", 48, out, sizeof out, csv, sizeof csv);
    for (long row = 0; row < 48; row++) {
        char parts[32], join[32];
        char *ps = e2e_csv_cell(csv, row, "parts"), *js = e2e_csv_cell(csv, row, "join");
        snprintf(parts, sizeof parts, "%s", ps ? ps : "");
        snprintf(join, sizeof join, "%s", js ? js : "");
        free(ps);
        free(js);
        const int exact = strcmp(parts, "exact") == 0, rconj = strcmp(join, "rconj") == 0;
        cr_assert(exact || strcmp(parts, "disk") == 0, "row %ld parts '%s'", row, parts);
        const double alpha = e2e_csv_get(csv, row, "alpha");
        const int p = (int)e2e_csv_get(csv, row, "p");
        const double r = e2e_csv_get(csv, row, "r");
        const double a = alpha * DFL_PI / 180;
        cr_expect_eq(e2e_csv_get(csv, row, "violations"), 0.0, "row %ld", row);
        cr_expect(e2e_csv_get(csv, row, "fd_maxdiff") < 1e-6, "row %ld", row);
        const double gmin = e2e_csv_get(csv, row, "grad_min");
        const double gmax = e2e_csv_get(csv, row, "grad_max");
        /* strictly inside (0, 1) up to the parts' own defect */
        cr_expect(gmin > 0.1 && gmax <= 1 + e2e_csv_get(csv, row, "part_gdef_max") + 1e-12,
                  "row %ld: %g %g", row, gmin, gmax);
        if (exact) {
            cr_expect_eq(e2e_csv_get(csv, row, "violations_paper"), 0.0, "row %ld", row);
            double tb;
            const double bm = brute_min(rconj, p, a, r, &tb);
            cr_expect(fabs(gmin - bm) < 2e-6, "row %ld (%s p %d alpha %g): %.10f vs brute %.10f",
                      row, join, p, alpha, gmin, bm);
            cr_expect(fabs(e2e_csv_get(csv, row, "grad_min_theory") - bm) < 2e-6, "row %ld", row);
            /* the bisector of the convex sector */
            const double tbis = alpha <= 180 ? a / 2 : a / 2 + DFL_PI;
            cr_expect_float_eq(e2e_csv_get(csv, row, "bisector_deg"), tbis * 180 / DFL_PI, 1e-9);
            const double gbis = g_at(rconj, p, a, r, tbis);
            cr_expect(fabs(e2e_csv_get(csv, row, "grad_bisector") - gbis) < 1e-6, "row %ld", row);
            if (alpha != 180) {
                /* minimum on the bisector, as bs04 says */
                cr_expect(e2e_csv_get(csv, row, "theta_min_err_deg") < 1e-3, "row %ld", row);
                cr_expect(fabs(gbis - bm) < 2e-6, "row %ld: brute force min is off the bisector", row);
            } else {
                /* collinear: the minimum leaves the bisector (mixed regime) */
                cr_expect_eq(e2e_csv_get(csv, row, "min_on_bisector"), 0.0, "row %ld", row);
                cr_expect(gbis - bm > 1e-3, "row %ld: bisector %g, brute min %g", row, gbis, bm);
                /* 2^(-1/p) resp. 2 - 2^(1/p) on the hatched ray */
                cr_expect_float_eq(gbis, rconj ? 2 - pow(2, 1.0 / p) : pow(2, -1.0 / p), 1e-6);
            }
        } else {
            const double pg = e2e_csv_get(csv, row, "part_gdef_max");
            cr_expect(pg > 0 && e2e_csv_get(csv, row, "excess_paper_max") <= pg + 1e-12,
                      "row %ld", row);
            if (row % 2 == 1) {
                /* rows r = 1e-3 L then 1e-2 L of the same point */
                cr_expect_float_eq(r, 10 * e2e_csv_get(csv, row - 1, "r"), 1e-15);
                const double ratio = pg / e2e_csv_get(csv, row - 1, "part_gdef_max");
                cr_expect(ratio > 8 && ratio < 12, "row %ld: defect ratio %g", row, ratio);
            }
        }
    }
    /* Fig. 5 claims: rows requiv p = 2, 7, 12 then rconj */
    snprintf(csv, sizeof csv, "%s/fig5_claims.csv", out);
    cr_assert_eq(e2e_csv_rows(csv), 6);
    for (long row = 0; row < 6; row++) {
        const int p = (int)e2e_csv_get(csv, row, "p");
        cr_expect_eq(p, row % 3 == 0 ? 2 : row % 3 == 1 ? 7 : 12);
        const double th = row < 3 ? pow(2, -1.0 / p) : 2 - pow(2, 1.0 / p);
        cr_expect_float_eq(e2e_csv_get(csv, row, "sum_min"), th, 1e-13, "row %ld", row);
        cr_expect_float_eq(e2e_csv_get(csv, row, "sum_min_phi_deg"), 45.0, 1e-4, "row %ld", row);
        cr_expect(fabs(e2e_csv_get(csv, row, "diff_at_45")) < 1e-14, "row %ld", row);
        cr_expect(e2e_csv_get(csv, row, "sum_max") <= 1 + 1e-14, "row %ld", row);
        cr_expect(e2e_csv_get(csv, row, "diff_max") <= 1 + 1e-14, "row %ld", row);
    }
    /* Fig. 5 table: eq. 14 at phi = 45 degrees, R-equivalence p = 2 */
    snprintf(csv, sizeof csv, "%s/fig5_bounds.csv", out);
    cr_assert_eq(e2e_csv_rows(csv), 6 * 91);
    cr_expect_float_eq(e2e_csv_get(csv, 45, "phi_deg"), 45.0, 1e-12);
    cr_expect_float_eq(e2e_csv_get(csv, 45, "F1"), pow(2, -1.5), 1e-15);
    cr_expect_float_eq(e2e_csv_get(csv, 45, "upper"), sqrt(0.5), 1e-15);
    cr_expect_float_eq(e2e_csv_get(csv, 0, "upper"), 1.0, 1e-15);
    /* profiles of alpha = 60 (points 0..7: p x join x parts) */
    for (int pt = 0; pt < 8; pt++) {
        snprintf(csv, sizeof csv, "%s/profile_pt%03d.csv", out, pt);
        cr_assert_eq(e2e_csv_rows(csv), 144, "%s", csv);
        for (long row = 0; row < 144; row++) {
            const double g = e2e_csv_get(csv, row, "grad_norm");
            cr_expect(g >= e2e_csv_get(csv, row, "lower_parts") - 1e-12 &&
                      g <= e2e_csv_get(csv, row, "upper_parts") + 1e-12, "%s row %ld", csv, row);
            /* exact parts: h1 = h2 = q in the hatched sector, phi = 45 */
            if (pt % 2 == 0 && e2e_csv_get(csv, row, "hatched") == 1.0)
                cr_expect_float_eq(e2e_csv_get(csv, row, "phi_deg"), 45.0, 1e-12);
        }
    }
    snprintf(csv, sizeof csv, "%s/profile_pt008.csv", out);
    cr_expect_eq(e2e_csv_rows(csv), -1, "profiles only for alpha = 60");
}

Test(e2e_bs04_gradbounds, bad_input_exits_2_without_files)
{
    static const char *const sets[][2] = {
        {"--set study.alpha=0", "study.alpha"},
        {"--set study.join=requiv_corrected", "requiv|rconj"},
        {"--set study.p=1", "study.p"},
        {"--set study.radii=0.7", "study.radii"},
        {"--set study.profile_samples=7", "does not divide"},
        {"--set study.fig5_p=2.5", "study.fig5_p"},
        {"--set study.colour=red", "study.colour"},
    };
    e2e_expect_bad_runs(CFG,
                        "--set study.alpha=90 --set study.p=2 --set study.join=rconj"
                        " --set study.parts=exact",
                        sets, sizeof sets / sizeof sets[0]);
}
