/* CSG of SDFs: exact min/max and the polynomial smooth variants. */
#include "geom/shape_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- CSG ----------------------------------------------------------------- */

typedef struct csg {
    dfl_csg_op op;
    double k;
    dfl_shape a, b;
} csg;

double dfl_csg_smin(double a, double b, double k)
{
    double h = 0.5 + 0.5 * (b - a) / k;
    h = h < 0.0 ? 0.0 : (h > 1.0 ? 1.0 : h);
    return b * (1.0 - h) + a * h - k * h * (1.0 - h);
}

/* Sign flips that reduce every op to min: union = min(a, b),
 * intersection = -min(-a, -b), difference = -min(-a, b). */
static void csg_signs(dfl_csg_op op, double *sa, double *sb, double *so)
{
    switch (op) {
    case DFL_CSG_UNION:
    case DFL_CSG_SMOOTH_UNION: *sa = 1; *sb = 1; *so = 1; break;
    case DFL_CSG_INTERSECTION:
    case DFL_CSG_SMOOTH_INTERSECTION: *sa = -1; *sb = -1; *so = -1; break;
    default: *sa = -1; *sb = 1; *so = -1; break;
    }
}

static int csg_smooth(dfl_csg_op op)
{
    return op == DFL_CSG_SMOOTH_UNION || op == DFL_CSG_SMOOTH_INTERSECTION ||
           op == DFL_CSG_SMOOTH_DIFFERENCE;
}

#define CSG_CHUNK 64

static void csg_eval(const void *impl, size_t m, const double *pts, double *val, double *grad)
{
    const csg *c = impl;
    const int n = c->a.dim;
    double sa, sb, so;
    csg_signs(c->op, &sa, &sb, &so);
    const int smooth = csg_smooth(c->op);
    double va[CSG_CHUNK], vb[CSG_CHUNK], ga[CSG_CHUNK * 3], gb[CSG_CHUNK * 3];
    for (size_t i0 = 0; i0 < m; i0 += CSG_CHUNK) {
        size_t cnt = m - i0 < CSG_CHUNK ? m - i0 : CSG_CHUNK;
        const double *x = pts + i0 * (size_t)n;
        c->a.ops->eval(c->a.impl, cnt, x, va, grad ? ga : NULL);
        c->b.ops->eval(c->b.impl, cnt, x, vb, grad ? gb : NULL);
        for (size_t i = 0; i < cnt; i++) {
            double a = sa * va[i], b = sb * vb[i], v, wa, wb;
            if (!smooth) {
                /* ties go to a, deterministically */
                if (a <= b) { v = a; wa = 1; wb = 0; } else { v = b; wa = 0; wb = 1; }
            } else {
                double k = c->k, h = 0.5 + 0.5 * (b - a) / k;
                if (h <= 0.0) { v = b; wa = 0; wb = 1; }
                else if (h >= 1.0) { v = a; wa = 1; wb = 0; }
                else {
                    v = b * (1.0 - h) + a * h - k * h * (1.0 - h);
                    /* dv = (1-h) db + h da + dh (a - b - k + 2kh), and with
                     * h = 1/2 + (b - a)/(2k) the last factor vanishes: the
                     * polynomial smin is stationary in h */
                    wa = h;
                    wb = 1.0 - h;
                }
            }
            val[i0 + i] = so * v;
            if (grad)
                for (int j = 0; j < n; j++)
                    grad[(i0 + i) * (size_t)n + j] =
                        so * (wa * sa * ga[i * (size_t)n + j] + wb * sb * gb[i * (size_t)n + j]);
        }
    }
}

static dfl_status csg_jet(const void *impl, const double *x, const double *dir, int K,
                          dfl_jet *out, dfl_err *err)
{
    const csg *c = impl;
    double sa, sb, so;
    csg_signs(c->op, &sa, &sb, &so);
    dfl_jet a, b;
    dfl_status st = c->a.ops->jet(c->a.impl, x, dir, K, &a, err);
    if (st != DFL_OK) return st;
    if ((st = c->b.ops->jet(c->b.impl, x, dir, K, &b, err)) != DFL_OK) return st;
    dfl_jet_scale(&a, sa, &a);
    dfl_jet_scale(&b, sb, &b);
    if (!csg_smooth(c->op)) {
        *out = jet_cmp(&a, &b) <= 0 ? a : b;
    } else {
        double k = c->k;
        dfl_jet h, t, one;
        dfl_jet_sub(&b, &a, &h);
        dfl_jet_scale(&h, 0.5 / k, &h);
        dfl_jet_add_const(&h, 0.5, &h);
        dfl_jet_const(1.0, K, &one);
        if (jet_sign(&h) <= 0) {
            *out = b;
        } else if (jet_cmp(&h, &one) >= 0) {
            *out = a;
        } else {
            /* v = b + h (a - b) - k h (1 - h) */
            dfl_jet d, w;
            dfl_jet_sub(&a, &b, &d);
            dfl_jet_mul(&h, &d, &d);
            dfl_jet_sub(&one, &h, &w);
            dfl_jet_mul(&h, &w, &w);
            dfl_jet_scale(&w, -k, &w);
            dfl_jet_add(&b, &d, &t);
            dfl_jet_add(&t, &w, out);
        }
    }
    dfl_jet_scale(out, so, out);
    return DFL_OK;
}

static void csg_free(void *impl)
{
    csg *c = impl;
    dfl_shape_free(&c->a);
    dfl_shape_free(&c->b);
    free(c);
}

static const dfl_shape_ops csg_ops = {"csg", csg_eval, csg_jet, csg_free, NULL};
static const dfl_shape_ops csg_nojet_ops = {"csg", csg_eval, NULL, csg_free, NULL};

dfl_status dfl_shape_csg(dfl_csg_op op, double k, dfl_shape *a, dfl_shape *b, dfl_shape *out,
                         dfl_err *err)
{
    dfl_status st = DFL_OK;
    if (!a->ops || !b->ops)
        st = dfl_err_set(err, DFL_E_INPUT, "csg: missing operand");
    else if (a->dim != b->dim)
        st = dfl_err_set(err, DFL_E_INPUT, "csg: operands of dimension %d and %d", a->dim,
                         b->dim);
    else if ((int)op < 0 || op > DFL_CSG_SMOOTH_DIFFERENCE)
        st = dfl_err_set(err, DFL_E_INPUT, "csg: unknown operation %d", (int)op);
    else if (csg_smooth(op) && (!(k > 0.0) || !isfinite(k)))
        st = dfl_err_set(err, DFL_E_INPUT, "csg: smoothing width k must be > 0, got %g", k);
    csg *c = NULL;
    if (st == DFL_OK && !(c = calloc(1, sizeof *c)))
        st = dfl_err_set(err, DFL_E_NOMEM, "csg: out of memory");
    if (st != DFL_OK) {
        dfl_shape_free(a);
        dfl_shape_free(b);
        return st;
    }
    c->op = op;
    c->k = k;
    c->a = *a;
    c->b = *b;
    shape_set(a->dim, (a->ops->jet && b->ops->jet) ? &csg_ops : &csg_nojet_ops, c, out);
    memset(a, 0, sizeof *a);
    memset(b, 0, sizeof *b);
    return DFL_OK;
}

/* Exact ops in 3D: the closed-form Hessian of the branch eval takes at x
 * (ties to a) with its sign flips, when that child has one. */
int dfl_shape_csg_hess(const dfl_shape *s, const double *x, double *H)
{
    if (s->ops != &csg_ops && s->ops != &csg_nojet_ops) return 0;
    const csg *c = s->impl;
    if (s->dim != 3 || csg_smooth(c->op)) return 0;
    double sa, sb, so, va, vb;
    csg_signs(c->op, &sa, &sb, &so);
    c->a.ops->eval(c->a.impl, 1, x, &va, NULL);
    c->b.ops->eval(c->b.impl, 1, x, &vb, NULL);
    int take_a = sa * va <= sb * vb;
    const dfl_shape *ch = take_a ? &c->a : &c->b;
    if (!dfl_shape_analytic_hess(ch, x, H) && !dfl_shape_csg_hess(ch, x, H)) return 0;
    double f = so * (take_a ? sa : sb);
    for (int j = 0; j < 9; j++) H[j] *= f;
    return 1;
}
