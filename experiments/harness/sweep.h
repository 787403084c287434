/* Private to the harness (runner.c, point.c, merge.c, plan.c): a loaded,
 * validated sweep and the names of its folders.
 *
 *   dfl_sweep_open     load, override, find the study, validate every point
 *   dfl_sweep_close    free
 *   dfl_sweep_label    "sec.key=value ..." of a point
 *   dfl_sweep_outdir   the default output folder of a config and overrides
 *   dfl_point_run      compute one point into OUT.points/ptNNN (point.c)
 *   dfl_point_current  whether OUT.points/ptNNN is up to date (point.c)
 *   dfl_merge_into     assemble OUT from its points (merge.c)
 *   dfl_sweep_clean_stale  remove dead runs' stage folders of OUT (merge.c)
 *   dfl_sweep_budgets      [study] memory_budget (GB) and work_budget (hours)
 *   dfl_sweep_check_budget a point's estimate against them (budget_check.c)
 */
#ifndef DFL_EXPERIMENTS_SWEEP_H
#define DFL_EXPERIMENTS_SWEEP_H

#include <stdbool.h>
#include <stddef.h>

#include "harness/experiment.h"
#include "harness/runner.h"
#include "io/config.h"

typedef struct dfl_sweep {
    const dfl_run_opts *o;
    dfl_cfg *cfg;
    const dfl_study *study;
    size_t np, na;
    char outdir[4096];
    char points[4200];      /* OUT.points */
    char sweep_sha[65];     /* dfl_cfg_sweep_hash of the whole sweep */
    char binary_sha[65];    /* sha256 of the running dflab */
    int threads;            /* what the study gets (>= 1) */
} dfl_sweep;

dfl_status dfl_sweep_open(const dfl_run_opts *o, dfl_sweep *s, dfl_err *err);
void dfl_sweep_close(dfl_sweep *s);
const char *dfl_sweep_label(const dfl_sweep *s, const dfl_cfg *pt, char *buf, size_t size);
void dfl_sweep_outdir(const dfl_run_opts *o, char *buf, size_t size);
/* OUT.points/ptNNN into buf. */
const char *dfl_point_dir(const dfl_sweep *s, size_t k, char *buf, size_t size);

dfl_status dfl_point_run(const dfl_sweep *s, size_t k, double *seconds, dfl_err *err);
bool dfl_point_current(const dfl_sweep *s, size_t k);

dfl_status dfl_merge_into(const char *dir, const dfl_sweep *expect, int quiet,
                          const char *cmdline, dfl_err *err);
void dfl_sweep_clean_stale(const char *outdir);

/* [study] memory_budget = <GB> (1e-3 .. 1e6; default core/budget.h's
 * dfl_budget_memory_default) and work_budget = <hours> (1e-6 .. 1e6;
 * default 24) of point pt, in bytes and seconds (marks both used). */
dfl_status dfl_sweep_budgets(const dfl_cfg *pt, double *mem_bytes, double *work_seconds,
                             dfl_err *err);
/* The study's estimate of point pt (its hook or dfl_study_estimate_default)
 * against the budgets: DFL_E_INPUT naming the key that dominates, the
 * estimate and the budget, when the point's peak memory or its time on
 * ctx->threads cores is above them.  Builds nothing. */
dfl_status dfl_sweep_check_budget(const dfl_sweep *s, const dfl_cfg *pt, const dfl_study_ctx *ctx,
                                  dfl_err *err);

#endif
