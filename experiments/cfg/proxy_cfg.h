/* [field] kind = proxy -> a proxy grid and its decoding filter (hvb25,
 * issue 9's probe contract), with the shape in [shape].
 *
 * Function index
 *   dfl_proxy_cfg             the grid and filter keys, parsed
 *   dfl_proxy_cfg_read        [sec] -> dfl_proxy_cfg (no input, no build)
 *   dfl_proxy_grid_from_cfg   [sec] + [shape_sec] -> built grid + filter options
 *   dfl_proxy_field_from_cfg  the field kind's factory (field_cfg.c's row)
 *
 * Keys of [sec] (besides kind and the input's keys, which
 * experiments/cfg/proxy_input_cfg.h reads: input, curvature, footpoint,
 * fit_grid, fit_spacing, param_grid):
 *   order       1 | 2                                  (default 1)
 *   res         N >= 1 cells per axis (N^3 proxies)    (default 16)
 *   lo, hi      the box: one number for all axes or "x y z" (default -1, 1)
 *   filter      nearest | trilinear | hermite          (default nearest)
 *   storage     double | float | half                  (default double)
 *   position    displacement | absolute: what the footpoint's 3 scalars
 *               store (proxy/store.h)                  (default displacement)
 *   clip        bound | paper | off: the sphere constraint's formula
 *               (proxy/filter.h: dflab's lower bound, the paper's proxy
 *               solid intersected with the ball, or none) (default bound)
 *   clip_radius the sphere constraint's radius in CELL SIZES (max_j h_j),
 *               > 0 (default: 1 for nearest, no clip for trilinear and
 *               hermite); refused with clip = off
 *   shape       the section holding the shape          (default shape)
 *   signed      true: signed output (needs an input with an inside)
 *               (default false: unsigned, as the paper)
 *   noise       footpoint noise length >= 0, in config length units
 *               (default 0; proxy/proxy.h)
 *   seed        the noise's seed >= 0                  (default 1)
 *   noise_at    x y z: only the cell holding this point gets noise (the
 *               paper's variant: it moved one footpoint); a point outside
 *               the box is refused                     (default: every cell)
 * Bad values exit 2 naming the key: res < 1, clip_radius <= 0 or given
 * with clip = off, lo >= hi
 * (named as hi), signed with an input that has no inside, an input the
 * shape lacks (named as input, by proxy_input_cfg).
 */
#ifndef DFL_EXPERIMENTS_PROXY_CFG_H
#define DFL_EXPERIMENTS_PROXY_CFG_H

#include "core/status.h"
#include "field/field.h"
#include "io/config.h"
#include "proxy/filter.h"
#include "proxy/proxy.h"

typedef struct dfl_proxy_cfg {
    dfl_proxy_build_opts build;
    dfl_proxy_filter filter;
    double clip_cells;     /* clip radius in cell sizes; 0: the filter's default */
    dfl_proxy_clip clip_kind;
    int is_signed;
} dfl_proxy_cfg;

/* Reads and checks the grid and filter keys of [sec] (marks them used). */
dfl_status dfl_proxy_cfg_read(const dfl_cfg *cfg, const char *sec, dfl_proxy_cfg *out,
                              dfl_err *err);

/* Reads [sec], builds the input from [sec] and [shape_sec], builds the grid
 * into *grid and the filter options into *fo (clip in length units).
 * *grid holds no buffers on failure; release it with dfl_proxy_grid_free.
 * The input is released before returning.  DFL_E_INPUT at [sec] curvature
 * for order 2 on a triangle mesh ([shape_sec] kind = mesh) with the sdf
 * input's analytic curvature: a mesh's SDF has no curvature at edges and
 * vertices (curvature = fit, or order 1). */
dfl_status dfl_proxy_grid_from_cfg(const dfl_cfg *cfg, const char *sec, const char *shape_sec,
                                   dfl_proxy_grid *grid, dfl_proxy_filter_opts *fo,
                                   dfl_err *err);

/* The factory of kind = proxy: dfl_proxy_grid_from_cfg(cfg, sec, S)
 * wrapped by dfl_proxy_field_new, where S is [sec] shape (default "shape",
 * as kind = gridpeer and kind = pht; a missing section is DFL_E_INPUT at
 * key shape). */
dfl_status dfl_proxy_field_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out,
                                    dfl_err *err);

#endif
