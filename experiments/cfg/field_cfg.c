#include "cfg/field_cfg.h"

#include "field/exact.h"
#include "geom/shape.h"
#include "cfg/rfunc_cfg.h"
#include "cfg/shape_cfg.h"

dfl_status dfl_field_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out, dfl_err *err)
{
    static const char *const kinds[] = {"exact", "rfunc"};
    int kind;
    dfl_status st = dfl_cfg_enum(cfg, sec, "kind", kinds, 2, &kind, err);
    if (st != DFL_OK) return st;
    if (kind == 0) {
        dfl_shape shape;
        st = dfl_shape_from_cfg(cfg, "shape", &shape, err);
        if (st != DFL_OK) return st;
        st = dfl_field_exact_new(&shape, out, err);
        if (st != DFL_OK) dfl_shape_free(&shape);
        return st;
    }
    return dfl_rfunc_field_from_cfg(cfg, sec, out, err);
}
