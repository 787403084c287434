/* Error metrics of a sampled field u against a reference (usually the exact
 * signed distance d), over all samples or over a band of the reference.
 *
 * Function index
 *   dfl_metrics_compute        L1, MSE, RMS, Linf, gradient-norm defect
 *   dfl_metrics_compute_masked the same over the samples a mask selects
 *   dfl_metrics_compute_saturating  the same, non-finite errors as +inf
 *   dfl_metrics_bandstats      bias, relative bias, L1, RMS, Linf, |grad u|
 *   dfl_metrics_gradstat       min, mean, max of |grad u| over a mask
 *   dfl_metrics_put            the dfl_metrics as cells of a table row
 *   dfl_metrics_put_bandstats  the dfl_bandstats as cells of a table row
 *   dfl_metrics_put_gradstat   the dfl_gradstat as cells of a table row
 *
 * The band rule (every computation with a band): the band is the set of
 * samples with |ref| <= band.  band <= 0 or band = +inf means every
 * sample; a NaN band is DFL_E_INPUT.
 *
 * The non-finite rule (every computation of errors, every study): a sample
 * whose value u (or, where a gradient is given to dfl_metrics_compute, a
 * gradient component) is NaN or +-inf has an error of +inf.  It is never
 * left out: it enters count, is counted in nonfinite, and makes every
 * metric of its set +inf (L1, MSE, RMS, Linf; the gradient defects when a
 * gradient is given; bias, relative bias, L1, RMS, Linf of a band).  Its
 * band membership is decided by its reference, which must be finite
 * (a non-finite reference is DFL_E_NUMERIC: the reference is dflab's own).
 * The tables carry the count in a column whose name holds "nonfinite", and
 * a run whose tables hold a non-zero one exits with status 1 unless the
 * config allows it (harness/runner.h).
 *
 * dfl_metrics:
 *   L1   = mean |u - d|          MSE  = mean (u - d)^2
 *   RMS  = sqrt(MSE)             Linf = max |u - d|
 *   gradient-norm defect: mean and max of | |grad u| - 1 |
 * hvb25 calls MSE "L2"; dflab names each metric by what it is.
 *
 * dfl_bandstats (what the bs04 level-set studies report beside their
 * level-set measures):
 *   bias = mean (u - d)     l1 = mean |u - d|     rms = sqrt(mean (u - d)^2)
 *   linf = max |u - d|      relative bias = mean ((u - d) / |d|) over the
 *                           band's samples with d != 0
 *   gmin, gmean, gmax       of |grad u| over the band's samples with u != 0
 *                           (bs04 fields have gradient 0 by convention on
 *                           their zero set, where they are not
 *                           differentiable)
 *
 * dfl_gradstat: min, mean, max of |grad u| over the selected samples.
 *
 * |grad u| is sqrt(sum_j g_j^2) summed in axis order from 0, everywhere
 * except in dfl_metrics_compute_saturating (C's hypot, see there).
 */
#ifndef DFL_FIELD_METRICS_H
#define DFL_FIELD_METRICS_H

#include <stddef.h>

#include "core/status.h"
#include "io/table.h"

/* Samples per chunk of dfl_metrics_compute's sums (fixes the summation
 * order; changing it changes the last bits of l1, mse, gdef_mean). */
#define DFL_METRICS_CHUNK 4096

typedef struct dfl_metrics {
    size_t count;        /* samples that entered the metrics */
    double l1, mse, rms, linf;
    double gdef_mean, gdef_max;  /* NAN when no gradient was given */
    size_t nonfinite;    /* of count: samples with a non-finite value (error +inf) */
} dfl_metrics;

typedef struct dfl_gradstat {
    size_t count;                 /* selected samples */
    double min, mean, max;
} dfl_gradstat;

typedef struct dfl_bandstats {
    size_t count;                 /* samples in the band */
    double bias, rel_bias, l1, rms, linf;
    size_t gcount;                /* band samples with u != 0, u finite */
    double gmin, gmean, gmax;
    size_t nonfinite;             /* of count: samples with u not finite */
} dfl_bandstats;

/* u, ref: m values; gu: m*dim gradient of u (may be NULL).  Band: see the
 * band rule above.  Non-finite u or gradient: the non-finite rule above
 * (error +inf, counted in nonfinite).  A non-finite ref at any sample (in
 * the band or not): DFL_E_NUMERIC naming the first such sample.  count == 0
 * (empty band) gives NAN metrics, nonfinite 0 and DFL_OK.  Parallel (OpenMP) over fixed
 * chunks of DFL_METRICS_CHUNK samples whose sums are added in chunk order,
 * so the result is bitwise the same at any thread count.  DFL_E_NOMEM when
 * the chunk sums cannot be allocated. */
dfl_status dfl_metrics_compute(size_t m, int dim, const double *u, const double *gu,
                               const double *ref, double band, dfl_metrics *out, dfl_err *err);

/* dfl_metrics_compute (band: every sample) over the samples i with
 * mask[i] != 0, taken in index order into compacted copies, so the result
 * equals dfl_metrics_compute of the selected samples alone.  gu may be
 * NULL.  Failures: DFL_E_NOMEM for the copies, else as dfl_metrics_compute
 * (the sample a DFL_E_NUMERIC message names is the index among the
 * selected samples). */
dfl_status dfl_metrics_compute_masked(size_t m, int dim, const double *u, const double *gu,
                                      const double *ref, const unsigned char *mask,
                                      dfl_metrics *out, dfl_err *err);

/* dfl_metrics for fields that may overflow far from their zero set (e.g.
 * rfunc's recursive normalization): the band rule above, but a sample
 * whose |u - ref| or gradient defect is not finite enters it as +inf
 * instead of failing, so linf (gdef_max) and the means become +inf; a NaN
 * ref lies in no finite band.  nonfinite counts the samples of the band
 * whose u or gradient is not finite (as the non-finite rule above).  Serial, summed in sample order; |grad u| is
 * hypot(g0, g1) (dim 2; dim 1: |g0|; dim 3: hypot(hypot(g0, g1), g2)), as
 * bs04_recursive's tables were computed.  dim 1..3 (asserted).  Empty band:
 * count 0 and NAN metrics.  Fails only with DFL_E_INPUT for a NaN band. */
dfl_status dfl_metrics_compute_saturating(size_t m, int dim, const double *u, const double *gu,
                                          const double *ref, double band, dfl_metrics *out,
                                          dfl_err *err);

/* u, ref: m values; gu: m*dim gradient components (may be NULL: gradient
 * statistics NAN).  Band: see the band rule above.  Empty band: count 0 and
 * NAN statistics, DFL_OK.  A non-finite u inside the band: the non-finite
 * rule above (counted in nonfinite; bias, rel_bias (when ref != 0), l1, rms,
 * linf become +inf; the gradient statistics leave the sample out).
 * DFL_E_NUMERIC naming the sample for a NaN ref anywhere or an infinite ref
 * inside the band.  Serial. */
dfl_status dfl_metrics_bandstats(size_t m, int dim, const double *u, const double *gu,
                                 const double *ref, double band, dfl_bandstats *out,
                                 dfl_err *err);

/* Statistics of |grad u| (grad: m*dim components) over the samples whose
 * mask entry is non-zero (mask NULL: all): count, min, mean (summed in
 * sample order), max; NAN statistics when none is selected.  Cannot fail;
 * non-finite gradients propagate (fmin/fmax skip a NaN norm, the mean
 * does not). */
void dfl_metrics_gradstat(size_t m, int dim, const double *grad, const unsigned char *mask,
                          dfl_gradstat *out);

/* Sets count<sfx>, l1<sfx>, mse<sfx>, rms<sfx>, linf<sfx>,
 * graddefect_mean<sfx>, graddefect_max<sfx>, nonfinite<sfx> in the current
 * row of t.
 * Fails as the table setters do (table.h), at the first failed cell. */
dfl_status dfl_metrics_put(dfl_table *t, const char *sfx, const dfl_metrics *m, dfl_err *err);

/* Sets band_count, band_bias, band_rel_bias, band_l1, band_rms, band_linf,
 * grad_min, grad_mean, grad_max, band_nonfinite in the current row of t.  Fails as the
 * table setters do.  These grad_* are dfl_bandstats' gmin, gmean, gmax: over
 * the band's samples with a finite u != 0 (their count is gcount, not
 * written), not over every band sample as dfl_metrics_put_gradstat's. */
dfl_status dfl_metrics_put_bandstats(dfl_table *t, const dfl_bandstats *b, dfl_err *err);

/* Sets grad_min<sfx>, grad_mean<sfx>, grad_max<sfx> (not the count) in the
 * current row of t.  Fails as the table setters do.  The samples are
 * dfl_metrics_gradstat's: every selected one, u == 0 included, unlike the
 * grad_* of dfl_metrics_put_bandstats (finite u != 0 only); the studies
 * keep the two apart by the suffix (_band, _s<k>_band beside bandstats'
 * bare names) and both stay as they are so that published tables keep
 * their values. */
dfl_status dfl_metrics_put_gradstat(dfl_table *t, const char *sfx, const dfl_gradstat *g,
                                    dfl_err *err);

#endif
