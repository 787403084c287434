/* metrics: hand-computed metrics and band statistics of tiny samples, the
 * band rule, the table cells. */
#include <criterion/criterion.h>
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "field/metrics.h"
#include "io/table.h"

/* A 4-sample case with hand-computed metrics, which dfl_metrics_compute
 * and its saturating variant (finite data) both must give. */
static const double hc_ref[4] = {-0.2, 0.0, 0.05, 0.5};
static const double hc_u[4] = {-0.1, 0.0, 0.05, 0.2};
static const double hc_g[8] = {1, 0, 0, 2, 0.6, 0.8, 3, 4};

typedef dfl_status (*metrics_fn)(size_t m, int dim, const double *u, const double *gu,
                                 const double *ref, double band, dfl_metrics *out, dfl_err *err);

static void hand_case(metrics_fn compute)
{
    const double *ref = hc_ref, *u = hc_u, *g = hc_g;
    dfl_metrics m;
    dfl_err err;
    cr_assert_eq(compute(4, 2, u, g, ref, 0.0, &m, &err), DFL_OK);
    cr_expect_eq(m.count, 4);
    cr_expect_float_eq(m.l1, (0.1 + 0 + 0 + 0.3) / 4, 1e-15);
    cr_expect_float_eq(m.mse, (0.01 + 0.09) / 4, 1e-15);
    cr_expect_float_eq(m.rms, sqrt(0.1 / 4), 1e-15);
    cr_expect_float_eq(m.linf, 0.3, 1e-15);
    /* |g| = 1, 2, 1, 5 -> defects 0, 1, 0, 4 */
    cr_expect_float_eq(m.gdef_mean, 5.0 / 4, 1e-15);
    cr_expect_float_eq(m.gdef_max, 4.0, 1e-15);
    /* band |ref| <= 0.1 keeps samples 1 and 2 only */
    cr_assert_eq(compute(4, 2, u, g, ref, 0.1, &m, &err), DFL_OK);
    cr_expect_eq(m.count, 2);
    cr_expect_float_eq(m.gdef_mean, 0.5, 1e-15);
}

Test(metrics, hand_computed) { hand_case(dfl_metrics_compute); }

/* The non-finite rule: a NaN or infinite value is an error of +inf, in the
 * set its reference puts it in, counted; a non-finite reference fails. */
Test(metrics, non_finite_value_is_an_error_of_inf)
{
    /* samples 1 (NaN) and 3 (-inf) are not finite; refs 1 and 3 lie outside
     * the band 0.5, sample 1's inside the band 2 */
    const double ref[5] = {0.0, 1.0, 0.25, 3.0, -0.5};
    const double u[5] = {0.0, NAN, 0.5, -INFINITY, -0.25};
    dfl_metrics m;
    dfl_err err;
    cr_assert_eq(dfl_metrics_compute(5, 2, u, NULL, ref, 0.0, &m, &err), DFL_OK);
    cr_expect_eq(m.count, 5);
    cr_expect_eq(m.nonfinite, 2);
    cr_expect(isinf(m.l1) && m.l1 > 0 && isinf(m.mse) && isinf(m.rms) && isinf(m.linf));
    cr_expect(m.linf > 0);
    /* band 0.5: samples 0, 2, 4, all finite: errors 0, 0.25, 0.25 */
    cr_assert_eq(dfl_metrics_compute(5, 2, u, NULL, ref, 0.5, &m, &err), DFL_OK);
    cr_expect(m.count == 3 && m.nonfinite == 0);
    cr_expect_float_eq(m.l1, 0.5 / 3, 1e-15);
    cr_expect_float_eq(m.linf, 0.25, 1e-15);
    /* band 2: sample 1 joins (its reference is in the band) */
    cr_assert_eq(dfl_metrics_compute(5, 2, u, NULL, ref, 2.0, &m, &err), DFL_OK);
    cr_expect(m.count == 4 && m.nonfinite == 1 && isinf(m.linf) && isinf(m.l1));
    /* a finite value with a NaN gradient component: gradient defect +inf */
    const double g[10] = {1, 0, 0, 1, 0, NAN, 0, 1, 1, 0};
    const double uf[5] = {0.0, 1.0, 0.25, 3.0, -0.5};
    cr_assert_eq(dfl_metrics_compute(5, 2, uf, g, ref, 0.0, &m, &err), DFL_OK);
    cr_expect(m.count == 5 && m.nonfinite == 1 && isinf(m.gdef_max) && isinf(m.linf));
    /* the masked variant counts the same way */
    const unsigned char mask[5] = {1, 1, 0, 0, 1};
    cr_assert_eq(dfl_metrics_compute_masked(5, 2, u, NULL, ref, mask, &m, &err), DFL_OK);
    cr_expect(m.count == 3 && m.nonfinite == 1 && isinf(m.linf));
    /* a non-finite reference is dflab's own failure */
    const double bref[2] = {0.0, NAN}, bu[2] = {0.0, 0.0};
    cr_expect_eq(dfl_metrics_compute(2, 2, bu, NULL, bref, 0.0, &m, &err), DFL_E_NUMERIC);
    cr_expect(strstr(err.msg, "sample 1") != NULL, "%s", err.msg);
}

/* A field that is NaN at known nodes of a large sample (several chunks):
 * the count is exact and the result the same at any thread count. */
Test(metrics, non_finite_counted_across_chunks)
{
    const size_t m = 3 * DFL_METRICS_CHUNK + 17;
    double *u = malloc(m * sizeof *u), *ref = malloc(m * sizeof *ref);
    cr_assert(u && ref);
    size_t expect = 0, expect_band = 0;
    for (size_t i = 0; i < m; i++) {
        ref[i] = (double)(i % 100) / 100.0; /* 0 .. 0.99 */
        u[i] = ref[i];
        if (i % 1000 == 7) { /* NaN at 7, 1007, ...: ref 0.07 (in band 0.5) */
            u[i] = NAN;
            expect++, expect_band++;
        }
        if (i % 1000 == 555) { /* +inf at 555, ...: ref 0.55 (outside band 0.5) */
            u[i] = INFINITY;
            expect++;
        }
    }
    dfl_metrics a, b;
    cr_assert_eq(dfl_metrics_compute(m, 1, u, NULL, ref, 0.0, &a, NULL), DFL_OK);
    cr_expect_eq(a.count, m);
    cr_expect_eq(a.nonfinite, expect);
    cr_expect(isinf(a.linf) && isinf(a.l1));
    cr_assert_eq(dfl_metrics_compute(m, 1, u, NULL, ref, 0.5, &b, NULL), DFL_OK);
    cr_expect_eq(b.nonfinite, expect_band);
    const int t0 = omp_get_max_threads();
    omp_set_num_threads(1);
    dfl_metrics c;
    cr_assert_eq(dfl_metrics_compute(m, 1, u, NULL, ref, 0.5, &c, NULL), DFL_OK);
    omp_set_num_threads(t0);
    cr_expect(c.count == b.count && c.nonfinite == b.nonfinite);
    free(u), free(ref);
}

Test(metrics, bandstats_hand_computed_band)
{
    /* nodes: ref 0 (u 0: zero set), 0.1, 0.2, 0.5 (outside band 0.3) */
    const double ref[4] = {0.0, 0.1, 0.2, 0.5};
    const double u[4] = {0.0, 0.12, 0.15, 7.0};
    const double gu[8] = {0, 0, 0.6, 0.8, 0, 0.5, 3, 4};
    dfl_bandstats b;
    cr_assert_eq(dfl_metrics_bandstats(4, 2, u, gu, ref, 0.3, &b, NULL), DFL_OK);
    cr_expect_eq(b.count, 3);
    /* errors 0, 0.02, -0.05 */
    cr_expect_float_eq(b.bias, (0.02 - 0.05) / 3, 1e-15);
    cr_expect_float_eq(b.l1, 0.07 / 3, 1e-15);
    cr_expect_float_eq(b.rms, sqrt((0.02 * 0.02 + 0.05 * 0.05) / 3), 1e-15);
    cr_expect_float_eq(b.linf, 0.05, 1e-15);
    /* relative: 0.02/0.1, -0.05/0.2 over the nodes with ref != 0 */
    cr_expect_float_eq(b.rel_bias, (0.2 - 0.25) / 2, 1e-15);
    /* |grad u| 1 and 0.5 (the u = 0 node is left out) */
    cr_expect_eq(b.gcount, 2);
    cr_expect_float_eq(b.gmin, 0.5, 1e-15);
    cr_expect_float_eq(b.gmax, 1.0, 1e-15);
    cr_expect_float_eq(b.gmean, 0.75, 1e-15);
    /* every node: an infinite band, and band <= 0 (the band rule) */
    cr_assert_eq(dfl_metrics_bandstats(4, 2, u, gu, ref, INFINITY, &b, NULL), DFL_OK);
    cr_expect_eq(b.count, 4);
    cr_expect_float_eq(b.gmax, 5.0, 1e-15);
    dfl_bandstats b0;
    cr_assert_eq(dfl_metrics_bandstats(4, 2, u, gu, ref, 0.0, &b0, NULL), DFL_OK);
    cr_expect(b0.count == 4 && b0.gcount == b.gcount);
    cr_expect(b0.bias == b.bias && b0.l1 == b.l1 && b0.rms == b.rms && b0.linf == b.linf);
    cr_expect(b0.rel_bias == b.rel_bias && b0.gmin == b.gmin && b0.gmax == b.gmax);
    cr_expect(b0.gmean == b.gmean);
    /* no gradient: NAN gradient statistics */
    cr_assert_eq(dfl_metrics_bandstats(4, 2, u, NULL, ref, 0.3, &b, NULL), DFL_OK);
    cr_expect(isnan(b.gmin) && isnan(b.gmean) && b.gcount == 0);
}

Test(metrics, bandstats_empty_band_and_errors)
{
    const double ref[2] = {1.0, 2.0}, u[2] = {1.0, NAN};
    dfl_bandstats b;
    cr_assert_eq(dfl_metrics_bandstats(2, 2, u, NULL, ref, 0.5, &b, NULL), DFL_OK);
    cr_expect(b.count == 0 && isnan(b.bias) && isnan(b.linf) && b.nonfinite == 0);
    /* node 1's NaN inside the band: an error of +inf, counted */
    dfl_err err;
    cr_assert_eq(dfl_metrics_bandstats(2, 2, u, NULL, ref, 3.0, &b, &err), DFL_OK);
    cr_expect(b.count == 2 && b.nonfinite == 1);
    cr_expect(isinf(b.bias) && isinf(b.rel_bias) && isinf(b.l1) && isinf(b.rms) && isinf(b.linf));
    /* band <= 0 means every node (the band rule): node 1's NaN is inside */
    cr_assert_eq(dfl_metrics_bandstats(2, 2, u, NULL, ref, 0.0, &b, NULL), DFL_OK);
    cr_expect(b.nonfinite == 1 && isinf(b.linf));
    cr_assert_eq(dfl_metrics_bandstats(2, 2, u, NULL, ref, -1.0, &b, NULL), DFL_OK);
    cr_expect(b.nonfinite == 1 && isinf(b.linf));
    cr_expect_eq(dfl_metrics_bandstats(2, 2, u, NULL, ref, NAN, &b, NULL), DFL_E_INPUT);
    /* the gradient statistics leave a non-finite node out */
    const double g[4] = {0.6, 0.8, NAN, NAN};
    cr_assert_eq(dfl_metrics_bandstats(2, 2, u, g, ref, 3.0, &b, NULL), DFL_OK);
    cr_expect(b.gcount == 1 && b.gmax == 1.0 && b.gmin == 1.0);
    /* a NaN reference is an error wherever it is */
    const double nref[2] = {NAN, 0.1}, nu[2] = {0.0, 0.1};
    cr_expect_eq(dfl_metrics_bandstats(2, 2, nu, NULL, nref, 0.3, &b, &err), DFL_E_NUMERIC);
    cr_expect(strstr(err.msg, "node 0") != NULL, "%s", err.msg);
}

/* The band rule holds for dfl_metrics_compute too: band <= 0 and +inf are
 * every sample, NaN is an input error. */
Test(metrics, band_rule)
{
    const double ref[3] = {-0.2, 0.05, 0.5};
    const double u[3] = {-0.1, 0.05, 0.2};
    dfl_metrics all, m;
    dfl_err err;
    cr_assert_eq(dfl_metrics_compute(3, 2, u, NULL, ref, 0.0, &all, &err), DFL_OK);
    cr_expect_eq(all.count, 3);
    cr_expect(isnan(all.gdef_mean) && isnan(all.gdef_max));
    const double every[2] = {-1.0, INFINITY};
    for (int i = 0; i < 2; i++) {
        cr_assert_eq(dfl_metrics_compute(3, 2, u, NULL, ref, every[i], &m, &err), DFL_OK);
        cr_expect(m.count == 3 && m.l1 == all.l1 && m.linf == all.linf && m.mse == all.mse);
    }
    cr_expect_eq(dfl_metrics_compute(3, 2, u, NULL, ref, NAN, &m, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "band") != NULL, "%s", err.msg);
    /* an empty band: NAN metrics, DFL_OK */
    const double far[3] = {1, 2, 3};
    cr_assert_eq(dfl_metrics_compute(3, 2, u, NULL, far, 0.5, &m, &err), DFL_OK);
    cr_expect(m.count == 0 && isnan(m.l1) && isnan(m.rms) && isnan(m.linf));
}

/* The cells of a row, with their suffix, as the studies' tables hold them. */
Test(metrics, table_cells)
{
    const dfl_metrics m = {3, 0.25, 0.5, 0.75, 1.0, 0.125, 2.0, 1};
    const dfl_bandstats b = {4, -0.5, 0.25, 1.5, 2.5, 3.5, 2, 0.5, 0.75, 1.0, 2};
    dfl_table *t = dfl_table_new();
    dfl_err err;
    cr_assert_eq(dfl_table_row(t, &err), DFL_OK);
    cr_assert_eq(dfl_metrics_put(t, "_band", &m, &err), DFL_OK);
    cr_assert_eq(dfl_metrics_put_bandstats(t, &b, &err), DFL_OK);
    const char *cols[18] = {"count_band", "l1_band", "mse_band", "rms_band", "linf_band",
                            "graddefect_mean_band", "graddefect_max_band", "nonfinite_band",
                            "band_count", "band_bias", "band_rel_bias", "band_l1", "band_rms",
                            "band_linf", "grad_min", "grad_mean", "grad_max", "band_nonfinite"};
    const char *vals[18] = {"3", "0.25", "0.5", "0.75", "1", "0.125", "2", "1", "4",
                            "-0.5", "0.25", "1.5", "2.5", "3.5", "0.5", "0.75", "1", "2"};
    cr_assert_eq(dfl_table_cols(t), 18);
    for (int j = 0; j < 18; j++) {
        cr_expect_str_eq(dfl_table_col_name(t, (size_t)j), cols[j]);
        cr_expect_str_eq(dfl_table_get(t, 0, cols[j]), vals[j], "%s", cols[j]);
    }
    dfl_table_free(t);
    /* no row yet: the table's error comes through */
    t = dfl_table_new();
    cr_expect_eq(dfl_metrics_put(t, "", &m, &err), DFL_E_INTERNAL);
    cr_expect(strstr(err.msg, "count") != NULL, "%s", err.msg);
    dfl_table_free(t);
}

/* gradstat: hand-computed norms over a mask, all samples, none. */
Test(metrics, gradstat_over_a_mask)
{
    /* |g| = 5, 1, 13, 2 (3D: (3, 4, 0), (0, 0, 1), (3, 4, 12), (0, 2, 0)) */
    const double g[12] = {3, 4, 0, 0, 0, 1, 3, 4, 12, 0, 2, 0};
    const unsigned char mask[4] = {1, 0, 1, 1};
    dfl_gradstat s;
    dfl_metrics_gradstat(4, 3, g, mask, &s);
    cr_expect_eq(s.count, 3);
    cr_expect_eq(s.min, 2.0);
    cr_expect_eq(s.max, 13.0);
    cr_expect_eq(s.mean, 20.0 / 3.0);
    dfl_metrics_gradstat(4, 3, g, NULL, &s);
    cr_expect(s.count == 4 && s.min == 1.0 && s.max == 13.0 && s.mean == 21.0 / 4.0);
    /* 2D reading of the same numbers: |(3, 4)|, |(0, 0)|, ... */
    dfl_metrics_gradstat(2, 2, g, NULL, &s);
    cr_expect(s.count == 2 && s.min == 0.0 && s.max == 5.0 && s.mean == 2.5);
    const unsigned char none[4] = {0, 0, 0, 0};
    dfl_metrics_gradstat(4, 3, g, none, &s);
    cr_expect(s.count == 0 && isnan(s.min) && isnan(s.mean) && isnan(s.max));
}

/* compute_masked is dfl_metrics_compute of the selected samples alone, to
 * the bit, with and without gradients. */
Test(metrics, masked_is_compute_of_the_selection)
{
    const double ref[5] = {0.1, -0.3, 0.7, 0.2, 1.5};
    const double u[5] = {0.12, -0.2, 0.9, 0.2, 1.0};
    const double g[10] = {1, 0, 0.6, 0.7, 3, 4, 0.1, 0.2, 1, 1};
    const unsigned char mask[5] = {0, 1, 1, 0, 1};
    const double su[3] = {-0.2, 0.9, 1.0}, sr[3] = {-0.3, 0.7, 1.5};
    const double sg[6] = {0.6, 0.7, 3, 4, 1, 1};
    dfl_metrics a, b;
    dfl_err err;
    cr_assert_eq(dfl_metrics_compute_masked(5, 2, u, g, ref, mask, &a, &err), DFL_OK);
    cr_assert_eq(dfl_metrics_compute(3, 2, su, sg, sr, 0.0, &b, &err), DFL_OK);
    cr_expect(a.count == 3 && a.l1 == b.l1 && a.mse == b.mse && a.rms == b.rms &&
              a.linf == b.linf && a.gdef_mean == b.gdef_mean && a.gdef_max == b.gdef_max);
    cr_expect_float_eq(a.linf, 0.5, 1e-15);
    cr_assert_eq(dfl_metrics_compute_masked(5, 2, u, NULL, ref, mask, &a, &err), DFL_OK);
    cr_expect(a.count == 3 && a.l1 == b.l1 && isnan(a.gdef_mean) && isnan(a.gdef_max));
    /* an unselected non-finite sample does not matter, a selected one is an
     * error of +inf (the non-finite rule) */
    const double bad[5] = {NAN, -0.2, 0.9, 0.2, INFINITY};
    const unsigned char first[5] = {0, 1, 1, 1, 0};
    cr_assert_eq(dfl_metrics_compute_masked(5, 2, bad, g, ref, first, &a, &err), DFL_OK);
    cr_expect(a.nonfinite == 0 && isfinite(a.linf));
    cr_assert_eq(dfl_metrics_compute_masked(5, 2, bad, g, ref, mask, &a, &err), DFL_OK);
    cr_expect(a.count == 3 && a.nonfinite == 1 && isinf(a.linf) && isinf(a.gdef_max));
    const unsigned char none[5] = {0};
    cr_assert_eq(dfl_metrics_compute_masked(5, 2, u, g, ref, none, &a, &err), DFL_OK);
    cr_expect(a.count == 0 && isnan(a.l1));
}

/* The saturating variant: hand-computed values with hypot norms, +inf for
 * non-finite errors instead of a failure, the band rule, and the serial
 * sum written out bit for bit. */
Test(metrics, saturating_hand_computed_and_inf)
{
    hand_case(dfl_metrics_compute_saturating);
    const double *ref = hc_ref, *u = hc_u, *g = hc_g;
    dfl_metrics m;
    dfl_err err;
    cr_assert_eq(dfl_metrics_compute_saturating(4, 2, u, g, ref, 0.1, &m, &err), DFL_OK);
    cr_expect(m.count == 2 && m.l1 == 0.0);
    cr_expect_float_eq(m.gdef_max, 1.0, 1e-15);
    /* the band rule: band <= 0 and +inf mean every sample */
    const double every[2] = {-1.0, INFINITY};
    for (int i = 0; i < 2; i++) {
        cr_assert_eq(dfl_metrics_compute_saturating(4, 2, u, g, ref, every[i], &m, &err), DFL_OK);
        cr_expect_eq(m.count, 4);
    }
    /* overflowed samples: +inf, not a failure */
    const double uo[4] = {-0.1, INFINITY, NAN, 0.2};
    const double go[8] = {1, 0, NAN, 0, 0.6, 0.8, 1e308, 1e308};
    cr_assert_eq(dfl_metrics_compute_saturating(4, 2, uo, go, ref, 0.0, &m, &err), DFL_OK);
    cr_expect(m.count == 4 && isinf(m.l1) && isinf(m.rms) && isinf(m.linf));
    cr_expect(isinf(m.gdef_mean) && isinf(m.gdef_max));
    /* samples 1 and 2 are not finite; sample 3's gradient is (its norm overflows) */
    cr_expect_eq(m.nonfinite, 2);
    /* outside the band they do not count */
    const double uf[4] = {NAN, 0.0, 0.05, NAN};
    cr_assert_eq(dfl_metrics_compute_saturating(4, 2, uf, g, ref, 0.1, &m, &err), DFL_OK);
    cr_expect(m.count == 2 && m.linf == 0.0 && m.nonfinite == 0);
    /* a NaN reference lies in no band */
    const double rn[4] = {NAN, 0.0, 0.05, 0.5};
    cr_assert_eq(dfl_metrics_compute_saturating(4, 2, u, g, rn, 1.0, &m, &err), DFL_OK);
    cr_expect_eq(m.count, 3);
    cr_expect_eq(dfl_metrics_compute_saturating(4, 2, u, g, ref, NAN, &m, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_metrics_compute_saturating(4, 2, u, g, ref, 1e-3, &m, &err), DFL_OK);
    cr_expect(m.count == 1 && m.l1 == 0.0);
    const double none[4] = {1, 2, 3, 4};
    cr_assert_eq(dfl_metrics_compute_saturating(4, 2, u, g, none, 0.5, &m, &err), DFL_OK);
    cr_expect(m.count == 0 && isnan(m.l1) && isnan(m.gdef_max));
    cr_assert_eq(dfl_metrics_compute_saturating(4, 2, u, NULL, ref, 0.0, &m, &err), DFL_OK);
    cr_expect(m.count == 4 && isnan(m.gdef_mean) && isnan(m.gdef_max));
}

Test(metrics, saturating_serial_hypot_bit_for_bit)
{
    enum { N = 257 };
    double u[N], r[N], g[3 * N];
    for (int i = 0; i < N; i++) {
        r[i] = sin(0.37 * i) * (1 + i % 7);
        u[i] = r[i] + 1e-3 * cos(1.3 * i);
        for (int j = 0; j < 3; j++) g[3 * i + j] = 0.5 + 0.3 * sin(0.11 * i + j);
    }
    for (int dim = 1; dim <= 3; dim++) {
        double s1 = 0, s2 = 0, mx = 0, g1 = 0, gmx = 0;
        size_t c = 0;
        for (int i = 0; i < N; i++) {
            if (!(fabs(r[i]) <= 2.5)) continue;
            const double e = fabs(u[i] - r[i]);
            const double *q = g + i * dim;
            const double h = dim == 1 ? fabs(q[0])
                             : dim == 2 ? hypot(q[0], q[1])
                                        : hypot(hypot(q[0], q[1]), q[2]);
            const double gd = fabs(h - 1.0);
            c++, s1 += e, s2 += e * e, g1 += gd;
            if (e > mx) mx = e;
            if (gd > gmx) gmx = gd;
        }
        dfl_metrics m;
        dfl_err err;
        cr_assert_eq(dfl_metrics_compute_saturating(N, dim, u, g, r, 2.5, &m, &err), DFL_OK);
        cr_expect(m.count == c && m.l1 == s1 / (double)c && m.mse == s2 / (double)c, "dim %d", dim);
        cr_expect(m.rms == sqrt(s2 / (double)c) && m.linf == mx, "dim %d", dim);
        cr_expect(m.gdef_mean == g1 / (double)c && m.gdef_max == gmx, "dim %d", dim);
    }
}

/* Bitwise independence of the team size: the same samples give the same
 * bits at 1, 2, 3 and 7 threads, and equal the serial sum over fixed
 * chunks of DFL_METRICS_CHUNK combined in chunk order. */
Test(metrics, same_bits_at_any_thread_count)
{
    const size_t m = 5 * DFL_METRICS_CHUNK + 123;
    double *u = malloc(m * sizeof *u), *r = malloc(m * sizeof *r), *g = malloc(2 * m * sizeof *g);
    cr_assert(u && r && g);
    for (size_t i = 0; i < m; i++) {
        r[i] = sin(0.001 * (double)i) * 0.7;
        u[i] = r[i] + 1e-3 * cos(0.37 * (double)i) + 1e-9 * (double)(i % 17);
        g[2 * i] = cos(0.01 * (double)i), g[2 * i + 1] = sin(0.013 * (double)i);
    }
    dfl_metrics ref, got;
    dfl_err err;
    omp_set_num_threads(1);
    cr_assert_eq(dfl_metrics_compute(m, 2, u, g, r, 0.5, &ref, &err), DFL_OK);
    /* the serial fixed-chunk sum */
    double s1 = 0;
    for (size_t c = 0; c * DFL_METRICS_CHUNK < m; c++) {
        double p = 0;
        for (size_t i = c * DFL_METRICS_CHUNK; i < m && i < (c + 1) * DFL_METRICS_CHUNK; i++)
            if (fabs(r[i]) <= 0.5) p += fabs(u[i] - r[i]);
        s1 += p;
    }
    cr_expect_eq(ref.l1, s1 / (double)ref.count);
    const int teams[] = {2, 3, 7};
    for (int t = 0; t < 3; t++) {
        omp_set_num_threads(teams[t]);
        cr_assert_eq(dfl_metrics_compute(m, 2, u, g, r, 0.5, &got, &err), DFL_OK);
        cr_expect(memcmp(&ref, &got, sizeof ref) == 0, "%d threads: l1 %.17g vs %.17g", teams[t],
                  got.l1, ref.l1);
    }
    omp_set_num_threads(1);
    free(u), free(r), free(g);
}

/* metrics.h: relative bias = mean ((u - d) / |d|): the error's sign is
 * kept and the divisor is |d|, so inside (d < 0) a field that is too large
 * (u > d) has a positive relative bias, as outside. */
Test(metrics, bandstats_relative_bias_divides_by_abs_ref)
{
    const double ref[2] = {-0.1, -0.2};
    const double u[2] = {-0.08, -0.25}; /* errors +0.02, -0.05 */
    dfl_bandstats b;
    cr_assert_eq(dfl_metrics_bandstats(2, 2, u, NULL, ref, 0.0, &b, NULL), DFL_OK);
    cr_expect_float_eq(b.bias, (0.02 - 0.05) / 2, 1e-15);
    cr_expect_float_eq(b.rel_bias, (0.02 / 0.1 - 0.05 / 0.2) / 2, 1e-15);
}
