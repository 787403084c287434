/* `[field] kind = pht`: a PHT spline fitted to a shape's SDF (pht/fit.h).
 *
 * Keys of the field section (all optional):
 *   shape     = section holding the shape (default "shape"); its SDF must have
 *               derivatives and be signed (closed curves, circle, sphere,
 *               torus, implicit surfaces, ...)
 *   eps       = target estimator error > 0 (default 1e-3)
 *   max_level = deepest level, 0..30 (cross) or 0..30*dim (binary) (default 10)
 *   samples   = estimator points per cell, 1..4096 (default 16)
 *   split     = cross | binary (default cross)
 *   estimator = random | grid | gradient (default random)
 *   seed      = non-negative integer (default 1)
 *   lo, hi    = the box (dim numbers each, lo < hi; default the unit square/cube)
 * Errors: DFL_E_INPUT naming file:line, [section] and key (eps <= 0,
 * max_level out of range, a shape without derivatives or an open curve:
 * the shape's `kind` or `closed` key is named).
 *
 * Function index:
 *   dfl_pht_opts_from_cfg     fit options from a section (for studies)
 *   dfl_pht_source_from_cfg   the shape and its Hermite source from a section
 *   dfl_pht_field_from_cfg    the field kind's factory (one row in field_cfg.c)
 *   dfl_pht_field_target_from_cfg  the same, with the fit's eps outcome
 */
#ifndef DFL_EXPERIMENTS_PHT_CFG_H
#define DFL_EXPERIMENTS_PHT_CFG_H

#include "core/status.h"
#include "cfg/field_cfg.h"
#include "field/field.h"
#include "geom/shape.h"
#include "io/config.h"
#include "pht/fit.h"
#include "pht/hermite.h"

/* Options of [sec] for dimension dim into *o (defaults for absent keys). */
dfl_status dfl_pht_opts_from_cfg(const dfl_cfg *cfg, const char *sec, int dim,
                                 dfl_pht_fit_opts *o, dfl_err *err);

/* The shape section that [sec]'s `shape` key names (default "shape") into
 * *shape and a source on it into *src (free the source first, then the
 * shape).  Both untouched on failure. */
dfl_status dfl_pht_source_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_shape *shape,
                                   dfl_pht_source **src, dfl_err *err);

/* Fits and wraps the spline as a field (the mesh is dropped). */
dfl_status dfl_pht_field_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out,
                                  dfl_err *err);

/* dfl_pht_field_from_cfg, and the fit's outcome against eps into *target:
 * value = eps, met = the fit's converged (1: every leaf cell's estimate
 * <= eps; 0: max_level stopped the refinement with cells above it), over =
 * the fit's capped (those cells).  A validation pass (no fit) gives
 * dfl_field_target_none.  *target is untouched on failure. */
dfl_status dfl_pht_field_target_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out,
                                         dfl_field_target *target, dfl_err *err);

#endif
