/* Distance shapes of parametric curves and surfaces: dfl_shape wrappers
 * around the locators (geom/footpoint.h) and the closed-curve SDF
 * (geom/curve_sdf.h), the shape kinds bspline_curve, bspline_surface and
 * bezier_surface.
 *
 * Gradients where the distance is not differentiable: on a curve, a
 * deterministic unit normal (2D: the right normal (T_y, -T_x); 3D: the
 * coordinate axis least aligned with T made orthogonal to it); on a surface
 * the unit normal S_u x S_v (e_x where it vanishes).  Thread safety as for
 * the locators; the shapes own everything they use. */
#ifndef DFL_GEOM_PARAM_SHAPE_H
#define DFL_GEOM_PARAM_SHAPE_H

#include "core/status.h"
#include "geom/bspline.h"
#include "geom/footpoint.h"
#include "geom/shape.h"
#include "geom/surface.h"

/* Distance shape of a curve; takes ownership of *c (zeroed on success and
 * failure).  signed_dist != 0 requires a closed planar curve (the signed
 * distance of geom/curve_sdf.h); otherwise the unsigned distance |x - C|
 * (dim 2 or 3, >= 0 everywhere).  Jets exist for both (unsigned: off the
 * curve, or with a footpoint inside the domain).  DFL_E_INPUT for another
 * dimension or bad options, DFL_E_NOMEM. */
dfl_status dfl_shape_param_curve(dfl_bspline *c, const dfl_foot_opts *opt, int signed_dist,
                                 dfl_shape *out, dfl_err *err);

/* Unsigned distance shape of a surface; takes ownership of *s (zeroed).  No
 * jets.  Gradient (x - S)/|x - S|; on the surface the unit normal.
 * DFL_E_INPUT for bad options, DFL_E_NOMEM. */
dfl_status dfl_shape_param_surface(dfl_surface_set *s, const dfl_foot_opts *opt, dfl_shape *out,
                                   dfl_err *err);

#endif
