/* Euclidean distances from a point to straight segments: dflab's one
 * family of point-segment distances (shapes, polygonization checks and the
 * exact parts of bs04's joins all call these).
 *
 *   dfl_segdist_eval(dim, a, b, x, grad)         end points exact, lengths of core/hypot.h
 *   dfl_segdist_closest_is_start(dim, a, b, x)   is the closest point a?
 *   dfl_segdist_residual(dim, a, e, ee, x, r)    clamped projection, residual r
 *   dfl_point_segment_dist(dim, x, a, b)         dfl_segdist_residual with e = b - a
 *   dfl_point_segment_dist_hypot(x, a, b)        the same residual, length by hypot (2D)
 *
 * Three roundings, all exact to a few ulps, kept apart because results are
 * reproduced bit for bit:
 *   - eval treats the end-point regions as distances to the end point itself
 *     (x - a, x - b) and measures lengths with dfl_hypot_vec, so that it
 *     equals the vertex distances of rfunc's joins bit for bit (bs04's
 *     corrected join cancels exactly in the hatched sector only then);
 *   - residual projects, clamps the parameter to [0, 1] and subtracts
 *     s e from x - a (also at the ends), and takes the square root of the
 *     sum of squares accumulated from 0.0 in coordinate order;
 *   - the hypot member takes the same residual and measures it with C's
 *     hypot(r0, r1) (no intermediate overflow or underflow, rounded once
 *     by libm): bs04_fields' exact distances to its two segments.
 *
 * dim is 2 or 3 (residual and dfl_point_segment_dist: 1 to 3; asserted).
 * Everything is pure, allocation-free and thread-safe. */
#ifndef DFL_GEOM_SEGDIST_H
#define DFL_GEOM_SEGDIST_H

#include <stdbool.h>

/* Distance from x to the segment a-b and, when grad != NULL, its gradient
 * (x - c) / |x - c| with c the closest point (dim doubles; 0 on the
 * segment, where the distance is not differentiable).  a == b is allowed
 * (distance to a point).  When the closest point is an end point, c is that
 * end point bit for bit, so the result equals dfl_hypot_vec(x - a) (or
 * x - b). */
double dfl_segdist_eval(int dim, const double *a, const double *b, const double *x,
                        double *grad);

/* 1 when the closest point of the segment a-b to x (dim coordinates) is a,
 * i.e. (x - a) . (b - a) <= 0 (exact geometric test, no tolerance). */
bool dfl_segdist_closest_is_start(int dim, const double *a, const double *b, const double *x);

/* Distance from x to the segment from a along e (e = b - a, ee = e.e as
 * the caller computed it: sum of e_j^2 from 0.0; ee == 0 means the point
 * a).  With s = clamp((x - a).e / ee, 0, 1) it writes the residual
 * r = (x - a) - s e (dim doubles, r may not alias the inputs) and returns
 * sqrt(r.r).  Non-finite input propagates (NaN s stays NaN). */
double dfl_segdist_residual(int dim, const double *a, const double *e, double ee,
                            const double *x, double *r);

/* dfl_segdist_residual for the segment a-b without the residual (note the
 * argument order: the point first). */
double dfl_point_segment_dist(int dim, const double *x, const double *a, const double *b);

/* 2D: hypot(r0, r1) of the residual r that dfl_point_segment_dist(2, x, a,
 * b) forms (the clamped projection, a == b: the point a).  Differs from
 * dfl_point_segment_dist in the last bits only; used where reproduced
 * tables were computed with hypot (bs04_fields). */
double dfl_point_segment_dist_hypot(const double *x, const double *a, const double *b);

#endif
