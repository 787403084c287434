/* `[field] kind = exact`: the exact signed distance of a shape as a field.
 *
 * The field forwards value, gradient and (when the shape has them) jets to
 * the shape unchanged, so it is the reference every approximation is
 * measured against.  Units and sign are the shape's (negative inside;
 * segments are unsigned).  Domain: the shape's (geom/shape.h); for the
 * analytic kinds every point with |x_j| <= 1e150 (core/domain.h) gives a
 * finite value.
 */
#ifndef DFL_FIELD_EXACT_H
#define DFL_FIELD_EXACT_H

#include "core/status.h"
#include "field/field.h"
#include "geom/shape.h"

/* Wraps *shape.  Ownership of the shape moves into the field: on success
 * *shape is zeroed and dfl_field_destroy frees it; on failure (DFL_E_INPUT
 * for an empty shape, DFL_E_NOMEM) the shape is left with the caller.
 * The field's jet op is NULL when the shape has no jets. */
dfl_status dfl_field_exact_new(dfl_shape *shape, dfl_field *out, dfl_err *err);

/* The exact field of *shape without taking it: the field borrows the
 * shape (which must outlive it; dfl_field_destroy leaves it alone).  Same
 * values, gradients and jets as dfl_field_exact_new's; dfl_field_exact_shape
 * finds the shape too. */
void dfl_field_exact_view(const dfl_shape *shape, dfl_field *out);

/* The shape inside an exact field (borrowed; NULL if f is not exact). */
const dfl_shape *dfl_field_exact_shape(const dfl_field *f);

#endif
