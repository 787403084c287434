#include "pht/fit.h"

const char * dfl_pht_estimator_name(dfl_pht_estimator e)
{
    (void)e;
    return NULL;
}

int dfl_pht_estimator_from_name(const char *name)
{
    (void)name;
    return 0;
}

void dfl_pht_fit_opts_default(int dim, dfl_pht_fit_opts *o)
{
    (void)dim;
    (void)o;
}

dfl_status dfl_pht_fit_opts_check(int dim, const dfl_pht_fit_opts *o, dfl_err *err)
{
    (void)dim;
    (void)o;
    (void)err;
    return dfl_err_set(err, DFL_E_INTERNAL, "%s: not implemented yet", __func__);
}

dfl_status dfl_pht_fit_run(const dfl_pht_source *src, const dfl_pht_fit_opts *o, dfl_pht_fit *out, dfl_err *err)
{
    (void)src;
    (void)o;
    (void)out;
    (void)err;
    return dfl_err_set(err, DFL_E_INTERNAL, "%s: not implemented yet", __func__);
}

dfl_status dfl_pht_fit_uniform(const dfl_pht_source *src, const dfl_pht_fit_opts *o, int level, dfl_pht_fit *out, dfl_err *err)
{
    (void)src;
    (void)o;
    (void)level;
    (void)out;
    (void)err;
    return dfl_err_set(err, DFL_E_INTERNAL, "%s: not implemented yet", __func__);
}

void dfl_pht_fit_free(dfl_pht_fit *f)
{
    (void)f;
}

