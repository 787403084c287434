/* `[field] kind = rfunc` -> a bs04 R-function field (rfunc/rfield.h).
 *
 * Keys of the section (the caller has read `kind`):
 *   vertices = x0 y0; x1 y1; ...   a 2D polyline, or x y z; ... (3D space
 *              polyline; the dimension is the number of values of the
 *              first vertex), at least 2 vertices (3 when closed), no two
 *              consecutive vertices equal
 *   closed   = false | true        with vertices only: adds the segment
 *              from the last vertex back to the first
 *   curve    = <section>           instead of vertices: a [section] with
 *              kind = bspline_curve (experiments/curve_cfg.h), polygonized
 *              with Hausdorff bound
 *   eps      = <max deviation>     > 0, required with curve; a closed curve
 *              (first point == last) gives a closed polyline
 *   join     = requiv | rconj | requiv_corrected     default requiv
 *   p        = integer 1..64       default 2; rconj needs p >= 2
 *   trim     = disk | disk_smooth | strip | strip_smooth   default disk
 * The field is unsigned (bs04's approximate distance to the set), 0 on the
 * polyline.  Errors: DFL_E_INPUT naming file:line, [section] and key.
 */
#ifndef DFL_EXPERIMENTS_RFUNC_CFG_H
#define DFL_EXPERIMENTS_RFUNC_CFG_H

#include "core/status.h"
#include "field/field.h"
#include "io/config.h"

/* Reads [sec] (kind already checked to be "rfunc") into *out (release with
 * dfl_field_destroy); *out is untouched on failure. */
dfl_status dfl_rfunc_field_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out,
                                    dfl_err *err);

#endif
