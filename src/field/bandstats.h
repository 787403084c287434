/* Error and gradient statistics of a sampled approximate distance u against
 * the exact distance d in the band |d| <= band: what the bs04 studies report
 * beside their level-set measures.
 *
 *   bias = mean (u - d)     l1 = mean |u - d|     rms = sqrt(mean (u - d)^2)
 *   linf = max |u - d|      relative bias = mean ((u - d) / |d|) over the
 *                           band's nodes with d != 0
 *   gmin, gmean, gmax       of |grad u| over the band's nodes with u != 0
 *                           (bs04 fields have gradient 0 by convention on
 *                           their zero set, where they are not
 *                           differentiable)
 */
#ifndef DFL_EXPERIMENTS_BANDSTATS_H
#define DFL_EXPERIMENTS_BANDSTATS_H

#include <stddef.h>

#include "core/status.h"
#include "io/table.h"

typedef struct dfl_bandstats {
    size_t count;                 /* nodes in the band */
    double bias, rel_bias, l1, rms, linf;
    size_t gcount;                /* band nodes with u != 0 */
    double gmin, gmean, gmax;
} dfl_bandstats;

/* u, ref: m values; gu: m*dim gradient components (may be NULL: gradient
 * statistics NAN).  band > 0 (infinite: every node).  Empty band: count 0
 * and NAN statistics, DFL_OK.  DFL_E_NUMERIC naming the node for a
 * non-finite u or ref inside the band; DFL_E_INPUT for band <= 0 or NaN. */
dfl_status dfl_bandstats_compute(size_t m, int dim, const double *u, const double *gu,
                                 const double *ref, double band, dfl_bandstats *out,
                                 dfl_err *err);

/* Sets columns band_count, band_bias, band_rel_bias, band_l1, band_rms,
 * band_linf, grad_min, grad_mean, grad_max of the current row. */
dfl_status dfl_bandstats_put(dfl_table *t, const dfl_bandstats *b, dfl_err *err);

#endif
