/* The pht probe contract through the binary: `dflab probe` on a
 * `[field] kind = pht` circle fit gives values within eps of the closed-form
 * SDF |x - c| - r (dflab sign: negative inside), gradients close to the
 * radial unit vector, and jets that agree with the gradient (d1 = grad . dir)
 * and with the circle's second directional derivative (the curvature term
 * (|dir|^2 - (u . dir)^2) / |x - c|, to the fit's accuracy); bad keys exit 2
 * naming the key. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/e2e_util.h"

#define CFG                                                                                  \
    "[field]\nkind = pht\neps = 1e-5\nmax_level = 20\nsamples = 16\nsplit = cross\n"        \
    "estimator = random\nseed = 3\n[shape]\nkind = circle\ncenter = 0.5 0.5\nradius = 0.3\n"

Test(e2e_probe_pht, circle_values_gradients_and_jets, .timeout = 60)
{
    char dir[256], path[600], args[1024];
    e2e_tmpdir(dir, sizeof dir);
    e2e_write(dir, "f.ini", CFG, path, sizeof path);
    /* inside, outside, near the curve, and on a cell boundary (x = 0.75) */
    static const double P[][4] = {{0.6, 0.55, 1, 0},     {0.1, 0.2, 0.6, 0.8},
                                  {0.79, 0.5, -1, 0},    {0.75, 0.3, 0, 1},
                                  {0.25, 0.75, 0.3, -0.4}};
    const int n = 5;
    char pts[1024] = "x,y,dx,dy\n";
    for (int i = 0; i < n; i++) {
        char row[128];
        snprintf(row, sizeof row, "%.17g,%.17g,%.17g,%.17g\n", P[i][0], P[i][1], P[i][2], P[i][3]);
        strcat(pts, row);
    }
    e2e_write(dir, "p.csv", pts, path, sizeof path);
    snprintf(args, sizeof args, "probe %s/f.ini --points %s/p.csv --jet 3", dir, dir);
    int rc = e2e_dflab(dir, args);
    char *msg = e2e_err_text(dir);
    cr_assert_eq(rc, 0, "%s", msg);
    free(msg);
    snprintf(path, sizeof path, "%s/out.txt", dir);
    cr_assert_eq(e2e_csv_rows(path), n);
    for (int i = 0; i < n; i++) {
        double x = P[i][0] - 0.5, y = P[i][1] - 0.5, r = hypot(x, y), u[2] = {x / r, y / r};
        double v = e2e_csv_get(path, (size_t)i, "value");
        double gx = e2e_csv_get(path, (size_t)i, "gx"), gy = e2e_csv_get(path, (size_t)i, "gy");
        cr_expect(fabs(v - (r - 0.3)) <= 1e-5, "row %d: value %.12g vs %.12g", i, v, r - 0.3);
        cr_expect(fabs(gx - u[0]) < 1e-3 && fabs(gy - u[1]) < 1e-3, "row %d: grad %g %g", i, gx,
                  gy);
        double d1 = e2e_csv_get(path, (size_t)i, "d1"), d2 = e2e_csv_get(path, (size_t)i, "d2");
        /* the jet is the cell polynomial's: d1 = grad . dir exactly (off cell faces) */
        if (i != 3)
            cr_expect(fabs(d1 - (gx * P[i][2] + gy * P[i][3])) < 1e-10, "row %d: d1 %.15g", i, d1);
        double ud = u[0] * P[i][2] + u[1] * P[i][3];
        double dd = P[i][2] * P[i][2] + P[i][3] * P[i][3];
        cr_expect(fabs(d1 - ud) < 1e-3, "row %d: d1 %g vs %g", i, d1, ud);
        cr_expect(fabs(d2 - (dd - ud * ud) / r) < 0.05 * (1 + fabs(dd / r)), "row %d: d2 %g vs %g",
                  i, d2, (dd - ud * ud) / r);
    }
    /* a bad key: exit 2, the key named */
    snprintf(args, sizeof args, "probe %s/f.ini --points %s/p.csv --set field.eps=0", dir, dir);
    rc = e2e_dflab(dir, args);
    msg = e2e_err_text(dir);
    cr_expect_eq(rc, 2);
    cr_expect(strstr(msg, "eps"), "%s", msg);
    free(msg);
    snprintf(args, sizeof args, "probe %s/f.ini --points %s/p.csv --set field.max_level=99", dir,
             dir);
    rc = e2e_dflab(dir, args);
    msg = e2e_err_text(dir);
    cr_expect_eq(rc, 2);
    cr_expect(strstr(msg, "max_level"), "%s", msg);
    free(msg);
    cr_expect_eq(e2e_rmtree(dir), 0);
}
