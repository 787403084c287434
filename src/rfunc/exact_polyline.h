/* Open polylines of exact segment distances joined by the bs04 R-functions.
 *
 * Why this exists beside rfunc/rfield.h's trimmed polylines: the trimmed
 * fields of bs04 (eq. 4 and 5) are normalized only to first order at the end
 * points, so near a joining point |grad h_i| = 1 + O(|x - v| / length).
 * bs04's analysis of joining points (eq. 13-14) and of the corrected join
 * (eq. 20: "h1 = h2 = q" in the hatched sector) assumes exact distances.
 * This field realizes that assumption, so the claims can be checked to
 * rounding error and the trims' own contribution can be told apart.
 *
 * The parts are geom/segdist.h's dfl_segdist_eval, whose end-point regions
 * measure |x - v| exactly as the corrected join measures q_v (core/hypot.h):
 * there h_i == q_v bit for bit and eq. 20 cancels exactly.
 *
 * Evaluation is pure, allocation-free per point and thread-safe. */
#ifndef DFL_RFUNC_EXACT_POLYLINE_H
#define DFL_RFUNC_EXACT_POLYLINE_H

#include <stddef.h>

#include "core/status.h"
#include "field/field.h"
#include "rfunc/join.h"

/* The open polyline v[0..n-1] (n >= 2 vertices, dim coordinates each, no
 * two consecutive ones equal) as a field: the exact distances h_i to its
 * n - 1 segments joined by `join` of order p (rfunc/join.h); for
 * DFL_RFUNC_REQUIV_CORRECTED the interior vertices enter eq. 20 with
 * q_v = |x - v| and the library's guard max(q_v, h_i, h_j) (a no-op for
 * exact distances, where h_i, h_j <= q_v).  The field copies v and has no
 * jets.  DFL_E_INPUT for a bad dim (2 or 3), n < 2, repeated consecutive
 * vertices, non-finite coordinates or bad p; DFL_E_NOMEM; *out untouched
 * on failure.  Release with dfl_field_destroy. */
dfl_status dfl_rfunc_exact_polyline_field(int dim, const double *v, size_t n,
                                          dfl_rfunc_join join, int p, dfl_field *out,
                                          dfl_err *err);
/* The same with the corrected join's form corr (rfunc/join.h): eq20 takes
 * the raw q_v and is NaN where its radicand <= 0. */
dfl_status dfl_rfunc_exact_polyline_field_corr(int dim, const double *v, size_t n,
                                               dfl_rfunc_join join, dfl_rfunc_correction corr,
                                               int p, dfl_field *out, dfl_err *err);

#endif
