/* Config sections for parametric shapes (B-spline/Bezier curves and surfaces).
 *
 * kind_name is "bspline_curve", "bspline_surface" or "bezier_surface".
 * Keys are documented with the implementation (filled in below).
 */
#ifndef DFL_EXPERIMENTS_CURVE_CFG_H
#define DFL_EXPERIMENTS_CURVE_CFG_H

#include "core/status.h"
#include "geom/shape.h"
#include "io/config.h"

/* Builds the parametric shape section sec describes into *out (caller frees
 * with dfl_shape_free).  *out is untouched on failure.  DFL_E_INPUT naming
 * file:line, [sec] and key for bad input. */
dfl_status dfl_param_shape_from_cfg(const dfl_cfg *cfg, const char *sec, const char *kind_name,
                                    dfl_shape *out, dfl_err *err);

#endif
