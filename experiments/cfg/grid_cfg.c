#include "cfg/grid_cfg.h"

#include <string.h>


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
    return dfl_grid_check(out, err);
}
