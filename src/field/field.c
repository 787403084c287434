#include "field/field.h"

#include <assert.h>
#include <math.h>
#include <string.h>

double dfl_field_eval1(const dfl_field *f, const double *x, double *g)
{
    double v = 0.0;
    f->ops->eval(f->ctx, 1, x, &v, g);
    return v;
}

dfl_status dfl_field_jet(const dfl_field *f, const double *x, const double *dir, int K,
                         dfl_jet *out, dfl_err *err)
{
    return dfl_jet_dir_call(f->ops->jet, f->ctx, "field", f->ops->name, x, dir, K, out, err);
}

int dfl_field_bytes(const dfl_field *f, size_t *out)
{
    if (!f->ops->bytes) return 0;
    *out = f->ops->bytes(f->ctx);
    return 1;
}

void dfl_field_destroy(dfl_field *f)
{
    if (!f) return;
    if (f->ops && f->ops->destroy && f->ctx) f->ops->destroy(f->ctx);
    memset(f, 0, sizeof *f);
}

/* The placeholder's values are NaN, not 0, so that a study that evaluated
 * one by mistake reports non-finite values instead of a plausible table. */
static void placeholder_eval(const void *ctx, size_t m, const double *pts, double *val,
                             double *grad)
{
    const int dim = *(const int *)ctx;
    (void)pts;
    for (size_t i = 0; i < m; i++) {
        val[i] = NAN;
        if (grad)
            for (int j = 0; j < dim; j++) grad[i * (size_t)dim + (size_t)j] = NAN;
    }
}

static const dfl_field_ops placeholder_ops = {"placeholder", placeholder_eval, NULL, NULL, NULL};
static const int placeholder_dims[4] = {0, 1, 2, 3};

void dfl_field_placeholder(int dim, dfl_field *out)
{
    assert(dim == 2 || dim == 3);
    out->dim = dim;
    out->ops = &placeholder_ops;
    out->ctx = (void *)&placeholder_dims[dim];
}
