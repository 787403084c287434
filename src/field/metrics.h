/* Error metrics of a sampled field u against a reference (usually the exact
 * signed distance d), over all samples or over the band |d| <= band.
 *
 *   L1   = mean |u - d|          MSE  = mean (u - d)^2
 *   RMS  = sqrt(MSE)             Linf = max |u - d|
 *   gradient-norm defect: mean and max of | |grad u| - 1 |
 *
 * hvb25 calls MSE "L2"; dflab names each metric by what it is.
 */
#ifndef DFL_FIELD_METRICS_H
#define DFL_FIELD_METRICS_H

#include <stddef.h>

#include "core/status.h"

typedef struct dfl_metrics {
    size_t count;        /* samples that entered the metrics */
    double l1, mse, rms, linf;
    double gdef_mean, gdef_max;  /* NAN when no gradient was given */
} dfl_metrics;

/* u, ref: m values; gu: m*dim gradient of u (may be NULL).  band <= 0 or
 * infinite means all samples.  Non-finite u or ref: DFL_E_NUMERIC naming the
 * sample index.  count == 0 (empty band) gives NAN metrics and DFL_OK. */
dfl_status dfl_metrics_compute(size_t m, int dim, const double *u, const double *gu,
                               const double *ref, double band, dfl_metrics *out, dfl_err *err);

#endif
