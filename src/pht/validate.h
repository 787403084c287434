/* Validation error of an approximate distance field against the exact SDF,
 * separate from the fit's estimator (sjp10 Sec. 4 reports estimator errors;
 * this is what eps actually bought).
 *
 * Points: a dense grid of n^dim nodes over the box plus the (n-1)^dim
 * midpoints of its cells (none of them the estimator's random points), or a
 * caller's point set.  Errors: e = |f - d| and the gradient error
 * |grad f - grad d| (Euclidean norm), over all points and over the points
 * OFF the medial band.
 *
 * The medial band of width w (the criterion, dfl_pht_medial_band): with
 * d, n = grad d at x and sigma = sign(d) (+1 on d = 0), the point
 * y = x + w sigma n lies on x's normal line, farther from the surface.  If
 * the open normal segment from x to y contains no point of the medial axis,
 * x's footpoint p stays the footpoint of every point of the segment, so
 * |d(y)| = |d(x)| + w exactly; once the segment crosses the medial axis the
 * distance grows slower (1-Lipschitz, and the footpoint changes branch), so
 * |d(y)| < |d(x)| + w.  x is IN the band iff
 *     |d(x)| + w - |d(y)| > 1e-6 w + 1e-12 (1 + |x|),
 * i.e. iff the medial axis is closer than w along x's normal line, on the
 * side away from the surface (the side where it can be: between the surface
 * and x there is none, p being x's footpoint).  The distance along the
 * normal line is >= the Euclidean distance to the medial axis, and equal
 * for a circle/sphere (whose medial axis is the centre) and wherever the
 * medial axis crosses the normal line at a right angle; a crossing so
 * shallow that it costs less than 1e-6 w of distance is not seen, and such a
 * weak kink also costs a C1 approximation little.  It needs one extra exact
 * distance per point and no second footpoint, so it works for every shape.
 *
 * Per-cell protocol (dfl_pht_validate_cells): a grid never samples cells
 * finer than its spacing, and the SDF's kink on the medial axis, where every
 * C1 fit errs most, sits in the finest cells (circle, eps 1e-4: a 301^2 grid
 * + midpoints sees 8.3e-5, the fit's error is 2.9e-4).  So every leaf cell
 * gets its own points: the 3^dim nodes of its halving (corners, edge
 * midpoints, centre, in 3D also face centres) and `random` seeded uniform
 * points.  A cell is "medial" when one of those nodes is within 2 diag (the
 * cell's diagonal) of the medial axis along its normal line (the band
 * criterion above with w = 2 diag); a medial cell also gets the `dense`^dim
 * nodes of a uniform sub-grid, and from each sub-grid node x that sees the
 * medial axis within 2 diag (at most (dense + 1) / 2 of them, spread evenly over
 * the flagged nodes in node order) the crossing of x's normal line with the medial axis is bisected on
 * the band criterion's defect (it is 0 while the footpoint stays x's and
 * positive past the crossing; at most 60 halvings, down to 1e-6 of 2 diag):
 * the crossing x_m (if inside the cell; a crossing within the cell's
 * neighbourhood still gives offsets) and x_m +- e 2^-k n, x_m +- (3/4) e
 * 2^-k n, k = 1..scales (n = grad d(x), e the cell's shortest edge; points
 * outside the cell are dropped) are the "near-medial" points, counted in
 * the band whenever w > 0 (they are within e of the medial axis).  Points are
 * evaluated with the
 * polynomial of their own cell; duplicates at shared corners are kept (they
 * do not change a maximum).
 *
 * Function index:
 *   dfl_pht_medial_band       band flags of points (exact SDF, batched)
 *   dfl_pht_validate_points   errors of a field at given points
 *   dfl_pht_validate_grid     errors on the grid + midpoints protocol
 *   dfl_pht_cellval_opts_default / dfl_pht_validate_cells   per-cell protocol
 */
#ifndef DFL_PHT_VALIDATE_H
#define DFL_PHT_VALIDATE_H

#include <stddef.h>
#include <stdint.h>

#include "core/status.h"
#include "field/field.h"
#include "geom/shape.h"
#include "pht/spline.h"

typedef struct dfl_pht_val_stats {
    size_t n;            /* points counted */
    double max, mean;    /* of |f - d| */
    double rms;          /* sqrt(mean of (f - d)^2) */
    double gmax, gmean;  /* of |grad f - grad d| */
} dfl_pht_val_stats;

typedef struct dfl_pht_val {
    dfl_pht_val_stats all;   /* every point with a finite exact SDF */
    dfl_pht_val_stats off;   /* the points off the medial band */
    size_t band;             /* points in the band */
    size_t skipped;          /* points where the exact SDF is not finite */
    size_t nonfinite;        /* of all.n: points where f or grad f is not finite;
                                each is an error of +inf in max (and mean, rms) */
} dfl_pht_val;

typedef struct dfl_pht_val_opts {
    double lo[3], hi[3];     /* box (dim entries) */
    int n;                   /* grid nodes per axis, >= 2 */
    double band;             /* medial band width w >= 0 (0: off == all) */
} dfl_pht_val_opts;

/* near[i] = 1 if pts[i] is in the medial band of width w >= 0 of shape
 * (criterion above), else 0; w == 0 flags nothing.  Exact SDF evaluations
 * are batched and run in parallel chunks; deterministic.  DFL_E_NOMEM. */
dfl_status dfl_pht_medial_band(const dfl_shape *shape, size_t m, const double *pts, double w,
                               unsigned char *near, dfl_err *err);

/* Errors of f against shape (same dim, asserted) at m points pts[i*dim+j],
 * band width w (0: no band).  Parallel over fixed chunks, combined in chunk
 * order: bit-identical at any thread count.  DFL_E_NOMEM. */
dfl_status dfl_pht_validate_points(const dfl_field *f, const dfl_shape *shape, size_t m,
                                   const double *pts, double w, dfl_pht_val *out, dfl_err *err);

/* The grid protocol: n^dim nodes of the box and the (n-1)^dim cell
 * midpoints.  DFL_E_INPUT for n < 2 or a bad box, DFL_E_NOMEM. */
dfl_status dfl_pht_validate_grid(const dfl_field *f, const dfl_shape *shape,
                                 const dfl_pht_val_opts *o, dfl_pht_val *out, dfl_err *err);

/* The per-cell protocol's options and results. */
typedef struct dfl_pht_cellval_opts {
    double band;     /* medial band width w >= 0 of the in/off-band split (0: all off) */
    double eps;      /* points with error > eps are counted (NaN or <= 0: none) */
    int random;      /* seeded random points per leaf cell, 0..256; default 4 */
    uint64_t seed;   /* default 1 */
    int dense;       /* sub-grid nodes per axis of a medial cell, 2..33; default 5 (2D), 4 (3D) */
    int scales;      /* near-medial offsets per side, 0..40; default 8 */
} dfl_pht_cellval_opts;

typedef struct dfl_pht_cellval {
    size_t n;            /* points with a finite exact SDF (all below count these) */
    size_t skipped;      /* points where the exact SDF is not finite */
    double max, gmax;    /* whole domain: max |f - d|, max |grad f - grad d| (NaN if n = 0) */
    size_t band;         /* points in the band of width w */
    double band_max;     /* max |f - d| over them (NaN if none) */
    size_t off;          /* points off the band */
    double off_max;      /* max |f - d| over them (NaN if none) */
    size_t medial;       /* near-medial points (x_m and its offsets) */
    double medial_max;   /* max |f - d| over them (NaN if none) */
    size_t medial_cells; /* leaf cells that got the dense sub-grid */
    size_t above;        /* points with |f - d| > eps */
    size_t nonfinite;    /* of n: points where the spline's value or gradient is
                            not finite (errors of +inf, in every max they enter) */
} dfl_pht_cellval;

/* Defaults above for dimension dim (band 0, eps NaN). */
void dfl_pht_cellval_opts_default(int dim, dfl_pht_cellval_opts *o);

/* Errors of spline s (every point evaluated with its own cell's polynomial)
 * against shape (same dim, asserted) on the per-cell protocol above.  A
 * non-finite spline value is an error of +inf, counted.  Parallel over
 * cells, per-cell results combined in cell order: bit-identical at any
 * thread count.  DFL_E_INPUT for options out of range, DFL_E_NOMEM. */
dfl_status dfl_pht_validate_cells(const dfl_pht_spline *s, const dfl_shape *shape,
                                  const dfl_pht_cellval_opts *o, dfl_pht_cellval *out,
                                  dfl_err *err);

#endif
