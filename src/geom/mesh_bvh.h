/* The two spatial queries of a triangle mesh, on Embree 3 (libembree-dev):
 * the exact closest point (rtcPointQuery over a user geometry with one
 * primitive per triangle) and the generalized winding number
 * (geom/winding.h) summed over a BVH that rtcBuildBVH builds, with a
 * certified error bound.
 *
 *   dfl_mesh_bvh_new(verts, nverts, tris, ntris, out, err)
 *   dfl_mesh_bvh_closest(b, x, hit)          exact distance, closest point, triangle, feature
 *   dfl_mesh_bvh_winding(b, x, beta, bound)  clustered winding number and its error bound
 *   dfl_mesh_bvh_inside(b, x)                w(x) > 1/2, certified
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
 * centroid p, radius r (every vertex of the cluster within r of p) and
 * area vector N = sum of the triangles' (b - a) x (c - a) / 2.  Since
 * w(x) = 1/(4 pi) sum_t int_t n_t . (y - x) / |y - x|^3 dA(y) exactly for
 * flat triangles, a cluster with R = |x - p| > beta r is replaced by its
 * monopole N . (p - x) / (4 pi R^3) (the first term of Barill, Dickson,
 * Schmidt, Levin, Jacobson: "Fast winding numbers for soups and clouds",
 * ACM Transactions on Graphics 37(4), 43:1-12, 2018,
 * doi:10.1145/3197517.3201337); the kernel's Jacobian (I - 3 u u^T)/|y-x|^3
 * has norm 2/|y - x|^3, so that cluster's error is at most
 * A r / (2 pi (R - r)^3).  The sum of these is the returned bound; leaves
 * that are not accepted are summed exactly (Van Oosterom-Strackee).
 * dfl_mesh_bvh_inside uses beta = DFL_MESH_WINDING_BETA and, when
 * |w - 1/2| <= bound + 1e-9, the exact sum over every triangle instead, so
 * its answer is that of the exact winding number (up to the rounding of
 * that sum).
 *
 * Thread-safety: after dfl_mesh_bvh_new everything is read-only; queries
 * allocate nothing (a fixed stack of DFL_MESH_BVH_STACK nodes; the tree's
 * depth is capped below it at build).  The arrays passed to _new are
 * borrowed and must outlive b.  Errors of _new: DFL_E_INPUT for no
 * triangles or more than 2^32 - 1; DFL_E_NOMEM; DFL_E_NUMERIC when Embree
 * reports an error (its message in err). */
#ifndef DFL_GEOM_MESH_BVH_H
#define DFL_GEOM_MESH_BVH_H

#include <stddef.h>

#include "core/status.h"
#include "geom/tridist.h"

#define DFL_MESH_WINDING_BETA 2.5
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
/* beta > 1; *bound (may be NULL) gets the error bound of the result. */
double dfl_mesh_bvh_winding(const dfl_mesh_bvh *b, const double *x, double beta, double *bound);
int dfl_mesh_bvh_inside(const dfl_mesh_bvh *b, const double *x);
void dfl_mesh_bvh_free(dfl_mesh_bvh *b);

#endif
