/* The exact distance to a triangle mesh (geom/polygonize.h dfl_trimesh),
 * by brute force over its triangles: the reference that separates a
 * triangulation's own error from a field's error (bs04_surface).
 *
 *   dfl_meshdist_eval(M, x)                   distance from one point
 *   dfl_meshdist_sample(M, g, threads, out)   at every node of a grid
 *
 * Cost: one dfl_point_triangle_dist per triangle and point.  Neither
 * allocates nor fails. */
#ifndef DFL_FIELD_MESHDIST_H
#define DFL_FIELD_MESHDIST_H

#include "field/sample.h"
#include "geom/polygonize.h"

/* min over the triangles t = 0 .. ntris - 1 (in that order, fmin from
 * +inf) of dfl_point_triangle_dist(x, ...): +inf for a mesh without
 * triangles.  x: 3 coordinates. */
double dfl_meshdist_eval(const dfl_trimesh *M, const double *x);

/* out[i] = dfl_meshdist_eval(M, node i of g) for every node of the 3D grid
 * g (dim 3: a volume or a plane grid, asserted).  Parallel over nodes with
 * `threads` OpenMP threads (<= 0: one); each node's value does not depend
 * on the thread count. */
void dfl_meshdist_sample(const dfl_trimesh *M, const dfl_grid *g, int threads, double *out);

#endif
