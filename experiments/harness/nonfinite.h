/* The run's side of field/metrics' non-finite rule: a table that holds a
 * point whose value was not finite (an error of +inf) makes the run fail
 * with exit status 1, after its outputs are written, unless the config
 * allows it.
 *
 * Function index
 *   dfl_study_allow_nonfinite  reads [study] allow_nonfinite (bool, false)
 *   dfl_nonfinite_check        scans a folder's CSV tables
 *
 * A column counts non-finite points when its name contains "nonfinite"
 * (nonfinite, nonfinite_band, band_nonfinite, nonfinite_nodes, ...); a cell
 * of such a column that reads as a number > 0 is a table holding one.
 */
#ifndef DFL_HARNESS_NONFINITE_H
#define DFL_HARNESS_NONFINITE_H

#include <stdbool.h>
#include <stddef.h>

#include "core/status.h"
#include "io/config.h"

/* [study] allow_nonfinite of a point's config (default false); fails as
 * dfl_cfg_bool_opt does (DFL_E_INPUT naming file, line and key). */
dfl_status dfl_study_allow_nonfinite(const dfl_cfg *pt, bool *out, dfl_err *err);

/* Scans every regular *.csv file directly in dir, in name order.  A row's
 * sweep point is its "point" cell (absent or out of range: point 0);
 * allow[k] (np entries) says whether point k accepts non-finite values.
 * The first row of a point that does not accept them with a non-zero
 * count gives DFL_E_NUMERIC "TABLE: row R (point K): COLUMN: N non-finite
 * point(s) (error +inf); ..." (R counts data rows from 1).  A file that
 * cannot be read is DFL_E_IO.  DFL_OK when none holds one. */
dfl_status dfl_nonfinite_check(const char *dir, const bool *allow, size_t np, dfl_err *err);

#endif
