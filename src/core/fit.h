/* Least-squares fits of small data sets.
 *
 *   dfl_fit_loglog_slope(n, x, y)   slope of log y against log x
 *
 * Pure, allocation-free, thread-safe; no input checks (degenerate data
 * gives a meaningless number, see each function, never a trap). */
#ifndef DFL_CORE_FIT_H
#define DFL_CORE_FIT_H

#include <stddef.h>

/* The least-squares slope k of log(y_i) = k log(x_i) + c over n pairs: the
 * growth exponent of y in x (y ~ x^k gives k exactly up to rounding).
 * Meaningful for n >= 2, x_i, y_i > 0 and not all x_i equal; otherwise the
 * result is meaningless and never traps: n < 2 gives NaN (0/0), equal x
 * give 0/0 when the sums cancel exactly (x = 1) and a huge or NaN value
 * when rounding leaves a residue, x or y <= 0 give NaN or -inf logs.  The
 * sums of log x, log y, log^2 x and log x log y
 * are accumulated from 0 in index order and combined as
 * (n Sxy - Sx Sy) / (n Sxx - Sx^2). */
double dfl_fit_loglog_slope(size_t n, const double *x, const double *y);

#endif
