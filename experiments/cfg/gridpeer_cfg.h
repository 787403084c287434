/* `[field] kind = gridpeer`: a simple grid of the [shape]'s exact SDF
 * (field/gridpeer.h), the peer of a proxy grid at equal storage.
 *
 *   method  = trilinear0 | taylor1 | taylor2 | tricubic   (default taylor1)
 *   storage = float64 | float16                (default float64)
 *   res     = N cells per axis, 1 .. 1024      (default 16)
 *   lo, hi  = box corners                      (default -1 -1 -1, 1 1 1)
 *   shape   = <section>                        (default shape)
 *
 * Errors: DFL_E_INPUT naming file:line and key (unknown method, lo >= hi,
 * taylor2 of a shape without jets, tricubic with res < 4, a float16
 * overflow).
 */
#ifndef DFL_EXPERIMENTS_GRIDPEER_CFG_H
#define DFL_EXPERIMENTS_GRIDPEER_CFG_H

#include "core/status.h"
#include "field/field.h"
#include "io/config.h"

dfl_status dfl_gridpeer_field_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out,
                                       dfl_err *err);

#endif
