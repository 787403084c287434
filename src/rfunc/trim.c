#include "rfunc/trim.h"

#include <assert.h>
#include <math.h>
#include <stddef.h>

#include "core/hypot.h"

/* Jet helpers ----------------------------------------------------------- */

int dfl_rfunc_jet_sign(const dfl_jet *a)
{
    if (a->zero) return 0;
    return a->c[0] > 0.0 ? 1 : -1;
}

void dfl_rfunc_jet_zero(dfl_jet *out)
{
    /* An empty polynomial is zero to every stored order: the exact zero. */
    dfl_jet_poly(NULL, 0, DFL_JET_MAX, out);
}

void dfl_rfunc_jet_pos(const dfl_jet *a, dfl_jet *out)
{
    /* max(a, 0) for small s > 0 is a branch choice by the leading sign; a
     * zero jet stays the same zero (its precision is kept). */
    if (dfl_rfunc_jet_sign(a) > 0 || a->zero)
        *out = *a;
    else
        dfl_rfunc_jet_zero(out);
}

double dfl_rfunc_snap(double v, double scale)
{
    return fabs(v) <= DFL_RFUNC_SNAP_TOL * scale ? 0.0 : v;
}

/* Composition ----------------------------------------------------------- */

double dfl_rfunc_compose(int dim, int smooth, double fa, const double *hgF, double t,
                         const double *gt, double *gh)
{
    assert(fa >= 0.0);
    double h;
    if (!smooth) {
        const double m = t < 0.0 ? -t : 0.0;
        h = dfl_hypot2(fa, m);
        if (gh) {
            /* h grad h = f grad f + m grad m, grad m = -grad t where t < 0. */
            /* Near the domain's edge (rfunc/domain.h: |t| up to 4e300)
             * t grad t overflows; divide first there (elsewhere the plain
             * form, whose rounding the studies' numbers were made with). */
            const int big = fabs(t) > 1e150;
            for (int j = 0; j < dim; j++) {
                if (big) {
                    gh[j] = hgF[j] / h + (t < 0.0 ? (t / h) * gt[j] : 0.0);
                    continue;
                }
                double num = hgF[j] + (t < 0.0 ? t * gt[j] : 0.0);
                gh[j] = h > 0.0 ? num / h : 0.0;
            }
        }
        return h;
    }
    /* g = sqrt(t^2 + F^2) - t, written without cancellation for t > 0. */
    const double F = fa * fa;
    const double r = dfl_hypot2(t, F);
    /* F * F overflows beyond F ~ 1e154 (the domain's edge): F (F / (r + t)) there. */
    const double g = t > 0.0 ? (F > 1e150 ? F * (F / (r + t)) : F * F / (r + t)) : r - t;
    h = dfl_hypot2(fa, 0.5 * g);
    if (gh) {
        /* grad g = (t grad t + F grad F) / r - grad t = (-g grad t + F grad F) / r
         * (no cancellation); h grad h = grad F / 2 + g grad g / 4. */
        for (int j = 0; j < dim; j++) {
            double gg = r > 0.0 ? (-g * gt[j] + 2.0 * F * hgF[j]) / r : 0.0;
            double num = hgF[j] + 0.25 * g * gg;
            gh[j] = h > 0.0 ? num / h : 0.0;
        }
    }
    return h;
}

dfl_status dfl_rfunc_compose_jet(int smooth, const dfl_jet *F, const dfl_jet *t, dfl_jet *out,
                                 dfl_err *err)
{
    dfl_jet h2, m, tmp;
    if (!smooth) {
        dfl_jet mt;
        dfl_jet_neg(t, &mt);
        dfl_rfunc_jet_pos(&mt, &m);
        dfl_jet_mul(&m, &m, &tmp);
        dfl_jet_add(F, &tmp, &h2);
        return dfl_jet_sqrt(&h2, out, err);
    }
    dfl_jet F2, tt, r, g;
    dfl_status st;
    dfl_jet_mul(F, F, &F2);
    dfl_jet_mul(t, t, &tt);
    dfl_jet_add(&tt, &F2, &tmp);
    if ((st = dfl_jet_sqrt(&tmp, &r, err)) != DFL_OK) return st;
    if (dfl_rfunc_jet_sign(t) > 0) {
        /* r - t would leave rounding residue in the low orders; F^2/(r+t)
         * has the exact valuation 4 v(f). */
        dfl_jet_add(&r, t, &tmp);
        if ((st = dfl_jet_div(&F2, &tmp, &g, err)) != DFL_OK) return st;
    } else {
        dfl_jet_sub(&r, t, &g);
    }
    dfl_jet_mul(&g, &g, &tmp);
    dfl_jet_scale(&tmp, 0.25, &tmp);
    dfl_jet_add(F, &tmp, &h2);
    return dfl_jet_sqrt(&h2, out, err);
}

/* R0-conjunction --------------------------------------------------------- */

double dfl_rfunc_conj0(double x, double y, double c, double *dx, double *dy, double *dc)
{
    assert(c >= 0.0);
    const double r = sqrt(x * x + y * y + c);
    const double s = x + y;
    double v = s > 0.0 ? (2.0 * x * y - c) / (s + r) : s - r;
    if (r > 0.0) {
        if (dx) *dx = 1.0 - x / r;
        if (dy) *dy = 1.0 - y / r;
        if (dc) *dc = -0.5 / r;
    } else {
        const double b = 1.0 - 1.0 / sqrt(2.0);
        if (dx) *dx = b;
        if (dy) *dy = b;
        if (dc) *dc = 0.0;
    }
    return v;
}

dfl_status dfl_rfunc_conj0_jet(const dfl_jet *x, const dfl_jet *y, const dfl_jet *c,
                               dfl_jet *out, dfl_err *err)
{
    dfl_jet q, tmp, r, s;
    dfl_status st;
    dfl_jet_mul(x, x, &q);
    dfl_jet_mul(y, y, &tmp);
    dfl_jet_add(&q, &tmp, &q);
    if (c) dfl_jet_add(&q, c, &q);
    if ((st = dfl_jet_sqrt(&q, &r, err)) != DFL_OK) return st;
    dfl_jet_add(x, y, &s);
    if (dfl_rfunc_jet_sign(&s) > 0) {
        dfl_jet num, den;
        dfl_jet_mul(x, y, &num);
        dfl_jet_scale(&num, 2.0, &num);
        if (c) dfl_jet_sub(&num, c, &num);
        dfl_jet_add(&s, &r, &den);
        return dfl_jet_div(&num, &den, out, err);
    }
    dfl_jet_sub(&s, &r, out);
    return DFL_OK;
}
