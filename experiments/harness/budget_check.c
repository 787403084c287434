/* The runner's resource guard: every sweep point's estimate (its study's
 * estimate hook, or the [field] section's cost) against [study]
 * memory_budget and work_budget, during validation, before any point
 * computes (sweep.h).  Points run one after another in a process, so the
 * memory that counts is each point's own; work is per point too (each
 * point is a unit a Slurm array or GNU parallel runs alone). */
#include <math.h>
#include <stdio.h>

#include "cfg/field_cost.h"
#include "harness/experiment.h"
#include "harness/sweep.h"

dfl_status dfl_study_estimate_default(const dfl_cfg *cfg, const dfl_study_ctx *ctx,
                                      dfl_cost *cost, dfl_err *err)
{
    (void)ctx;
    if (!dfl_cfg_has_section(cfg, "field") || !dfl_cfg_has(cfg, "field", "kind")) return DFL_OK;
    return dfl_field_cost_from_cfg(cfg, "field", cost, err);
}

dfl_status dfl_sweep_budgets(const dfl_cfg *pt, double *mem_bytes, double *work_seconds,
                             dfl_err *err)
{
    double gb, hours;
    dfl_status st = dfl_cfg_double_opt(pt, "study", "memory_budget",
                                       dfl_budget_memory_default() / 1e9, 1e-3, 1e6, &gb, err);
    if (!st) st = dfl_cfg_double_opt(pt, "study", "work_budget", 24, 1e-6, 1e6, &hours, err);
    if (st) return st;
    *mem_bytes = gb * 1e9;
    *work_seconds = hours * 3600;
    return DFL_OK;
}

static const char *human_time(double s, char *buf, size_t size)
{
    if (!isfinite(s)) snprintf(buf, size, "forever");
    else if (s < 120) snprintf(buf, size, "%.3g s", s);
    else if (s < 2 * 3600) snprintf(buf, size, "%.3g min", s / 60);
    else if (s < 3 * 86400) snprintf(buf, size, "%.3g h", s / 3600);
    else snprintf(buf, size, "%.3g days", s / 86400);
    return buf;
}

dfl_status dfl_sweep_check_budget(const dfl_sweep *s, const dfl_cfg *pt, const dfl_study_ctx *ctx,
                                  dfl_err *err)
{
    double mem, work;
    dfl_status st = dfl_sweep_budgets(pt, &mem, &work, err);
    if (st) return st;
    dfl_cost c = {0};
    st = s->study->estimate ? s->study->estimate(pt, ctx, &c, err)
                            : dfl_study_estimate_default(pt, ctx, &c, err);
    if (st) return st;
    if (c.bytes > mem && c.mem_key)
        return dfl_cfg_reject(pt, c.mem_sec, c.mem_key, err,
                              "needs about %.3g GB (%s), above the memory budget of %.3g GB "
                              "(%s; set [study] memory_budget = <GB> to change it)",
                              c.bytes / 1e9, c.mem_what, mem / 1e9,
                              dfl_cfg_has(pt, "study", "memory_budget")
                                  ? "memory_budget"
                                  : "the default: half the machine's or cgroup's memory");
    const double sec = dfl_cost_seconds(&c, ctx->threads);
    if (sec > work && c.work_key) {
        char a[64], b[64];
        return dfl_cfg_reject(pt, c.work_sec, c.work_key, err,
                              "would take about %s on %d thread%s (%s; estimated from "
                              "conservative per-evaluation times), above the work budget of %s "
                              "(%s; set [study] work_budget = <hours> to change it)",
                              human_time(sec, a, sizeof a), ctx->threads,
                              ctx->threads == 1 ? "" : "s", c.work_what,
                              human_time(work, b, sizeof b),
                              dfl_cfg_has(pt, "study", "work_budget") ? "work_budget"
                                                                      : "the default: 24 h");
    }
    return DFL_OK;
}

dfl_status dfl_sweep_estimate(const dfl_sweep *s, size_t k, int threads, double *bytes,
                              double *seconds, dfl_err *err)
{
    dfl_cfg *pt = NULL;
    dfl_status st = dfl_cfg_sweep_point(s->cfg, k, &pt, err);
    char tag[32];
    dfl_study_tag(k, s->np, tag, sizeof tag);
    dfl_study_ctx ctx = {.stage_dir = "/nonexistent/dflab-estimate", .tag = tag, .point = k,
                         .npoints = s->np, .threads = threads};
    dfl_cost c = {0};
    if (!st)
        st = s->study->estimate ? s->study->estimate(pt, &ctx, &c, err)
                                : dfl_study_estimate_default(pt, &ctx, &c, err);
    dfl_cfg_free(pt);
    *bytes = c.bytes;
    *seconds = dfl_cost_seconds(&c, threads);
    return st;
}
