/* The domain of validity of the rfunc fields (rfield.h and its parts).
 *
 *   dfl_rfunc_domain_coords(dim, x, what, err)   geometry coordinates in range
 *   dfl_rfunc_domain_point(dim, x, jet, err)     an evaluation point in range
 *
 * What is promised.  For part coordinates and evaluation points with every
 * |coordinate| <= DFL_RFUNC_COORD_MAX (1e100) and segments (triangle edges)
 * of length >= DFL_RFUNC_LEN_MIN (1e-100), every value and gradient of an
 * rfunc field is finite and correct to rounding (relative ~1e-13): the
 * largest intermediate, a disk trim t ~ |x - c|^2 / d <= 4e300, stays below
 * DBL_MAX, and the compositions are evaluated in scaled forms (hypot,
 * ratios <= 1) so that no square of it is formed.  The one exception is
 * join = requiv_corrected with correction = eq20, which is NaN where bs04's
 * radicand is not positive (join.h): that NaN is the formula's, not a
 * failure.  Jets (exact derivatives) multiply up to 2 p powers of the
 * coordinates; they are promised for |coordinate| <= DFL_RFUNC_JET_COORD_MAX
 * (1e30) and fail with DFL_E_INPUT (never an abort) outside.
 * Geometry outside the ranges is rejected when the part is added
 * (DFL_E_INPUT naming the coordinate); points outside are rejected by
 * dfl_rfunc_domain_point, which the field's check hook calls
 * (field/field.h dfl_field_check_point, used by `dflab probe`).
 * Pure functions, no allocation.
 */
#ifndef DFL_RFUNC_DOMAIN_H
#define DFL_RFUNC_DOMAIN_H

#include <stdbool.h>

#include "core/status.h"

#define DFL_RFUNC_COORD_MAX 1e100
#define DFL_RFUNC_LEN_MIN 1e-100
#define DFL_RFUNC_JET_COORD_MAX 1e30

/* DFL_OK when x[0..dim-1] are finite with |x_j| <= DFL_RFUNC_COORD_MAX;
 * else DFL_E_INPUT "<what> (x, y[, z]): coordinate ... outside ..." (err
 * may be NULL). */
dfl_status dfl_rfunc_domain_coords(int dim, const double *x, const char *what, dfl_err *err);

/* The same for an evaluation point, with the jet bound when jet is true. */
dfl_status dfl_rfunc_domain_point(int dim, const double *x, bool jet, dfl_err *err);

#endif
