#include "cfg/field_cfg.h"

#include <math.h>

#include "cfg/proxy_cfg.h"
#include "cfg/gridpeer_cfg.h"
#include "cfg/pht_cfg.h"
#include "cfg/rfunc_cfg.h"
#include "cfg/shape_cfg.h"
#include "cfg/vdb_cfg.h"
#include "field/exact.h"
#include "geom/shape.h"

/* kind = exact: the exact distance of the section its key `shape` names
 * (default [shape], as kind = proxy, gridpeer and pht). */
static dfl_status exact_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out,
                                 dfl_err *err)
{
    const char *ssec;
    dfl_status st = dfl_cfg_string_opt(cfg, sec, "shape", "shape", &ssec, err);
    if (st != DFL_OK) return st;
    if (!dfl_cfg_has_section(cfg, ssec))
        return dfl_cfg_reject(cfg, sec, "shape", err, "no section [%s]", ssec);
    dfl_shape shape;
    st = dfl_shape_from_cfg(cfg, ssec, &shape, err);
    if (st != DFL_OK) return st;
    st = dfl_field_exact_new(&shape, out, err);
    if (st != DFL_OK) dfl_shape_free(&shape);
    return st;
}

/* One row per kind of field. */
static const dfl_field_kind kinds[] = {
    {"exact", exact_from_cfg, NULL},
    {"rfunc", dfl_rfunc_field_from_cfg, NULL},
    {"normalized", dfl_rfunc_normalized_from_cfg, NULL},
    {"proxy", dfl_proxy_field_from_cfg, NULL},
    {"gridpeer", dfl_gridpeer_field_from_cfg, NULL},
    {"pht", dfl_pht_field_from_cfg, dfl_pht_field_target_from_cfg},
    {"openvdb", dfl_vdb_field_from_cfg, NULL},
};
#define NKINDS (sizeof kinds / sizeof kinds[0])

const dfl_field_kind *dfl_field_kinds(size_t *count)
{
    *count = NKINDS;
    return kinds;
}

dfl_status dfl_field_kind_from_cfg(const dfl_cfg *cfg, const char *sec,
                                   const dfl_field_kind **out, dfl_err *err)
{
    const char *names[NKINDS];
    for (size_t i = 0; i < NKINDS; i++) names[i] = kinds[i].name;
    int k;
    dfl_status st = dfl_cfg_enum(cfg, sec, "kind", names, (int)NKINDS, &k, err);
    if (st == DFL_OK) *out = &kinds[k];
    return st;
}

dfl_status dfl_field_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out, dfl_err *err)
{
    const dfl_field_kind *kind;
    dfl_status st = dfl_field_kind_from_cfg(cfg, sec, &kind, err);
    if (st != DFL_OK) return st;
    return kind->build(cfg, sec, out, err);
}

void dfl_field_target_none(dfl_field_target *out)
{
    out->value = NAN;
    out->met = -1;
    out->over = 0;
}

dfl_status dfl_field_from_cfg_target(const dfl_cfg *cfg, const char *sec, dfl_field *out,
                                     dfl_field_target *target, dfl_err *err)
{
    const dfl_field_kind *kind;
    dfl_status st = dfl_field_kind_from_cfg(cfg, sec, &kind, err);
    if (st != DFL_OK) return st;
    if (kind->build_target) return kind->build_target(cfg, sec, out, target, err);
    if ((st = kind->build(cfg, sec, out, err)) == DFL_OK) dfl_field_target_none(target);
    return st;
}
