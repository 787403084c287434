/* End-to-end: the bs04 'S' curve study at eps = 1e-2 (both joins) on a
 * small grid.  Expected values are derived, not recorded:
 *   - segments, bound: the certified polygonization of configs/shapes/S.ini;
 *   - max |u| on the curve <= C bound, C = sqrt(1 + (1 + bound/L_min)^2)
 *     (derivation in experiments/bs04_scurve.c: a curve point is within
 *     r <= bound of a segment, whose disk-trimmed field is then at most
 *     r sqrt(1 + (1 + r/L)^2), and both joins give u <= min h);
 *   - R-equivalence: u >= h_min N^(-1/p) and h >= the distance to the
 *     polyline, so max |u| on the curve >= (max deviation) N^(-1/2) (0.9 of
 *     it, for the sampled search), and the level set u = delta lies within
 *     N^(1/2) delta + bound (+ one bracketing step) along a valid ray;
 *   - band counts: the grid nodes with exact distance <= delta, counted here
 *     from the exact distance shape. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "curve_cfg.h"
#include "e2e_util.h"
#include "geom/polygonize.h"
#include "io/config.h"
#include "shape_cfg.h"

#define CFG "configs/paper/bs04_scurve.ini"
#define GN 41
#define STEPS 32
#define SMAX 8.0

static int is_join(const char *path, long row, const char *want)
{
    /* the join column: find it textually (long format, no quoting) */
    char *all = e2e_slurp(path);
    cr_assert_not_null(all);
    char *save = NULL, *line = strtok_r(all, "\n", &save);
    int ci = -1, k = 0;
    for (char *p = line, *q; p; p = q ? q + 1 : NULL, k++) {
        q = strchr(p, ',');
        size_t len = q ? (size_t)(q - p) : strlen(p);
        if (len == 4 && strncmp(p, "join", 4) == 0) ci = k;
    }
    int res = 0;
    for (long r = 0; (line = strtok_r(NULL, "\n", &save)); r++) {
        if (r != row) continue;
        char *p = line;
        for (int j = 0; j < ci && p; j++) {
            p = strchr(p, ',');
            if (p) p++;
        }
        res = p && strncmp(p, want, strlen(want)) == 0 && (p[strlen(want)] == ',' || !p[strlen(want)]);
    }
    free(all);
    return res;
}

Test(e2e_bs04_scurve, curve_bound_bands_and_offsets, .timeout = 120)
{
    char dir[256], out[512], args[1024], path[700];
    e2e_tmpdir(dir, sizeof dir);
    snprintf(out, sizeof out, "%s/res", dir);
    snprintf(args, sizeof args,
             "run " CFG " --out %s --quiet --set field.eps=1e-2 --set study.rays=51"
             " --set study.cap_rays=4 --set grid.n=%d --set study.steps=%d --set study.smax=%g",
             out, GN, STEPS, SMAX);
    int rc = e2e_dflab(dir, args);
    snprintf(path, sizeof path, "%s/err.txt", dir);
    char *msg = e2e_slurp(path);
    cr_assert_eq(rc, 0, "dflab run failed: %s", msg);
    free(msg);
    snprintf(path, sizeof path, "%s/bs04_scurve.csv", out);
    const long nrows = e2e_csv_rows(path);
    cr_assert_eq(nrows, 2 * 5, "2 joins x 5 offsets");
    /* 2 u images (vti + exr) + 1 exact image + csv, config, manifest */
    cr_expect_eq(e2e_count_entries(out), 4 + 2 + 3);

    dfl_cfg *cfg;
    dfl_err err;
    dfl_bspline S;
    cr_assert_eq(dfl_cfg_load("configs/shapes/S.ini", &cfg, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_curve_from_cfg(cfg, "shape", &S, &err), DFL_OK, "%s", err.msg);
    dfl_shape sh;
    cr_assert_eq(dfl_shape_from_cfg(cfg, "shape", &sh, &err), DFL_OK, "%s", err.msg);
    dfl_polyline pl;
    cr_assert_eq(dfl_polygonize_curve(&S, 1e-2, 0, &pl, NULL), DFL_OK);
    double lmin = INFINITY;
    for (size_t i = 0; i + 1 < pl.n; i++)
        lmin = fmin(lmin, hypot(pl.pts[2 * i + 2] - pl.pts[2 * i], pl.pts[2 * i + 3] - pl.pts[2 * i + 1]));
    double dev;
    cr_assert_eq(dfl_polyline_deviation(&S, &pl, 64, &dev, NULL), DFL_OK);
    const double N = (double)(pl.n - 1);
    const double C = sqrt(1 + (1 + pl.bound / lmin) * (1 + pl.bound / lmin));
    /* exact distances at the nodes of the [0, 1]^2 grid */
    double *d = malloc(GN * GN * sizeof *d);
    for (int j = 0; j < GN; j++)
        for (int i = 0; i < GN; i++) {
            const double x[2] = {(double)i / (GN - 1), (double)j / (GN - 1)};
            d[i + GN * j] = dfl_shape_eval1(&sh, x, NULL);
        }
    long prev_count = -1;
    for (long r = 0; r < nrows; r++) {
        const int req = is_join(path, r, "requiv");
        cr_expect(req || is_join(path, r, "rconj"), "row %ld join", r);
        cr_expect_eq(e2e_csv_get(path, (size_t)r, "segments"), N);
        cr_expect_float_eq(e2e_csv_get(path, (size_t)r, "bound"), pl.bound, 1e-15);
        cr_expect_float_eq(e2e_csv_get(path, (size_t)r, "seg_min"), lmin, 1e-14);
        const double um = e2e_csv_get(path, (size_t)r, "u_curve_max");
        cr_expect_float_eq(e2e_csv_get(path, (size_t)r, "u_curve_bound"), C * pl.bound, 1e-14);
        cr_expect(um <= C * pl.bound, "row %ld: max |u| on the curve %g > %g", r, um, C * pl.bound);
        cr_expect(um > 0);
        if (req) cr_expect(um >= 0.9 * dev / sqrt(N), "row %ld: %g < %g", r, um, 0.9 * dev / sqrt(N));
        const double delta = e2e_csv_get(path, (size_t)r, "delta");
        long cnt = 0;
        for (int i = 0; i < GN * GN; i++) cnt += d[i] <= delta;
        const double bc = e2e_csv_get(path, (size_t)r, "band_count");
        cr_expect(fabs(bc - (double)cnt) <= 2, "row %ld: band %g vs %ld nodes", r, bc, cnt);
        if (r % 5) cr_expect(bc >= (double)prev_count, "bands grow with delta");
        prev_count = (long)bc;
        const double l1 = e2e_csv_get(path, (size_t)r, "band_l1");
        const double rms = e2e_csv_get(path, (size_t)r, "band_rms");
        const double li = e2e_csv_get(path, (size_t)r, "band_linf");
        const double bias = e2e_csv_get(path, (size_t)r, "band_bias");
        cr_expect(fabs(bias) <= l1 + 1e-15 && l1 <= rms + 1e-15 && rms <= li + 1e-15,
                  "row %ld: |bias| %g l1 %g rms %g linf %g", r, bias, l1, rms, li);
        const double merged = e2e_csv_get(path, (size_t)r, "merged");
        cr_expect(merged >= 0 && merged <= 1);
        cr_expect(e2e_csv_get(path, (size_t)r, "rays_valid") <= e2e_csv_get(path, (size_t)r, "rays"));
        const double w = e2e_csv_get(path, (size_t)r, "widening");
        cr_expect_float_eq(w, e2e_csv_get(path, (size_t)r, "offset_flat_mean") -
                                  e2e_csv_get(path, (size_t)r, "offset_curved_mean"), 1e-15);
        if (req) {
            const double om = e2e_csv_get(path, (size_t)r, "offset_max");
            const double ub = sqrt(N) - 1 + (pl.bound + SMAX * delta / STEPS) / delta;
            cr_expect(om <= ub, "row %ld: offset %g above the bound %g", r, om, ub);
        }
    }
    free(d);
    dfl_shape_free(&sh);
    dfl_polyline_free(&pl);
    dfl_bspline_free(&S);
    dfl_cfg_free(cfg);
}

Test(e2e_bs04_scurve, S_section_equals_the_shape_config)
{
    dfl_cfg *study, *shape;
    dfl_err err;
    cr_assert_eq(dfl_cfg_load(CFG, &study, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_cfg_load("configs/shapes/S.ini", &shape, &err), DFL_OK, "%s", err.msg);
    const char *keys[3] = {"kind", "order", "control"};
    for (int k = 0; k < 3; k++) {
        const char *a, *b;
        cr_assert_eq(dfl_cfg_string(study, "S", keys[k], &a, &err), DFL_OK, "%s", err.msg);
        cr_assert_eq(dfl_cfg_string(shape, "shape", keys[k], &b, &err), DFL_OK, "%s", err.msg);
        cr_expect_str_eq(a, b, "[S] %s differs from configs/shapes/S.ini", keys[k]);
    }
    dfl_cfg_free(shape);
    dfl_cfg_free(study);
}

Test(e2e_bs04_scurve, bad_input_exits_2_without_files)
{
    char dir[256], out[512], args[1024], path[700];
    const char *sets[][2] = {
        {"field.kind=exact", "needs kind = rfunc with a curve"},
        {"study.levels=0", "study.levels: expected offsets > 0"},
        {"field.curve=T", "no section [T]"},
        {"field.eps=0", "field.eps"},
        {"study.rays=1", "study.rays"},
        {"study.colour=red", "study.colour: unknown key"},
    };
    for (size_t i = 0; i < sizeof sets / sizeof sets[0]; i++) {
        e2e_tmpdir(dir, sizeof dir);
        snprintf(out, sizeof out, "%s/res", dir);
        snprintf(args, sizeof args, "run " CFG " --out %s --quiet --set '%s'", out, sets[i][0]);
        int rc = e2e_dflab(dir, args);
        snprintf(path, sizeof path, "%s/err.txt", dir);
        char *msg = e2e_slurp(path);
        cr_expect_eq(rc, 2, "%s: exit %d, %s", sets[i][0], rc, msg);
        cr_expect(msg && strstr(msg, sets[i][1]), "%s: message '%s'", sets[i][0], msg);
        cr_expect_eq(e2e_count_entries(out), -1, "%s left %s behind", sets[i][0], out);
        free(msg);
    }
}
