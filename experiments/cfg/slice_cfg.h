/* Config -> section planes: the "section planes" of bs04 Figs. 8, 9c, 11b
 * and 12, as grids with a flat axis (field/sample.h: dfl_grid_plane), to be
 * sampled with dfl_field_sample and written with dfl_field_out_write.
 */
#ifndef DFL_EXPERIMENTS_CFG_SLICE_CFG_H
#define DFL_EXPERIMENTS_CFG_SLICE_CFG_H

#include <stddef.h>

#include "core/status.h"
#include "field/sample.h"
#include "io/config.h"

/* Reads "[sec] slices = z 0.5; y 0.25 -1 -1 1 1 ..." (at least one, at
 * most max entries "<x|y|z> <at> [lo0 lo1 hi0 hi1]", the extent in the
 * plane's two in-plane coordinates, lo < hi), "[sec] slice_n" (nodes per
 * in-plane axis, 2..2048, default 200) and the default extent
 * "slice_lo = a b", "slice_hi = a b" (lo < hi; defaults 0 0 and 1 1) for
 * slices without their own, into out[0 .. *count - 1].  DFL_E_INPUT naming
 * file, line and key on a bad entry. */
dfl_status dfl_slices_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_grid *out, int max,
                               int *count, dfl_err *err);

/* "z = 0.5": the plane grid's normal axis and coordinate as the tables name
 * a slice; into buf, returns buf. */
const char *dfl_slice_label(const dfl_grid *plane, char *buf, size_t size);

#endif
