/* Anchored sign test of a triangle mesh: w(x) > 1/2 from a nearby point of
 * known winding number, the surface crossings between them and a bound on
 * how much w can change along the way (the fast path of geom/mesh_bvh.h's
 * dfl_mesh_bvh_inside; that header's certified-answer rule holds for it).
 *
 *   dfl_mesh_anchor_new(verts, nverts, tris, ntris, bvh, out, err)
 *   dfl_mesh_anchor_estimate(a, x, est, margin)   w(c) + J and its certified margin
 *   dfl_mesh_anchor_estimate_near(a, x, stop, est, margin)  the same, near edges exact
 *   dfl_mesh_anchor_decide(a, x, inside)          1 if the anchor decides w(x) > 1/2
 *   dfl_mesh_anchor_crossings(verts, tris, list, n, c, x, tol, J)  signed crossings of c -> x
 *   dfl_mesh_anchor_hint(a, x)                    a triangle near x (a closest-point start)
 *   dfl_mesh_anchor_stats(a, leaves, bytes)
 *   dfl_mesh_anchor_free(a)
 *
 * Why it is exact.  Off the mesh, grad w is the Biot-Savart field of the
 * mesh's boundary: a triangle's solid angle has gradient (1/4 pi) times a
 * line integral over its three edges of (l - x) x dl / |l - x|^3 (the
 * magnetic scalar potential of a current loop; Binysh and Alexander,
 * "Maxwell's theory of solid angle and the construction of knotted
 * fields", J. Phys. A 51 (2018) 385202, doi:10.1088/1751-8121/aad8c6).
 * Summed over the triangles, an undirected edge {a, b} (vertices welded by
 * index) carries the net count n_e = sum over the triangles using it of +1
 * if the triangle runs a -> b with a < b, -1 otherwise; edges with n_e = 0
 * (interior edges of consistently oriented triangles) cancel.  For a
 * straight edge of length len at distance d >= 0 from y the line integral
 * has norm at most min(len / d^2, 2 / d) (every point is at least d away;
 * over the whole line it is (sin t2 - sin t1) / rho with rho <= d the
 * distance to the line, and with the foot beyond the edge at most 1/d).
 * So along a segment P off the mesh |w(end) - w(start)| <= |P| G with
 *   G = 1/(4 pi) sum_e |n_e| min(len_e / d_e^2, 2 / d_e),  d_e = dist(e, P).
 * Where P crosses a triangle's interior w jumps by exactly +1 if P goes
 * from the normal side ((b - a) x (c - a)) to the back and -1 the other way
 * (geom/winding.h: w_t is positive on the side opposite the normal).
 *
 * The anchors.  An octree over the cube of side twice the mesh's largest
 * extent about its box's centre is refined where a cell meets more than a
 * few triangles, where it lies near an edge of nonzero n_e, and (down to a
 * moderate depth) wherever the boundary's bound G r over the cell is
 * large (the parameters and their measured effect are in mesh_anchor.c).
 * Each leaf keeps an anchor c in it (its centre moved by a fixed small
 * fraction of the cell, clear of the leaf's triangles), w(c) within a
 * bound B_c (dfl_mesh_bvh_winding_budget), the triangles that may meet
 * the cell, the edges of nonzero n_e near it with their distance D from
 * the cell's ball, and for the other ("far") edges the first-order term
 * of their part g of grad w: an edge dropped at an ancestor cell (beyond a
 * few of its radii) contributes its field at that cell's centre, with R =
 * sum H_e r over them bounding |g_e(y) - that| in the leaf (H_e the bound
 * k min(2 len / d^3, 4 / d^2) of the field's derivative: the Jacobian of
 * r / |r|^3 has norm 2 / |r|^3); an edge dropped at the leaf contributes
 * its field at the anchor, the rest of its integral bounded by H_e |x -
 * c|^2 / 2.  For x in the leaf the segment c -> x stays in the cell: J is
 * counted over the leaf's triangles, g0 is the sum of the far edges'
 * fields so kept, G is R plus the near edges' terms, each at D or, where
 * needed, at its distance from the segment (a rigorous lower bound: the
 * gap of the two segments' projections on the direction between their
 * computed closest points; refined largest term first, only until the
 * margin decides), and
 *   est = w(c) + J + g0 . (x - c),
 *   margin = G |x - c| + H |x - c|^2 / 2 + B_c (+ 1e-12 of the far
 *            edges' |g| bound times |x - c|, for the rounding of g0),
 * |w(x) - est| <= margin in exact arithmetic.  The anchor decides when
 * |est - 1/2| > margin + 1e-9, with the answer est > 1/2, the exact sum's
 * answer up to the 1e-9 of mesh_bvh.h.  Where it does not, decide tries
 * once more with the near edges' parts taken exactly (largest bound
 * first, until the rest's bound fits): an edge's field integrated along
 * the segment is the Gauss linking integral of the two segments, the
 * solid angle of the parallelogram the edge sweeps when moved by c - x,
 * seen from c (mesh_anchor.c), with a bound of its rounding in the margin.
 * It refuses (returns 0) when x is
 * outside the root cube or not finite, the leaf has no usable anchor, or a
 * crossing is not clear (see _crossings), or a near edge touches the
 * segment.
 *
 * Memory: the octree nodes (4 bytes each), 112 bytes per leaf, 4 bytes per
 * listed triangle and 24 per listed near edge (dfl_mesh_anchor_stats; on
 * Wuson about 9 MB, on a single triangle about 10 MB too: the cells follow
 * the rims).  The octree has at most 64 ntris + 2^18 nodes and its lists
 * at most 256 ntris + 2^20 entries (so at most about 45 MB + 10 kB per
 * triangle in all): a mesh that would need more
 * (or has 2^23 triangles or more) gets no anchors (*out = NULL, DFL_OK;
 * dfl_mesh_bvh_inside then uses the traversal alone).  Build: one budgeted
 * winding sum and one closest-point query per leaf, in parallel (OpenMP).  Everything is
 * read-only after _new; queries allocate nothing and are thread-safe.
 * The arrays are borrowed and must outlive a; bvh is used only during
 * _new.  Errors: DFL_E_NOMEM. */
#ifndef DFL_GEOM_MESH_ANCHOR_H
#define DFL_GEOM_MESH_ANCHOR_H

#include <stddef.h>
#include <stdint.h>

#include "core/status.h"

typedef struct dfl_mesh_anchor dfl_mesh_anchor;
struct dfl_mesh_bvh;

dfl_status dfl_mesh_anchor_new(const double *verts, size_t nverts, const size_t *tris, size_t ntris,
                               const struct dfl_mesh_bvh *bvh, dfl_mesh_anchor **out, dfl_err *err);
/* 1 if the path from x's leaf anchor is usable: *est = w(c) + J and
 * *margin = G |x - c| + B_c (|w(x) - est| <= margin in exact arithmetic);
 * 0 if it refuses (est, margin untouched). */
int dfl_mesh_anchor_estimate(const dfl_mesh_anchor *a, const double *x, double *est, double *margin);
/* The second chance: as _estimate, with near edges' parts taken exactly,
 * largest bound first, until |est - 1/2| - stop exceeds the margin with
 * the rest's bound (stop = INFINITY: every near edge exactly); the rest's
 * bound is in *margin.  0 also when a near edge touches the segment. */
int dfl_mesh_anchor_estimate_near(const dfl_mesh_anchor *a, const double *x, double stop,
                                  double *est, double *margin);
/* 1 and *inside = (w(x) > 1/2) when |est - 1/2| > margin + 1e-9, or when
 * that holds with the near edges' parts taken exactly (the header's
 * second chance); else 0. */
int dfl_mesh_anchor_decide(const dfl_mesh_anchor *a, const double *x, int *inside);
/* Signed crossings J of the segment c -> x with triangles list[0..n) (all
 * n triangles if list is NULL): +1 per triangle interior crossed from the
 * normal side to the back, -1 the other way.  Returns 0 when every
 * triangle is clearly crossed or missed, -1 (J undefined) when an end
 * point lies within tol (a length) of a triangle's plane with its
 * projection within 1e-9 (relative, barycentric) of the triangle, or the
 * segment meets a plane within 1e-9 of the triangle's boundary, or both
 * ends are within tol of a plane.  Triangles of zero area are skipped
 * (their winding number is 0 everywhere). */
int dfl_mesh_anchor_crossings(const double *verts, const size_t *tris, const uint32_t *list,
                              size_t n, const double *c, const double *x, double tol, int *J);
/* The triangle closest to the anchor of x's leaf (the start of
 * dfl_mesh_bvh_closest_hint: near x when the leaf is small), SIZE_MAX when
 * x is outside the root cube, not finite or its leaf has no anchor. */
size_t dfl_mesh_anchor_hint(const dfl_mesh_anchor *a, const double *x);
void dfl_mesh_anchor_stats(const dfl_mesh_anchor *a, size_t *leaves, size_t *bytes);
void dfl_mesh_anchor_free(dfl_mesh_anchor *a);

#endif
