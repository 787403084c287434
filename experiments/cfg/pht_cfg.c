#include "cfg/pht_cfg.h"

dfl_status dfl_pht_opts_from_cfg(const dfl_cfg *cfg, const char *sec, int dim, dfl_pht_fit_opts *o, dfl_err *err)
{
    (void)cfg;
    (void)sec;
    (void)dim;
    (void)o;
    (void)err;
    return dfl_err_set(err, DFL_E_INTERNAL, "%s: not implemented yet", __func__);
}

dfl_status dfl_pht_source_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_shape *shape, dfl_pht_source **src, dfl_err *err)
{
    (void)cfg;
    (void)sec;
    (void)shape;
    (void)src;
    (void)err;
    return dfl_err_set(err, DFL_E_INTERNAL, "%s: not implemented yet", __func__);
}

dfl_status dfl_pht_field_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out, dfl_err *err)
{
    (void)cfg;
    (void)sec;
    (void)out;
    (void)err;
    return dfl_err_set(err, DFL_E_INTERNAL, "%s: not implemented yet", __func__);
}

