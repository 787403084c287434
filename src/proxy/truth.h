/* Ground truth for the hvb25 metrics: the distance field a proxy grid is
 * measured against, as a dfl_field (field/field.h).
 *
 * Function index
 *   dfl_proxy_truth_exact     the exact SDF of an analytic shape (sphere,
 *                             torus, cylinder, plane, cone, box; CSG: the
 *                             shape's own min/max SDF)
 *   dfl_proxy_truth_input     d and n of a proxy input as a field
 *   dfl_proxy_truth_param     brute-force-seeded footpoints on parametric
 *                             surfaces (Bezier, cone lateral surface)
 *   dfl_proxy_truth_implicit  robust certified footpoints on an implicit
 *
 * Values: signed (negative inside) where the surface is closed, unsigned
 * (>= 0) for open surfaces (patches, the cone's lateral surface), in the
 * units of the shape.  Gradient: the unit normal n at the footpoint,
 * oriented as proxy/input.h says (towards x for open surfaces).  Where an
 * input-backed truth could not certify its footpoint it still returns its
 * best answer (finite): the robust implicit input certifies every cell
 * centre of the studies' grids (tests/proxy/test_truth.c), and a
 * brute-force-seeded parametric search with 64 x 64 starts per patch
 * cannot miss a basin wider than the grid step.
 * No jets.  Thread-safe; eval allocates nothing (chunks of 64 on the stack).
 */
#ifndef DFL_PROXY_TRUTH_H
#define DFL_PROXY_TRUTH_H

#include "core/status.h"
#include "field/field.h"
#include "geom/implicit.h"
#include "geom/shape.h"
#include "geom/surface.h"
#include "proxy/input.h"

/* Takes ownership of *shape (3D; zeroed on success, left with the caller on
 * failure, as field/exact.h). */
dfl_status dfl_proxy_truth_exact(dfl_shape *shape, dfl_field *out, dfl_err *err);

/* Takes ownership of *in (zeroed on success and failure). */
dfl_status dfl_proxy_truth_input(dfl_proxy_input *in, dfl_field *out, dfl_err *err);

/* The brute-force-seeded parametric truth: parameter grid `grid` (>= 16;
 * 0 = 64) per patch and direction, 100 Newton steps.  _param takes
 * ownership of *set (zeroed also on failure); _cone_lateral is the open
 * lateral surface of proxy/input_param.h's cone. */
dfl_status dfl_proxy_truth_param(dfl_surface_set *set, int grid, dfl_field *out, dfl_err *err);
dfl_status dfl_proxy_truth_cone_lateral(const double a[3], const double b[3], double ra,
                                        double rb, int grid, dfl_field *out, dfl_err *err);

/* Takes ownership of *imp (set to NULL, also on failure). */
dfl_status dfl_proxy_truth_implicit(dfl_implicit **imp, dfl_field *out, dfl_err *err);

#endif
