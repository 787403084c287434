/* Tests for experiments/hvb25/hvb25_eval: the slab-by-slab metrics equal
 * field/metrics over the whole grid at once (count and L-inf exactly, the
 * means to rounding), at 1 and 2 threads alike; the band and the unsigned
 * comparison follow their definitions. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>

#include "field/exact.h"
#include "field/gridpeer.h"
#include "field/metrics.h"
#include "field/sample.h"
#include "hvb25/hvb25_eval.h"

static void fields(dfl_field *u, dfl_field *ref, int n)
{
    const double c[3] = {0.02, -0.01, 0.03};
    dfl_shape s;
    cr_assert_eq(dfl_shape_sphere(c, 0.5, &s, NULL), DFL_OK);
    dfl_gridpeer_opts o = {DFL_GRIDPEER_TAYLOR1, DFL_GRIDPEER_FLOAT64, n, {-1, -1, -1},
                           {1, 1, 1}, 1};
    cr_assert_eq(dfl_gridpeer_new(&s, &o, u, NULL), DFL_OK);
    cr_assert_eq(dfl_field_exact_new(&s, ref, NULL), DFL_OK);
}

Test(hvb25_eval, slabs_match_whole_grid_metrics)
{
    dfl_field u, ref;
    fields(&u, &ref, 6);
    const dfl_grid g = {3, {19, 19, 19}, {-1, -1, -1}, {1, 1, 1}};
    const size_t m = dfl_grid_size(&g);
    double *a = malloc(m * sizeof *a), *d = malloc(m * sizeof *d);
    cr_assert_eq(dfl_field_sample(&u, &g, 1, a, NULL, NULL), DFL_OK);
    cr_assert_eq(dfl_field_sample(&ref, &g, 1, d, NULL, NULL), DFL_OK);
    dfl_metrics all, band;
    cr_assert_eq(dfl_metrics_compute(m, 3, a, NULL, d, 0, &all, NULL), DFL_OK);
    cr_assert_eq(dfl_metrics_compute(m, 3, a, NULL, d, 0.1, &band, NULL), DFL_OK);
    for (int threads = 1; threads <= 2; threads++) {
        hvb25_acc_spec s = {.field = &u, .field_signed = 1, .cells = {6, {-1, -1, -1},
                                                                      {1.0 / 3, 1.0 / 3, 1.0 / 3}},
                            .ref = &ref, .eval = g, .band = 0.1, .medial = 1,
                            .threads = threads};
        hvb25_acc_result r;
        cr_assert_eq(hvb25_acc_run(&s, &r, NULL), DFL_OK);
        cr_assert_eq(r.all.count, m);
        cr_assert_eq(r.all.linf, all.linf);
        cr_assert(fabs(r.all.l1 - all.l1) <= 1e-13 * all.l1);
        cr_assert(fabs(r.all.mse - all.mse) <= 1e-13 * all.mse);
        cr_assert_eq(r.band.count, band.count);
        cr_assert_eq(r.band.linf, band.linf);
        cr_assert(fabs(r.band.l1 - band.l1) <= 1e-13 * band.l1);
        cr_assert_eq(r.worst_err, all.linf);
        cr_assert_eq(r.nonfinite, 0);
        cr_assert(r.off.count + r.medial == m);
        cr_assert(r.medial > 0, "the sphere's centre region is medial");
    }
    free(a), free(d);
    dfl_field_destroy(&u);
    dfl_field_destroy(&ref);
}

/* Unsigned decoding against |d|: the exact field itself, folded, has the
 * error |d| - d = 2|d| inside, 0 outside, so L-inf is twice the deepest
 * inside value on the grid (the centre node at distance |c| from the centre). */
Test(hvb25_eval, unsigned_compares_with_abs_d)
{
    dfl_field u, ref;
    fields(&u, &ref, 4);
    const dfl_grid g = {3, {9, 9, 9}, {-1, -1, -1}, {1, 1, 1}};
    hvb25_acc_spec s = {.field = &ref, .field_signed = 0, .ref = &ref, .eval = g, .band = 0,
                        .medial = 1, .threads = 1};
    hvb25_acc_result r;
    cr_assert_eq(hvb25_acc_run(&s, &r, NULL), DFL_OK);
    const double cn = sqrt(0.02 * 0.02 + 0.01 * 0.01 + 0.03 * 0.03);
    cr_assert(fabs(r.all.linf - 2 * (0.5 - cn)) < 1e-15, "%g", r.all.linf);
    cr_assert(fabs(r.worst[0]) + fabs(r.worst[1]) + fabs(r.worst[2]) == 0);
    cr_assert_eq(r.medial, 0, "no cell grid, no medial points");
    dfl_field_destroy(&u);
    dfl_field_destroy(&ref);
}
