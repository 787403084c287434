#include "cfg/grid_cfg.h"

#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "core/budget.h"

/* Bytes a study holds per grid node: values, dim gradient components and
 * the reference (8 bytes each), and about as much again for the output
 * files' buffers (issue 11 measured 13.6 GB at 512^3), an estimate that errs
 * high so that a run is refused before it allocates, not after. */
static double bytes_per_node(int dim) { return 24.0 * (dim + 2); }

/* The machine's default (core/budget.h): half of physical memory or of the
 * cgroup limit, whichever is smaller, so a run inside a small cgroup is
 * refused instead of killed by the kernel. */
double dfl_grid_memory_default(void) { return dfl_budget_memory_default(); }

/* The grid's memory against [sec] memory_budget (GB; default half the
 * machine's memory). */
static dfl_status check_memory(const dfl_cfg *cfg, const char *sec, const dfl_grid *g,
                               dfl_err *err)
{
    double budget;
    const double def = dfl_grid_memory_default() / 1e9;
    dfl_status st = dfl_cfg_double_opt(cfg, sec, "memory_budget", def, 1e-3, 1e6, &budget, err);
    if (st != DFL_OK) return st;
    double nodes = 1.0;
    for (int d = 0; d < g->dim; d++) nodes *= g->n[d];
    const double need = nodes * bytes_per_node(g->dim) / 1e9;
    if (need > budget)
        return dfl_cfg_reject(cfg, sec, "n", err,
                              "a grid of %.0f nodes needs about %.3g GB, above the memory "
                              "budget of %.3g GB (%s; set [%s] memory_budget = <GB> to change it)",
                              nodes, need, budget,
                              dfl_cfg_has(cfg, sec, "memory_budget") ? "memory_budget"
                                                                     : "the default: half the "
                                                                       "machine's or cgroup's memory",
                              sec);
    return DFL_OK;
}

dfl_status dfl_grid_from_cfg(const dfl_cfg *cfg, const char *sec, int dim, dfl_grid *out,
                             dfl_err *err)
{
    static const double zero[3] = {0, 0, 0}, one[3] = {1, 1, 1};
    memset(out, 0, sizeof *out);
    out->dim = dim;
    long n;
    dfl_status st = dfl_cfg_int(cfg, sec, "n", 2, dim == 2 ? 4096 : 512, &n, err);
    if (st != DFL_OK) return st;
    st = dfl_cfg_vec_opt(cfg, sec, "lo", dim, zero, out->lo, err);
    if (st != DFL_OK) return st;
    st = dfl_cfg_vec_opt(cfg, sec, "hi", dim, one, out->hi, err);
    if (st != DFL_OK) return st;
    for (int d = 0; d < 3; d++) out->n[d] = d < dim ? (int)n : 1;
    for (int d = 0; d < dim; d++)
        if (!(out->lo[d] < out->hi[d])) {
            return dfl_cfg_reject(cfg, sec, "hi", err,
                                  "expected hi > lo on every axis (axis %d: %g <= %g)", d,
                                  out->hi[d], out->lo[d]);
        }
    st = check_memory(cfg, sec, out, err);
    if (st != DFL_OK) return st;
    return dfl_grid_check(out, err);
}

dfl_status dfl_grid_cost_from_cfg(const dfl_cfg *cfg, const char *sec, int dim,
                                  double bytes_per_node, const char *what, dfl_cost *c,
                                  dfl_grid *out, dfl_err *err)
{
    dfl_status st = dfl_grid_from_cfg(cfg, sec, dim, out, err);
    if (st != DFL_OK) return st;
    const double nodes = (double)dfl_grid_size(out);
    dfl_cost_add_bytes(c, dfl_cfg_section_name(cfg, sec), "n", nodes * bytes_per_node,
                       "%s on a grid of %d^%d nodes", what, out->n[0], dim);
    return DFL_OK;
}
