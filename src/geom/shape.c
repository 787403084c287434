/* The shape interface in use: evaluation, jets, footpoints of SDF input,
 * Hermite data, the kind names. */
#include "geom/shape_impl.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

DFL_NAMES_DEFINE(dfl_shape_kind, DFL_SHAPE_KIND_LIST, DFL_SHAPE_KIND_COUNT, dfl_shape_kind_names,
                 dfl_shape_kind_name, dfl_shape_kind_parse, "shape kind")

/* ---- generic use --------------------------------------------------------- */

double dfl_shape_eval1(const dfl_shape *s, const double *x, double *grad)
{
    double v = 0.0;
    s->ops->eval(s->impl, 1, x, &v, grad);
    return v;
}

void dfl_shape_eval(const dfl_shape *s, size_t m, const double *pts, double *val, double *grad)
{
    s->ops->eval(s->impl, m, pts, val, grad);
}

void dfl_shape_eval_unsigned(const dfl_shape *s, size_t m, const double *pts, double *val,
                             double *grad)
{
    if (s->ops->eval_unsigned) {
        s->ops->eval_unsigned(s->impl, m, pts, val, grad);
        return;
    }
    s->ops->eval(s->impl, m, pts, val, grad);
    const size_t dim = (size_t)s->dim;
    for (size_t i = 0; i < m; i++)
        if (val[i] < 0) {
            val[i] = -val[i];
            if (grad)
                for (size_t j = 0; j < dim; j++) grad[dim * i + j] = -grad[dim * i + j];
        }
}

dfl_status dfl_shape_jet(const dfl_shape *s, const double *x, const double *dir, int K,
                         dfl_jet *out, dfl_err *err)
{
    return dfl_jet_dir_call(s->ops->jet, s->impl, "shape", s->ops->kind, x, dir, K, out, err);
}

dfl_status dfl_shape_footpoint(const dfl_shape *s, const double *x, double *p, dfl_err *err)
{
    const int n = s->dim;
    double g[3];
    double d = dfl_shape_eval1(s, x, g);
    for (int j = 0; j < n; j++) p[j] = x[j] - d * g[j];
    double tol = 1e-14 * (1.0 + sqrt(dfl_vecn_dot(n, x, x)));
    for (int it = 0; it < 20; it++) {
        d = dfl_shape_eval1(s, p, g);
        if (fabs(d) <= tol) return DFL_OK;
        for (int j = 0; j < n; j++) p[j] -= d * g[j];
    }
    d = dfl_shape_eval1(s, p, g);
    if (fabs(d) <= tol) return DFL_OK;
    return dfl_err_set(err, DFL_E_NUMERIC,
                       "footpoint of shape '%s': |d(p)| = %g after 20 projections", s->ops->kind,
                       fabs(d));
}

dfl_status dfl_jets_polarize(int n, dfl_dir_jet_fn jet, const void *ctx, const double *x,
                             double *H, double *dxyz, dfl_err *err)
{
    assert(n == 2 || n == 3);
    dfl_jet j;
    double D2[3];
    dfl_status st;
    for (int i = 0; i < n; i++) {
        double e[3] = {0, 0, 0};
        e[i] = 1.0;
        if ((st = jet(ctx, x, e, 2, &j, err)) != DFL_OK) return st;
        D2[i] = H[i * n + i] = dfl_jet_deriv(&j, 2);
    }
    /* D^2_{e_i + e_k} = H_ii + 2 H_ik + H_kk */
    for (int i = 0; i < n; i++)
        for (int k = i + 1; k < n; k++) {
            double e[3] = {0, 0, 0};
            e[i] = e[k] = 1.0;
            if ((st = jet(ctx, x, e, 2, &j, err)) != DFL_OK) return st;
            H[i * n + k] = H[k * n + i] = 0.5 * (dfl_jet_deriv(&j, 2) - D2[i] - D2[k]);
        }
    if (n == 3 && dxyz) {
        static const double E[4][3] = {{1, 1, 1}, {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}};
        double acc = 0.0;
        for (int m = 0; m < 4; m++) {
            if ((st = jet(ctx, x, E[m], 3, &j, err)) != DFL_OK) return st;
            acc += E[m][0] * E[m][1] * E[m][2] * dfl_jet_deriv(&j, 3);
        }
        *dxyz = acc / 24.0;
    }
    return DFL_OK;
}

static dfl_status shape_dir_jet(const void *ctx, const double *x, const double *dir, int K,
                                dfl_jet *out, dfl_err *err)
{
    return dfl_shape_jet(ctx, x, dir, K, out, err);
}

dfl_status dfl_shape_derivs_at(const dfl_shape *s, const double *x, dfl_shape_derivs *out,
                               dfl_err *err)
{
    memset(out, 0, sizeof *out);
    out->d = dfl_shape_eval1(s, x, out->g);
    return dfl_jets_polarize(s->dim, shape_dir_jet, s, x, out->H, &out->dxyz, err);
}

dfl_status dfl_shape_hessian(const dfl_shape *s, const double *x, double *H, dfl_err *err)
{
    if (!s || !s->ops || s->dim != 3)
        return dfl_err_set(err, DFL_E_INPUT, "shape hessian: need a 3D shape");
    if (dfl_shape_analytic_hess(s, x, H) || dfl_shape_csg_hess(s, x, H)) return DFL_OK;
    if (!s->ops->jet)
        return dfl_err_set(err, DFL_E_INPUT, "shape hessian: %s has no jets", s->ops->kind);
    /* the second-order half of the one polarization (no third derivatives) */
    return dfl_jets_polarize(3, shape_dir_jet, s, x, H, NULL, err);
}

void dfl_shape_free(dfl_shape *s)
{
    if (!s) return;
    if (s->ops && s->ops->free && s->impl) s->ops->free(s->impl);
    memset(s, 0, sizeof *s);
}
