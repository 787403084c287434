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

#include "cfg/curve_cfg.h"
#include "util/e2e_util.h"
#include "geom/polygonize.h"
#include "io/config.h"
#include "cfg/shape_cfg.h"

#define CFG "configs/paper/bs04/bs04_scurve.ini"
#define GN 41
#define STEPS 32
#define SMAX 8.0

Test(e2e_bs04_scurve, curve_bound_bands_and_offsets, .timeout = 120)
{
    char out[512], args[1024], path[700];
    snprintf(args, sizeof args,
             "--set field.eps=1e-2 --set study.rays=51"
             " --set study.cap_rays=4 --set grid.n=%d --set study.steps=%d --set study.smax=%g",
             GN, STEPS, SMAX);
    /* 2 joins x 5 offsets */
    const long nrows = e2e_run_table(CFG, args, "bs04_scurve", 2 * 5, out, sizeof out, path,
                                     sizeof path);
    /* 2 u images (vti + exr) + 1 exact image + csv, config, manifest + the u
     * images' collection over the 2 joins */
    cr_expect_eq(e2e_count_entries(out), 4 + 2 + 3 + 1);

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
        char *join = e2e_csv_cell(path, r, "join");
        cr_assert_not_null(join, "row %ld: no join cell", r);
        const int req = strcmp(join, "requiv") == 0;
        cr_expect(req || strcmp(join, "rconj") == 0, "row %ld join", r);
        free(join);
        cr_expect_eq(e2e_csv_get(path, (size_t)r, "segments"), N);
        cr_expect_float_eq(e2e_csv_get(path, (size_t)r, "bound"), pl.bound, 1e-15);
        cr_expect_float_eq(e2e_csv_get(path, (size_t)r, "seg_min"), lmin, 1e-14);
        const double um = e2e_csv_get(path, (size_t)r, "u_curve_max");
        cr_expect_float_eq(e2e_csv_get(path, (size_t)r, "u_curve_bound"), C * pl.bound, 1e-14);
        cr_expect(um <= C * pl.bound, "row %ld: max |u| on the curve %g > %g", r, um, C * pl.bound);
        cr_expect(um > 0);
        /* the interior maximum is one of the band's values (the norm rounded as
         * metrics.h does, or within 1 ulp); both lie in the band */
        const double dl = e2e_csv_get(path, (size_t)r, "delta");
        const double gm = e2e_csv_get(path, (size_t)r, "grad_max");
        const double gi = e2e_csv_get(path, (size_t)r, "grad_max_interior");
        cr_expect(gi <= gm * (1 + 1e-15) && gi > 0, "row %ld: interior %g, all %g", r, gi, gm);
        cr_expect(fabs(e2e_csv_get(path, (size_t)r, "grad_max_d")) <= dl);
        cr_expect(fabs(e2e_csv_get(path, (size_t)r, "grad_max_interior_d")) <= dl);
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

Test(e2e_bs04_scurve, bad_input_exits_2_without_files)
{
    static const char *const sets[][2] = {
        {"--set field.kind=exact", "needs kind = rfunc with a curve"},
        {"--set study.levels=0", "study.levels: expected offsets > 0"},
        {"--set field.curve=T", "no section [T]"},
        {"--set field.eps=0", "field.eps"},
        {"--set study.rays=1", "study.rays"},
        {"--set study.colour=red", "study.colour: unknown key"},
    };
    e2e_expect_bad_runs(CFG, NULL, sets, sizeof sets / sizeof sets[0]);
}
