/* Smoke study: the exact signed distance of [shape] sampled on [grid],
 * and the error metrics of a deliberately perturbed copy
 *
 *     u = (1 + scale) d + offset,   grad u = (1 + scale) grad d
 *
 * against d.  The perturbation is affine on purpose: its metrics are known
 * in closed form (e = scale*d + offset; the gradient-norm defect is |scale|
 * wherever |grad d| = 1), so the end-to-end test can check the harness
 * without trusting it.  Writes smoke.csv (one row per sweep point), field
 * .vti and .exr.
 *
 * Keys:  [grid] n, lo, hi   [perturb] scale (default 0.02), offset (0.005)
 *        [metrics] band (default 0.1: |d| <= band)   [output] see field_out.h
 */
#include <stdio.h>
#include <stdlib.h>

#include "harness/experiment.h"
#include "field/metrics.h"
#include "field/sample.h"
#include "cfg/field_cfg.h"
#include "harness/field_out.h"
#include "cfg/field_cost.h"
#include "cfg/grid_cfg.h"

static dfl_status smoke_run(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_table *table,
                            dfl_err *err)
{
    dfl_field f = {0};
    dfl_grid g;
    double scale, offset, band;
    dfl_field_write_opts oo;
    double *d = NULL, *gd = NULL, *u = NULL, *gu = NULL;
    dfl_status st = dfl_field_from_cfg(cfg, "field", &f, err);
    if (st == DFL_OK) st = dfl_grid_from_cfg(cfg, "grid", f.dim, &g, err);
    if (st == DFL_OK) st = dfl_cfg_double_opt(cfg, "perturb", "scale", 0.02, -0.5, 0.5, &scale, err);
    if (st == DFL_OK) st = dfl_cfg_double_opt(cfg, "perturb", "offset", 0.005, -1, 1, &offset, err);
    if (st == DFL_OK) st = dfl_cfg_double_opt(cfg, "metrics", "band", 0.1, 0, 1e300, &band, err);
    if (st == DFL_OK) st = dfl_field_out_from_cfg(cfg, &oo, err);
    if (st == DFL_OK) st = dfl_cfg_check_used(cfg, err);
    if (st != DFL_OK) goto done;

    const size_t m = dfl_grid_size(&g);
    const int dim = g.dim;
    d = malloc(m * sizeof *d);
    gd = malloc(m * (size_t)dim * sizeof *gd);
    u = malloc(m * sizeof *u);
    gu = malloc(m * (size_t)dim * sizeof *gu);
    if (!d || !gd || !u || !gu) {
        st = dfl_err_set(err, DFL_E_NOMEM, "out of memory for %zu samples", m);
        goto done;
    }
    st = dfl_field_sample(&f, &g, ctx->threads, d, gd, err);
    if (st != DFL_OK) goto done;
    for (size_t i = 0; i < m; i++) {
        u[i] = (1.0 + scale) * d[i] + offset;
        for (int k = 0; k < dim; k++) gu[i * (size_t)dim + k] = (1.0 + scale) * gd[i * (size_t)dim + k];
    }
    dfl_metrics all, inband;
    st = dfl_metrics_compute(m, dim, u, gu, d, 0.0, &all, err);
    if (st == DFL_OK) st = dfl_metrics_compute(m, dim, u, gu, d, band, &inband, err);
    if (st != DFL_OK) goto done;

    st = dfl_table_row(table, err);
    if (st == DFL_OK) st = dfl_table_set_int(table, "dim", dim, err);
    if (st == DFL_OK) st = dfl_table_set_int(table, "nodes", (long)m, err);
    if (st == DFL_OK) st = dfl_table_set_double(table, "scale", scale, err);
    if (st == DFL_OK) st = dfl_table_set_double(table, "offset", offset, err);
    if (st == DFL_OK) st = dfl_table_set_double(table, "band", band, err);
    if (st == DFL_OK) st = dfl_metrics_put(table, "", &all, err);
    if (st == DFL_OK) st = dfl_metrics_put(table, "_band", &inband, err);
    if (st != DFL_OK) goto done;
    st = dfl_field_out_write(ctx, "field", &g, u, gu, d, &oo, err);
done:
    free(d), free(gd), free(u), free(gu);
    dfl_field_destroy(&f);
    return st;
}

/* Peak memory: the field ([field]'s cost), the four sample arrays of the
 * grid (d, u: 8 bytes a node each; grad d, grad u: 8 dim each, all held
 * until the files are written) and the writer's own arrays
 * (dfl_field_out_bytes).  Work: one evaluation of the field per node
 * (dfl_field_eval_cost: the shape's class for kind = exact) and the
 * files (dfl_field_out_units). */
static dfl_status smoke_estimate(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_cost *c,
                                 dfl_err *err)
{
    dfl_field_write_opts oo;
    dfl_grid g;
    dfl_cost_class cls;
    double units;
    const int dim = dfl_field_dim_guess(cfg, "field");
    dfl_status st = dfl_study_estimate_default(cfg, ctx, c, err);
    if (!st) st = dfl_field_eval_cost(cfg, "field", &cls, &units, err);
    if (!st) st = dfl_field_out_from_cfg(cfg, &oo, err);
    if (!st)
        st = dfl_grid_cost_from_cfg(cfg, "grid", dim, 16.0 * (dim + 1), "the samples", c, &g,
                                    err);
    if (st) return st;
    const double m = (double)dfl_grid_size(&g);
    dfl_cost_add_bytes(c, "grid", "n", dfl_field_out_bytes(&oo, m), "the field files' buffers");
    dfl_cost_add_work(c, "grid", "n", cls, m * units, "%.3g field evaluations", m * units);
    dfl_cost_add_work(c, "grid", "n", DFL_COST_CHEAP, dfl_field_out_units(&oo, m),
                      "the field files of %.3g nodes", m);
    return DFL_OK;
}

DFL_STUDY_DEFINE_ESTIMATED(smoke, smoke_run, smoke_estimate,
                 "exact SDF of [shape] on a grid + metrics of an affinely perturbed copy");

const dfl_study *const dfl_smoke_studies[] = {&dfl_study_smoke, NULL};
