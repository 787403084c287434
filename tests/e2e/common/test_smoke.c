/* End-to-end: the smoke study and probe on the circle/sphere configs.
 * Expected numbers are derived from the closed-form SDF, not copied from a
 * previous run: with u = (1+a) d + b the error is e = a d + b, so the
 * metrics are sums over the grid nodes of |a d + b| computed here. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "io/exr.h"
#include "util/e2e_util.h"

static double circle_d(double x, double y) { return hypot(x - 0.5, y - 0.5) - 0.3; }

Test(e2e_smoke, circle_files_and_metrics)
{
    char dir[256], out[512], args[1024], path[600];
    e2e_tmpdir(dir, sizeof dir);
    snprintf(out, sizeof out, "%s/res", dir);
    snprintf(args, sizeof args, "run configs/smoke/smoke.ini --out %s --set grid.n=33 --quiet", out);
    int rc = e2e_dflab(dir, args);
    char *msg = e2e_err_text(dir);
    cr_assert_eq(rc, 0, "dflab run failed: %s", msg);
    free(msg);
    const char *files[] = {"smoke.csv", "field.vti", "field.exr", "config.ini", "manifest.json"};
    for (size_t i = 0; i < 5; i++) {
        snprintf(path, sizeof path, "%s/%s", out, files[i]);
        FILE *fp = fopen(path, "rb");
        cr_assert_not_null(fp, "missing %s", files[i]);
        fclose(fp);
    }
    cr_expect_eq(e2e_count_entries(out), 5, "unexpected extra files");

    /* derived metrics: a = 0.02, b = 0.005 (configs/smoke/smoke.ini), n = 33 */
    const int n = 33;
    const double a = 0.02, b = 0.005, band = 0.1;
    double s1 = 0, s2 = 0, mx = 0, bs1 = 0, bmx = 0;
    long cnt = 0, bcnt = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double d = circle_d((double)i / (n - 1), (double)j / (n - 1));
            double e = fabs(a * d + b);
            s1 += e, s2 += e * e, mx = fmax(mx, e), cnt++;
            if (fabs(d) <= band) bs1 += e, bmx = fmax(bmx, e), bcnt++;
        }
    snprintf(path, sizeof path, "%s/smoke.csv", out);
    cr_assert_eq(e2e_csv_rows(path), 1);
    cr_expect_eq((long)e2e_csv_get(path, 0, "nodes"), n * n);
    cr_expect_float_eq(e2e_csv_get(path, 0, "l1"), s1 / cnt, 1e-14);
    cr_expect_float_eq(e2e_csv_get(path, 0, "mse"), s2 / cnt, 1e-15);
    cr_expect_float_eq(e2e_csv_get(path, 0, "rms"), sqrt(s2 / cnt), 1e-14);
    cr_expect_float_eq(e2e_csv_get(path, 0, "linf"), mx, 1e-14);
    cr_expect_eq((long)e2e_csv_get(path, 0, "count_band"), bcnt);
    cr_expect_float_eq(e2e_csv_get(path, 0, "l1_band"), bs1 / bcnt, 1e-14);
    cr_expect_float_eq(e2e_csv_get(path, 0, "linf_band"), bmx, 1e-14);
    /* |grad u| = 1 + a everywhere, so the defect is a exactly */
    cr_expect_float_eq(e2e_csv_get(path, 0, "graddefect_mean"), a, 1e-12);
    cr_expect_float_eq(e2e_csv_get(path, 0, "graddefect_max"), a, 1e-12);

    /* the .vti through VTK's own reader */
    int prc = e2e_python_run(dir, &msg,
                             "tests/e2e/common/check_smoke.py %s/field.vti 33 0.5 0.5 0.3 0.02 0.005",
                             out);
    cr_expect_eq(prc, 0, "VTK check failed: %s", msg);
    free(msg);

    /* the .exr through the OpenEXR C API: row 0 is the top (y = 1) */
    float *val = NULL;
    int w = 0, h = 0;
    dfl_err err;
    snprintf(path, sizeof path, "%s/field.exr", out);
    cr_assert_eq(dfl_exr_read_channel(path, "value", &w, &h, &val, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(w, n);
    cr_assert_eq(h, n);
    double maxdev = 0;
    for (int r = 0; r < h; r++)
        for (int i = 0; i < w; i++) {
            double y = (double)(h - 1 - r) / (n - 1), x = (double)i / (n - 1);
            double expv = (float)((1 + a) * circle_d(x, y) + b);
            maxdev = fmax(maxdev, fabs(val[r * w + i] - expv));
        }
    cr_expect_lt(maxdev, 1e-7, "exr value deviates by %g", maxdev);
    free(val);
    cr_expect_eq(e2e_rmtree(dir), 0);
}

Test(e2e_smoke, sweep_three_rows)
{
    char dir[256], out[512], args[1024], path[600];
    e2e_tmpdir(dir, sizeof dir);
    snprintf(out, sizeof out, "%s/res", dir);
    snprintf(args, sizeof args, "run configs/smoke/smoke.ini --out %s --set grid.n=16,32,64 --quiet", out);
    cr_assert_eq(e2e_dflab(dir, args), 0);
    snprintf(path, sizeof path, "%s/smoke.csv", out);
    cr_assert_eq(e2e_csv_rows(path), 3);
    const long ns[3] = {16, 32, 64};
    for (size_t i = 0; i < 3; i++) {
        cr_expect_eq((long)e2e_csv_get(path, i, "grid.n"), ns[i]);
        cr_expect_eq((long)e2e_csv_get(path, i, "nodes"), ns[i] * ns[i]);
    }
    /* one field file per sweep point, tagged by point index */
    for (int i = 0; i < 3; i++) {
        snprintf(path, sizeof path, "%s/field_pt%03d.vti", out, i);
        FILE *fp = fopen(path, "rb");
        cr_expect_not_null(fp, "missing %s", path);
        if (fp) fclose(fp);
    }
    cr_expect_eq(e2e_rmtree(dir), 0);
}

Test(e2e_smoke, sphere_3d)
{
    char dir[256], out[512], args[1024];
    e2e_tmpdir(dir, sizeof dir);
    snprintf(out, sizeof out, "%s/res", dir);
    snprintf(args, sizeof args, "run configs/smoke/smoke3d.ini --out %s --set grid.n=17 --quiet", out);
    cr_assert_eq(e2e_dflab(dir, args), 0);
    char *msg;
    int prc = e2e_python_run(
        dir, &msg, "tests/e2e/common/check_smoke.py %s/field.vti 17 0.5 0.5 0.5 0.3 0.02 0.005", out);
    cr_expect_eq(prc, 0, "VTK check failed: %s", msg);
    free(msg);
    cr_expect_eq(e2e_rmtree(dir), 0);
}

/* probe reproduces the circle SDF and gradient at random points to 1e-12 */
Test(e2e_smoke, probe_random_points)
{
    char dir[256], path[600], args[1024];
    e2e_tmpdir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/pts.csv", dir);
    FILE *fp = fopen(path, "w");
    cr_assert_not_null(fp);
    fprintf(fp, "x,y\n");
    unsigned s = 12345;
    double px[200], py[200];
    for (int i = 0; i < 200; i++) {
        px[i] = -0.5 + 2.0 * dfl_rng_lcg(&s);
        py[i] = -0.5 + 2.0 * dfl_rng_lcg(&s);
        fprintf(fp, "%.17g,%.17g\n", px[i], py[i]);
    }
    fclose(fp);
    snprintf(args, sizeof args, "probe configs/smoke/smoke.ini --points %s", path);
    cr_assert_eq(e2e_dflab(dir, args), 0);
    snprintf(path, sizeof path, "%s/out.txt", dir);
    cr_assert_eq(e2e_csv_rows(path), 200);
    double worst = 0, gworst = 0;
    for (int i = 0; i < 200; i++) {
        double dx = px[i] - 0.5, dy = py[i] - 0.5, r = hypot(dx, dy);
        worst = fmax(worst, fabs(e2e_csv_get(path, (size_t)i, "value") - (r - 0.3)));
        gworst = fmax(gworst, fabs(e2e_csv_get(path, (size_t)i, "gx") - dx / r));
        gworst = fmax(gworst, fabs(e2e_csv_get(path, (size_t)i, "gy") - dy / r));
        cr_expect_eq(e2e_csv_get(path, (size_t)i, "z"), 0.0);
    }
    cr_expect_lt(worst, 1e-12, "value error %g", worst);
    cr_expect_lt(gworst, 1e-12, "gradient error %g", gworst);
    cr_expect_eq(e2e_rmtree(dir), 0);
}

/* Along the tangent at a boundary point, d(s) = sqrt(r^2 + s^2) - r, whose
 * derivatives at 0 are d1 = 0, d2 = 1/r, d3 = 0, d4 = -3/r^3; along the
 * outward normal d(s) = s: d1 = 1, d2.. = 0. */
Test(e2e_smoke, probe_jets)
{
    char dir[256], path[600], args[1024];
    e2e_tmpdir(dir, sizeof dir);
    e2e_write(dir, "pts.csv", "x,y,dx,dy\n0.8,0.5,0,1\n0.8,0.5,1,0\n", path, sizeof path);
    snprintf(args, sizeof args, "probe configs/smoke/smoke.ini --points %s --jet 4", path);
    cr_assert_eq(e2e_dflab(dir, args), 0);
    snprintf(path, sizeof path, "%s/out.txt", dir);
    const double r = 0.3;
    cr_expect(fabs(e2e_csv_get(path, 0, "d1")) < 1e-12);
    cr_expect_float_eq(e2e_csv_get(path, 0, "d2"), 1 / r, 1e-10);
    cr_expect(fabs(e2e_csv_get(path, 0, "d3")) < 1e-9);
    cr_expect_float_eq(e2e_csv_get(path, 0, "d4"), -3 / (r * r * r), 1e-8);
    cr_expect_float_eq(e2e_csv_get(path, 1, "d1"), 1.0, 1e-12);
    for (int k = 2; k <= 4; k++) {
        char col[16];
        snprintf(col, sizeof col, "d%d", k);
        cr_expect(fabs(e2e_csv_get(path, 1, col)) < 1e-10, "%s = %g", col, e2e_csv_get(path, 1, col));
    }
    cr_expect_eq(e2e_rmtree(dir), 0);
}
