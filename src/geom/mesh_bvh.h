/* The two spatial queries of a triangle mesh, on Embree 3 (libembree-dev):
 * the exact closest point (rtcPointQuery over a user geometry with one
 * primitive per triangle) and the generalized winding number
 * (geom/winding.h) summed over a BVH that rtcBuildBVH builds, with a
 * certified error bound.
 *
 *   dfl_mesh_bvh_new(verts, nverts, tris, ntris, out, err)
 *   dfl_mesh_bvh_closest(b, x, hit)          exact distance, closest point, triangle, feature
 *   dfl_mesh_bvh_closest_hint(b, x, t0, hit) the same, started from triangle t0
 *   dfl_mesh_bvh_winding(b, x, beta, bound)  clustered winding number and its error bound
 *   dfl_mesh_bvh_winding_within(b, x, tol, bound)  adaptive, bound <= tol
 *   dfl_mesh_bvh_winding_budget(b, x, tol, bound)  one pass, bound <= tol
 *   dfl_mesh_bvh_inside(b, x)                w(x) > 1/2, certified
 *   dfl_mesh_bvh_inside_traversal(b, x)      the same answer without the anchors
 *   dfl_mesh_bvh_anchors(b)                  the anchor octree (geom/mesh_anchor.h)
 *   dfl_mesh_bvh_free(b)
 *
 * Closest point.  Every triangle's distance is geom/tridist.h's
 * dfl_tridist_closest in double precision; Embree only prunes.  Its boxes
 * and query radius are floats, so they are made conservative: each
 * triangle's box is rounded outwards and widened by 2^-20 of the largest
 * coordinate magnitude of the mesh and of the query point, and the radius
 * is the current best distance rounded up and widened the same way.  No
 * triangle that could be closer is pruned, so the distance equals the
 * brute-force minimum of dfl_tridist_closest over all triangles bit for
 * bit (field/meshdist.h); on ties the triangle of smallest index is kept.
 * Points beyond 1e30 in some coordinate (outside float range after the
 * widening) are answered by brute force, with the same result.  A
 * non-finite x gives d = NaN (hit->tri = SIZE_MAX).
 *
 * Winding number.  Clusters are BVH nodes with area A, area-weighted
 * centroid p, radius r (every vertex of the cluster within r of p), area
 * vector N = sum_t A_t n_t and first moment M = sum_t A_t n_t (c_t - p)^T
 * (c_t the triangles' centroids).  Exactly, for flat triangles,
 * w(x) = 1/(4 pi) sum_t n_t . int_t K(y) dA(y), K(y) = (y - x) / |y - x|^3.
 * A cluster with R = |x - p| > beta r is replaced by the first two terms
 * of K's Taylor series about p (the expansion of Barill, Dickson, Schmidt,
 * Levin, Jacobson: "Fast winding numbers for soups and clouds", ACM
 * Transactions on Graphics 37(4), 43:1-12, 2018, doi:10.1145/3197517.3201337,
 * to first order):  (N . K(p) + sum_jk J_jk M_jk) / (4 pi) with
 * J = (I - 3 u u^T) / R^3, u = (p - x) / R; since int_t (y - p) dA =
 * A_t (c_t - p) that is exact to first order.  The remainder involves
 * D^2 K = -D^3 (1/|y - x|), whose norm is at most 3! / |y - x|^4 (the
 * Legendre bound |P_3| <= 1 of the Newton kernel's derivatives; for a
 * symmetric trilinear form the norm is reached with equal arguments), so that
 * cluster's error is at most 3 A r^2 / (4 pi (R - r)^4).  The sum of these
 * is the returned bound; leaves that are not accepted are summed exactly
 * (Van Oosterom-Strackee).
 * dfl_mesh_bvh_inside makes one adaptive traversal: it keeps the sum W of
 * the exact leaves and far fields of a frontier of clusters and the sum B
 * of their bounds (the sharper bound of dfl_mesh_bvh_winding_within
 * below; a cluster is usable when it is finite), starts from the frontier
 * of a depth-first pass in which every bound is at most 0.01, then opens
 * the frontier cluster of largest bound (a leaf: its exact sum) while
 * |W - 1/2| <= B + 1e-9 or an unusable cluster is left, and returns
 * W > 1/2 as soon as |W - 1/2| > B + 1e-9; when everything is exact and
 * still undecided (or the frontier would exceed its fixed capacity), the
 * exact sum over every triangle decides.  Its answer is therefore that of
 * the exact winding number (up to the rounding of the sums, the 1e-9),
 * the same as the earlier ladder of beta = 3, 6, 12 and exact sum.
 * Before that traversal, dfl_mesh_bvh_inside asks the anchors
 * (geom/mesh_anchor.h, built by _new): a point of known winding number
 * near x, the signed surface crossings between them and a certified bound
 * on the change of w along the way decide w(x) > 1/2 when the estimate is
 * more than its bound + 1e-9 away from 1/2; the same rule, so the same
 * answer; the traversal (dfl_mesh_bvh_inside_traversal) answers the
 * rest.
 *
 * Thread-safety: after dfl_mesh_bvh_new everything is read-only but the
 * anchor octree, which the first dfl_mesh_bvh_inside or
 * dfl_mesh_bvh_anchors call builds, once, under the BVH's lock (other
 * threads wait for it; about 0.9 s of CPU and 9 MB on Wuson, so that a
 * mesh that is only validated or queried unsigned never pays it); queries
 * allocate nothing else (a fixed stack of DFL_MESH_BVH_STACK nodes; the
 * tree's depth is capped below it at build).  The arrays passed to _new are
 * borrowed and must outlive b.  Errors of _new: DFL_E_INPUT for no
 * triangles or more than 2^32 - 1; DFL_E_NOMEM; DFL_E_NUMERIC when Embree
 * reports an error (its message in err). */
#ifndef DFL_GEOM_MESH_BVH_H
#define DFL_GEOM_MESH_BVH_H

#include <stddef.h>

#include "core/status.h"
#include "geom/tridist.h"

#define DFL_MESH_WINDING_BETA 3.0
#define DFL_MESH_BVH_STACK 128

typedef struct dfl_mesh_bvh dfl_mesh_bvh;

typedef struct dfl_mesh_hit {
    double d;             /* distance >= 0 (NaN for non-finite x) */
    double q[3];          /* closest point */
    size_t tri;           /* its triangle */
    dfl_tri_feature feat; /* the triangle's feature q lies on */
} dfl_mesh_hit;

dfl_status dfl_mesh_bvh_new(const double *verts, size_t nverts, const size_t *tris, size_t ntris,
                            dfl_mesh_bvh **out, dfl_err *err);
void dfl_mesh_bvh_closest(const dfl_mesh_bvh *b, const double *x, dfl_mesh_hit *hit);
/* dfl_mesh_bvh_closest's result, bit for bit and with its tie rule,
 * whatever t0: triangle t0 (when t0 < ntris; any other value is no hint)
 * is considered first, so that the search starts with its distance as the
 * radius (fast when t0 is near x, e.g. dfl_mesh_anchor_hint). */
void dfl_mesh_bvh_closest_hint(const dfl_mesh_bvh *b, const double *x, size_t t0,
                               dfl_mesh_hit *hit);
/* beta > 1; *bound (may be NULL) gets the error bound of the result. */
double dfl_mesh_bvh_winding(const dfl_mesh_bvh *b, const double *x, double beta, double *bound);
/* The adaptive traversal of dfl_mesh_bvh_inside (above) run until its
 * bound B <= tol (tol >= 0; 0 opens every cluster, the sum is then exact
 * to rounding): returns W, *bound (may be NULL) gets B.  The bound used is
 * 3 I2 / (4 pi g^4) per cluster, I2 = sum_t int_t |y - p|^2 dA <= A r^2
 * and g = max(R - rx, dist(x, box)) >= R - r, rx the farthest vertex from
 * p and box the vertices' bounding box (derived in mesh_bvh.c).  If the
 * fixed frontier would overflow: the exact sum, bound 0. */
double dfl_mesh_bvh_winding_within(const dfl_mesh_bvh *b, const double *x, double tol,
                                   double *bound);
/* One depth-first pass in which a cluster's far field is used when its
 * bound (that of _within) is at most tol times its share of the mesh's
 * area (tol >= 0): returns W with *bound (may be NULL) the sum of the
 * bounds used, <= tol.  Cheaper than _within far from 1/2 (no heap). */
double dfl_mesh_bvh_winding_budget(const dfl_mesh_bvh *b, const double *x, double tol,
                                   double *bound);
int dfl_mesh_bvh_inside(const dfl_mesh_bvh *b, const double *x);
int dfl_mesh_bvh_inside_traversal(const dfl_mesh_bvh *b, const double *x);
/* The anchor octree, built on the first call (thread-safe, see above);
 * NULL when the mesh exceeds mesh_anchor.h's size caps or memory ran out
 * (dfl_mesh_bvh_inside then answers by the traversal alone). */
const struct dfl_mesh_anchor *dfl_mesh_bvh_anchors(const dfl_mesh_bvh *b);
void dfl_mesh_bvh_free(dfl_mesh_bvh *b);

#endif
