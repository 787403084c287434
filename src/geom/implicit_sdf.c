/* The implicit SDF beyond its value: jets along rays, Hermite data, and
 * the dfl_shape wrapper. */
#include "geom/implicit_impl.h"

#include <math.h>
#include <string.h>

#include "core/linalg.h"
#include "core/series.h"

/* Footpoint system Jacobian [[I + t H, G], [G^T, 0]]. */
static void foot_jacobian(const double G[3], const double H[9], double t, double J[16])
{
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) J[4 * i + j] = (i == j ? 1.0 : 0.0) + t * H[3 * i + j];
        J[4 * i + 3] = G[i];
        J[12 + i] = G[i];
    }
    J[15] = 0.0;
}

/* ---- jets along a ray ------------------------------------------------------ */

dfl_status dfl_implicit_jet(const dfl_implicit *s, const dfl_footpoint *foot, const double x[3],
                            const double dir[3], int K, dfl_jet *out, dfl_err *err)
{
    dfl_status st = dfl_jet_check_order(K, err);
    if (st != DFL_OK) return st;
    dfl_footpoint fp;
    if (!foot) {
        st = dfl_implicit_footpoint(s, x, &fp, err);
        if (st != DFL_OK) return st;
        foot = &fp;
    }
    double q[3], dl[3], p[3];
    to_local(s, x, q);
    vec_to_local(s, dir, dl);
    to_local(s, foot->p, p);
    double G[3], H[9], J[16];
    int piv[4];
    g_local(s, p, G, H);
    double t = foot->t;
    foot_jacobian(G, H, t, J);
    if (dfl_lu_factor(4, J, piv, 1e-13, NULL) != DFL_OK)
        return dfl_err_set(err, DFL_E_NUMERIC,
                           "implicit jet at (%g, %g, %g): singular footpoint system (focal point)",
                           x[0], x[1], x[2]);
    /* Unknowns P(s), T(s) with F = (P - q - s dl + T grad g(P), g(P)) = 0.
     * Frozen-Jacobian Newton: the error is O(s^k) after k steps. */
    dfl_series P[3], T, GS[3], gs;
    for (int a = 0; a < 3; a++) {
        dfl_series_zero(&P[a]);
        P[a].c[0] = p[a];
    }
    dfl_series_zero(&T);
    T.c[0] = t;
    for (int it = 0; it < K; it++) {
        for (int a = 0; a < 3; a++) dfl_poly3_eval_series(&s->gd[a], P, K, &GS[a]);
        dfl_poly3_eval_series(&s->g, P, K, &gs);
        dfl_series F[4];
        for (int a = 0; a < 3; a++) {
            dfl_series tg;
            dfl_series_mul(&T, &GS[a], K, &tg);
            for (int k = 0; k <= K; k++) {
                double xs = (k == 0 ? q[a] : (k == 1 ? dl[a] : 0.0));
                F[a].c[k] = P[a].c[k] - xs + tg.c[k];
            }
        }
        F[3] = gs;
        /* coefficient 0 is already solved; keep it to avoid drift */
        for (int k = 1; k <= K; k++) {
            double b[4] = {-F[0].c[k], -F[1].c[k], -F[2].c[k], -F[3].c[k]};
            dfl_lu_solve(4, J, piv, b);
            for (int a = 0; a < 3; a++) P[a].c[k] += b[a];
            T.c[k] += b[3];
        }
    }
    /* d(s) = T(s) |grad g(P(s))|: x - p = t grad g and n = grad g / |grad g| */
    for (int a = 0; a < 3; a++) dfl_poly3_eval_series(&s->gd[a], P, K, &GS[a]);
    dfl_series n2, tmp;
    dfl_series_zero(&n2);
    for (int a = 0; a < 3; a++) {
        dfl_series_mul(&GS[a], &GS[a], K, &tmp);
        dfl_series_add(&n2, &tmp, K, &n2);
    }
    if (dfl_series_sqrt(&n2, K, &tmp, NULL) != DFL_OK)
        return dfl_err_set(err, DFL_E_NUMERIC, "implicit jet: grad g vanishes at the footpoint");
    dfl_series_mul(&T, &tmp, K, &tmp);
    /* the value itself is the footpoint's (sign of g), the rest the series' */
    tmp.c[0] = foot->d;
    dfl_jet_poly(tmp.c, K + 1, K, out);
    return DFL_OK;
}

typedef struct foot_jet_ctx {
    const dfl_implicit *s;
    const dfl_footpoint *foot;
} foot_jet_ctx;

static dfl_status foot_dir_jet(const void *ctx, const double *x, const double *dir, int K,
                               dfl_jet *out, dfl_err *err)
{
    const foot_jet_ctx *c = ctx;
    return dfl_implicit_jet(c->s, c->foot, x, dir, K, out, err);
}

dfl_status dfl_implicit_sdf_derivs(const dfl_implicit *s, const double x[3], dfl_sdf_derivs *out,
                                   dfl_err *err)
{
    dfl_status st = dfl_implicit_footpoint(s, x, &out->foot, err);
    if (st != DFL_OK) return st;
    out->d = out->foot.d;
    memcpy(out->g, out->foot.n, sizeof out->g);
    /* every jet continues the one footpoint found above */
    const foot_jet_ctx ctx = {s, &out->foot};
    return dfl_jets_polarize(3, foot_dir_jet, &ctx, x, out->H, &out->dxyz, err);
}

/* ---- as a shape ------------------------------------------------------------ */

static void implicit_eval(const void *impl, size_t m, const double *pts, double *val,
                          double *grad)
{
    const dfl_implicit *s = impl;
    for (size_t i = 0; i < m; i++) {
        dfl_footpoint f;
        if (dfl_implicit_footpoint(s, pts + 3 * i, &f, NULL) != DFL_OK) {
            val[i] = NAN;
            if (grad) grad[3 * i] = grad[3 * i + 1] = grad[3 * i + 2] = NAN;
            continue;
        }
        val[i] = f.d;
        if (grad) memcpy(grad + 3 * i, f.n, sizeof f.n);
    }
}

static dfl_status implicit_jet_op(const void *impl, const double *x, const double *dir, int K,
                                  dfl_jet *out, dfl_err *err)
{
    return dfl_implicit_jet(impl, NULL, x, dir, K, out, err);
}

static void implicit_free_op(void *impl) { dfl_implicit_free(impl); }

static const dfl_shape_ops implicit_ops = {"implicit", implicit_eval, implicit_jet_op,
                                           implicit_free_op, NULL};

dfl_status dfl_implicit_shape(dfl_implicit **s, dfl_shape *out, dfl_err *err)
{
    if (!s || !*s) return dfl_err_set(err, DFL_E_INPUT, "implicit shape: no surface");
    out->dim = 3;
    out->ops = &implicit_ops;
    out->impl = *s;
    *s = NULL;
    return DFL_OK;
}

const dfl_implicit *dfl_implicit_of_shape(const dfl_shape *shape)
{
    return (shape && shape->ops == &implicit_ops) ? shape->impl : NULL;
}
