/* [field] section -> dfl_field.
 *
 *   kind = exact   the exact signed distance of the [shape] section
 *   kind = rfunc   a bs04 R-function field (see experiments/rfunc_cfg.h)
 *
 * Reads only [field] and the sections it names; marks what it reads.
 */
#ifndef DFL_EXPERIMENTS_FIELD_CFG_H
#define DFL_EXPERIMENTS_FIELD_CFG_H

#include "core/status.h"
#include "field/field.h"
#include "io/config.h"

dfl_status dfl_field_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out, dfl_err *err);

#endif
