/* [grid] section -> dfl_grid.
 *
 *   n  = <nodes per axis>        (2 .. 4096 in 2D, 2 .. 512 in 3D)
 *   lo = x y [z]                 lower corner (default 0 0 [0])
 *   hi = x y [z]                 upper corner (default 1 1 [1]); hi > lo
 */
#ifndef DFL_EXPERIMENTS_GRID_CFG_H
#define DFL_EXPERIMENTS_GRID_CFG_H

#include "field/sample.h"
#include "io/config.h"

dfl_status dfl_grid_from_cfg(const dfl_cfg *cfg, const char *sec, int dim, dfl_grid *out,
                             dfl_err *err);

#endif
