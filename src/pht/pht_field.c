#include "pht/pht_field.h"

dfl_status dfl_pht_field_new(dfl_pht_spline **s, dfl_field *out, dfl_err *err)
{
    (void)s;
    (void)out;
    (void)err;
    return dfl_err_set(err, DFL_E_INTERNAL, "%s: not implemented yet", __func__);
}

const dfl_pht_spline * dfl_pht_field_spline(const dfl_field *f)
{
    (void)f;
    return NULL;
}

