#include "rfunc/region.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/hypot.h"
#include "rfunc/trim.h"

dfl_status dfl_rfunc_point_init(int dim, const double *c, dfl_rfunc_point *out, dfl_err *err)
{
    if (dim != 2 && dim != 3)
        return dfl_err_set(err, DFL_E_INPUT, "point: dimension %d (expected 2 or 3)", dim);
    dfl_rfunc_point p;
    memset(&p, 0, sizeof p);
    p.dim = dim;
    for (int j = 0; j < dim; j++) {
        if (!isfinite(c[j])) return dfl_err_set(err, DFL_E_INPUT, "point: non-finite coordinate");
        p.c[j] = c[j];
    }
    *out = p;
    return DFL_OK;
}

double dfl_rfunc_point_eval(const dfl_rfunc_point *p, const double *x, double *grad)
{
    double w[3] = {0, 0, 0};
    for (int j = 0; j < p->dim; j++) w[j] = x[j] - p->c[j];
    const double h = dfl_hypot_vec(p->dim, w);
    if (grad)
        for (int j = 0; j < p->dim; j++) grad[j] = h > 0.0 ? w[j] / h : 0.0;
    return h;
}

dfl_status dfl_rfunc_point_jet(const dfl_rfunc_point *p, const double *x, const double *dir,
                               int K, dfl_jet *out, dfl_err *err)
{
    /* |w + s dir|^2 is an exact quadratic; at x = c it is s^2 |dir|^2. */
    double c[3] = {0, 0, 0};
    for (int j = 0; j < p->dim; j++) {
        const double w = x[j] - p->c[j];
        c[0] += w * w;
        c[1] += 2.0 * w * dir[j];
        c[2] += dir[j] * dir[j];
    }
    dfl_jet q;
    if (c[0] == 0.0) {
        /* At the point: (s |dir|)^2 as a square keeps the relative precision
         * (order K after the root). */
        dfl_jet l;
        dfl_jet_linear(0.0, sqrt(c[2]), K, &l);
        dfl_jet_mul(&l, &l, &q);
    } else {
        dfl_jet_poly(c, 3, K, &q);
    }
    return dfl_jet_sqrt(&q, out, err);
}

dfl_status dfl_rfunc_region_init(const double *v, size_t n, dfl_rfunc_region *out, dfl_err *err)
{
    if (n < 3) return dfl_err_set(err, DFL_E_INPUT, "region: %zu vertices (need >= 3)", n);
    double area2 = 0.0, size = 0.0;
    for (size_t i = 0; i < n; i++) {
        const double *a = v + 2 * i, *b = v + 2 * ((i + 1) % n);
        if (!isfinite(a[0]) || !isfinite(a[1]))
            return dfl_err_set(err, DFL_E_INPUT, "region: non-finite vertex coordinate");
        area2 += a[0] * b[1] - a[1] * b[0];
        size = fmax(size, fmax(fabs(a[0]), fabs(a[1])));
    }
    if (!(fabs(area2) > 0.0))
        return dfl_err_set(err, DFL_E_INPUT, "region: polygon has zero area");
    const double orient = area2 > 0.0 ? 1.0 : -1.0;
    dfl_rfunc_region r;
    memset(&r, 0, sizeof r);
    r.n = n;
    r.v = malloc(2 * n * sizeof *r.v);
    r.m = malloc(2 * n * sizeof *r.m);
    if (!r.v || !r.m) {
        free(r.v);
        free(r.m);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    }
    memcpy(r.v, v, 2 * n * sizeof *r.v);
    for (size_t i = 0; i < n; i++) {
        const double *a = v + 2 * i, *b = v + 2 * ((i + 1) % n), *c = v + 2 * ((i + 2) % n);
        const double ex = b[0] - a[0], ey = b[1] - a[1];
        const double len = hypot(ex, ey);
        /* Strict convexity: every turn has the polygon's orientation. */
        const double turn = ex * (c[1] - b[1]) - ey * (c[0] - b[0]);
        if (!(len > 1e-12 * size) || !(turn * orient > 1e-12 * len * len)) {
            dfl_rfunc_region_free(&r);
            return dfl_err_set(err, DFL_E_INPUT,
                               "region: polygon is not strictly convex at vertex %zu", i + 1);
        }
        /* Left normal for counter-clockwise polygons points inside. */
        r.m[2 * i] = -orient * ey / len;
        r.m[2 * i + 1] = orient * ex / len;
        r.scale = fmax(r.scale, len);
    }
    r.scale = fmax(r.scale, size);
    *out = r;
    return DFL_OK;
}

void dfl_rfunc_region_free(dfl_rfunc_region *r)
{
    if (!r) return;
    free(r->v);
    free(r->m);
    memset(r, 0, sizeof *r);
}

double dfl_rfunc_region_eval(const dfl_rfunc_region *r, const double *x, double *grad)
{
    /* Scaled 2-norm of the violations so far: h = big * sqrt(acc). */
    double big = 0.0, acc = 0.0, g[2] = {0.0, 0.0};
    for (size_t i = 0; i < r->n; i++) {
        const double *a = r->v + 2 * i, *m = r->m + 2 * i;
        const double q = -((x[0] - a[0]) * m[0] + (x[1] - a[1]) * m[1]);
        if (!(q > 0.0)) continue;
        if (q > big) {
            acc = acc * (big / q) * (big / q) + 1.0;
            big = q;
        } else {
            acc += (q / big) * (q / big);
        }
        /* h grad h = sum q grad q, grad q = -m */
        g[0] -= q * m[0];
        g[1] -= q * m[1];
    }
    const double h = big * sqrt(acc);
    if (grad) {
        grad[0] = h > 0.0 ? g[0] / h : 0.0;
        grad[1] = h > 0.0 ? g[1] / h : 0.0;
    }
    return h;
}

dfl_status dfl_rfunc_region_jet(const dfl_rfunc_region *r, const double *x, const double *dir,
                                int K, dfl_jet *out, dfl_err *err)
{
    const double xs = fmax(r->scale, fmax(fabs(x[0]), fabs(x[1])));
    const double dn = hypot(dir[0], dir[1]);
    dfl_jet sum, q, qp;
    dfl_rfunc_jet_zero(&sum);
    for (size_t i = 0; i < r->n; i++) {
        const double *a = r->v + 2 * i, *m = r->m + 2 * i;
        const double q0 = -((x[0] - a[0]) * m[0] + (x[1] - a[1]) * m[1]);
        const double q1 = -(dir[0] * m[0] + dir[1] * m[1]);
        dfl_jet_linear(dfl_rfunc_snap(q0, xs), dfl_rfunc_snap(q1, dn), K, &q);
        dfl_rfunc_jet_pos(&q, &qp);
        dfl_jet_mul(&qp, &qp, &q);
        dfl_jet_add(&sum, &q, &sum);
    }
    return dfl_jet_sqrt(&sum, out, err);
}
