#include "cfg/gridpeer_cfg.h"

#include "cfg/shape_cfg.h"
#include "field/gridpeer.h"

dfl_status dfl_gridpeer_field_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out,
                                       dfl_err *err)
{
    static const double dlo[3] = {-1, -1, -1}, dhi[3] = {1, 1, 1};
    dfl_gridpeer_opts o = {0};
    int kind = DFL_GRIDPEER_TAYLOR1, storage = DFL_GRIDPEER_FLOAT64;
    long n = 16;
    const char *shape_sec;
    dfl_status st = dfl_cfg_enum_opt(cfg, sec, "method", dfl_gridpeer_kind_names,
                                     DFL_GRIDPEER_KIND_COUNT, kind, &kind, err);
    if (!st) st = dfl_cfg_enum_opt(cfg, sec, "storage", dfl_gridpeer_storage_names,
                                   DFL_GRIDPEER_STORAGE_COUNT, storage, &storage, err);
    if (!st) st = dfl_cfg_int_opt(cfg, sec, "res", 16, 1, 1024, &n, err);
    if (!st) st = dfl_cfg_vec_opt(cfg, sec, "lo", 3, dlo, o.lo, err);
    if (!st) st = dfl_cfg_vec_opt(cfg, sec, "hi", 3, dhi, o.hi, err);
    if (!st) st = dfl_cfg_string_opt(cfg, sec, "shape", "shape", &shape_sec, err);
    if (st) return st;
    if (kind == DFL_GRIDPEER_TRICUBIC && n < 4)
        return dfl_cfg_reject(cfg, sec, "res", err, "expected res >= 4 for tricubic, got %ld", n);
    for (int a = 0; a < 3; a++)
        if (!(o.lo[a] < o.hi[a]))
            return dfl_cfg_reject(cfg, sec, "hi", err, "expected hi > lo on axis %d", a);
    if (!dfl_cfg_has_section(cfg, shape_sec))
        return dfl_cfg_reject(cfg, sec, "shape", err, "no section [%s]", shape_sec);
    o.kind = (dfl_gridpeer_kind)kind;
    o.storage = (dfl_gridpeer_storage)storage;
    o.n = (int)n;
    dfl_shape shape;
    if ((st = dfl_shape_from_cfg(cfg, shape_sec, &shape, err))) return st;
    if (dfl_cfg_validating(cfg)) { /* keys read and checked: no samples (io/config.h) */
        dfl_shape_free(&shape);
        dfl_field_placeholder(3, out);
        return DFL_OK;
    }
    st = dfl_gridpeer_new(&shape, &o, out, err);
    dfl_shape_free(&shape);
    if (st == DFL_E_INPUT) {
        char w[600];
        return dfl_err_prefix(err, "%s", dfl_cfg_where(cfg, sec, "method", w, sizeof w));
    }
    return st;
}
