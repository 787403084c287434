/* The closest point of a triangle in R^3 and the feature it lies on: the
 * one point-triangle distance of dflab (geom/polygonize.h's
 * dfl_point_triangle_dist, field/meshdist.h's brute force and the mesh
 * shape of geom/mesh.h all return this function's distance, so they agree
 * bit for bit).
 *
 *   dfl_tridist_closest(x, a, b, c, q, feat)   distance, closest point, feature
 *
 * Method: Ericson, Real-Time Collision Detection (2005), 5.1.5: the
 * Voronoi regions of the vertices, edges and face, tested in that order
 * with exact sign tests (no tolerance).  The distance is sqrt of the sum
 * (x_j - q_j)^2 accumulated from 0.0 in coordinate order; in a vertex
 * region q is that vertex bit for bit.  A degenerate triangle (collinear or
 * coincident vertices) is allowed: the region tests still select a point
 * of the triangle (its face branch divides by zero only when all three
 * edge tests fail, which a degenerate triangle cannot reach except for
 * NaN input).  Pure, allocation-free, thread-safe. */
#ifndef DFL_GEOM_TRIDIST_H
#define DFL_GEOM_TRIDIST_H

/* Closest features, in the order the regions are tested. */
typedef enum dfl_tri_feature {
    DFL_TRI_VERT_A = 0,
    DFL_TRI_VERT_B,
    DFL_TRI_EDGE_AB,
    DFL_TRI_VERT_C,
    DFL_TRI_EDGE_AC,
    DFL_TRI_EDGE_BC,
    DFL_TRI_FACE
} dfl_tri_feature;

/* Distance from x to triangle abc; q (3 doubles, may be NULL) gets the
 * closest point and *feat (may be NULL) its feature. */
double dfl_tridist_closest(const double *x, const double *a, const double *b, const double *c,
                           double *q, dfl_tri_feature *feat);

#endif
