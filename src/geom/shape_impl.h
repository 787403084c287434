/* Private to the shape files (shape.c, shape_analytic.c, shape_csg.c,
 * ellipse.c): the jet and frame helpers the analytic kinds share.  Not an
 * API: include geom/shape.h. */
#ifndef DFL_GEOM_SHAPE_IMPL_H
#define DFL_GEOM_SHAPE_IMPL_H

#include <math.h>

#include "core/jet.h"
#include "core/vec.h"
#include "geom/shape.h"

static inline int finite_vec(int n, const double *a)
{
    for (int j = 0; j < n; j++)
        if (!isfinite(a[j])) return 0;
    return 1;
}

/* Drops coefficients above absolute order K (keeps at least one). */
static inline void jet_truncate(dfl_jet *a, int K)
{
    if (a->zero) return;
    int keep = K - a->v + 1;
    if (keep >= 1 && a->n > keep) a->n = keep;
}

/* Jet of s -> sqrt(q0 + q1 s + q2 s^2) to order K.  The polynomial is exact,
 * so the jet module's valuation makes the centre/axis cases (q0 = q1 = 0)
 * exact too: sqrt of a series starting at s^2 starts at s.  Halving the
 * valuation costs one order of relative precision, so the polynomial is
 * taken one order further (it is exact anyway) and the result cut back to K
 * (at K = DFL_JET_MAX that one order is lost). */
static inline dfl_status jet_sqrt_quad(double q0, double q1, double q2, int K, dfl_jet *out,
                                dfl_err *err)
{
    double a[3] = {q0, q1, q2};
    dfl_jet q;
    dfl_jet_poly(a, 3, K < DFL_JET_MAX ? K + 1 : K, &q);
    dfl_status st = dfl_jet_sqrt(&q, out, err);
    if (st == DFL_OK) jet_truncate(out, K);
    return st;
}

/* Jet of s -> |p + s d| (n coordinates) to order K: the exact quadratic
 * |p|^2 + 2 (p.d) s + |d|^2 s^2 under jet_sqrt_quad. */
static inline dfl_status jet_norm_line(int n, const double *p, const double *d, int K,
                                       dfl_jet *out, dfl_err *err)
{
    return jet_sqrt_quad(dfl_vecn_dot(n, p, p), 2.0 * dfl_vecn_dot(n, p, d), dfl_vecn_dot(n, d, d),
                         K, out, err);
}

/* Sign of a jet at s = 0+: the sign of its first non-zero coefficient (0 for
 * a jet that is zero to its known order).  This is the order that decides
 * which branch of a min/max/abs/clamp holds on (0, eps). */
static inline int jet_sign(const dfl_jet *a)
{
    if (a->zero) return 0;
    for (int k = 0; k < a->n; k++) {
        if (a->c[k] > 0.0) return 1;
        if (a->c[k] < 0.0) return -1;
    }
    return 0;
}

static inline int jet_cmp(const dfl_jet *a, const dfl_jet *b)
{
    dfl_jet d;
    dfl_jet_sub(a, b, &d);
    return jet_sign(&d);
}

/* Sign of the linear function a0 + a1 s at 0+ (0 only if both vanish). */
static inline int lin_sign(double a0, double a1)
{
    if (a0 != 0.0) return a0 > 0.0 ? 1 : -1;
    if (a1 != 0.0) return a1 > 0.0 ? 1 : -1;
    return 0;
}

static inline dfl_status unit_axis(const char *name, const char *what, const double *a, int n,
                            double *w, dfl_err *err)
{
    if (!finite_vec(n, a)) return dfl_err_set(err, DFL_E_INPUT, "%s: %s not finite", name, what);
    double len = sqrt(dfl_vecn_dot(n, a, a));
    if (!(len > 0.0)) return dfl_err_set(err, DFL_E_INPUT, "%s: %s is the zero vector", name, what);
    for (int j = 0; j < n; j++) w[j] = a[j] / len;
    return DFL_OK;
}

/* Perpendicular part of p w.r.t. the unit axis w: writes pp, returns p.w. */
static inline double split_axis(const double p[3], const double w[3], double pp[3])
{
    double z = dfl_vecn_dot(3, p, w);
    for (int j = 0; j < 3; j++) pp[j] = p[j] - z * w[j];
    return z;
}

/* Installs impl with ops as a shape of dimension dim: the common tail of the
 * constructors (impl is fully built; nothing can fail after this). */
static inline dfl_status shape_set(int dim, const dfl_shape_ops *ops, void *impl, dfl_shape *out)
{
    out->dim = dim;
    out->ops = ops;
    out->impl = impl;
    return DFL_OK;
}

/* Closed-form Hessians at a 3D point (9 doubles): 1 when s is a kind that
 * has one (shape_analytic.c: sphere, torus, cylinder, 3D plane;
 * shape_csg.c: exact CSG whose active branch has one), 0 otherwise (H
 * untouched). */
int dfl_shape_analytic_hess(const dfl_shape *s, const double *x, double *H);
int dfl_shape_csg_hess(const dfl_shape *s, const double *x, double *H);

#endif
