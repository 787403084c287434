/* Stub: the full implementation follows. */
#include "curve_cfg.h"

dfl_status dfl_param_shape_from_cfg(const dfl_cfg *cfg, const char *sec, const char *kind_name,
                                    dfl_shape *out, dfl_err *err)
{
    (void)cfg;
    (void)out;
    return dfl_err_set(err, DFL_E_INPUT, "[%s] kind = %s: not implemented yet", sec, kind_name);
}
