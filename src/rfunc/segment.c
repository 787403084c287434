#include "rfunc/segment.h"

#include <assert.h>
#include <math.h>
#include <string.h>

#include "core/hypot.h"
#include "core/vec.h"
#include "rfunc/domain.h"
#include "rfunc/trim.h"

static double amax(int dim, const double *u)
{
    double m = 0.0;
    for (int j = 0; j < dim; j++) m = fmax(m, fabs(u[j]));
    return m;
}

DFL_NAMES_DEFINE(dfl_rfunc_trim, DFL_RFUNC_TRIM_LIST, DFL_RFUNC_TRIM_COUNT, dfl_rfunc_trim_names,
                 dfl_rfunc_trim_name, dfl_rfunc_trim_parse, "trim")

static int in_list(dfl_rfunc_trim t) { return (int)t >= 0 && (int)t < DFL_RFUNC_TRIM_COUNT; }

/* The list's properties by code: smooth, strip. */
#define PROPS_(code, name, smooth, strip) [code] = {smooth, strip},
static const unsigned char trim_props[DFL_RFUNC_TRIM_COUNT][2] = {DFL_RFUNC_TRIM_LIST(PROPS_)};
#undef PROPS_

int dfl_rfunc_trim_smooth(dfl_rfunc_trim trim) { return in_list(trim) ? trim_props[trim][0] : 0; }

int dfl_rfunc_trim_strip(dfl_rfunc_trim trim) { return in_list(trim) ? trim_props[trim][1] : 0; }

dfl_status dfl_rfunc_seg_init(int dim, const double *a, const double *b, dfl_rfunc_trim trim,
                              dfl_rfunc_seg *out, dfl_err *err)
{
    if (dim != 2 && dim != 3)
        return dfl_err_set(err, DFL_E_INPUT, "segment: dimension %d (expected 2 or 3)", dim);
    if (!in_list(trim))
        return dfl_err_set(err, DFL_E_INPUT, "segment: unknown trim %d", (int)trim);
    for (int j = 0; j < dim; j++)
        if (!isfinite(a[j]) || !isfinite(b[j]))
            return dfl_err_set(err, DFL_E_INPUT, "segment: non-finite end point coordinate");
    dfl_rfunc_seg s;
    memset(&s, 0, sizeof s);
    s.dim = dim;
    s.trim = trim;
    double ab[3] = {0, 0, 0};
    for (int j = 0; j < dim; j++) {
        s.a[j] = a[j];
        s.b[j] = b[j];
        ab[j] = b[j] - a[j];
    }
    s.d = sqrt(dfl_vecn_dot(dim, ab, ab));
    const double size = fmax(amax(dim, a), amax(dim, b));
    if (!(s.d > 1e-12 * size) || s.d == 0.0)
        return dfl_err_set(err, DFL_E_INPUT,
                           "degenerate segment: end points coincide (length %g)", s.d);
    if (!(s.d >= DFL_RFUNC_LEN_MIN))
        return dfl_err_set(err, DFL_E_INPUT,
                           "segment of length %g, below the rfunc fields' smallest length %g"
                           " (rfunc/domain.h)",
                           s.d, DFL_RFUNC_LEN_MIN);
    for (int j = 0; j < dim; j++) s.e[j] = ab[j] / s.d;
    if (dim == 2) {
        /* eq. 2: f = (x - a) . (y2 - y1, -(x2 - x1)) / d */
        s.n1[0] = s.e[1];
        s.n1[1] = -s.e[0];
    } else {
        /* Cross e with the axis it is least aligned with: well conditioned. */
        int k = 0;
        for (int j = 1; j < 3; j++)
            if (fabs(s.e[j]) < fabs(s.e[k])) k = j;
        double ax[3] = {0, 0, 0};
        ax[k] = 1.0;
        double c[3] = {s.e[1] * ax[2] - s.e[2] * ax[1], s.e[2] * ax[0] - s.e[0] * ax[2],
                       s.e[0] * ax[1] - s.e[1] * ax[0]};
        double cn = sqrt(dfl_vecn_dot(3, c, c));
        for (int j = 0; j < 3; j++) s.n1[j] = c[j] / cn;
        s.n2[0] = s.e[1] * s.n1[2] - s.e[2] * s.n1[1];
        s.n2[1] = s.e[2] * s.n1[0] - s.e[0] * s.n1[2];
        s.n2[2] = s.e[0] * s.n1[1] - s.e[1] * s.n1[0];
    }
    s.scale = fmax(size, s.d);
    *out = s;
    return DFL_OK;
}

/* |f| and grad(f^2)/2 of the carrier. */
static double carrier(const dfl_rfunc_seg *s, const double *wa, double *hgF)
{
    if (s->dim == 2) {
        const double f = wa[0] * s->n1[0] + wa[1] * s->n1[1];
        hgF[0] = f * s->n1[0];
        hgF[1] = f * s->n1[1];
        return fabs(f);
    }
    const double s1 = dfl_vecn_dot(3, wa, s->n1), s2 = dfl_vecn_dot(3, wa, s->n2);
    for (int j = 0; j < 3; j++) hgF[j] = s1 * s->n1[j] + s2 * s->n2[j];
    return dfl_hypot2(s1, s2);
}

double dfl_rfunc_seg_line(const dfl_rfunc_seg *s, const double *x, double *grad)
{
    double wa[3], hgF[3];
    for (int j = 0; j < s->dim; j++) wa[j] = x[j] - s->a[j];
    if (s->dim == 2) {
        const double f = wa[0] * s->n1[0] + wa[1] * s->n1[1];
        if (grad) {
            grad[0] = s->n1[0];
            grad[1] = s->n1[1];
        }
        return f;
    }
    const double fa = carrier(s, wa, hgF);
    if (grad)
        for (int j = 0; j < 3; j++) grad[j] = fa > 0.0 ? hgF[j] / fa : 0.0;
    return fa;
}

static double trim_eval(const dfl_rfunc_seg *s, const double *wa, const double *wb, double *gt)
{
    const int dim = s->dim;
    if (!dfl_rfunc_trim_strip(s->trim)) {
        for (int j = 0; j < dim; j++) gt[j] = -(wa[j] + wb[j]) / s->d;
        return -dfl_vecn_dot(dim, wa, wb) / s->d;
    }
    const double p1 = dfl_vecn_dot(dim, wa, s->e), p2 = -dfl_vecn_dot(dim, wb, s->e);
    double dx, dy;
    const double t = dfl_rfunc_conj0(p1, p2, 0.0, &dx, &dy, NULL);
    for (int j = 0; j < dim; j++) gt[j] = (dx - dy) * s->e[j];
    return t;
}

double dfl_rfunc_seg_trim(const dfl_rfunc_seg *s, const double *x, double *grad)
{
    double wa[3], wb[3], gt[3];
    for (int j = 0; j < s->dim; j++) {
        wa[j] = x[j] - s->a[j];
        wb[j] = x[j] - s->b[j];
    }
    const double t = trim_eval(s, wa, wb, gt);
    if (grad)
        for (int j = 0; j < s->dim; j++) grad[j] = gt[j];
    return t;
}

double dfl_rfunc_seg_eval(const dfl_rfunc_seg *s, const double *x, double *grad)
{
    double wa[3], wb[3], gt[3], hgF[3];
    for (int j = 0; j < s->dim; j++) {
        wa[j] = x[j] - s->a[j];
        wb[j] = x[j] - s->b[j];
    }
    const double fa = carrier(s, wa, hgF);
    const double t = trim_eval(s, wa, wb, gt);
    return dfl_rfunc_compose(s->dim, dfl_rfunc_trim_smooth(s->trim), fa, hgF, t, gt, grad);
}

/* Jet of a linear function c0 + c1 s whose constant vanishes on a line or
 * plane and whose slope vanishes along it: both snapped. */
static void snapped_linear(double c0, double scale0, double c1, double scale1, int K,
                           dfl_jet *out)
{
    dfl_jet_linear(dfl_rfunc_snap(c0, scale0), dfl_rfunc_snap(c1, scale1), K, out);
}

dfl_status dfl_rfunc_seg_jet(const dfl_rfunc_seg *s, const double *x, const double *dir, int K,
                             dfl_jet *out, dfl_err *err)
{
    assert(K >= 0 && K <= DFL_JET_MAX);
    const int dim = s->dim;
    double wa[3], wb[3];
    for (int j = 0; j < dim; j++) {
        wa[j] = x[j] - s->a[j];
        wb[j] = x[j] - s->b[j];
    }
    const double xs = fmax(s->scale, amax(dim, x));
    const double dn = sqrt(dfl_vecn_dot(dim, dir, dir));
    dfl_jet F, t, tmp;

    /* Carrier: F = f^2 (2D) or s^2 + q^2 (3D) from exactly linear pieces. */
    snapped_linear(dfl_vecn_dot(dim, wa, s->n1), xs, dfl_vecn_dot(dim, dir, s->n1), dn, K, &tmp);
    dfl_jet_mul(&tmp, &tmp, &F);
    if (dim == 3) {
        dfl_jet q2;
        snapped_linear(dfl_vecn_dot(dim, wa, s->n2), xs, dfl_vecn_dot(dim, dir, s->n2), dn, K,
                       &tmp);
        dfl_jet_mul(&tmp, &tmp, &q2);
        dfl_jet_add(&F, &q2, &F);
    }

    dfl_status st;
    if (!dfl_rfunc_trim_strip(s->trim)) {
        /* t(x + s dir) = -(wa.wb + s dir.(wa + wb) + s^2 |dir|^2) / d */
        double wab = 0.0, dw = 0.0;
        for (int j = 0; j < dim; j++) {
            wab += wa[j] * wb[j];
            dw += dir[j] * (wa[j] + wb[j]);
        }
        const double wsum = sqrt(dfl_vecn_dot(dim, wa, wa)) + sqrt(dfl_vecn_dot(dim, wb, wb));
        double c[3];
        c[0] = -dfl_rfunc_snap(wab, xs * wsum) / s->d;
        c[1] = -dfl_rfunc_snap(dw, dn * wsum) / s->d;
        c[2] = -(dn * dn) / s->d;
        dfl_jet_poly(c, 3, K, &t);
    } else {
        dfl_jet p1, p2;
        const double de = dfl_vecn_dot(dim, dir, s->e);
        snapped_linear(dfl_vecn_dot(dim, wa, s->e), xs, de, dn, K, &p1);
        snapped_linear(-dfl_vecn_dot(dim, wb, s->e), xs, -de, dn, K, &p2);
        if ((st = dfl_rfunc_conj0_jet(&p1, &p2, NULL, &t, err)) != DFL_OK) return st;
    }
    return dfl_rfunc_compose_jet(dfl_rfunc_trim_smooth(s->trim), &F, &t, out, err);
}
