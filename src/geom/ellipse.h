/* Exact signed distance to an axis-aligned ellipse, negative inside, as a
 * function (dfl_ellipse_sdist: centred at the origin, the reference of the
 * bs04 recursive normalization study) and as a shape kind
 * (dfl_shape_ellipse: [shape] kind = ellipse).
 *
 * Method (D. Eberly, "Distance from a point to an ellipse, an ellipsoid,
 * or a hyperellipsoid", 2013): by symmetry the query is reflected into the
 * first quadrant and the axes are ordered so that e0 >= e1.  The footpoint
 * x = (r0 y0 / (s + r0), y1 / (s + 1)), r0 = (e0/e1)^2, where s is the
 * unique root of the strictly decreasing
 *     G(s) = (r0 z0 / (s + r0))^2 + (z1 / (s + 1))^2 - 1,   z = y / e,
 * on [z1 - 1, |(r0 z0, z1)| - 1] (G changes sign there), found by bisection
 * to the last bit: no starting guess, no divergence, exact near the
 * evolute.  Points on an axis are closed-form cases (the interior part of
 * the major axis has the footpoint x0 = e0^2 y0 / (e0^2 - e1^2)).
 */
#ifndef DFL_GEOM_ELLIPSE_H
#define DFL_GEOM_ELLIPSE_H

#include "core/status.h"
#include "geom/shape.h"

/* Signed distance of the point x[0..1] to the ellipse with semi-axes a, b
 * (> 0, finite; asserted).  foot (2 doubles, may be NULL) receives the
 * closest point; grad (2, may be NULL) the gradient of the signed distance,
 * which is the outward unit normal at the footpoint (on the medial axis,
 * the segment between the foci's evolute cusps, the footpoint in the
 * quadrant of x with ties going to +x, +y).  Pure, thread-safe, no
 * allocation. */
double dfl_ellipse_sdist(double a, double b, const double *x, double *foot, double *grad);

/* The ellipse with centre c and semi-axes a (along x) and b (along y) as a
 * 2D shape: d(x) = dfl_ellipse_sdist(a, b, x - c) and its gradient, the
 * outward unit normal at the footpoint (|grad d| = 1 everywhere, also on
 * the medial axis and at the centre, where the footpoint rule of
 * dfl_ellipse_sdist picks one side).  a == b is a circle.  No jets.
 * DFL_E_INPUT "ellipse: ..." for a non-finite centre or semi-axes that are
 * not finite and > 0; DFL_E_NOMEM; *out untouched on failure. */
dfl_status dfl_shape_ellipse(const double c[2], double a, double b, dfl_shape *out,
                             dfl_err *err);

#endif
