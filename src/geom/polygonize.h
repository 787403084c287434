/* Polygonization of curves and triangulation of surfaces with a guaranteed
 * maximum deviation eps (a bound on the Hausdorff distance), by adaptive
 * subdivision of Bezier pieces.
 *
 * Curves.  Every non-empty knot span is converted to Bezier form by
 * blossoming and split at its parameter midpoint (de Casteljau) until the
 * certified bound of each piece is <= eps; the piece is then replaced by its
 * chord.  The bound of a piece with control points b_0..b_p, chord
 * e = b_p - b_0, is
 *   - if the control polygon is monotone along the chord (e.(b_{i+1}-b_i)
 *     >= 0 for all i): max_i dist(b_i, line(b_0, b_p)).  By the convex-hull
 *     property this bounds the distance from every curve point to the chord,
 *     and since the curve's projection onto the chord is then monotone and
 *     onto, every chord point has a curve point at the same projection,
 *     within the same distance: a two-sided (Hausdorff) bound;
 *   - otherwise max_i |b_i - (b_0 + (i/p) e)|, which bounds |C(s) - chord(s)|
 *     for all s (linear precision of the Bernstein basis), again two-sided.
 * Growth: a piece of length h of a curve with curvature k deviates by about
 * k h^2 / 8, so the segment count grows like eps^(-1/2) for smooth curves.
 *
 * Surfaces.  Every patch is cut into a tensor grid of cells (initially its
 * knot spans); each cell's Bezier net (blossoming) b_ij gives the bound
 *   max_ij |b_ij - L_ij| + |w| / 4,
 * where L_ij is the bilinear interpolant of the four corners at (i/p, j/q)
 * and w = P00 - P10 - P01 + P11 the corner twist: the first term bounds the
 * patch against the bilinear patch of its corners (bilinear precision), the
 * second the bilinear patch against the two triangles (P00,P10,P01) and
 * (P11,P01,P10), whose difference is u v w resp. (1-u)(1-v) w.  The map is a
 * parametrization of both, so this is a Hausdorff bound.  Cells above eps
 * split the whole u- or v-interval they lie in (the direction with the
 * larger row/column chord deviation), which keeps the mesh of one patch
 * conforming (no T-junctions).  Different patches are meshed independently
 * (their common edges may be split differently).
 *
 * Memory: outputs are malloc'ed and released by the matching _free.
 */
#ifndef DFL_GEOM_POLYGONIZE_H
#define DFL_GEOM_POLYGONIZE_H

#include <stddef.h>

#include "core/status.h"
#include "geom/bspline.h"
#include "geom/segdist.h" /* dfl_point_segment_dist, used with polylines */
#include "geom/surface.h"

typedef struct dfl_polyline {
    int dim;
    size_t n;          /* points; n - 1 segments (closed curves repeat the first point) */
    double *pts;       /* n*dim, on the curve */
    double *t;         /* n parameters, increasing from t0 to t1 */
    double *seg_bound; /* n - 1 certified bounds, one per segment */
    double bound;      /* max of seg_bound: certified Hausdorff bound, <= eps */
} dfl_polyline;

/* Certified two-sided bound of a Bezier piece against its chord (see above);
 * np points of dimension dim. */
double dfl_bezier_chord_bound(const double *bez, int np, int dim);

/* Polygonizes c with Hausdorff bound eps > 0.  max_segments caps the output
 * (0: 10^7).  DFL_E_INPUT if eps is not finite and > 0; DFL_E_NUMERIC if eps
 * is too small for double precision (a piece still above eps after 60
 * bisections) or the cap is hit; DFL_E_NOMEM. */
dfl_status dfl_polygonize_curve(const dfl_bspline *c, double eps, size_t max_segments,
                                dfl_polyline *out, dfl_err *err);
void dfl_polyline_free(dfl_polyline *p);

/* An upper bound on the segments dfl_polygonize_curve(c, eps, 0, ...)
 * makes, from the spans' Bezier nets alone (no subdivision), for cost
 * estimates.  Proof: both chord bounds are <= max_i |g_i|, g_i = b_i -
 * (b_0 + (i/p) e), and g (zero at both ends) has the second differences of
 * b, so |g_i| <= D i (p - i) / 2 <= D p^2 / 8 with D = max_i |b_{i+2} -
 * 2 b_{i+1} + b_i| (the discrete Green's function of the second
 * difference).  De Casteljau halving at 1/2 makes every second difference
 * of a half a convex combination of the parent's, times 1/4.  So every
 * piece of a span at depth k has bound <= D p^2 / (8 4^k): no piece deeper
 * than the first k where that is <= eps (less a rounding allowance) is
 * split, and the span makes at most 2^k segments.  The sum over spans,
 * capped at the polygonizer's own cap of 10^7 (beyond it the call fails
 * instead) and at depth 60 (the same). */
double dfl_polygonize_curve_segments_bound(const dfl_bspline *c, double eps);

/* Measured one-sided deviation max_t dist(C(t), polyline): every segment's
 * parameter interval is sampled at `samples` (>= 2) points, the distance to
 * the whole polyline (all segments, found through a uniform grid) is taken,
 * and the largest sample of each segment is refined by golden-section
 * search.  Allocates scratch internally (DFL_E_NOMEM). */
dfl_status dfl_polyline_deviation(const dfl_bspline *c, const dfl_polyline *p, int samples,
                                  double *out, dfl_err *err);

typedef struct dfl_trimesh {
    size_t nverts;
    double *verts;     /* 3*nverts, on the surface */
    double *uv;        /* 2*nverts parameters */
    size_t ntris;
    size_t *tris;      /* 3*ntris vertex indices; triangles 2c and 2c+1 form cell c */
    size_t *tri_patch; /* ntris patch indices */
    double *cell_bound;/* ntris/2 certified bounds */
    double bound;      /* max of cell_bound, <= eps */
} dfl_trimesh;

/* Certified bound of a Bezier cell net (ku*kv points, (i + ku*j)*3) against
 * its two triangles. */
double dfl_bezier_cell_bound(const double *bez, int ku, int kv);

/* Triangulates every patch with Hausdorff bound eps > 0.  max_tris caps the
 * output (0: 10^7).  Errors as dfl_polygonize_curve. */
dfl_status dfl_polygonize_surface(const dfl_surface_set *s, double eps, size_t max_tris,
                                  dfl_trimesh *out, dfl_err *err);
void dfl_trimesh_free(dfl_trimesh *m);

/* Measured deviation: for every cell, (samples+1)^2 parameter points are
 * mapped to the surface and their distance to the cell's two triangles is
 * taken; the largest of each cell is refined by a compass search.  This is
 * the deviation along the parametric correspondence, an upper estimate of
 * the distance to the whole mesh and a lower estimate of the bound. */
dfl_status dfl_trimesh_deviation(const dfl_surface_set *s, const dfl_trimesh *m, int samples,
                                 double *out, dfl_err *err);

/* Distance from x to the triangle abc in R^3 (geom/tridist.h's
 * dfl_tridist_closest, bit for bit). */
double dfl_point_triangle_dist(const double *x, const double *a, const double *b,
                               const double *c);

#endif
