#include "field/field.h"

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
