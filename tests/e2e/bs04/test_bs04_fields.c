/* End-to-end: the bs04 Fig. 1 / Fig. 3(b) fields study on a coarse grid.
 *
 * The .vti values are compared, through VTK's own reader, with the fields
 * written out here in closed form (eq. 2-6: line function, disk or strip
 * trim, eq. 4/5 composition, R-equivalence of order p), the reference with
 * the exact distance to the segments, and grad_norm with central
 * differences of the closed forms.  The CSV's theory columns are checked
 * against what the closed forms imply: on the trim region eq. 4 is |f|
 * exactly (|grad u| = 1), off it |grad h| >= 1 (the trim's gradient is at
 * least 1 outside its region and orthogonal to, or adding to, the line's),
 * and 2^(-1/p) min(h_a, h_b) <= u <= min(h_a, h_b) for the join. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/e2e_util.h"
#include "io/config.h"

#define CFG "configs/paper/bs04/bs04_fields.ini"

typedef struct cf_seg {
    double a[2], b[2];
} cf_seg;

/* trim: 0 disk, 1 disk_smooth, 2 strip (eq. 2-5). */
static double cf_h(const cf_seg *s, int trim, const double *x)
{
    const double ex = s->b[0] - s->a[0], ey = s->b[1] - s->a[1], d = hypot(ex, ey);
    const double f = ((x[0] - s->a[0]) * ey - (x[1] - s->a[1]) * ex) / d;
    double t;
    if (trim == 2) {
        const double p1 = ((x[0] - s->a[0]) * ex + (x[1] - s->a[1]) * ey) / d;
        const double p2 = ((s->b[0] - x[0]) * ex + (s->b[1] - x[1]) * ey) / d;
        t = d - hypot(p1, p2);
    } else {
        const double cx = 0.5 * (s->a[0] + s->b[0]), cy = 0.5 * (s->a[1] + s->b[1]);
        t = (0.25 * d * d - (x[0] - cx) * (x[0] - cx) - (x[1] - cy) * (x[1] - cy)) / d;
    }
    if (trim == 1) {
        const double g = sqrt(t * t + f * f * f * f) - t;
        return sqrt(f * f + g * g / 4);
    }
    return sqrt(f * f + (t < 0 ? t * t : 0.0));
}

static double cf_dist(const cf_seg *s, const double *x)
{
    const double ex = s->b[0] - s->a[0], ey = s->b[1] - s->a[1];
    double l = ((x[0] - s->a[0]) * ex + (x[1] - s->a[1]) * ey) / (ex * ex + ey * ey);
    l = fmin(1.0, fmax(0.0, l));
    return hypot(x[0] - s->a[0] - l * ex, x[1] - s->a[1] - l * ey);
}

/* field: 0 = a, 1 = b, 2 = join (R-equivalence of order p). */
static double cf_u(const cf_seg *s, int field, int trim, int p, const double *x)
{
    if (field < 2) return cf_h(&s[field], trim, x);
    return pow(pow(cf_h(&s[0], trim, x), -p) + pow(cf_h(&s[1], trim, x), -p), -1.0 / p);
}

static int trim_index(const char *name)
{
    return strcmp(name, "disk") == 0 ? 0 : strcmp(name, "disk_smooth") == 0 ? 1 : 2;
}

Test(e2e_bs04_fields, values_gradients_and_theory_columns, .timeout = 60)
{
    char dir[256], out[512], csv[700], path[800];
    e2e_tmpdir(dir, sizeof dir);
    const int N = 31;
    char extra[128];
    snprintf(extra, sizeof extra, "--set grid.n=%d", N);
    /* 3 trims x (a, b, join) */
    e2e_run_table(CFG, extra, "bs04_fields", 9, out, sizeof out, csv, sizeof csv);
    /* 9 .vti + 9 .exr + csv + config + manifest + a .pvd per stem (a, b, join)
     * over the 3 trims */
    cr_expect_eq(e2e_count_entries(out), 21 + 3);

    dfl_cfg *cfg;
    dfl_err err;
    cr_assert_eq(dfl_cfg_load(CFG, &cfg, &err), DFL_OK, "%s", err.msg);
    cf_seg s[2];
    double *pts, lo[2], hi[2];
    size_t n;
    /* [field] vertices v0 v1 v2: A = v0-v1, B = v1-v2 */
    cr_assert_eq(dfl_cfg_points(cfg, "field", "vertices", 2, 3, &pts, &n, &err), DFL_OK);
    cr_assert_eq(n, 3u);
    for (int i = 0; i < 2; i++) {
        memcpy(s[i].a, pts + 2 * i, 2 * sizeof(double));
        memcpy(s[i].b, pts + 2 * i + 2, 2 * sizeof(double));
    }
    free(pts);
    long p;
    cr_assert_eq(dfl_cfg_int(cfg, "field", "p", 1, 64, &p, &err), DFL_OK);
    cr_assert_eq(dfl_cfg_vec(cfg, "grid", "lo", 2, lo, &err), DFL_OK);
    cr_assert_eq(dfl_cfg_vec(cfg, "grid", "hi", 2, hi, &err), DFL_OK);
    dfl_cfg_free(cfg);

    for (long r = 0; r < 9; r++) {
        char *field = e2e_csv_cell(csv, r, "field"), *trim = e2e_csv_cell(csv, r, "trim");
        char *vti = e2e_csv_cell(csv, r, "vti");
        const int fi = strcmp(field, "a") == 0 ? 0 : strcmp(field, "b") == 0 ? 1 : 2;
        const int it = trim_index(trim);
        char what[64];
        snprintf(what, sizeof what, "%s %s", field, trim);
        /* theory columns */
        if (fi < 2 && it != 1) {
            cr_expect(e2e_csv_get(csv, (size_t)r, "trim_nodes") > 10, "%s", what);
            cr_expect(e2e_csv_get(csv, (size_t)r, "trim_value_maxdev") <= 1e-15, "%s", what);
            cr_expect(e2e_csv_get(csv, (size_t)r, "trim_gradnorm_maxdev") <= 1e-12, "%s", what);
            cr_expect(e2e_csv_get(csv, (size_t)r, "gradnorm_min") >= 1 - 1e-12, "%s", what);
        }
        if (fi == 2) {
            const double lo_r = pow(2.0, -1.0 / (double)p);
            cr_expect_float_eq(e2e_csv_get(csv, (size_t)r, "ratio_lo"), lo_r, 1e-15);
            cr_expect(e2e_csv_get(csv, (size_t)r, "ratio_min") >= lo_r * (1 - 1e-12), "%s", what);
            cr_expect(e2e_csv_get(csv, (size_t)r, "ratio_max") <= 1.0, "%s", what);
        }
        /* the image through VTK's reader */
        const char *arrays[] = {"value", "reference", "grad_norm", "error"};
        e2e_vti img;
        snprintf(path, sizeof path, "%s/%s", out, vti);
        e2e_vti_read(dir, path, arrays, 4, &img);
        cr_assert(img.dims[0] == N && img.dims[1] == N && img.dims[2] == 1);
        cr_expect_float_eq(img.origin[0], lo[0], 1e-15);
        cr_expect_float_eq(img.spacing[1], (hi[1] - lo[1]) / (N - 1), 1e-15);
        double vmaxdev = 0, rmaxdev = 0;
        for (int j = 0; j < N * N; j++) {
            const double *a = img.val + 4 * (size_t)j;
            const double val = a[0], ref = a[1], gn = a[2], er = a[3];
            const double x[2] = {lo[0] + (j % N) * (hi[0] - lo[0]) / (N - 1),
                                 lo[1] + (j / N) * (hi[1] - lo[1]) / (N - 1)};
            const double want = cf_u(s, fi, it, (int)p, x);
            const double dref = fi < 2 ? cf_dist(&s[fi], x) : fmin(cf_dist(&s[0], x), cf_dist(&s[1], x));
            vmaxdev = e2e_max(vmaxdev, fabs(val - want) / (1e-3 + want));
            rmaxdev = e2e_max(rmaxdev, fabs(ref - dref));
            cr_expect(fabs(er - (val - ref)) <= 1e-15, "error = value - reference");
            if (j % 37 == 0 && want > 1e-3) {
                /* |grad u| by central differences of the closed form */
                const double hs = 1e-6;
                double g[2];
                for (int c = 0; c < 2; c++) {
                    double xp[2] = {x[0], x[1]}, xm[2] = {x[0], x[1]};
                    xp[c] += hs;
                    xm[c] -= hs;
                    g[c] = (cf_u(s, fi, it, (int)p, xp) - cf_u(s, fi, it, (int)p, xm)) / (xp[c] - xm[c]);
                }
                cr_expect(fabs(gn - hypot(g[0], g[1])) <= 1e-6 * (1 + gn), "%s node %d: %g vs %g",
                          what, j, gn, hypot(g[0], g[1]));
            }
        }
        e2e_vti_free(&img);
        cr_expect(vmaxdev <= 1e-12, "%s: values differ from the closed form by %g", what, vmaxdev);
        cr_expect(rmaxdev <= 1e-15, "%s: reference differs from the exact distance by %g", what,
                  rmaxdev);
        free(field), free(trim), free(vti);
    }
}

Test(e2e_bs04_fields, bad_input_exits_2_without_files)
{
    static const char *const sets[][2] = {
        {"--set 'field.vertices=0 0; 0 0; 1 1'", "field.vertices"},
        {"--set 'field.vertices=0 0; 1 1; 2 0; 3 3'", "[field] of bs04_fields"},
        {"--set field.join=rconj --set field.p=1", "field.p"},
        {"--set study.band=0", "study.band"},
        {"--set grid.n=1", "grid.n"},
        {"--set field.trim=square", "field.trim"},
    };
    e2e_expect_bad_runs(CFG, NULL, sets, sizeof sets / sizeof sets[0]);
}
