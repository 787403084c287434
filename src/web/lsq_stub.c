/* solve/lsq.h for the WebAssembly build: Ceres (C++) is not compiled for
 * the page, so every solver entry fails with DFL_E_INPUT and a message
 * saying so.  geom's footpoint code names the solver only for its "ceres"
 * backend; the page uses the default Newton backend, so these are never
 * reached in practice.  Compiled only by src/web/web.mk, never into the
 * native library. */
#include "solve/lsq.h"

#include <stddef.h>
#include <string.h>

/* No solver runs, so no option is ever read: zeros. */
void dfl_lsq_options_default(dfl_lsq_options *opt)
{
    memset(opt, 0, sizeof *opt);
}

dfl_status dfl_lsq_ctx_new(dfl_lsq_ctx **out, dfl_err *err)
{
    *out = NULL;
    return dfl_err_set(err, DFL_E_INPUT, "the least-squares solver (Ceres) is not part of the web build");
}

void dfl_lsq_ctx_free(dfl_lsq_ctx *ctx)
{
    (void)ctx;
}

dfl_status dfl_lsq_solve(dfl_lsq_ctx *ctx, int n, int m, dfl_lsq_residual_fn fn, void *user,
                         const double *lo, const double *hi, const dfl_lsq_options *opt,
                         double *x, dfl_lsq_result *res, dfl_err *err)
{
    (void)ctx, (void)n, (void)m, (void)fn, (void)user, (void)lo, (void)hi, (void)opt, (void)x;
    if (res) res->final_cost = 0, res->iterations = 0, res->converged = 0;
    return dfl_err_set(err, DFL_E_INPUT, "the least-squares solver (Ceres) is not part of the web build");
}
