/* `[shape]` config section -> dfl_shape.
 *
 * Keys (contract):
 *   kind = one of geom/shape.h's DFL_SHAPE_KINDS: circle | sphere | torus |
 *          cylinder | plane | cone | box | segment | ellipse | bspline_curve |
 *          bspline_surface | bezier_surface | implicit | csg (shape_cfg.c has
 *          one parser per kind)
 *   circle:   center = x y,      radius = r > 0
 *   sphere:   center = x y z,    radius = r > 0
 *   torus:    center = x y z, axis = ax ay az (non-zero), major = R > 0,
 *             minor = r in (0, R)
 *   cylinder: center = x y z (a point on the axis), axis, radius > 0
 *   plane:    dim = 2|3 (default 3), point = ..., normal = ... (non-zero;
 *             points to the outside)
 *   cone:     a = x y z, b = x y z (a != b), ra >= 0, rb >= 0, not both 0
 *   box:      dim = 2|3 (default 3), center, half = h... (all > 0)
 *   segment:  dim = 2|3 (default 2), a, b (a != b); unsigned distance
 *   ellipse:  center = x y, a = semi-axis along x > 0, b = semi-axis along
 *             y > 0 (axis-aligned; exact signed distance, no jets)
 *   bspline_curve | bspline_surface | bezier_surface: handed to
 *             dfl_param_shape_from_cfg (experiments/cfg/curve_cfg.h)
 *   implicit: see geom/implicit.h; surface = torus | goursat | genus2 |
 *             sphere | ellipsoid,
 *             solver = newton | ceres (default newton), plus the surface's
 *             parameters (dfl_implicit_from_cfg in this module documents them)
 *   csg:      op = union | intersection | difference | smooth_union |
 *             smooth_intersection | smooth_difference, a = <section>,
 *             b = <section> (each a shape section of its own), k = width > 0
 *             (smooth ops only)
 *
 * Errors: DFL_E_INPUT naming file:line, [section] and key (missing key,
 * wrong type, radius <= 0, zero axis, unknown kind, CSG cycles).
 */
#ifndef DFL_EXPERIMENTS_SHAPE_CFG_H
#define DFL_EXPERIMENTS_SHAPE_CFG_H

#include "core/status.h"
#include "geom/implicit.h"
#include "geom/shape.h"
#include "io/config.h"

/* Builds the shape section sec describes into *out (caller frees with
 * dfl_shape_free).  *out is untouched on failure. */
dfl_status dfl_shape_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_shape *out, dfl_err *err);

/* The implicit surface of a kind = implicit section (the keys above) into
 * *out (caller frees with dfl_implicit_free); *out untouched on failure. */
dfl_status dfl_implicit_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_implicit **out,
                                 dfl_err *err);

#endif
