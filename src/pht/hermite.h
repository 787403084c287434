/* Hermite data of a signed distance function for PHT splines (sjp10 Sec. 3).
 *
 * At a base vertex x a C1 PHT spline needs, in dflab's sign (d < 0 inside;
 * sjp10 takes d > 0 inside, so every datum here is the negative of the
 * paper's):
 *   2D: f, fx, fy, fxy                               (4 values)
 *   3D: f, fx, fy, fxy, fz, fxz, fyz, fxyz           (8 values)
 * stored in "mask order": data[b] is the derivative with respect to the
 * coordinates whose bits are set in b (bit j = x_j), so data[0] = f,
 * data[1] = fx, data[2] = fy, data[3] = fxy, data[4] = fz, ..., data[7] =
 * fxyz.  This is the order the tensor-product Hermite bases use.
 *
 * A source wraps any dflab shape whose SDF has derivatives (a jet op):
 * circle, sphere, torus, closed B-spline curves (geom/curve_sdf.h),
 * implicit surfaces (geom/implicit.h: torus, genus 2, Goursat), boxes, CSG
 * of such shapes.  Implicit surfaces go through dfl_implicit_sdf_derivs (one
 * robust footpoint per vertex, geom's dfl_jets_polarize); every other shape
 * through the shape's value and gradient plus order-2 (2D) or order-3 (3D)
 * jets along the diagonals (1, +-1[, +-1]), polarized in hermite.c: 2 jets
 * per vertex in 2D and 4 in 3D, where dfl_shape_derivs_at's coordinate-sum
 * polarization takes 3 and 10 and rounds the mixed derivatives differently.
 * The derivation of the paper's eq. 2-7 and how they map onto these closed
 * forms is in hermite.c.
 *
 * Function index:
 *   dfl_pht_source_new / _free     wrap a shape (borrowed) as a Hermite data source
 *   dfl_pht_source_dim             2 or 3
 *   dfl_pht_source_shape           the wrapped shape (borrowed)
 *   dfl_pht_source_check_signed    DFL_E_INPUT for an unsigned distance (open curves)
 *   dfl_pht_hermite                the 4 / 8 data at one point (+ flags)
 *   dfl_pht_source_eval            batched value (+ gradient) of the exact SDF
 *   DFL_PHT_NDATA(dim)             4 or 8
 */
#ifndef DFL_PHT_HERMITE_H
#define DFL_PHT_HERMITE_H

#include <stddef.h>

#include "core/status.h"
#include "geom/shape.h"

#define DFL_PHT_NDATA(dim) ((dim) == 2 ? 4 : 8)
#define DFL_PHT_NDATA_MAX 8

/* Flags of dfl_pht_hermite. */
#define DFL_PHT_HERMITE_MEDIAL 1  /* the point is (numerically) on the medial axis:
                                     the data are those of one footpoint's branch */
#define DFL_PHT_HERMITE_FALLBACK 2 /* the jets failed (a focal point such as a torus'
                                      axis) or the footpoint ties (implicit surfaces
                                      report ties): value and gradient
                                      are the shape's eval (its deterministic one-sided
                                      gradient), the mixed derivatives are 0 */

typedef struct dfl_pht_source dfl_pht_source;

/* Wraps *shape (borrowed: it must outlive the source).  DFL_E_INPUT with a
 * message naming the kind if the shape has no derivatives (no jet op:
 * ellipse, parametric surfaces) or its kind is `segment` (an unsigned
 * distance by construction); DFL_E_NOMEM.  Other unsigned distances (an
 * open bspline_curve has jets and the same kind as a closed one) pass here:
 * dfl_pht_source_check_signed refuses them, and the fits call it. */
dfl_status dfl_pht_source_new(const dfl_shape *shape, dfl_pht_source **out, dfl_err *err);
/* src may be NULL. */
void dfl_pht_source_free(dfl_pht_source *src);

int dfl_pht_source_dim(const dfl_pht_source *src);
const dfl_shape *dfl_pht_source_shape(const dfl_pht_source *src);

/* DFL_OK iff the source's distance is signed, as seen from the box [lo, hi]
 * (dim doubles each): d < 0 at the box centre c, or d < 0 at a point just
 * past the nearest surface point c - d(c) grad d(c) (a few evaluations;
 * the step shrinks towards rounding while it lands outside).  A closed
 * curve or surface always passes, wherever it lies; an unsigned distance
 * (segment, open curve) never does.  Otherwise DFL_E_INPUT "PHT source:
 * shape '<kind>' has no inside ...".  Thread-safe. */
dfl_status dfl_pht_source_check_signed(const dfl_pht_source *src, const double *lo,
                                       const double *hi, dfl_err *err);

/* The DFL_PHT_NDATA(dim) data at x into data (mask order, dflab sign);
 * *flags (may be NULL) gets DFL_PHT_HERMITE_* bits.  Where the SDF is not
 * differentiable (medial axis, focal points) any data are a choice: when
 * the jets fail there the FALLBACK data are returned (flagged).  Thread-safe,
 * no allocation outside the shape's own footpoint solver.  DFL_E_NUMERIC
 * only if even the value or gradient is not finite (data then untouched). */
dfl_status dfl_pht_hermite(const dfl_pht_source *src, const double *x, double *data, int *flags,
                           dfl_err *err);

/* Exact SDF at m points (pts[i*dim+j]) into val, gradient into grad (may be
 * NULL): the shape's batched eval.  Thread-safe. */
void dfl_pht_source_eval(const dfl_pht_source *src, size_t m, const double *pts, double *val,
                         double *grad);

#endif
