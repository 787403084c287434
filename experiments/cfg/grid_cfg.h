/* [grid] section -> dfl_grid.
 *
 *   n  = <nodes per axis>        (2 .. 4096 in 2D, 2 .. 512 in 3D)
 *   lo = x y [z]                 lower corner (default 0 0 [0])
 *   hi = x y [z]                 upper corner (default 1 1 [1]); hi > lo
 *   memory_budget = <GB>         most memory the grid's buffers may take
 *                                (default: half the machine's memory or of its
 *                                cgroup limit, core/budget.h)
 *
 * Resource guard: the memory a study holds for the grid (about 24 (dim + 2)
 * bytes per node: values, gradients, reference and the output buffers) is
 * estimated before anything is allocated; above memory_budget the run is
 * refused with exit status 2, naming [grid] n, the estimate and the budget.
 * dfl_grid_memory_default() gives the default budget in bytes.
 */
#ifndef DFL_EXPERIMENTS_GRID_CFG_H
#define DFL_EXPERIMENTS_GRID_CFG_H

#include "core/budget.h"
#include "field/sample.h"
#include "io/config.h"

double dfl_grid_memory_default(void);
dfl_status dfl_grid_from_cfg(const dfl_cfg *cfg, const char *sec, int dim, dfl_grid *out,
                             dfl_err *err);

/* For a study's estimate (core/budget.h): the grid of [sec] read as
 * dfl_grid_from_cfg reads it (same checks, nothing allocated) into *out,
 * and bytes_per_node times its nodes added to *c, named [sec] n. */
dfl_status dfl_grid_cost_from_cfg(const dfl_cfg *cfg, const char *sec, int dim,
                                  double bytes_per_node, const char *what, dfl_cost *c,
                                  dfl_grid *out, dfl_err *err);

#endif
