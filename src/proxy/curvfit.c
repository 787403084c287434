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

/* W = -[[A, B], [B, C]] in the frame (b1, b2, n): its eigenpairs. */
static void curvature_of(double A, double B, double C, const double b1[3], const double b2[3],
                         const double n[3], dfl_curvature *out)
{
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

void dfl_curvfit_from_heights(const dfl_curvfit *F, const double *z, const double b1[3],
                              const double b2[3], const double n[3], dfl_curvature *out)
{
    curvature_of(dfl_vecn_dot(F->npts, F->pinv[0], z), dfl_vecn_dot(F->npts, F->pinv[1], z),
                 dfl_vecn_dot(F->npts, F->pinv[2], z), b1, b2, n, out);
}

/* The least squares of the nodes not missing (normal equations, as in
 * dfl_curvfit_init): -1 if fewer than DFL_CURVFIT_MIN_NODES remain or
 * their design is singular. */
static int partial_fit(const dfl_curvfit *F, const double *z, const unsigned char *missing,
                       const double b1[3], const double b2[3], const double n[3],
                       dfl_curvature *out)
{
    double N[DFL_CURVFIT_NCOEF * DFL_CURVFIT_NCOEF] = {0}, rhs[DFL_CURVFIT_NCOEF] = {0};
    int used = 0;
    for (int k = 0; k < F->npts; k++) {
        if (missing[k]) continue;
        double r[DFL_CURVFIT_NCOEF];
        design_row(F->xy[2 * k], F->xy[2 * k + 1], r);
        for (int a = 0; a < DFL_CURVFIT_NCOEF; a++) {
            rhs[a] += r[a] * z[k];
            for (int b = 0; b < DFL_CURVFIT_NCOEF; b++) N[a * DFL_CURVFIT_NCOEF + b] += r[a] * r[b];
        }
        used++;
    }
    int piv[DFL_CURVFIT_NCOEF];
    if (used < DFL_CURVFIT_MIN_NODES || dfl_lu_factor(DFL_CURVFIT_NCOEF, N, piv, 1e-13, NULL) != DFL_OK)
        return -1;
    dfl_lu_solve(DFL_CURVFIT_NCOEF, N, piv, rhs);
    curvature_of(rhs[0], rhs[1], rhs[2], b1, b2, n, out);
    return 0;
}

/* The root of t -> f(base + t n) in [-reach, reach] by bracketing: the
 * nearest sign change to t = 0 on the ladder +-w, +-2w, ... (w the grid
 * spacing / 2), then Illinois steps to the Newton loop's tolerance.  For
 * the nodes Newton gives up on: where f has kinks (a triangle mesh's edges
 * and vertices, where its gradient jumps and the normal line may meet a
 * face at a grazing angle), Newton cycles or steps off, while f, continuous
 * and 1-Lipschitz, changes sign across the surface.  -1 if no sign change
 * is found or f is not finite. */
static int bracket_root(const dfl_shape *s, const double base[3], const double n[3], double w,
                        double reach, double *root)
{
    double x[3];
    for (int j = 0; j < 3; j++) x[j] = base[j];
    const double f0 = dfl_shape_eval1(s, x, NULL);
    if (!isfinite(f0)) return -1;
    if (f0 == 0.0) {
        *root = 0.0;
        return 0;
    }
    double a = 0.0, fa = f0, b = 0.0, fb = 0.0;
    int found = 0;
    for (double r = fmin(w, reach);; r = fmin(2.0 * r, reach)) {
        for (int sg = -1; sg <= 1 && !found; sg += 2) {
            for (int j = 0; j < 3; j++) x[j] = base[j] + sg * r * n[j];
            const double fr = dfl_shape_eval1(s, x, NULL);
            if (!isfinite(fr)) return -1;
            if ((fr <= 0.0) != (f0 <= 0.0)) b = sg * r, fb = fr, found = 1;
        }
        if (found || r >= reach) break;
    }
    if (!found) return -1;
    /* Illinois (regula falsi with the stale end's value halved) */
    int side = 0;
    double t = b, ft = fb;
    for (int it = 0; it < 200; it++) {
        t = (a * fb - b * fa) / (fb - fa);
        for (int j = 0; j < 3; j++) x[j] = base[j] + t * n[j];
        ft = dfl_shape_eval1(s, x, NULL);
        if (!isfinite(ft)) return -1;
        if (ft == 0.0 || fabs(b - a) <= 1e-13 * (1.0 + fabs(t))) break;
        if ((ft <= 0.0) == (fb <= 0.0)) {
            b = t, fb = ft;
            if (side == -1) fa *= 0.5;
            side = -1;
        } else {
            a = t, fa = ft;
            if (side == 1) fb *= 0.5;
            side = 1;
        }
    }
    /* A sign change of a continuous, 1-Lipschitz f brackets a root, and
     * every t of the bracket then has |f(t)| <= b - a.  A larger |f| means
     * the sign changed by a jump, not through 0: a sign of f that is not
     * continuous (an open mesh's winding number jumps across a sheet that
     * spans its rims, off the surface).  Illinois converges to the jump
     * there, which is no point of the surface: no height. */
    if (!(fabs(ft) <= fabs(b - a) + 1e-12 * (1.0 + fabs(t)))) return -1;
    *root = t;
    return 0;
}

dfl_status dfl_curvfit_sdf(const dfl_curvfit *F, const dfl_shape *s, const double p[3],
                           const double n[3], dfl_curvature *out)
{
    double b1[3], b2[3];
    dfl_vec3_tangent_basis(n, b1, b2);
    double q[3 * MAXP], base[3 * MAXP], t[MAXP], f[MAXP], gr[3 * MAXP];
    unsigned char bad[MAXP], moving[MAXP];
    const int np = F->npts;
    const double reach = 3.0 * (F->g - 1) * F->h;
    for (int k = 0; k < np; k++) {
        for (int j = 0; j < 3; j++)
            base[3 * k + j] = p[j] + F->xy[2 * k] * b1[j] + F->xy[2 * k + 1] * b2[j];
        t[k] = 0.0;
        bad[k] = 0;
    }
    memcpy(q, base, 3 * np * sizeof *q);
    /* Newton on every node together (one batched evaluation per step); a
     * node it fails on (a small slope along n, a non-finite value, a step
     * beyond the reach) is left to bracket_root, the others go on as if it
     * were not there.  The step f / (grad f . n) does not change when f and
     * grad f are both negated (IEEE negation is exact, and so is a sum or a
     * quotient of negated terms), so the unsigned evaluation gives the
     * signed one's steps bit for bit without deciding the side: a signed
     * mesh's winding number, most of a mesh's projection otherwise.
     * bracket_root looks for a sign change and keeps the signed d. */
    int done = 0;
    for (int it = 0; it < 30 && !done; it++) {
        dfl_shape_eval_unsigned(s, (size_t)np, q, f, gr);
        done = 1;
        for (int k = 0; k < np; k++) {
            moving[k] = 0;
            if (bad[k]) continue;
            double dn = dfl_vec3_dot(gr + 3 * k, n);
            if (!(fabs(dn) > 0.1) || !isfinite(f[k])) {
                bad[k] = 1;
                continue;
            }
            double step = f[k] / dn;
            t[k] -= step;
            if (!(fabs(t[k]) <= reach)) {
                bad[k] = 1;
                continue;
            }
            if (fabs(step) > 1e-13 * (1.0 + fabs(t[k]))) done = 0, moving[k] = 1;
            for (int j = 0; j < 3; j++) q[3 * k + j] = base[3 * k + j] + t[k] * n[j];
        }
    }
    unsigned char missing[MAXP];
    int nmissing = 0;
    for (int k = 0; k < np; k++) {
        missing[k] = 0;
        if (bad[k] || (!done && moving[k]))
            if (bracket_root(s, base + 3 * k, n, 0.5 * F->h, reach, &t[k]) != 0)
                missing[k] = 1, nmissing++;
    }
    if (!nmissing) {
        dfl_curvfit_from_heights(F, t, b1, b2, n, out);
        return DFL_OK;
    }
    return partial_fit(F, t, missing, b1, b2, n, out) == 0 ? DFL_OK : DFL_E_NUMERIC;
}
