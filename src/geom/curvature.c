#include "geom/curvature.h"

#include <assert.h>
#include <math.h>
#include <string.h>

#include "core/linalg.h"
#include "core/vec.h"

/* Fills k1 <= k2 and directions from the shape operator written in the
 * orthonormal tangent basis (t1, t2) with t1 x t2 = n. */
static void finish(const double t1[3], const double t2[3], double a, double b, double c,
                   dfl_curvature *out)
{
    double lo, hi, th;
    dfl_sym2_eigen(a, b, c, &lo, &hi, &th);
    double cs = cos(th), sn = sin(th);
    out->k1 = lo;
    out->k2 = hi;
    for (int j = 0; j < 3; j++) {
        out->e2[j] = cs * t1[j] + sn * t2[j];
        out->e1[j] = -sn * t1[j] + cs * t2[j];
    }
    /* (-s t1 + c t2) x (c t1 + s t2) = -n: flip e1 so that e1 x e2 = n */
    for (int j = 0; j < 3; j++) out->e1[j] = -out->e1[j];
    out->K = lo * hi;
    out->H = 0.5 * (lo + hi);
}

dfl_status dfl_curvature_implicit(const double grad[3], const double hess[9], dfl_curvature *out,
                                  dfl_err *err)
{
    double gn = sqrt(dfl_vec3_dot(grad, grad));
    if (!(gn > 0.0) || !isfinite(gn))
        return dfl_err_set(err, DFL_E_NUMERIC, "curvature: gradient of g vanishes");
    for (int j = 0; j < 3; j++) out->n[j] = grad[j] / gn;
    double t1[3], t2[3], Ht1[3], Ht2[3];
    dfl_vec3_tangent_basis(out->n, t1, t2);
    /* n = grad g/|grad g| => dn = (I - n n^T) Hess g / |grad g| on tangents */
    for (int i = 0; i < 3; i++) {
        Ht1[i] = dfl_vec3_dot(hess + 3 * i, t1);
        Ht2[i] = dfl_vec3_dot(hess + 3 * i, t2);
    }
    double a = dfl_vec3_dot(t1, Ht1) / gn, c = dfl_vec3_dot(t2, Ht2) / gn;
    double b = 0.5 * (dfl_vec3_dot(t1, Ht2) + dfl_vec3_dot(t2, Ht1)) / gn;
    finish(t1, t2, a, b, c, out);
    return DFL_OK;
}

void dfl_fundamental_forms_eval(const double Su[3], const double Sv[3], const double Suu[3],
                                const double Suv[3], const double Svv[3], const double n[3],
                                dfl_fundamental_forms *out)
{
    out->E = dfl_vec3_dot(Su, Su);
    out->F = dfl_vec3_dot(Su, Sv);
    out->G = dfl_vec3_dot(Sv, Sv);
    out->L = dfl_vec3_dot(Suu, n);
    out->M = dfl_vec3_dot(Suv, n);
    out->N = dfl_vec3_dot(Svv, n);
}

double dfl_gaussian_curvature_ff(const dfl_fundamental_forms *f)
{
    return (f->L * f->N - f->M * f->M) / (f->E * f->G - f->F * f->F);
}

double dfl_mean_curvature_ff(const dfl_fundamental_forms *f)
{
    return -(f->E * f->N - 2.0 * f->F * f->M + f->G * f->L) / (2.0 * (f->E * f->G - f->F * f->F));
}

dfl_status dfl_curvature_parametric(const double Su[3], const double Sv[3], const double Suu[3],
                                    const double Suv[3], const double Svv[3],
                                    const double *n_ref, dfl_curvature *out, dfl_err *err)
{
    double n[3];
    dfl_vec3_cross(Su, Sv, n);
    double nn = sqrt(dfl_vec3_dot(n, n));
    if (!(nn > 0.0) || !isfinite(nn))
        return dfl_err_set(err, DFL_E_NUMERIC, "curvature: singular parametrization (Su x Sv = 0)");
    double sg = (n_ref && dfl_vec3_dot(n, n_ref) < 0.0) ? -1.0 : 1.0;
    for (int j = 0; j < 3; j++) out->n[j] = sg * n[j] / nn;
    dfl_fundamental_forms f;
    dfl_fundamental_forms_eval(Su, Sv, Suu, Suv, Svv, out->n, &f);
    /* Orthonormal t1 = Su/|Su|, t2 = n x t1.  With B = [Su Sv] = T C,
     * C = [[|Su|, t1.Sv], [0, t2.Sv]], the Weingarten map -dn has matrix
     * C^-T II C^-1 in (t1, t2); our kappa are its negatives. */
    double t1[3], t2[3];
    double su = sqrt(f.E);
    for (int j = 0; j < 3; j++) t1[j] = Su[j] / su;
    dfl_vec3_cross(out->n, t1, t2);
    double c11 = su, c12 = dfl_vec3_dot(t1, Sv), c22 = dfl_vec3_dot(t2, Sv);
    assert(c11 > 0.0);
    /* C^-1 = [[1/c11, -c12/(c11 c22)], [0, 1/c22]] */
    double i11 = 1.0 / c11, i12 = -c12 / (c11 * c22), i22 = 1.0 / c22;
    /* W = C^-T II C^-1 with II = [[L, M], [M, N]] */
    double a = i11 * i11 * f.L;
    double b = i11 * (i12 * f.L + i22 * f.M);
    double c = i12 * i12 * f.L + 2.0 * i12 * i22 * f.M + i22 * i22 * f.N;
    finish(t1, t2, -a, -b, -c, out);
    return DFL_OK;
}

double dfl_curvature_implicit2(const double grad[2], const double hess[4])
{
    double gn = hypot(grad[0], grad[1]);
    if (!(gn > 0.0)) return NAN;
    double t[2] = {-grad[1] / gn, grad[0] / gn};
    double Ht[2] = {hess[0] * t[0] + hess[1] * t[1], hess[2] * t[0] + hess[3] * t[1]};
    return (t[0] * Ht[0] + t[1] * Ht[1]) / gn;
}

double dfl_curvature_curve2(const double d1[2], const double d2[2], const double n[2])
{
    double s2 = d1[0] * d1[0] + d1[1] * d1[1];
    if (!(s2 > 0.0)) return NAN;
    return -(d2[0] * n[0] + d2[1] * n[1]) / s2;
}
