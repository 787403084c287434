/* One corner evaluation (decode + distance + clip) serves all filters; the
 * blends only differ in their weight function, so trilinear and Hermite
 * share one loop with the weight picked once per batch. */
#include "proxy/filter.h"

#include <math.h>

#include "core/isa.h"
#include "core/vec.h"

DFL_NAMES_DEFINE(dfl_proxy_filter, DFL_PROXY_FILTER_LIST, DFL_PROXY_FILTER_COUNT,
                 dfl_proxy_filter_names, dfl_proxy_filter_name, dfl_proxy_filter_parse,
                 "filter")

void dfl_proxy_filter_opts_default(dfl_proxy_filter f, const dfl_proxy_grid *g,
                                   dfl_proxy_filter_opts *o)
{
    o->filter = f;
    o->clip = f == DFL_PROXY_NEAREST ? dfl_proxy_cell_size(g) : 0.0;
    o->is_signed = 0;
}

dfl_status dfl_proxy_filter_check(const dfl_proxy_grid *g, const dfl_proxy_filter_opts *o,
                                  dfl_err *err)
{
    if ((unsigned)o->filter >= DFL_PROXY_FILTER_COUNT)
        return dfl_err_set(err, DFL_E_INPUT, "proxy filter: unknown filter %d", (int)o->filter);
    if (!(o->clip >= 0) || !isfinite(o->clip))
        return dfl_err_set(err, DFL_E_INPUT, "proxy filter: clip radius %g (expected >= 0)",
                           o->clip);
    if (o->is_signed && !g->has_inside)
        return dfl_err_set(err, DFL_E_INPUT,
                           "proxy filter: signed output needs an input with an inside");
    return DFL_OK;
}

DFL_ISA_BODY double clipped(const dfl_proxy_geom *pgp, int order, double clip,
                             const double x[3], double *grad)
{
    const dfl_proxy_geom *pg = pgp;
    double phi = dfl_proxy_geom_eval(pg, order, x, grad);
    if (clip > 0) {
        const double v[3] = {x[0] - pg->p[0], x[1] - pg->p[1], x[2] - pg->p[2]};
        /* |x - p| - rho > |phi|, without a square root when it is not */
        const double lim = clip + fabs(phi), r2 = dfl_vec3_dot(v, v);
        if (r2 > lim * lim) {
            const double r = sqrt(r2), ball = r - clip;
            const double s = phi < 0 ? -1.0 : 1.0;
            phi = s * fmax(ball, fabs(phi));
            if (grad)
                for (int j = 0; j < 3; j++) grad[j] = s * v[j] / r;
        }
    }
    return phi;
}

double dfl_proxy_proxy_dist(const dfl_proxy_grid *g, size_t c, double clip, const double x[3],
                            double *grad)
{
    dfl_proxy_geom pg;
    dfl_proxy_cell_decode(g, c, &pg);
    return clipped(&pg, g->order, clip, x, grad);
}

/* D of cell (i, j, k) */
DFL_ISA_BODY double dist_ijk(const dfl_proxy_grid *g, size_t i, size_t j, size_t k,
                              double clip, const double x[3], double *grad)
{
    dfl_proxy_geom pg;
    dfl_proxy_cell_decode_ijk(g, i, j, k, &pg);
    return clipped(&pg, g->order, clip, x, grad);
}

DFL_ISA_BODY void fold(int is_signed, double *val, double *grad)
{
    if (is_signed || *val >= 0) return;
    *val = -*val;
    if (grad)
        for (int j = 0; j < 3; j++) grad[j] = -grad[j];
}

DFL_ISA_BODY void nearest_cell(const dfl_proxy_grid *g, const double x[3], size_t idx[3])
{
    for (int j = 0; j < 3; j++) {
        const double s = floor((x[j] - g->lo[j]) / g->h[j]);
        idx[j] = s < 0 ? 0 : s > g->res - 1 ? (size_t)g->res - 1 : (size_t)s;
    }
}

/* weight of the upper neighbour and its derivative in t */
DFL_ISA_BODY void weight(dfl_proxy_filter f, int order, double t, double *w, double *dw)
{
    if (f == DFL_PROXY_TRILINEAR) {
        *w = t;
        *dw = 1.0;
    } else if (order == 1) {
        *w = t * t * (3.0 - 2.0 * t);
        *dw = 6.0 * t * (1.0 - t);
    } else {
        *w = t * t * t * (10.0 + t * (-15.0 + 6.0 * t));
        const double u = t * (1.0 - t);
        *dw = 30.0 * u * u;
    }
}

DFL_ISA_BODY double blend(const dfl_proxy_grid *g, const dfl_proxy_filter_opts *o, const double x[3],
                    double *grad)
{
    const size_t n = (size_t)g->res;
    size_t i0[3], i1[3];
    double w[3][2], dw[3][2];
    for (int j = 0; j < 3; j++) {
        const double s = (x[j] - g->lo[j]) / g->h[j] - 0.5;
        double t, dt = 1.0 / g->h[j];
        if (g->res == 1) {
            i0[j] = 0;
            t = 0;
            dt = 0;
        } else if (s <= 0) {
            i0[j] = 0;
            t = 0;
            dt = 0;
        } else if (s >= g->res - 1) {
            i0[j] = n - 2;
            t = 1;
            dt = 0;
        } else {
            double f = floor(s);
            if (f > g->res - 2) f = g->res - 2;
            i0[j] = (size_t)f;
            t = s - f;
        }
        i1[j] = g->res == 1 ? 0 : i0[j] + 1;
        double wt, dwt;
        weight(o->filter, g->order, t, &wt, &dwt);
        w[j][0] = 1.0 - wt;
        w[j][1] = wt;
        dw[j][0] = -dwt * dt;
        dw[j][1] = dwt * dt;
    }
    double val = 0, gr[3] = {0, 0, 0};
    for (int q = 0; q < 8; q++) {
        const int a = q & 1, b = (q >> 1) & 1, c = (q >> 2) & 1;
        const double W = w[0][a] * w[1][b] * w[2][c];
        if (W == 0 && !grad) continue;
        double gd[3];
        double d = dist_ijk(g, a ? i1[0] : i0[0], b ? i1[1] : i0[1], c ? i1[2] : i0[2], o->clip,
                            x, grad ? gd : NULL);
        if (!o->is_signed && d < 0) {
            d = -d;
            if (grad)
                for (int j = 0; j < 3; j++) gd[j] = -gd[j];
        }
        val += W * d;
        if (grad) {
            const double gw[3] = {dw[0][a] * w[1][b] * w[2][c], w[0][a] * dw[1][b] * w[2][c],
                                  w[0][a] * w[1][b] * dw[2][c]};
            for (int j = 0; j < 3; j++) gr[j] += W * gd[j] + d * gw[j];
        }
    }
    if (grad)
        for (int j = 0; j < 3; j++) grad[j] = gr[j];
    return val;
}

/* The query loop, compiled per ISA (core/isa.h): same bytes on each. */
DFL_ISA_BODY void queries_body(const dfl_proxy_grid *g, const dfl_proxy_filter_opts *o, size_t m,
                               const double *x, double *val, double *grad)
{
    if (o->filter == DFL_PROXY_NEAREST) {
        for (size_t i = 0; i < m; i++) {
            double *gi = grad ? grad + 3 * i : NULL;
            size_t c[3];
            nearest_cell(g, x + 3 * i, c);
            val[i] = dist_ijk(g, c[0], c[1], c[2], o->clip, x + 3 * i, gi);
            fold(o->is_signed, &val[i], gi);
        }
        return;
    }
    for (size_t i = 0; i < m; i++) val[i] = blend(g, o, x + 3 * i, grad ? grad + 3 * i : NULL);
}
DFL_ISA_KERNEL(queries,
               (const dfl_proxy_grid *g, const dfl_proxy_filter_opts *o, size_t m,
                const double *x, double *val, double *grad),
               (g, o, m, x, val, grad))

void dfl_proxy_filter_eval(const dfl_proxy_grid *g, const dfl_proxy_filter_opts *o, size_t m,
                           const double *x, double *val, double *grad)
{
    queries(g, o, m, x, val, grad);
}
