#include "pht/spline.h"

void dfl_pht_resolve(const dfl_tmesh *m, double *data)
{
    (void)m;
    (void)data;
}

void dfl_pht_cell_poly(int dim, const double *lo, const double *hi, const double *corner, double *coef)
{
    (void)dim;
    (void)lo;
    (void)hi;
    (void)corner;
    (void)coef;
}

dfl_status dfl_pht_spline_new(const dfl_tmesh *m, const double *data, dfl_pht_spline **out, dfl_err *err)
{
    (void)m;
    (void)data;
    (void)out;
    (void)err;
    return dfl_err_set(err, DFL_E_INTERNAL, "%s: not implemented yet", __func__);
}

void dfl_pht_spline_free(dfl_pht_spline *s)
{
    (void)s;
}

int dfl_pht_spline_dim(const dfl_pht_spline *s)
{
    (void)s;
    return 0;
}

size_t dfl_pht_spline_ncells(const dfl_pht_spline *s)
{
    (void)s;
    return 0;
}

size_t dfl_pht_spline_nbase(const dfl_pht_spline *s)
{
    (void)s;
    return 0;
}

size_t dfl_pht_spline_dofs(const dfl_pht_spline *s)
{
    (void)s;
    return 0;
}

size_t dfl_pht_spline_bytes(const dfl_pht_spline *s)
{
    (void)s;
    return 0;
}

void dfl_pht_spline_box(const dfl_pht_spline *s, double *lo, double *hi)
{
    (void)s;
    (void)lo;
    (void)hi;
}

size_t dfl_pht_spline_locate(const dfl_pht_spline *s, const double *x, const double *dir)
{
    (void)s;
    (void)x;
    (void)dir;
    return 0;
}

const double * dfl_pht_spline_cell(const dfl_pht_spline *s, size_t i, double *lo, double *hi, int *level)
{
    (void)s;
    (void)i;
    (void)lo;
    (void)hi;
    (void)level;
    return NULL;
}

void dfl_pht_eval(const dfl_pht_spline *s, size_t m, const double *pts, double *val, double *grad, double *hess)
{
    (void)s;
    (void)m;
    (void)pts;
    (void)val;
    (void)grad;
    (void)hess;
}

dfl_status dfl_pht_jet(const void *spline, const double *x, const double *dir, int K, dfl_jet *out, dfl_err *err)
{
    (void)spline;
    (void)x;
    (void)dir;
    (void)K;
    (void)out;
    (void)err;
    return dfl_err_set(err, DFL_E_INTERNAL, "%s: not implemented yet", __func__);
}

