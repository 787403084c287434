#include "proxy/input.h"

#include <math.h>
#include <string.h>

dfl_status dfl_proxy_input_query(const dfl_proxy_input *in, size_t m, const double *x,
                                 int need_curv, dfl_surfpoint *out, dfl_err *err)
{
    if (!in || !in->query)
        return dfl_err_set(err, DFL_E_INPUT, "proxy input: no query function");
    return in->query(in->ctx, m, x, need_curv, out, err);
}

void dfl_proxy_input_free(dfl_proxy_input *in)
{
    if (!in) return;
    if (in->destroy && in->ctx) in->destroy(in->ctx);
    memset(in, 0, sizeof *in);
}

void dfl_curvature_set_nan(dfl_curvature *c)
{
    c->k1 = c->k2 = c->K = c->H = NAN;
    for (int j = 0; j < 3; j++) c->e1[j] = c->e2[j] = c->n[j] = NAN;
}
