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
 *
 * Targets: a kind whose build refines toward a tolerance of its own (pht:
 * eps, the fit's estimator error per cell, capped by max_level) has a
 * second factory, build_target, that also says whether the build met it
 * (dfl_field_target).  eps is a target, not a promise: a study reports
 * what the build reached through dfl_field_from_cfg_target, for any kind,
 * without knowing which kinds have one.
 */
#ifndef DFL_EXPERIMENTS_FIELD_CFG_H
#define DFL_EXPERIMENTS_FIELD_CFG_H

#include <stddef.h>

#include "core/status.h"
#include "field/field.h"
#include "io/config.h"

typedef dfl_status (*dfl_field_factory)(const dfl_cfg *cfg, const char *sec, dfl_field *out,
                                        dfl_err *err);

/* A build's outcome against the kind's own tolerance.  No target (a kind
 * without one, or a validation pass that built nothing): value NaN, met -1,
 * over 0 (dfl_field_target_none). */
typedef struct dfl_field_target {
    double value;   /* the tolerance, in the units of the kind's own error
                       estimate (pht: length); NaN: none */
    int met;        /* 1: every unit's estimate is <= value; 0: some unit's
                       is not (or is NaN); -1: no target */
    size_t over;    /* units whose estimate is not <= value (pht: leaf
                       cells); 0 when met or no target */
} dfl_field_target;

/* A factory that also fills *target on success (untouched on failure). */
typedef dfl_status (*dfl_field_target_factory)(const dfl_cfg *cfg, const char *sec,
                                               dfl_field *out, dfl_field_target *target,
                                               dfl_err *err);

typedef struct dfl_field_kind {
    const char *name;          /* the value of `kind` */
    dfl_field_factory build;
    dfl_field_target_factory build_target; /* NULL: the kind has no target */
} dfl_field_kind;

/* The no-target record: value NaN, met -1, over 0.  Never fails. */
void dfl_field_target_none(dfl_field_target *out);

/* The kinds, in table order (*count receives their number). */
const dfl_field_kind *dfl_field_kinds(size_t *count);

/* The row of [sec] kind into *out.  DFL_E_INPUT naming file:line, key and
 * the accepted names when kind is missing or not in the table. */
dfl_status dfl_field_kind_from_cfg(const dfl_cfg *cfg, const char *sec,
                                   const dfl_field_kind **out, dfl_err *err);

/* The field [sec] describes: its kind's factory.  *out is untouched on
 * failure; release it with dfl_field_destroy. */
dfl_status dfl_field_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out, dfl_err *err);

/* dfl_field_from_cfg, and the build's target into *target: the kind's
 * build_target when it has one, else dfl_field_target_none.  *out and
 * *target are untouched on failure. */
dfl_status dfl_field_from_cfg_target(const dfl_cfg *cfg, const char *sec, dfl_field *out,
                                     dfl_field_target *target, dfl_err *err);

#endif
