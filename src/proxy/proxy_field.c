#include "proxy/proxy_field.h"

#include "proxy/store.h"

#include <stdlib.h>
#include <string.h>

typedef struct pf_ctx {
    dfl_proxy_grid grid;
    dfl_proxy_filter_opts opts;
} pf_ctx;

static void pf_eval(const void *ctx, size_t m, const double *pts, double *val, double *grad)
{
    const pf_ctx *c = ctx;
    dfl_proxy_filter_eval(&c->grid, &c->opts, m, pts, val, grad);
}

static void pf_destroy(void *ctx)
{
    pf_ctx *c = ctx;
    dfl_proxy_grid_free(&c->grid);
    free(c);
}

/* Stored: the cells' scalars in their storage, and the sign byte per cell
 * an order-1 grid with an inside keeps. */
static size_t pf_bytes(const void *ctx)
{
    const pf_ctx *c = ctx;
    return dfl_proxy_grid_scalars(&c->grid) * dfl_proxy_storage_size(c->grid.storage) +
           (c->grid.side ? c->grid.ncells : 0);
}

static const dfl_field_ops pf_ops = {"proxy", pf_eval, NULL, pf_destroy, pf_bytes};

dfl_status dfl_proxy_field_new(dfl_proxy_grid *grid, const dfl_proxy_filter_opts *o,
                               dfl_field *out, dfl_err *err)
{
    if (!grid || !grid->data || !o)
        return dfl_err_set(err, DFL_E_INPUT, "proxy field: no grid or options");
    dfl_status st = dfl_proxy_filter_check(grid, o, err);
    if (st) return st;
    pf_ctx *c = malloc(sizeof *c);
    if (!c) return dfl_err_set(err, DFL_E_NOMEM, "proxy field: out of memory");
    c->grid = *grid;
    c->opts = *o;
    memset(grid, 0, sizeof *grid);
    out->dim = 3;
    out->ops = &pf_ops;
    out->ctx = c;
    return DFL_OK;
}

const dfl_proxy_grid *dfl_proxy_field_grid(const dfl_field *f)
{
    return f && f->ops == &pf_ops ? &((const pf_ctx *)f->ctx)->grid : NULL;
}

const dfl_proxy_filter_opts *dfl_proxy_field_opts(const dfl_field *f)
{
    return f && f->ops == &pf_ops ? &((const pf_ctx *)f->ctx)->opts : NULL;
}
