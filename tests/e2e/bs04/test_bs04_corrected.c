/* End-to-end: the bs04_corrected study (Fig. 14, eq. 20) on a small sweep.
 * Expected values are derived here:
 *   - exact parts, hatched sector: h1 = h2 = q, so eq. 6 gives u = 2^(-1/p) q
 *     (|grad u| defect 1 - 2^(-1/p) at every sample) and eq. 20 gives u = q
 *     (defect 0 to rounding);
 *   - exact parts, collinear (alpha = 180): off the sector one segment's
 *     closest point is O, h_far = q cancels in eq. 20, so the corrected field
 *     is the exact distance everywhere;
 *   - trimmed parts (disk): h_i >= q in the sector (t = y.e - |y|^2/d with
 *     y.e <= 0 only adds to h^2), the library's guard subtracts max(h1, h2)^-p
 *     and u = min(h1, h2): the defect is the parts' own, no more;
 *   - bs04's eq. 20 as printed (correction = eq20): with exact parts the
 *     same sector numbers as the guarded form and defined everywhere; with
 *     disk parts undefined beyond r* = L (sqrt(cos^2(alpha'/2) + 2^(2/p) -
 *     1) - cos(alpha'/2)) on the hatched bisector (rfunc/join.h);
 *   - alpha = 60, theta = 80, r = L/2, exact parts, p = 2: both closest
 *     points interior, h1 = r sin 80, h2 = r sin 20, q = r, so eq. 20 gives
 *     u = r (sin^-2 80 + sin^-2 20 - 1)^(-1/2) < d = r sin 20;
 *   - the .vti images through VTK's reader agree with the same closed forms. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/e2e_util.h"

#define CFG "configs/paper/bs04/bs04_corrected.ini"

Test(e2e_bs04_corrected, sector_defects_and_images, .timeout = 60)
{
    char dir[256], out[512], csv[700], path[800];
    e2e_tmpdir(dir, sizeof dir);
    /* points: alpha x p x parts (last fastest); rows: requiv, guarded, eq20 */
    e2e_run_table(CFG,
                  "--set 'study.alpha=90, 180' --set 'study.p=2, 7'"
                  " --set 'study.parts=exact, disk' --set grid.n=41 --set study.sector_nr=10"
                  " --set study.sector_nt=5",
                  "bs04_corrected", 24, out, sizeof out, csv, sizeof csv);
    for (int pt = 0; pt < 8; pt++) {
        const double alpha = pt < 4 ? 90 : 180;
        const int p = (pt / 2) % 2 ? 7 : 2, exact = pt % 2 == 0;
        const long rr = 3 * pt, rc_ = 3 * pt + 1, rl = 3 * pt + 2;
        cr_assert(strcmp(e2e_csv_cell(csv, rl, "correction"), "eq20") == 0);
        cr_assert_eq(e2e_csv_get(csv, rr, "alpha"), alpha);
        cr_assert_eq((int)e2e_csv_get(csv, rr, "p"), p);
        /* alpha = 90: 5 directions x 10 radii; 180: 2 rays x 10 radii */
        const double npts = alpha == 90 ? 50 : 20;
        cr_expect_eq(e2e_csv_get(csv, rr, "sector_points"), npts, "pt %d", pt);
        cr_expect_eq(e2e_csv_get(csv, rc_, "sector_points"), npts, "pt %d", pt);
        const double def = 1 - pow(2, -1.0 / p);
        if (exact) {
            cr_expect_float_eq(e2e_csv_get(csv, rr, "sector_gdef_max"), def, 1e-12, "pt %d", pt);
            cr_expect_float_eq(e2e_csv_get(csv, rr, "sector_gdef_min"), def, 1e-12, "pt %d", pt);
            cr_expect_float_eq(e2e_csv_get(csv, rr, "sector_value_relerr_max"), def, 1e-12);
            cr_expect(e2e_csv_get(csv, rc_, "sector_gdef_max") < 1e-9, "pt %d", pt);
            cr_expect(e2e_csv_get(csv, rc_, "sector_value_relerr_max") < 1e-12, "pt %d", pt);
            cr_expect_float_eq(e2e_csv_get(csv, rr, "sector_gdef_theory"), def, 1e-15);
            cr_expect_eq(e2e_csv_get(csv, rc_, "sector_gdef_theory"), 0.0);
            if (alpha == 180) {
                cr_expect(e2e_csv_get(csv, rc_, "band_linf") < 1e-12, "pt %d", pt);
                cr_expect(e2e_csv_get(csv, rc_, "band_gdef_max") < 1e-12, "pt %d", pt);
                cr_expect(e2e_csv_get(csv, rc_, "vertex_linf") < 1e-12, "pt %d", pt);
                cr_expect(e2e_csv_get(csv, rc_, "vertex_gdef_max") < 1e-12, "pt %d", pt);
                /* the plain join is not the distance near O */
                cr_expect(e2e_csv_get(csv, rr, "vertex_gdef_max") > 0.5 * def, "pt %d", pt);
            }
            cr_expect_eq(e2e_csv_get(csv, rl, "undefined_count"), 0.0, "pt %d", pt);
            cr_expect(fabs(e2e_csv_get(csv, rl, "sector_gdef_max") -
                           e2e_csv_get(csv, rc_, "sector_gdef_max")) < 1e-12, "pt %d", pt);
        } else {
            const double a = alpha == 90 ? sqrt(0.5) : 0.0;
            const double rs = sqrt(a * a + pow(2.0, 2.0 / p) - 1.0) - a;
            cr_expect_float_eq(e2e_csv_get(csv, rl, "onset_radius"), rs, 1e-9, "pt %d", pt);
            cr_expect_float_eq(e2e_csv_get(csv, rl, "onset_radius_theory"), rs, 1e-15);
            cr_expect(e2e_csv_get(csv, rl, "undefined_count") > 0, "pt %d", pt);
            cr_expect_eq(e2e_csv_get(csv, rc_, "undefined_count"), 0.0, "pt %d", pt);
            const double pg = e2e_csv_get(csv, rc_, "sector_part_gdef_max");
            cr_expect(e2e_csv_get(csv, rc_, "sector_gdef_max") <= pg + 1e-12, "pt %d", pt);
            /* Disk trim behind its end point O (y = x - O, e into the
             * segment, n its normal, d = L): f = y.n, t = y.e - |y|^2/d,
             * grad h = (f n + t e)/h - 2 t y/(d h) and |f n + t e| = h, |t| <= h:
             * | |grad h| - 1 | <= 2 |y| / L.  So on the innermost ring
             * (rho = r / L = 0.5 / 10) the corrected defect is <= 2 rho. */
            const double rho = 0.05;
            cr_expect(e2e_csv_get(csv, rc_, "sector_gdef_at_rmin") <= 2 * rho + 1e-12, "pt %d", pt);
            /* Plain join: h_i in [q, q (1 + rho)] (h^2 = q^2 (1 - 2 y.e/d +
             * q^2/d^2)), so phi is within atan(1 + rho) of 45 degrees and
             * |grad u| <= (F1 + F2)(phi) (1 + 2 rho), F1 + F2 largest at the
             * ends of that range (eq. 14, monotone on each side of 45). */
            const double ph = atan(1 + rho), c = cos(ph), sn = sin(ph);
            const double smax = (pow(c, p + 1) + pow(sn, p + 1)) / pow(pow(c, p) + pow(sn, p), (p + 1.0) / p);
            cr_expect(e2e_csv_get(csv, rr, "sector_gdef_at_rmin") >= 1 - smax * (1 + 2 * rho) - 1e-12,
                      "pt %d", pt);
        }
        cr_expect(e2e_csv_get(csv, rr, "band_count") > 0 && e2e_csv_get(csv, rr, "vertex_count") > 0);
    }
    /* images of point 0 (alpha 90, p 2, exact) through VTK */
    const char *arrays[] = {"grad_norm", "error", "reference"};
    int nx[2], ny[2], nm[2];
    double gmax[2], gmin[2], verr[2];
    for (int j = 0; j < 2; j++) {
        e2e_vti img;
        snprintf(path, sizeof path, "%s/%s_pt000.vti", out, j ? "corrected" : "requiv");
        e2e_vti_read(dir, path, arrays, 3, &img);
        nx[j] = img.dims[0], ny[j] = img.dims[1], nm[j] = 0;
        gmax[j] = verr[j] = -INFINITY, gmin[j] = INFINITY;
        /* the hatched sector x <= 0, y <= 0, off the set */
        for (size_t i = 0; i < img.npoints; i++) {
            const double *P = img.pts + 3 * i, g = img.val[3 * i], e = img.val[3 * i + 1],
                         ref = img.val[3 * i + 2];
            if (!(P[0] <= 0 && P[1] <= 0 && ref > 0)) continue;
            nm[j]++;
            gmax[j] = e2e_max(gmax[j], fabs(g - 1));
            gmin[j] = e2e_min(gmin[j], fabs(g - 1));
            verr[j] = e2e_max(verr[j], fabs(e + ref - hypot(P[0], P[1])));
        }
        e2e_vti_free(&img);
    }
    /* 41 x 41 on [-1.5, 1.5]^2: x <= 0 is 21 columns, minus the node at O */
    for (int j = 0; j < 2; j++) {
        cr_expect_eq(nx[j], 41);
        cr_expect_eq(ny[j], 41);
        cr_expect_eq(nm[j], 21 * 21 - 1);
    }
    /* value = error + reference; in the sector 2^(-1/2) q resp. q */
    cr_expect_float_eq(gmax[0], 1 - sqrt(0.5), 1e-6);
    cr_expect_float_eq(gmin[0], 1 - sqrt(0.5), 1e-6);
    cr_expect(verr[0] > 0.25);
    cr_expect(gmax[1] < 1e-9 && verr[1] < 1e-12, "corrected image: %g %g", gmax[1], verr[1]);
    static const char *const stems[3] = {"requiv", "corrected", "eq20"};
    for (int pt = 0; pt < 8; pt++)
        for (int j = 0; j < 3; j++) {
            snprintf(path, sizeof path, "%s/%s_pt%03d.exr", out, stems[j], pt);
            FILE *fp = fopen(path, "rb");
            cr_expect_not_null(fp, "%s", path);
            if (fp) fclose(fp);
        }
}

Test(e2e_bs04_corrected, eq20_below_90_degrees, .timeout = 60)
{
    char out[512], csv[700];
    e2e_run_table(CFG,
                  "--set study.alpha=60 --set study.p=2 --set study.parts=exact --set grid.n=21"
                  " --set study.sector_nr=4 --set study.sector_nt=3",
                  "bs04_corrected", 3, out, sizeof out, csv, sizeof csv);
    const double s80 = sin(80 * acos(-1.0) / 180), s20 = sin(20 * acos(-1.0) / 180);
    const double u = 1.0 / sqrt(1.0 / (s80 * s80) + 1.0 / (s20 * s20) - 1.0);
    cr_expect_float_eq(e2e_csv_get(csv, 2, "case_u"), u, 1e-13);
    cr_expect_float_eq(e2e_csv_get(csv, 2, "case_d"), s20, 1e-13);
    cr_expect(fabs(u - 0.34140) < 5e-6 && fabs(s20 - 0.34202) < 5e-6);
    /* the reflex side is no longer exact below 90 degrees */
    cr_expect(e2e_csv_get(csv, 2, "reflex_linf") > 1e-3);
}

Test(e2e_bs04_corrected, bad_input_exits_2_without_files)
{
    static const char *const sets[][2] = {
        {"--set study.alpha=360", "study.alpha"},
        {"--set study.parts=round", "study.parts"},
        {"--set study.p=0", "study.p"},
        {"--set study.length=0", "study.length"},
        {"--set grid.n=1", "grid.n"},
        {"--set study.colour=red", "study.colour"},
        {"--set study.onset_rmax=0", "study.onset_rmax"},
    };
    e2e_expect_bad_runs(CFG, "--set study.alpha=90 --set study.p=2 --set study.parts=exact", sets,
                        sizeof sets / sizeof sets[0]);
}
