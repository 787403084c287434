#include "field/exact.h"

#include <stdlib.h>
#include <string.h>

/* The field's ctx is the shape struct itself, heap-held so the field owns
 * it; dispatch costs one extra indirection per batch, not per point. */

static void exact_eval(const void *ctx, size_t m, const double *pts, double *val, double *grad)
{
    const dfl_shape *s = ctx;
    s->ops->eval(s->impl, m, pts, val, grad);
}

static dfl_status exact_jet(const void *ctx, const double *x, const double *dir, int K,
                            dfl_jet *out, dfl_err *err)
{
    const dfl_shape *s = ctx;
    return s->ops->jet(s->impl, x, dir, K, out, err);
}

static void exact_destroy(void *ctx)
{
    dfl_shape *s = ctx;
    dfl_shape_free(s);
    free(s);
}

static const dfl_field_ops exact_ops = {"exact", exact_eval, exact_jet, exact_destroy, NULL};
static const dfl_field_ops exact_nojet_ops = {"exact", exact_eval, NULL, exact_destroy, NULL};
/* borrowed shapes: nothing to free */
static const dfl_field_ops view_ops = {"exact", exact_eval, exact_jet, NULL, NULL};
static const dfl_field_ops view_nojet_ops = {"exact", exact_eval, NULL, NULL, NULL};

void dfl_field_exact_view(const dfl_shape *shape, dfl_field *out)
{
    out->dim = shape->dim;
    out->ops = shape->ops->jet ? &view_ops : &view_nojet_ops;
    out->ctx = (void *)shape; /* ops only read it; no destroy */
}

dfl_status dfl_field_exact_new(dfl_shape *shape, dfl_field *out, dfl_err *err)
{
    if (!shape || !shape->ops || !shape->impl)
        return dfl_err_set(err, DFL_E_INPUT, "exact field: no shape given");
    dfl_shape *s = malloc(sizeof *s);
    if (!s) return dfl_err_set(err, DFL_E_NOMEM, "exact field: out of memory");
    *s = *shape;
    memset(shape, 0, sizeof *shape);
    out->dim = s->dim;
    out->ops = s->ops->jet ? &exact_ops : &exact_nojet_ops;
    out->ctx = s;
    return DFL_OK;
}

const dfl_shape *dfl_field_exact_shape(const dfl_field *f)
{
    if (!f || (f->ops != &exact_ops && f->ops != &exact_nojet_ops && f->ops != &view_ops &&
               f->ops != &view_nojet_ops))
        return NULL;
    return f->ctx;
}
