/* A dfl_field built from bs04 parts joined by an R-function.
 *
 * Parts (in order; the order matters for R-conjunction only):
 *   segments (2D lines, 3D space-curve pieces; segment.h), triangles (3D;
 *   tri3d.h), points (region.h) and convex polygon regions (2D; region.h),
 * so heterogeneous sets (bs04 Fig. 13a: region, segment and point) are one
 * field.  The join is one of join.h; the corrected join also needs the
 * shared vertices v and their two adjacent parts: q_v = |x - v|, guarded by
 * the adjacent parts' fields, enters eq. 20.
 *
 * The field u >= 0 is unsigned (bs04's fields are distances to a set, not
 * signed distances), exactly 0 on every part, with gradient 0 there by
 * convention (u is not differentiable on its zero set) and finite
 * everywhere.  eval is serial, allocation-free and thread-safe; jets
 * allocate one array of n part jets per call.
 *
 * Fast path.  A field that is exactly a 2D or 3D polyline of at least two
 * segments (its parts are segments, all with the same eq. 4 trim, disk or
 * strip, each starting where the previous one ends; open or closed) joined
 * by R-equivalence (or a set of at least two point parts, of convex
 * regions, or of triangles with one eq. 4 trim, joined so)
 * evaluates through the vectorized evaluator of rfunc/batch.h (one call
 * per batch of points), which agrees with the per-point
 * accumulator to rounding (1e-12 relative; gradients relative to the sum
 * of absolute contributions) and falls back to it where its unscaled sums
 * are not trustworthy.  Jets and every other field use the per-point code.
 *
 * Domain of validity (rfunc/domain.h): parts are rejected (DFL_E_INPUT)
 * beyond |coordinate| 1e100; values and gradients are finite and correct
 * for points within it (except eq. 20's own NaN); jets need |x| <= 1e30
 * and a finite non-zero direction, and fail with DFL_E_INPUT otherwise.
 *
 * Ownership: the builder (dfl_rfield_new) collects parts; dfl_rfield_finish
 * moves everything into the field (freed by dfl_field_destroy) and frees the
 * builder, on success and on failure.
 */
#ifndef DFL_RFUNC_RFIELD_H
#define DFL_RFUNC_RFIELD_H

#include <stdbool.h>
#include <stddef.h>

#include "core/status.h"
#include "field/field.h"
#include "rfunc/join.h"
#include "rfunc/segment.h"
#include "rfunc/tri3d.h"

typedef struct dfl_rfield dfl_rfield;

/* Empty builder for a field of dimension dim (2 or 3).  DFL_E_INPUT for a
 * bad dim or p (dfl_rfunc_join_check), DFL_E_NOMEM. */
dfl_status dfl_rfield_new(int dim, dfl_rfunc_join join, int p, dfl_rfield **out, dfl_err *err);
void dfl_rfield_free(dfl_rfield *r);

/* Parts; DFL_E_INPUT for degenerate geometry (see the part modules) or a
 * part that does not fit the dimension, DFL_E_NOMEM. */
dfl_status dfl_rfield_add_segment(dfl_rfield *r, const double *a, const double *b,
                                  dfl_rfunc_trim trim, dfl_err *err);
dfl_status dfl_rfield_add_triangle(dfl_rfield *r, const double *A, const double *B,
                                   const double *C, const dfl_rfunc_tri_opts *o, dfl_err *err);
dfl_status dfl_rfield_add_point(dfl_rfield *r, const double *c, dfl_err *err);
dfl_status dfl_rfield_add_region(dfl_rfield *r, const double *v, size_t n, dfl_err *err);
/* A vertex v shared by parts i and j (indices in the order of addition,
 * i != j; checked by dfl_rfield_finish) for the corrected join, whose
 * guard needs the adjacent parts (join.h).  Ignored by the other joins. */
dfl_status dfl_rfield_add_vertex(dfl_rfield *r, const double *v, size_t i, size_t j,
                                 dfl_err *err);

/* Relative tolerance of the degenerate-polyline tests (dfl_rfield_add_polyline). */
#define DFL_RFIELD_POLY_TOL 1e-12

/* The polyline v[0..n-1] (n*dim coordinates; closed adds the segment
 * v[n-1] -> v[0]) as segments with trim plus its shared vertices (the
 * interior ones, or all when closed), appended to the parts.  DFL_E_INPUT
 * for n < 2 (n < 3 when closed), coordinates outside the domain
 * (domain.h), a segment shorter than DFL_RFIELD_POLY_TOL times the
 * polyline's bounding-box diagonal (repeated vertices included), an A-B-A
 * backtrack (consecutive segments antiparallel within the tolerance; this
 * includes every closed polyline with collinear vertices, i.e. no area,
 * at its extreme vertices); the message
 * names the vertex or segment (1-based).  Parts added before a failure
 * stay in the builder (free it). */
dfl_status dfl_rfield_add_polyline(dfl_rfield *r, const double *v, size_t n, bool closed,
                                   dfl_rfunc_trim trim, dfl_err *err);

/* Switches the fast path (see above) on (the default) or off for the field
 * this builder finishes into; off forces the per-point accumulator (tests,
 * the benchmark's baseline, and rfunc/batch.h's own reference field). */
void dfl_rfield_set_fast(dfl_rfield *r, bool on);

/* Corrected join only: dflab's guarded form (the default) or bs04's eq.
 * 20 literally (NaN where its radicand <= 0); join.h.  Ignored by the
 * other joins. */
void dfl_rfield_set_correction(dfl_rfield *r, dfl_rfunc_correction corr);

/* DFL_OK when x lies in the domain of validity of f's values (jet false)
 * or exact derivatives (jet true) -- rfunc/domain.h: |x_j| <= 1e100, and
 * for jets |x_j| <= 1e30 with the parts inside that bound too; DFL_E_INPUT
 * naming the point otherwise.  DFL_OK for any field that is not an rfield. */
dfl_status dfl_rfield_check_point(const dfl_field *f, const double *x, bool jet, dfl_err *err);

/* True when f is an rfield whose NaN values mean "undefined here" rather
 * than a failure: the corrected join with correction = eq20, which is NaN
 * exactly where bs04's radicand is <= 0.  False for every other field. */
bool dfl_rfield_nan_is_undefined(const dfl_field *f);

/* Whether f is an rfield whose eval runs the fast path (false for any
 * other field). */
bool dfl_rfield_is_fast(const dfl_field *f);

/* Number of parts added so far. */
size_t dfl_rfield_count(const dfl_rfield *r);

/* Turns the builder into a field (*r is freed and set to NULL in every
 * case).  DFL_E_INPUT if there are no parts or a vertex names a part that
 * does not exist (or the same part twice); DFL_E_NOMEM. */
dfl_status dfl_rfield_finish(dfl_rfield **r, dfl_field *out, dfl_err *err);

/* The polyline v[0..n-1] (n*dim coordinates; closed adds the segment
 * v[n-1] -> v[0]) as a field; the shared vertices are the interior ones
 * (open) or all (closed).  DFL_E_INPUT for what dfl_rfield_add_polyline
 * rejects and a bad p. */
dfl_status dfl_rfield_polyline(int dim, const double *v, size_t n, bool closed,
                               dfl_rfunc_join join, int p, dfl_rfunc_trim trim, dfl_field *out,
                               dfl_err *err);
/* dfl_rfield_polyline with the fast path on or off (dfl_rfield_set_fast). */
dfl_status dfl_rfield_polyline_opts(int dim, const double *v, size_t n, bool closed,
                                    dfl_rfunc_join join, int p, dfl_rfunc_trim trim, bool fast,
                                    dfl_field *out, dfl_err *err);

#endif
