/* End-to-end: the bs04_hetero study (Fig. 13a) on a 37 x 37 grid.
 * Expected values: the metrics recomputed from the library's field and the
 * exact distance to the union written here in closed form (box, segment,
 * point); the boundary normalization against the expansion
 * u = delta (1 + sum_j (delta/h_j)^p)^(-1/p) with D = the smallest other
 * part field on the probe curves (library part fields, brute force). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/vec.h"
#include "geom/polygonize.h"
#include "io/config.h"
#include "rfunc/region.h"
#include "rfunc/rfield.h"
#include "rfunc/segment.h"
#include "util/e2e_util.h"

#define CFG "configs/paper/bs04/bs04_hetero.ini"

static const double SQ[8] = {0.1, 0.1, 0.4, 0.1, 0.4, 0.4, 0.1, 0.4};
static const double SEG[4] = {0.55, 0.2, 0.9, 0.75};
static const double PT[2] = {0.25, 0.75};

static double exact(const double *x)
{
    /* axis-aligned square [0.1, 0.4]^2: the box distance */
    const double dx = fmax(fabs(x[0] - 0.25) - 0.15, 0), dy = fmax(fabs(x[1] - 0.25) - 0.15, 0);
    const double ds = dfl_point_segment_dist(2, x, SEG, SEG + 2);
    return fmin(hypot(dx, dy), fmin(ds, hypot(x[0] - PT[0], x[1] - PT[1])));
}

Test(e2e_bs04_hetero, metrics_and_boundary_normalization, .timeout = 60)
{
    char out[512], csv[700];
    e2e_run_table(CFG, "--set grid.n=37", "bs04_hetero", 2, out, sizeof out, csv, sizeof csv);
    /* the config's geometry is what this test assumes */
    dfl_cfg *cfg;
    dfl_err err;
    double *reg, *seg, pt[2];
    size_t nr, ns;
    cr_assert_eq(dfl_cfg_load(CFG, &cfg, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_cfg_points(cfg, "field", "region", 2, 3, &reg, &nr, &err), DFL_OK);
    cr_assert_eq(dfl_cfg_points(cfg, "field", "vertices", 2, 2, &seg, &ns, &err), DFL_OK);
    cr_assert_eq(dfl_cfg_vec(cfg, "field", "points", 2, pt, &err), DFL_OK);
    dfl_cfg_free(cfg);
    cr_assert(nr == 4 && ns == 2 && !memcmp(reg, SQ, sizeof SQ) && !memcmp(seg, SEG, sizeof SEG) &&
              !memcmp(pt, PT, sizeof PT));
    free(reg);
    free(seg);
    /* the parts' own fields, for D */
    dfl_rfunc_region R;
    dfl_rfunc_seg S;
    dfl_rfunc_point Pp;
    cr_assert_eq(dfl_rfunc_region_init(SQ, 4, &R, NULL), DFL_OK);
    cr_assert_eq(dfl_rfunc_seg_init(2, SEG, SEG + 2, DFL_RFUNC_TRIM_DISK, &S, NULL), DFL_OK);
    cr_assert_eq(dfl_rfunc_point_init(2, PT, &Pp, NULL), DFL_OK);
    const double delta = 1e-4;
    double D = INFINITY;
    for (int i = 0; i <= 2000; i++) {
        const double t = i / 2000.0;
        /* around the square (offset delta), along the segment, around the point */
        const double ph = 2 * DFL_PI * t;
        const double xs[2] = {0.1 + 0.3 * t, 0.1 - delta};
        const double xs2[2] = {0.4 + delta, 0.1 + 0.3 * t};
        const double xs3[2] = {0.1 + 0.3 * t, 0.4 + delta};
        const double xs4[2] = {0.1 - delta, 0.1 + 0.3 * t};
        const double xg[2] = {SEG[0] + t * (SEG[2] - SEG[0]), SEG[1] + t * (SEG[3] - SEG[1])};
        const double xp[2] = {PT[0] + delta * cos(ph), PT[1] + delta * sin(ph)};
        const double *sq[4] = {xs, xs2, xs3, xs4};
        for (int k = 0; k < 4; k++)
            D = fmin(D, fmin(dfl_rfunc_seg_eval(&S, sq[k], NULL),
                             dfl_rfunc_point_eval(&Pp, sq[k], NULL)));
        D = fmin(D, fmin(dfl_rfunc_region_eval(&R, xg, NULL), dfl_rfunc_point_eval(&Pp, xg, NULL)));
        D = fmin(D, fmin(dfl_rfunc_region_eval(&R, xp, NULL), dfl_rfunc_seg_eval(&S, xp, NULL)));
    }
    cr_assert(D > 0.1, "D = %g", D);
    for (long r = 0; r < 2; r++) {
        const int p = (int)e2e_csv_get(csv, (size_t)r, "p");
        cr_assert_eq(p, r == 0 ? 2 : 7);
        dfl_rfield *rf;
        dfl_field f;
        cr_assert_eq(dfl_rfield_new(2, DFL_RFUNC_REQUIV, p, &rf, NULL), DFL_OK);
        cr_assert_eq(dfl_rfield_add_region(rf, SQ, 4, NULL), DFL_OK);
        cr_assert_eq(dfl_rfield_add_segment(rf, SEG, SEG + 2, DFL_RFUNC_TRIM_DISK, NULL), DFL_OK);
        cr_assert_eq(dfl_rfield_add_point(rf, PT, NULL), DFL_OK);
        cr_assert_eq(dfl_rfield_finish(&rf, &f, NULL), DFL_OK);
        double l1 = 0, linf = 0, l1b = 0;
        long nb = 0;
        /* 37 nodes: no node lies at a tie d = band or on the square's edges */
        for (int j = 0; j < 37; j++)
            for (int i = 0; i < 37; i++) {
                const double x[2] = {i / 36.0, j / 36.0};
                const double u = dfl_field_eval1(&f, x, NULL), d = exact(x);
                l1 += fabs(u - d) / (37 * 37);
                linf = fmax(linf, fabs(u - d));
                if (d > 0 && d <= 0.05) {
                    l1b += fabs(u - d);
                    nb++;
                }
            }
        cr_expect(fabs(e2e_csv_get(csv, (size_t)r, "l1") - l1) <= 1e-12 * l1, "p %d: l1 %.15g vs %.15g",
                  p, e2e_csv_get(csv, (size_t)r, "l1"), l1);
        cr_expect(fabs(e2e_csv_get(csv, (size_t)r, "linf") - linf) <= 1e-12 * linf);
        cr_expect_eq((long)e2e_csv_get(csv, (size_t)r, "count_band"), nb);
        cr_expect(fabs(e2e_csv_get(csv, (size_t)r, "l1_band") - l1b / (double)nb) <= 1e-12);
        /* normalization at the boundary: n - 1 = 2 other parts */
        const double q = pow(delta / D, p);
        const double rat = e2e_csv_get(csv, (size_t)r, "boundary_ratio_err");
        const double grd = e2e_csv_get(csv, (size_t)r, "boundary_grad_err");
        cr_expect(rat <= 2 * q / p + 1e-11, "p %d: |u/delta - 1| = %g > %g", p, rat, 2 * q / p);
        cr_expect(grd <= 1.01 * 2 * q * (p + 1) / p + 1e-11, "p %d: ||grad u| - 1| = %g", p, grd);
        /* and not trivially 0: the order of magnitude is the predicted one */
        if (p == 2) cr_expect(rat >= 0.1 * q / p && grd >= 0.1 * q, "p 2: %g %g vs %g", rat, grd, q);
        dfl_field_destroy(&f);
    }
    dfl_rfunc_region_free(&R);
}

Test(e2e_bs04_hetero, bad_input)
{
    e2e_expect_bad_config("[study]\nname = bs04_hetero\n[field]\nkind = rfunc\n"
                          "region = 0 0; 1 1; 0 1; 1 0\nvertices = 2 2; 3 3\npoints = 5 5\n"
                          "[grid]\nn = 5\n",
                          "[field] region", NULL);
    e2e_expect_bad_config("[study]\nname = bs04_hetero\n[field]\nkind = rfunc\n"
                          "region = 0 0; 1 0; 1 1\nvertices = 2 2; 3 3\n[grid]\nn = 5\n",
                          "[field] of bs04_hetero", NULL);
}
