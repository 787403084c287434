#include "pht/validate.h"

dfl_status dfl_pht_medial_band(const dfl_shape *shape, size_t m, const double *pts, double w, unsigned char *near, dfl_err *err)
{
    (void)shape;
    (void)m;
    (void)pts;
    (void)w;
    (void)near;
    (void)err;
    return dfl_err_set(err, DFL_E_INTERNAL, "%s: not implemented yet", __func__);
}

dfl_status dfl_pht_validate_points(const dfl_field *f, const dfl_shape *shape, size_t m, const double *pts, double w, dfl_pht_val *out, dfl_err *err)
{
    (void)f;
    (void)shape;
    (void)m;
    (void)pts;
    (void)w;
    (void)out;
    (void)err;
    return dfl_err_set(err, DFL_E_INTERNAL, "%s: not implemented yet", __func__);
}

dfl_status dfl_pht_validate_grid(const dfl_field *f, const dfl_shape *shape, const dfl_pht_val_opts *o, dfl_pht_val *out, dfl_err *err)
{
    (void)f;
    (void)shape;
    (void)o;
    (void)out;
    (void)err;
    return dfl_err_set(err, DFL_E_INTERNAL, "%s: not implemented yet", __func__);
}

