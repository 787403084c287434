/* The rfunc probe contract through the binary: for every join, trim and p,
 * `dflab probe --jet K` at an interior point of a segment along its normal
 * gives d1 = 1 and d2..dm = 0 with m = p for R-equivalence (eq. 6) and
 * m = p - 1 for R-conjunction (eq. 7), then a non-zero derivative; the
 * value on the segment is 0.  (The smooth disk trim caps the order at 6:
 * h = s + s^7/(32 t0^2) + ..., see src/rfunc/trim.h, so p <= 5 here.) */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/e2e_util.h"

static const char *const joins[] = {"requiv", "rconj"};
static const char *const trims[] = {"disk", "strip", "disk_smooth"};

Test(e2e_probe_rfunc, orders_for_every_join_trim_p, .timeout = 60)
{
    char dir[256], path[600], args[2048];
    e2e_tmpdir(dir, sizeof dir);
    /* an open 3-segment polyline; probe at the midpoint of the middle
     * segment, along its unit normal (segment (1,0)-(2,1): normal (-1,1)/sqrt2) */
    e2e_write(dir, "f.ini",
              "[field]\nkind = rfunc\nvertices = 0 0; 1 0; 2 1; 2.5 3\nclosed = false\n", path,
              sizeof path);
    const double r = sqrt(0.5);
    char pts[256];
    snprintf(pts, sizeof pts, "x,y,dx,dy\n1.5,0.5,%.17g,%.17g\n1.5,0.5,%.17g,%.17g\n", -r, r, r, -r);
    e2e_write(dir, "p.csv", pts, path, sizeof path);
    const int K = 10;
    for (int j = 0; j < 2; j++)
        for (int t = 0; t < 3; t++)
            for (int p = 2; p <= 5; p++) {
                snprintf(args, sizeof args,
                         "probe %s/f.ini --points %s/p.csv --jet %d --set field.join=%s "
                         "--set field.trim=%s --set field.p=%d",
                         dir, dir, K, joins[j], trims[t], p);
                int rc = e2e_dflab(dir, args);
                char *msg = e2e_err_text(dir);
                cr_assert_eq(rc, 0, "%s: %s", args, msg);
                free(msg);
                snprintf(path, sizeof path, "%s/out.txt", dir);
                int m = j == 0 ? p : p - 1;
                for (size_t row = 0; row < 2; row++) {
                    cr_expect(fabs(e2e_csv_get(path, row, "value")) < 1e-15);
                    cr_expect_float_eq(e2e_csv_get(path, row, "d1"), 1.0, 1e-12, "%s %s p=%d",
                                       joins[j], trims[t], p);
                    for (int k = 2; k <= m; k++) {
                        char col[16];
                        snprintf(col, sizeof col, "d%d", k);
                        double dk = e2e_csv_get(path, row, col);
                        cr_expect(fabs(dk) < 1e-9, "%s %s p=%d: %s = %g", joins[j], trims[t], p,
                                  col, dk);
                    }
                    char col[16];
                    snprintf(col, sizeof col, "d%d", m + 1);
                    double next = e2e_csv_get(path, row, col);
                    cr_expect(fabs(next) > 1e-6, "%s %s p=%d: %s = %g should be non-zero",
                              joins[j], trims[t], p, col, next);
                }
            }
    cr_expect_eq(e2e_rmtree(dir), 0);
}
