/* Ground-truth fields (see proxy/truth.h). */
#include "proxy/truth.h"

#include <stdlib.h>
#include <string.h>

#include "field/exact.h"
#include "proxy/input_implicit.h"
#include "proxy/input_param.h"

#define CHUNK 64

dfl_status dfl_proxy_truth_exact(dfl_shape *shape, dfl_field *out, dfl_err *err)
{
    if (!shape || shape->dim != 3)
        return dfl_err_set(err, DFL_E_INPUT, "proxy truth: need a 3D shape");
    return dfl_field_exact_new(shape, out, err);
}

static void input_eval(const void *ctx, size_t m, const double *pts, double *val, double *grad)
{
    const dfl_proxy_input *in = ctx;
    dfl_surfpoint o[CHUNK];
    for (size_t i0 = 0; i0 < m; i0 += CHUNK) {
        size_t nb = m - i0 < CHUNK ? m - i0 : CHUNK;
        dfl_proxy_input_query(in, nb, pts + 3 * i0, 0, o, NULL);
        for (size_t k = 0; k < nb; k++) {
            val[i0 + k] = o[k].d;
            if (grad) memcpy(grad + 3 * (i0 + k), o[k].n, 3 * sizeof *grad);
        }
    }
}

static void input_destroy(void *ctx)
{
    dfl_proxy_input_free(ctx);
    free(ctx);
}

static const dfl_field_ops input_ops = {"proxy_truth", input_eval, NULL, input_destroy, NULL};

dfl_status dfl_proxy_truth_input(dfl_proxy_input *in, dfl_field *out, dfl_err *err)
{
    if (!in || !in->query) return dfl_err_set(err, DFL_E_INPUT, "proxy truth: no input");
    dfl_proxy_input *c = malloc(sizeof *c);
    if (!c) {
        dfl_proxy_input_free(in);
        return dfl_err_set(err, DFL_E_NOMEM, "proxy truth: out of memory");
    }
    *c = *in;
    memset(in, 0, sizeof *in);
    out->dim = 3;
    out->ops = &input_ops;
    out->ctx = c;
    return DFL_OK;
}

static dfl_status param_opts(int grid, dfl_param_input_opts *o, dfl_err *err)
{
    dfl_param_input_opts_default(o);
    o->grid = grid ? grid : 64;
    o->max_iter = 100;
    if (o->grid < 16) return dfl_err_set(err, DFL_E_INPUT, "proxy truth: grid %d < 16", grid);
    return DFL_OK;
}

dfl_status dfl_proxy_truth_param(dfl_surface_set *set, int grid, dfl_field *out, dfl_err *err)
{
    dfl_param_input_opts o;
    dfl_status st = param_opts(grid, &o, err);
    if (st != DFL_OK) {
        if (set) dfl_surface_set_free(set);
        return st;
    }
    dfl_proxy_input in;
    if ((st = dfl_proxy_input_param_surfaces(set, &o, &in, err)) != DFL_OK) return st;
    return dfl_proxy_truth_input(&in, out, err);
}

dfl_status dfl_proxy_truth_cone_lateral(const double a[3], const double b[3], double ra,
                                        double rb, int grid, dfl_field *out, dfl_err *err)
{
    dfl_param_input_opts o;
    dfl_status st = param_opts(grid, &o, err);
    if (st != DFL_OK) return st;
    dfl_proxy_input in;
    if ((st = dfl_proxy_input_param_cone(a, b, ra, rb, &o, &in, err)) != DFL_OK) return st;
    return dfl_proxy_truth_input(&in, out, err);
}

dfl_status dfl_proxy_truth_implicit(dfl_implicit **imp, dfl_field *out, dfl_err *err)
{
    dfl_proxy_input in;
    dfl_status st = dfl_proxy_input_implicit(imp, DFL_IMPLICIT_FOOT_ROBUST, &in, err);
    if (st != DFL_OK) return st;
    return dfl_proxy_truth_input(&in, out, err);
}
