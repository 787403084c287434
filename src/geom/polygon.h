/* Closed planar polygons given by their vertices (2n doubles, edge i from
 * v_i to v_(i+1 mod n)).
 *
 *   dfl_polygon_orientation(v, n)              +1 counter-clockwise, -1 otherwise
 *   dfl_convex_polygon_dist(v, n, orient, x)   distance to the region, 0 inside
 *
 * Pure, allocation-free, thread-safe. */
#ifndef DFL_GEOM_POLYGON_H
#define DFL_GEOM_POLYGON_H

#include <stddef.h>

/* +1.0 when the shoelace sum sum_i (v_i x v_(i+1)) (summed from 0 in
 * vertex order) is > 0, i.e. counter-clockwise, else -1.0 (also for a
 * degenerate polygon of zero area: callers that must reject it test the
 * area themselves).  n >= 1. */
double dfl_polygon_orientation(const double *v, size_t n);

/* Euclidean distance from x to the closed region of the convex polygon v
 * (n >= 3 vertices, orientation orient from dfl_polygon_orientation): 0.0
 * when x lies in it (on every edge's inner side, exact orientation test
 * o (b - a) x (x - a) >= 0, no tolerance), else the least distance to an
 * edge (geom/segdist.h dfl_point_segment_dist, edges in vertex order,
 * fmin).  Convexity is the caller's promise; for a non-convex polygon the
 * inside test is wrong. */
double dfl_convex_polygon_dist(const double *v, size_t n, double orient, const double *x);

#endif
