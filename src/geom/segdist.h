/* Exact Euclidean distances to straight segments, and open polylines of
 * exact segment distances joined by the bs04 R-functions.
 *
 * Why this exists beside rfunc/segment.h: the trimmed fields of bs04 (eq. 4
 * and 5) are normalized only to first order at the end points, so near a
 * joining point |grad h_i| = 1 + O(|x - v| / length).  bs04's analysis of
 * joining points (eq. 13-14) and of the corrected join (eq. 20: "h1 = h2 =
 * q" in the hatched sector) assumes exact distances.  These parts realize
 * that assumption, so the claims can be checked to rounding error and the
 * trims' own contribution can be told apart.  The library lacks such a part
 * (it belongs to the bs04 studies in experiments/, not to src/rfunc).
 *
 * Everything is pure, allocation-free per point and thread-safe.
 */
#ifndef DFL_EXPERIMENTS_SEGDIST_H
#define DFL_EXPERIMENTS_SEGDIST_H

#include <stdbool.h>
#include <stddef.h>

#include "core/status.h"
#include "field/field.h"
#include "rfunc/join.h"

/* Distance from x to the segment a-b (dim = 2 or 3 coordinates each) and,
 * when grad != NULL, its gradient (x - c) / |x - c| with c the closest
 * point (dim doubles; 0 on the segment, where the distance is not
 * differentiable).  a == b is allowed (distance to a point).  When the
 * closest point is an end point, c is that end point bit for bit, so the
 * result equals |x - a| (or |x - b|) computed the same way. */
double dfl_segdist_eval(int dim, const double *a, const double *b, const double *x,
                        double *grad);

/* 1 when the closest point of the segment a-b to x is the end point a,
 * i.e. (x - a) . (b - a) <= 0 (exact geometric test, no tolerance). */
bool dfl_segdist_closest_is_start(int dim, const double *a, const double *b, const double *x);

/* The open polyline v[0..n-1] (n >= 2 vertices, dim coordinates each, no
 * two consecutive ones equal) as a field: the exact distances h_i to its
 * n - 1 segments joined by `join` of order p (rfunc/join.h); for
 * DFL_RFUNC_REQUIV_CORRECTED the interior vertices enter eq. 20 with
 * q_v = |x - v| and the library's guard max(q_v, h_i, h_j) (a no-op for
 * exact distances, where h_i, h_j <= q_v).  The field has no jets.
 * DFL_E_INPUT for a bad dim, n < 2, repeated consecutive vertices,
 * non-finite coordinates or bad p; DFL_E_NOMEM.  Release with
 * dfl_field_destroy. */
dfl_status dfl_segdist_polyline_field(int dim, const double *v, size_t n, dfl_rfunc_join join,
                                      int p, dfl_field *out, dfl_err *err);

#endif
