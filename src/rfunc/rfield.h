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
 * Fast path.  A field that is exactly a 2D polyline of at least two
 * segments (its parts are segments, all with the disk trim, each starting
 * where the previous one ends; open or closed) joined by R-equivalence
 * evaluates through the vectorized evaluator of rfunc/batch.h (one call
 * per batch of points), which agrees with the per-point
 * accumulator to rounding (1e-12 relative; gradients relative to the sum
 * of absolute contributions) and falls back to it where its unscaled sums
 * are not trustworthy.  Jets and every other field use the per-point code.
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

/* Switches the fast path (see above) on (the default) or off for the field
 * this builder finishes into; off forces the per-point accumulator (tests,
 * the benchmark's baseline, and rfunc/batch.h's own reference field). */
void dfl_rfield_set_fast(dfl_rfield *r, bool on);

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
 * (open) or all (closed).  DFL_E_INPUT for n < 2 (n < 3 when closed),
 * repeated consecutive vertices, bad p. */
dfl_status dfl_rfield_polyline(int dim, const double *v, size_t n, bool closed,
                               dfl_rfunc_join join, int p, dfl_rfunc_trim trim, dfl_field *out,
                               dfl_err *err);
/* dfl_rfield_polyline with the fast path on or off (dfl_rfield_set_fast). */
dfl_status dfl_rfield_polyline_opts(int dim, const double *v, size_t n, bool closed,
                                    dfl_rfunc_join join, int p, dfl_rfunc_trim trim, bool fast,
                                    dfl_field *out, dfl_err *err);

#endif
