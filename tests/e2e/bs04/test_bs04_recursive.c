/* End-to-end: the bs04 recursive normalization study (appendix A) on a
 * coarse grid.
 *
 * Expected values derived here: the measured order is m at every boundary
 * point (A.4 cancels exactly the terms s^2..s^m), the error along a normal
 * line is a_(m+1) delta^(m+1) (1 + O(delta)) so its log-log slope is m + 1,
 * the m = 1 field is A.1 in closed form f / sqrt(f^2 + |grad f|^2), the
 * reference is the distance to the ellipse by brute force (dense sampling
 * and golden-section refinement), and the band columns are recomputed from
 * the .vti arrays read by VTK. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/vec.h"
#include "util/e2e_util.h"

#define CFG "configs/paper/bs04/bs04_recursive.ini"

static double brute_dist(double a, double b, const double *x)
{
    const int N = 2000;
    const double tp = 2 * DFL_PI;
    double best = INFINITY, tb = 0;
    for (int i = 0; i < N; i++) {
        const double t = tp * i / N, d = hypot(a * cos(t) - x[0], b * sin(t) - x[1]);
        if (d < best) best = d, tb = t;
    }
    /* the global minimum is within one sample of the best sample */
    double lo = tb - tp / N, hi = tb + tp / N;
    const double gr = 0.5 * (sqrt(5.0) - 1.0);
    for (int it = 0; it < 100; it++) {
        const double m1 = hi - gr * (hi - lo), m2 = lo + gr * (hi - lo);
        if (hypot(a * cos(m1) - x[0], b * sin(m1) - x[1]) < hypot(a * cos(m2) - x[0], b * sin(m2) - x[1]))
            hi = m2;
        else
            lo = m1;
    }
    const double t = 0.5 * (lo + hi);
    return fmin(best, hypot(a * cos(t) - x[0], b * sin(t) - x[1]));
}

Test(e2e_bs04_recursive, orders_slopes_and_fields, .timeout = 60)
{
    char dir[256], out[512], csv[700], path[800];
    e2e_tmpdir(dir, sizeof dir);
    const int N = 25;
    const double A = 1.0, B = 0.5, LO = -1.3, HI = 1.3;
    char extra[256];
    snprintf(extra, sizeof extra,
             "--set grid.n=%d --set 'field.m=1, 2, 3, 4' --set implicit.b=%g --set study.points=16",
             N, B);
    e2e_run_table(CFG, extra, "bs04_recursive", 4, out, sizeof out, csv, sizeof csv);
    for (long r = 0; r < 4; r++) {
        const int m = (int)e2e_csv_get(csv, (size_t)r, "m");
        cr_assert_eq(m, r + 1);
        cr_expect_eq((int)e2e_csv_get(csv, (size_t)r, "rays"), 32);
        cr_expect_eq((int)e2e_csv_get(csv, (size_t)r, "measured_order_min"), m);
        cr_expect_eq((int)e2e_csv_get(csv, (size_t)r, "measured_order_max"), m);
        cr_expect_eq((int)e2e_csv_get(csv, (size_t)r, "first_k"), m + 1);
        cr_expect(e2e_csv_get(csv, (size_t)r, "first_coef_min") > 1e-3, "m=%d: a_(m+1) vanishes", m);
        cr_expect(e2e_csv_get(csv, (size_t)r, "d1_maxdev") < 1e-12);
        const double slope = e2e_csv_get(csv, (size_t)r, "line_slope");
        if (m <= 3) cr_expect(fabs(slope - (m + 1)) < 0.25, "m=%d: slope %g", m, slope);
        /* errors shrink like delta^(m+1): each doubling multiplies by ~2^(m+1) */
        const double e1 = e2e_csv_get(csv, (size_t)r, "line_err_1");
        const double e2 = e2e_csv_get(csv, (size_t)r, "line_err_2");
        cr_expect(e2 / e1 > pow(2, m + 1) * 0.7 && e2 / e1 < pow(2, m + 1) * 1.5, "m=%d: %g %g", m,
                  e1, e2);
        cr_expect_eq(e2e_csv_get(csv, (size_t)r, "nonfinite_nodes"), 0);

        /* the image through VTK */
        char *vti = e2e_csv_cell(csv, r, "vti");
        const char *arrays[] = {"value", "reference", "grad_norm"};
        e2e_vti img;
        snprintf(path, sizeof path, "%s/%s", out, vti);
        e2e_vti_read(dir, path, arrays, 3, &img);
        cr_assert_eq(img.npoints, (size_t)(N * N));
        const double band1 = e2e_csv_get(csv, (size_t)r, "band_1");
        double linf1 = 0, sum1 = 0;
        long n1 = 0;
        for (int j = 0; j < N * N; j++) {
            const double val = img.val[3 * (size_t)j], ref = img.val[3 * (size_t)j + 1];
            const double x[2] = {LO + (j % N) * (HI - LO) / (N - 1), LO + (j / N) * (HI - LO) / (N - 1)};
            const double f = x[0] * x[0] / (A * A) + x[1] * x[1] / (B * B) - 1;
            if (j % 3 == 0) {
                const double bd = brute_dist(A, B, x) * (f < 0 ? -1 : 1);
                cr_expect(fabs(ref - bd) < 1e-9, "reference at (%g %g): %.12g vs %.12g", x[0], x[1],
                          ref, bd);
            }
            if (m == 1) {
                const double gx = 2 * x[0] / (A * A), gy = 2 * x[1] / (B * B);
                const double f1 = f / sqrt(f * f + gx * gx + gy * gy);
                cr_expect(fabs(val - f1) < 1e-14, "A.1 at (%g %g): %.17g vs %.17g", x[0], x[1], val,
                          f1);
            }
            if (fabs(ref) <= band1) {
                n1++;
                sum1 += fabs(val - ref);
                linf1 = e2e_max(linf1, fabs(val - ref));
            }
        }
        e2e_vti_free(&img);
        cr_expect_eq((long)e2e_csv_get(csv, (size_t)r, "band_nodes_1"), n1);
        cr_expect_float_eq(e2e_csv_get(csv, (size_t)r, "linf_band_1"), linf1, 1e-12 * (1 + linf1));
        cr_expect_float_eq(e2e_csv_get(csv, (size_t)r, "l1_band_1"), sum1 / (double)n1,
                           1e-12 * (1 + linf1));
        free(vti);
    }
}

Test(e2e_bs04_recursive, bad_input_exits_2_without_files)
{
    static const char *const sets[][2] = {
        {"--set field.m=7", "field.m"},
        {"--set study.K=3 --set field.m=3", "study.K"},
        {"--set 'study.deltas=0.01 0.005'", "study.deltas"},
        {"--set 'study.deltas=0.01 0.3'", "study.deltas"},
        {"--set 'study.bands=0.1 0'", "study.bands"},
        {"--set implicit.kind=circle", "implicit.kind"},
        {"--set implicit.a=0", "implicit.a"},
    };
    e2e_expect_bad_runs(CFG, NULL, sets, sizeof sets / sizeof sets[0]);
}
