/* End-to-end: the bs04_spacecurves study (Fig. 8) on a small grid.  The
 * expected numbers come from the library run directly (polygonization,
 * rfield of the polyline), a brute-force distance to the curve (dense
 * sampling, independent of the footpoint solver) and bs04's counts. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "geom/polygonize.h"
#include "rfunc/rfield.h"
#include "util/e2e_util.h"

#define CFG "configs/paper/bs04/bs04_spacecurves.ini"
#define NSAMP 100000

Test(e2e_bs04_spacecurves, counts_and_slice_metrics, .timeout = 60)
{
    char out[512], csv[700];
    e2e_run_table(CFG, "--set study.trim=disk --set grid.n=10 --set study.slice_n=12",
                  "bs04_spacecurves", 2, out, sizeof out, csv, sizeof csv);
    const char *files[2] = {"configs/shapes/space1.ini", "configs/shapes/space2.ini"};
    const long paper[2] = {56, 90}; /* bs04 Sec. 3.1 */
    for (long r = 0; r < 2; r++) {
        char *name = e2e_csv_cell(csv, r, "curve");
        cr_assert_str_eq(name, r == 0 ? "space1" : "space2");
        free(name);
        dfl_bspline c;
        e2e_load_curve(files[r], "shape", &c);
        const double eps = e2e_csv_get(csv, (size_t)r, "eps");
        dfl_polyline pl;
        cr_assert_eq(dfl_polygonize_curve(&c, eps, 0, &pl, NULL), DFL_OK);
        cr_expect_eq((long)e2e_csv_get(csv, (size_t)r, "segments"), (long)(pl.n - 1));
        cr_expect_eq((long)e2e_csv_get(csv, (size_t)r, "paper_segments"), paper[r]);
        /* the shipped eps reproduces bs04's counts for our curves */
        cr_expect_eq((long)(pl.n - 1), paper[r], "%s: %zu segments", files[r], pl.n - 1);
        cr_expect(e2e_csv_get(csv, (size_t)r, "bound") <= eps);
        cr_expect_eq((long)e2e_csv_get(csv, (size_t)r, "count"), 1000);

        /* slice 0 (z = 0.5, 12 x 12 on [0, 1]^2) recomputed: u from the
         * library's rfield of the same polyline (p = 2, sphere trim),
         * d by brute force over NSAMP curve points */
        const int closed = c.closed;
        dfl_field f;
        cr_assert_eq(dfl_rfield_polyline(3, pl.pts, closed ? pl.n - 1 : pl.n, closed,
                                         DFL_RFUNC_REQUIV, 2, DFL_RFUNC_TRIM_DISK, &f, NULL),
                     DFL_OK);
        double *cs = malloc(3 * NSAMP * sizeof *cs);
        for (int i = 0; i < NSAMP; i++)
            dfl_bspline_eval(&c, c.t0 + (c.t1 - c.t0) * i / (NSAMP - 1.0), 0, cs + 3 * i);
        double l1 = 0, linf = 0;
        long inband = 0;
        for (int j = 0; j < 12; j++)
            for (int i = 0; i < 12; i++) {
                const double x[3] = {i / 11.0, j / 11.0, 0.5};
                double d2 = INFINITY;
                for (int k = 0; k < NSAMP; k++) {
                    const double a = x[0] - cs[3 * k], b = x[1] - cs[3 * k + 1],
                                 e = x[2] - cs[3 * k + 2];
                    d2 = fmin(d2, a * a + b * b + e * e);
                }
                const double u = dfl_field_eval1(&f, x, NULL), d = sqrt(d2);
                l1 += fabs(u - d) / 144.0;
                linf = fmax(linf, fabs(u - d));
                inband += d <= 0.05;
            }
        /* sampling spacing <= 4e-5 (curve length < 4): the brute-force
         * distance is above the true one by at most 2e-5 */
        cr_expect(fabs(e2e_csv_get(csv, (size_t)r, "l1_s0") - l1) <= 2e-5, "row %ld: l1 %.9g vs %.9g",
                  r, e2e_csv_get(csv, (size_t)r, "l1_s0"), l1);
        cr_expect(fabs(e2e_csv_get(csv, (size_t)r, "linf_s0") - linf) <= 2e-5, "row %ld: linf", r);
        cr_expect(fabs(e2e_csv_get(csv, (size_t)r, "count_s0_band") - (double)inband) <= 1.0);
        free(cs);
        dfl_field_destroy(&f);
        dfl_polyline_free(&pl);
        dfl_bspline_free(&c);
    }
    /* files: per curve a polyline, a volume and two slices (vti + exr) */
    cr_expect_eq(e2e_count_entries(out), 3 + 2 * (1 + 2 + 4));
}

Test(e2e_bs04_spacecurves, bad_input)
{
    /* a planar curve is not a space curve */
    e2e_expect_bad_config("[study]\nname = bs04_spacecurves\ncurves = c\neps = 1e-2\n"
                          "slices = z 0.5\nvolume = false\n"
                          "[c]\nkind = bspline_curve\ncontrol = 0 0; 1 0; 1 1; 0 1\n",
                          "[c] control", "space curve");
    /* a malformed slice */
    e2e_expect_bad_config("[study]\nname = bs04_spacecurves\ncurves = c\neps = 1e-2\n"
                          "slices = w 0.5\nvolume = false\n"
                          "[c]\nkind = bspline_curve\ncontrol = 0 0 0; 1 0 0; 1 1 0; 0 1 1\n",
                          "[study] slices", "<x|y|z>");
}
