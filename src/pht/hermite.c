#include "pht/hermite.h"

dfl_status dfl_pht_source_new(const dfl_shape *shape, dfl_pht_source **out, dfl_err *err)
{
    (void)shape;
    (void)out;
    (void)err;
    return dfl_err_set(err, DFL_E_INTERNAL, "%s: not implemented yet", __func__);
}

void dfl_pht_source_free(dfl_pht_source *src)
{
    (void)src;
}

int dfl_pht_source_dim(const dfl_pht_source *src)
{
    (void)src;
    return 0;
}

const dfl_shape * dfl_pht_source_shape(const dfl_pht_source *src)
{
    (void)src;
    return NULL;
}

dfl_status dfl_pht_hermite(const dfl_pht_source *src, const double *x, double *data, int *flags, dfl_err *err)
{
    (void)src;
    (void)x;
    (void)data;
    (void)flags;
    (void)err;
    return dfl_err_set(err, DFL_E_INTERNAL, "%s: not implemented yet", __func__);
}

void dfl_pht_source_eval(const dfl_pht_source *src, size_t m, const double *pts, double *val, double *grad)
{
    (void)src;
    (void)m;
    (void)pts;
    (void)val;
    (void)grad;
}

