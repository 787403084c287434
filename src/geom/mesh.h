/* A triangle mesh as a dfl_shape (3D): the exact distance to the triangles
 * and the sign of the generalized winding number.
 *
 *   dfl_shape_mesh(m, dist, out, err)     the shape of a checked dfl_trimesh (taken over)
 *   dfl_shape_mesh_trimesh(s)             its triangles, for methods that take meshes
 *   dfl_shape_mesh_winding(s, x, bound)   w(x) by the BVH sum, with its error bound
 *
 * Value.  d(x) = min over triangles of the exact point-triangle distance
 * (geom/mesh_bvh.h: Embree point queries, equal bit for bit to the brute
 * force of field/meshdist.h).  With dist = DFL_MESH_SIGNED it is negated
 * where the generalized winding number w(x) > 1/2 (Jacobson, Kavan,
 * Sorkine-Hornung 2013, geom/winding.h), decided with the certified
 * hierarchical sum of geom/mesh_bvh.h (dfl_mesh_bvh_inside: the same
 * answer as the exact sum).  For a closed mesh oriented counter-clockwise
 * from outside that is the true inside; for a mesh with holes (Wuson) the
 * sign flips across the surface and across the "soap film" w = 1/2 that
 * spans the holes, which is where a user expects it.  On the surface
 * (d = 0) the value is +0.
 *
 * Gradient.  From the closest point q on the closest triangle:
 * sign * (x - q) / d off the surface (the face normal, or the direction
 * from the closest edge or vertex), the triangle's unit normal
 * (b - a) x (c - a) / |.| on it.  Exact (to rounding) wherever the
 * closest point is unique and the sign does not change; on the medial
 * axis (ties of the closest triangle) the triangle of smaller index is
 * taken, so |grad| = 1 everywhere.
 *
 * Jets (dfl_shape_jet, dfl_shape_derivs_at, dfl_shape_hessian).  Closed
 * form per closest feature, with the sign of x: a face gives the linear
 * s -> |h + s v.n| (h = (x - q).n), an edge the distance to its line
 * |P (x - q + s v)| (P the projection orthogonal to the edge), a vertex
 * |x - q + s v|, each as the square root of an exact quadratic (the
 * helpers of geom/shape_impl.h).  These are the jets of the branch at x:
 * exact while the closest feature stays the same along the ray, i.e. off
 * the medial axis and off the boundaries between the features' regions
 * (where the SDF is C1 but not C2 and the one-sided jets of the feature at
 * x are given).  On the surface the unsigned distance is not
 * differentiable; there the jet is that of the face's signed height
 * (v.n) s for a face feature, and for an edge or vertex feature the
 * unsigned jet with the sign of x + 1e-9 (1 + |x|) v / |v|.
 *
 * Thread-safety: eval and jet allocate nothing and are safe from many
 * threads (OpenMP callers).  Cost per point: one Embree point query plus,
 * when signed, one adaptive clustered winding traversal that opens
 * clusters only until the sign is certain (rarely the exact sum, when the
 * bounds do not decide). */
#ifndef DFL_GEOM_MESH_H
#define DFL_GEOM_MESH_H

#include "core/status.h"
#include "geom/polygonize.h"
#include "geom/shape.h"

typedef enum dfl_mesh_distance {
    DFL_MESH_SIGNED = 0,  /* negative where w > 1/2 */
    DFL_MESH_UNSIGNED     /* >= 0 everywhere */
} dfl_mesh_distance;

/* The mesh shape of *m, which must pass dfl_trimesh_check
 * (geom/trimesh.h; its message otherwise, DFL_E_INPUT).  Takes ownership
 * of *m on success (zeroed) and leaves it to the caller on failure.
 * DFL_E_NOMEM, or Embree's failure (geom/mesh_bvh.h). */
dfl_status dfl_shape_mesh(dfl_trimesh *m, dfl_mesh_distance dist, dfl_shape *out, dfl_err *err);

/* The triangles of a mesh shape (owned by the shape, valid while it
 * lives: for OpenVDB's meshToLevelSet, bs04's R-functions over triangles,
 * field/meshdist.h); NULL if s is not a mesh shape. */
const dfl_trimesh *dfl_shape_mesh_trimesh(const dfl_shape *s);

/* The clustered winding number at x (geom/mesh_bvh.h with
 * DFL_MESH_WINDING_BETA) and its error bound (*bound, may be NULL); NaN if
 * s is not a mesh shape or x has a NaN or infinite coordinate. */
double dfl_shape_mesh_winding(const dfl_shape *s, const double *x, double *bound);

#endif
