/* Cubic curvature fit on a tangent grid (see proxy/curvfit.h). */
#include "proxy/curvfit.h"

#include <math.h>
#include <string.h>

#include "core/linalg.h"
#include "core/vec.h"

#define MAXP (DFL_CURVFIT_MAX_G * DFL_CURVFIT_MAX_G)

static void design_row(double x, double y, double r[DFL_CURVFIT_NCOEF])
{
    r[0] = 0.5 * x * x;
    r[1] = x * y;
    r[2] = 0.5 * y * y;
    r[3] = x * x * x;
    r[4] = x * x * y;
    r[5] = x * y * y;
    r[6] = y * y * y;
}

dfl_status dfl_curvfit_init(int g, double h, dfl_curvfit *out, dfl_err *err)
{
    if (g < 3 || g > DFL_CURVFIT_MAX_G)
        return dfl_err_set(err, DFL_E_INPUT, "curvature fit: grid g = %d, expected 3..%d", g,
                           DFL_CURVFIT_MAX_G);
    if (!(h > 0.0) || !isfinite(h))
        return dfl_err_set(err, DFL_E_INPUT, "curvature fit: spacing %g, expected > 0", h);
    memset(out, 0, sizeof *out);
    out->g = g;
    out->h = h;
    out->npts = g * g;
    double rows[MAXP][DFL_CURVFIT_NCOEF];
    for (int j = 0; j < g; j++)
        for (int i = 0; i < g; i++) {
            int k = i + g * j;
            out->xy[2 * k] = (i - 0.5 * (g - 1)) * h;
            out->xy[2 * k + 1] = (j - 0.5 * (g - 1)) * h;
            design_row(out->xy[2 * k], out->xy[2 * k + 1], rows[k]);
        }
    /* normal equations M^T M c = M^T z; 7 x 7, well conditioned after the
     * column scaling by h^-2 / h^-3 that LU's pivot test sees as relative */
    double N[DFL_CURVFIT_NCOEF * DFL_CURVFIT_NCOEF] = {0};
    for (int k = 0; k < out->npts; k++)
        for (int a = 0; a < DFL_CURVFIT_NCOEF; a++)
            for (int b = 0; b < DFL_CURVFIT_NCOEF; b++)
                N[a * DFL_CURVFIT_NCOEF + b] += rows[k][a] * rows[k][b];
    int piv[DFL_CURVFIT_NCOEF];
    if (dfl_lu_factor(DFL_CURVFIT_NCOEF, N, piv, 1e-13, err) != DFL_OK)
        return dfl_err_set(err, DFL_E_NUMERIC, "curvature fit: singular design for g = %d", g);
    for (int k = 0; k < out->npts; k++) {
        double col[DFL_CURVFIT_NCOEF];
        memcpy(col, rows[k], sizeof col);
        dfl_lu_solve(DFL_CURVFIT_NCOEF, N, piv, col);
        for (int a = 0; a < DFL_CURVFIT_NCOEF; a++) out->pinv[a][k] = col[a];
    }
    return DFL_OK;
}

void dfl_curvfit_coeffs(const dfl_curvfit *F, const double *z, double coef[DFL_CURVFIT_NCOEF])
{
    for (int a = 0; a < DFL_CURVFIT_NCOEF; a++) coef[a] = dfl_vecn_dot(F->npts, F->pinv[a], z);
}

void dfl_curvfit_from_heights(const dfl_curvfit *F, const double *z, const double b1[3],
                              const double b2[3], const double n[3], dfl_curvature *out)
{
    double A = dfl_vecn_dot(F->npts, F->pinv[0], z);
    double B = dfl_vecn_dot(F->npts, F->pinv[1], z);
    double C = dfl_vecn_dot(F->npts, F->pinv[2], z);
    double lo, hi, th;
    dfl_sym2_eigen(-A, -B, -C, &lo, &hi, &th);
    double c = cos(th), s = sin(th);
    out->k1 = lo;
    out->k2 = hi;
    /* e2 = (c, s) for hi, e1 = (s, -c) so that e1 x e2 = b1 x b2 = n */
    for (int j = 0; j < 3; j++) {
        out->e2[j] = c * b1[j] + s * b2[j];
        out->e1[j] = s * b1[j] - c * b2[j];
        out->n[j] = n[j];
    }
    out->K = lo * hi;
    out->H = 0.5 * (lo + hi);
}

dfl_status dfl_curvfit_sdf(const dfl_curvfit *F, const dfl_shape *s, const double p[3],
                           const double n[3], dfl_curvature *out)
{
    double b1[3], b2[3];
    dfl_vec3_tangent_basis(n, b1, b2);
    double q[3 * MAXP], base[3 * MAXP], t[MAXP], f[MAXP], gr[3 * MAXP];
    const int np = F->npts;
    const double reach = 3.0 * (F->g - 1) * F->h;
    for (int k = 0; k < np; k++) {
        for (int j = 0; j < 3; j++)
            base[3 * k + j] = p[j] + F->xy[2 * k] * b1[j] + F->xy[2 * k + 1] * b2[j];
        t[k] = 0.0;
    }
    memcpy(q, base, 3 * np * sizeof *q);
    int done = 0;
    for (int it = 0; it < 30 && !done; it++) {
        s->ops->eval(s->impl, (size_t)np, q, f, gr);
        done = 1;
        for (int k = 0; k < np; k++) {
            double dn = dfl_vec3_dot(gr + 3 * k, n);
            if (!(fabs(dn) > 0.1) || !isfinite(f[k])) return DFL_E_NUMERIC;
            double step = f[k] / dn;
            t[k] -= step;
            if (!(fabs(t[k]) <= reach)) return DFL_E_NUMERIC;
            if (fabs(step) > 1e-13 * (1.0 + fabs(t[k]))) done = 0;
            for (int j = 0; j < 3; j++) q[3 * k + j] = base[3 * k + j] + t[k] * n[j];
        }
    }
    if (!done) return DFL_E_NUMERIC;
    dfl_curvfit_from_heights(F, t, b1, b2, n, out);
    return DFL_OK;
}
