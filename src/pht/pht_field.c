/* PHT spline as a field (pht_field.h). */
#include "pht/pht_field.h"

#include <stddef.h>

static void pht_eval(const void *ctx, size_t m, const double *pts, double *val, double *grad)
{
    dfl_pht_eval(ctx, m, pts, val, grad, NULL);
}

static void pht_destroy(void *ctx) { dfl_pht_spline_free(ctx); }

static size_t pht_bytes(const void *ctx) { return dfl_pht_spline_bytes(ctx); }

static const dfl_field_ops pht_ops = {"pht", pht_eval, dfl_pht_jet, pht_destroy, pht_bytes};

dfl_status dfl_pht_field_new(dfl_pht_spline **s, dfl_field *out, dfl_err *err)
{
    if (!s || !*s) return dfl_err_set(err, DFL_E_INPUT, "PHT field: no spline");
    out->dim = dfl_pht_spline_dim(*s);
    out->ops = &pht_ops;
    out->ctx = *s;
    *s = NULL;
    return DFL_OK;
}

const dfl_pht_spline *dfl_pht_field_spline(const dfl_field *f)
{
    return f && f->ops == &pht_ops ? f->ctx : NULL;
}
