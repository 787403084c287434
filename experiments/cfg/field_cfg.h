/* [field] section -> dfl_field, through a table of field kinds.
 *
 *   kind = exact   the exact signed distance of the [shape] section (key
 *                  shape names another section)
 *   kind = rfunc   a bs04 R-function field (experiments/cfg/rfunc_cfg.h)
 *   kind = proxy   an hvb25 proxy grid field (experiments/cfg/proxy_cfg.h)
 *   kind = gridpeer  a simple grid of [shape]'s SDF (experiments/cfg/gridpeer_cfg.h)
 *   kind = pht     an sjp10 PHT spline fitted to [shape] (experiments/cfg/pht_cfg.h)
 *   kind = openvdb an OpenVDB narrow-band level set of [shape] (experiments/cfg/vdb_cfg.h)
 *
 * Each kind is one row {name, factory} of the table in field_cfg.c; a
 * module that brings a new kind of field adds its row there and its
 * factory beside its other config glue.  A factory reads the rest of
 * [sec] (and the sections it names), marks what it reads, and leaves *out
 * untouched on failure.  In a validation pass (io/config.h
 * dfl_cfg_validating) a factory whose build computes (pht: the fit;
 * gridpeer: the samples; openvdb: the level set) reads and checks every
 * key and returns dfl_field_placeholder of the field's dimension; proxy
 * returns its grid with zeroed proxies (dfl_proxy_grid_alloc); exact and
 * rfunc fields are built (their build is the shape's).
 */
#ifndef DFL_EXPERIMENTS_FIELD_CFG_H
#define DFL_EXPERIMENTS_FIELD_CFG_H

#include <stddef.h>

#include "core/status.h"
#include "field/field.h"
#include "io/config.h"

typedef dfl_status (*dfl_field_factory)(const dfl_cfg *cfg, const char *sec, dfl_field *out,
                                        dfl_err *err);

typedef struct dfl_field_kind {
    const char *name;          /* the value of `kind` */
    dfl_field_factory build;
} dfl_field_kind;

/* The kinds, in table order (*count receives their number). */
const dfl_field_kind *dfl_field_kinds(size_t *count);

/* The row of [sec] kind into *out.  DFL_E_INPUT naming file:line, key and
 * the accepted names when kind is missing or not in the table. */
dfl_status dfl_field_kind_from_cfg(const dfl_cfg *cfg, const char *sec,
                                   const dfl_field_kind **out, dfl_err *err);

/* The field [sec] describes: its kind's factory.  *out is untouched on
 * failure; release it with dfl_field_destroy. */
dfl_status dfl_field_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out, dfl_err *err);

#endif
