/* Bounded nonlinear least squares through Ceres (Levenberg–Marquardt).
 *
 * A thin extern "C" adapter over Ceres' C++ API (lsq.cc): the caller gives a
 * residual callback with an analytic Jacobian; the adapter runs LM with
 * DENSE_QR, silent logging and optional box bounds.  Ceres' own C API is not
 * used because it takes no options and prints a report on every call.
 *
 * Thread safety: a dfl_lsq_ctx may be shared by threads; each solve is
 * independent.  Every C++ exception is caught and turned into a status.
 */
#ifndef DFL_SOLVE_LSQ_H
#define DFL_SOLVE_LSQ_H

#include <stddef.h>

#include "core/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Residuals r[0..m-1] at parameters x[0..n-1]; when J is not NULL also the
 * row-major Jacobian J[i*n + j] = d r_i / d x_j.  Returns 0 on success,
 * non-zero if the residual cannot be evaluated at x. */
typedef int (*dfl_lsq_residual_fn)(void *user, const double *x, double *r, double *J);

typedef struct dfl_lsq_options {
    int max_iterations;          /* default 100 */
    double function_tolerance;   /* default 1e-16 */
    double gradient_tolerance;   /* default 1e-16 */
    double parameter_tolerance;  /* default 1e-14 */
} dfl_lsq_options;

typedef struct dfl_lsq_result {
    double final_cost;           /* 0.5 * |r|^2 at the solution */
    int iterations;
    int converged;               /* 1 if Ceres reported CONVERGENCE */
} dfl_lsq_result;

typedef struct dfl_lsq_ctx dfl_lsq_ctx;

/* Fills defaults. */
void dfl_lsq_options_default(dfl_lsq_options *opt);

/* A shared Ceres context (thread pool, glog quieted).  Free with
 * dfl_lsq_ctx_free. */
dfl_status dfl_lsq_ctx_new(dfl_lsq_ctx **out, dfl_err *err);
void dfl_lsq_ctx_free(dfl_lsq_ctx *ctx);

/* Minimizes 0.5*|r(x)|^2 over x (n <= 16, m <= 64) starting from x, with
 * lo[j] <= x[j] <= hi[j] when lo/hi are not NULL (use +-HUGE_VAL for a free
 * coordinate; lo[j] == hi[j] holds x[j] at that value, and when every
 * coordinate is held the result is the cost at x after 0 iterations).
 * x is overwritten by the solution.  opt may be NULL.  DFL_E_INPUT for
 * sizes out of range, an empty bound (lo[j] > hi[j] or NaN) or a start
 * outside the box; DFL_E_NUMERIC when Ceres fails.  res->iterations counts
 * the iterations of every round of a bounded solve. */
dfl_status dfl_lsq_solve(dfl_lsq_ctx *ctx, int n, int m, dfl_lsq_residual_fn fn, void *user,
                         const double *lo, const double *hi, const dfl_lsq_options *opt,
                         double *x, dfl_lsq_result *res, dfl_err *err);

#ifdef __cplusplus
}
#endif

#endif
