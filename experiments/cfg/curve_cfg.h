/* Config sections for parametric shapes: B-spline/Bezier curves and
 * surfaces (geom/bspline.h, geom/surface.h, geom/footpoint.h).
 *
 * kind = bspline_curve
 *   order     = k            integer 2..16 (default 4; degree k - 1)
 *   control   = x0 y0; x1 y1; ...   (or x y z; planar or space curve: the
 *               dimension is the number of values of the first point)
 *   knots     = t0 t1 ...    optional.  Open curve: control + order values,
 *               non-decreasing (default: clamped uniform).  Closed curve:
 *               control + 1 breakpoints of one period (default 0 1 ... m).
 *   closed    = false        true: periodic curve through the control
 *               points wrapped around (at least 3 control points)
 *   distance  = signed | unsigned   default: signed for a closed planar
 *               curve (periodic, or clamped with first point == last),
 *               unsigned otherwise; signed requires a closed planar curve
 * kind = bspline_surface
 *   order_u, order_v = 4     orders 2..16
 *   nu, nv                   control grid size (nu >= order_u, ...)
 *   control  = x y z; ...    nu*nv points, u fastest (point (i, j) is
 *              entry i + nu*j)
 *   knots_u, knots_v         optional (default clamped uniform)
 * kind = bezier_surface
 *   order_u, order_v = 4     (degree + 1 in each direction)
 *   patches  = 1             number of Bezier patches
 *   control  = ...           patches * order_u * order_v points, patch by
 *              patch, u fastest within a patch
 *   continuity = any | C0 | G1   checked: with C0/G1 every patch must share
 *              an edge with another one and all shared edges must be at
 *              least that smooth (default any)
 * All parametric kinds:
 *   backend    = newton | ceres   footpoint solver (default newton)
 *   samples    = 16          initial-guess samples per knot span (2..10000)
 *   candidates = 4           initial guesses refined per query (1..16)
 *
 * The shape is the distance (signed or unsigned as above) of the curve or
 * surface; see geom/footpoint.h.  Errors: DFL_E_INPUT with file:line,
 * [section] and key, and what was expected (knot count, order < 2,
 * non-decreasing knots, degenerate control polygon, a closed curve where
 * one is required, ...).
 */
#ifndef DFL_EXPERIMENTS_CURVE_CFG_H
#define DFL_EXPERIMENTS_CURVE_CFG_H

#include "core/status.h"
#include "geom/bspline.h"
#include "geom/footpoint.h"
#include "geom/shape.h"
#include "geom/surface.h"
#include "io/config.h"

/* Builds the parametric shape section sec describes into *out (caller frees
 * with dfl_shape_free).  *out is untouched on failure.  kind_name selects
 * the kind; the `kind` key itself is read by the caller. */
dfl_status dfl_param_shape_from_cfg(const dfl_cfg *cfg, const char *sec, const char *kind_name,
                                    dfl_shape *out, dfl_err *err);

/* The curve of a bspline_curve section (keys order, control, knots,
 * closed).  Caller frees with dfl_bspline_free. */
dfl_status dfl_curve_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_bspline *out,
                              dfl_err *err);

/* The patches of a bspline_surface or bezier_surface section. */
dfl_status dfl_surface_from_cfg(const dfl_cfg *cfg, const char *sec, const char *kind_name,
                                dfl_surface_set *out, dfl_err *err);

/* The curve of section sec, which must say kind = bspline_curve
 * (DFL_E_INPUT "expected bspline_curve, got '<kind>'" at its kind key
 * otherwise), through dfl_curve_from_cfg.  The section must exist: the
 * caller says where it was named. */
dfl_status dfl_curve_section_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_bspline *out,
                                      dfl_err *err);

/* backend, samples, candidates of section sec (defaults when absent). */
dfl_status dfl_foot_opts_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_foot_opts *out,
                                  dfl_err *err);

#endif
