/* A fitted PHT spline as a dflab field (field/field.h): `[field] kind = pht`.
 *
 * eval: dfl_pht_eval per batch (value, gradient; no allocation).
 * jet:  dfl_pht_jet, exact (the spline is a polynomial per cell; the cell
 *       that the ray enters for s > 0+ is used).
 *
 * Function index:
 *   dfl_pht_field_new      wrap a spline (takes ownership)
 *   dfl_pht_field_spline   the spline inside a pht field (borrowed)
 */
#ifndef DFL_PHT_PHT_FIELD_H
#define DFL_PHT_PHT_FIELD_H

#include "core/status.h"
#include "field/field.h"
#include "pht/spline.h"

/* Takes ownership of *s (set to NULL on success; left on failure).
 * DFL_E_INPUT if *s is NULL, DFL_E_NOMEM. */
dfl_status dfl_pht_field_new(dfl_pht_spline **s, dfl_field *out, dfl_err *err);

/* The spline of a field made by dfl_pht_field_new, NULL for other fields. */
const dfl_pht_spline *dfl_pht_field_spline(const dfl_field *f);

#endif
