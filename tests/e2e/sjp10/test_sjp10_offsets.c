/* End-to-end: the sjp10_offsets study on small cases.  Expected values are
 * derived:
 *   - a plane's SDF is linear and reproduced exactly by the spline, so its
 *     level sets f = delta are the true offsets: one line each (2D: a
 *     segment across the square; 3D: a planar patch and one line on the
 *     cutting plane) at distance 0 (rounding) from {d = delta};
 *   - an elongated convex curve (a periodic cubic B-spline through 32
 *     points of the ellipse with semi-axes 0.4, 0.2: curvature ~ a / b^2 =
 *     10 at the ends of the long axis, ~ b / a^2 = 1.25 at the short one's)
 *     has, at the inner offset delta = -0.15 (1/kappa_max < 0.15 < b), a
 *     swallow-tail at each end of the long axis: 4 cusps, 2 tails, 2
 *     self-intersections, and a part closer to the curve than 0.15 that
 *     trimming removes; its outer offsets (delta > 0) are regular and never
 *     closer than delta (nothing removed);
 *   - the trimmed offsets of the convex curve are single closed curves, as
 *     the exact level sets {d = delta} are. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/vec.h"
#include "util/e2e_util.h"

static void ellipse_control(char *buf, size_t size)
{
    size_t k = 0;
    for (int i = 0; i < 32; i++) {
        const double t = 2 * DFL_PI * i / 32;
        k += (size_t)snprintf(buf + k, size - k, "%s%.17g %.17g", i ? "; " : "", 0.5 + 0.4 * cos(t),
                              0.5 + 0.2 * sin(t));
    }
}

Test(e2e_sjp10_offsets, plane_exact_ellipse_swallow_tails, .timeout = 120)
{
    char cp[4096], ini[8192], dir[256], cfg[512], out[512], csv[700];
    ellipse_control(cp, sizeof cp);
    snprintf(ini, sizeof ini,
             "[study]\nname = sjp10_offsets\ncases = ell plane2 plane3\nfit = fit\nfit3 = fit3\n"
             "[fit]\neps = 1e-3\nmax_level = 6\nsamples = 4\n"
             "[fit3]\neps = 1e-2\nmax_level = 2\nsamples = 2\n"
             "[ell]\nshape = ellipse_curve\ndeltas = -0.15 0.05\ngrid_n = 61\noffset_samples = 2000\n"
             "[plane2]\nshape = p2\ndeltas = -0.1 0.2\ngrid_n = 21\n"
             "[plane3]\nshape = p3\ndeltas = -0.2\nlo = -1 -1 -1\nhi = 1 1 1\ngrid_n = 9\n"
             "cut_lo = -1 -1 -1\ncut_hi = 1 1 0\nplane_axis = 2\nplane_at = 0\n"
             "[ellipse_curve]\nkind = bspline_curve\norder = 4\nclosed = true\ncontrol = %s\n"
             "[p2]\nkind = plane\ndim = 2\npoint = 0.5 0.5\nnormal = 1 2\n"
             "[p3]\nkind = plane\npoint = 0 0 0\nnormal = 1 1 0\n",
             cp);
    e2e_tmpdir(dir, sizeof dir);
    e2e_write(dir, "off.ini", ini, cfg, sizeof cfg);
    e2e_run_table(cfg, NULL, "sjp10_offsets", 5, out, sizeof out, csv, sizeof csv);
    for (long r = 0; r < 5; r++) {
        char *cs = e2e_csv_cell(csv, r, "case");
        cr_assert_not_null(cs);
        const double delta = e2e_csv_get(csv, (size_t)r, "delta");
        cr_expect_eq(e2e_csv_get(csv, (size_t)r, "sjp10_delta"), -delta);
        if (strcmp(cs, "ell") == 0) {
            const int inner = delta < 0;
            cr_expect_eq(e2e_csv_get(csv, (size_t)r, "cusps"), inner ? 4 : 0, "delta %g", delta);
            cr_expect_eq(e2e_csv_get(csv, (size_t)r, "swallow_tails"), inner ? 2 : 0);
            cr_expect_eq(e2e_csv_get(csv, (size_t)r, "self_intersections"), inner ? 2 : 0);
            const double rem = e2e_csv_get(csv, (size_t)r, "removed_fraction");
            if (inner) cr_expect_gt(rem, 0.0);
            else cr_expect_eq(rem, 0.0);
            cr_expect_eq(e2e_csv_get(csv, (size_t)r, "iso_lines"), 1);
            cr_expect_eq(e2e_csv_get(csv, (size_t)r, "iso_closed"), 1);
            cr_expect_eq(e2e_csv_get(csv, (size_t)r, "exact_lines"), 1);
        } else if (strcmp(cs, "plane2") == 0) {
            cr_expect_lt(e2e_csv_get(csv, (size_t)r, "err_max"), 1e-12);
            cr_expect_eq(e2e_csv_get(csv, (size_t)r, "iso_lines"), 1);
            cr_expect_eq(e2e_csv_get(csv, (size_t)r, "exact_lines"), 1);
            cr_expect_eq(e2e_csv_get(csv, (size_t)r, "untrimmed"), 0);
        } else {
            cr_expect_lt(e2e_csv_get(csv, (size_t)r, "err_max"), 1e-12);
            cr_expect_lt(e2e_csv_get(csv, (size_t)r, "plane_err_max"), 1e-12);
            cr_expect_gt(e2e_csv_get(csv, (size_t)r, "iso_triangles"), 0);
            cr_expect_eq(e2e_csv_get(csv, (size_t)r, "plane_lines"), 1);
        }
        free(cs);
    }
    e2e_rmtree(dir);
}
