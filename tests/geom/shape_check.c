/* The brute-force checks of tests/geom/test_shape*.c (see shape_check.h). */
#include "geom/shape_check.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>

#include "core/rng.h"
#include "core/vec.h"

/* One sequence per test process (Criterion forks each test), so every
 * test sees the same points on every run. */
static uint64_t rng_state = 88172645463325252ULL;

double sc_urand(double lo, double hi) { return dfl_rng_xorshift(&rng_state, lo, hi); }

void sc_normalize3(double *a)
{
    double l = sqrt(dfl_vecn_dot(3, a, a));
    for (int j = 0; j < 3; j++) a[j] /= l;
}

/* Orthonormal u, v perpendicular to unit w (Gram-Schmidt from e_x or e_y). */
void sc_perp_basis(const double w[3], double u[3], double v[3])
{
    double t[3] = {1, 0, 0};
    if (fabs(w[0]) > 0.8) { t[0] = 0; t[1] = 1; }
    double tw = dfl_vecn_dot(3, t, w);
    for (int j = 0; j < 3; j++) u[j] = t[j] - tw * w[j];
    sc_normalize3(u);
    v[0] = w[1] * u[2] - w[2] * u[1];
    v[1] = w[2] * u[0] - w[0] * u[2];
    v[2] = w[0] * u[1] - w[1] * u[0];
}

static double pdist(const sc_patch *P, int dim, const double *x, const double *prm)
{
    double p[3];
    P->point(P->ctx, prm, p);
    double d2 = 0;
    for (int j = 0; j < dim; j++) d2 += (x[j] - p[j]) * (x[j] - p[j]);
    return sqrt(d2);
}

/* Pattern search from prm with initial steps st (clamped to the box). */
static double refine(const sc_patch *P, int dim, const double *x, double *prm, const double *st0)
{
    double st[2] = {st0[0], st0[1]};
    double best = pdist(P, dim, x, prm);
    for (int it = 0; it < 4000; it++) {
        int improved = 0;
        for (int a = 0; a < P->np; a++)
            for (int sg = -1; sg <= 1; sg += 2) {
                double q[2] = {prm[0], prm[1]};
                q[a] += sg * st[a];
                if (q[a] < P->lo[a]) q[a] = P->lo[a];
                if (q[a] > P->hi[a]) q[a] = P->hi[a];
                double d = pdist(P, dim, x, q);
                if (d < best) {
                    best = d;
                    prm[0] = q[0];
                    prm[1] = q[1];
                    improved = 1;
                }
            }
        if (!improved) {
            int small = 1;
            for (int a = 0; a < P->np; a++) {
                st[a] *= 0.5;
                if (st[a] > 1e-14 * (P->hi[a] - P->lo[a])) small = 0;
            }
            if (small) break;
        }
    }
    return best;
}

/* Unsigned distance from x to the union of patches: dense grid (total
 * >= nsamp samples) then refinement of every patch's best sample. */
double sc_brute_dist(const sc_patch *P, int npatch, int dim, const double *x, long nsamp)
{
    double best = HUGE_VAL;
    for (int k = 0; k < npatch; k++) {
        long per = nsamp / npatch + 1;
        int n0 = P[k].np == 1 ? (int)per : (int)ceil(sqrt((double)per));
        int n1 = P[k].np == 1 ? 1 : n0;
        double bp[2] = {0, 0}, bd = HUGE_VAL;
        for (int i = 0; i < n0; i++)
            for (int j = 0; j < n1; j++) {
                double prm[2];
                prm[0] = P[k].lo[0] + (P[k].hi[0] - P[k].lo[0]) * i / (n0 - 1);
                prm[1] = P[k].np == 1 ? 0 : P[k].lo[1] + (P[k].hi[1] - P[k].lo[1]) * j / (n1 - 1);
                double d = pdist(&P[k], dim, x, prm);
                if (d < bd) { bd = d; bp[0] = prm[0]; bp[1] = prm[1]; }
            }
        double st[2] = {(P[k].hi[0] - P[k].lo[0]) / (n0 - 1),
                        P[k].np == 1 ? 0 : (P[k].hi[1] - P[k].lo[1]) / (n1 - 1)};
        double d = refine(&P[k], dim, x, bp, st);
        if (d < best) best = d;
    }
    return best;
}

/* f(s) = d(x + s dir) */
static double fray(const dfl_shape *s, const double *x, const double *dir, double t)
{
    double p[3];
    for (int j = 0; j < s->dim; j++) p[j] = x[j] + t * dir[j];
    return dfl_shape_eval1(s, p, NULL);
}

/* 7-point central stencils, error O(h^4) for orders 1..3. */
static double fd_deriv(const dfl_shape *s, const double *x, const double *dir, int order, double h)
{
    double f[7];
    for (int i = -3; i <= 3; i++) f[i + 3] = fray(s, x, dir, i * h);
    switch (order) {
    case 1: return (-f[5] + 8 * f[4] - 8 * f[2] + f[1]) / (12 * h);
    case 2: return (-f[5] + 16 * f[4] - 30 * f[3] + 16 * f[2] - f[1]) / (12 * h * h);
    default: return (-f[6] + 8 * f[5] - 13 * f[4] + 13 * f[2] - 8 * f[1] + f[0]) / (8 * h * h * h);
    }
}

void sc_check_shape(const dfl_shape *s, const sc_patch *P, int npatch, sc_inside_fn inside,
                    int is_signed, double lo, double hi, int npts, int check_values,
                    int unit_grad, int jets)
{
    const int dim = s->dim;
    int jet_tested = 0, jet_total = 0;
    for (int t = 0; t < npts; t++) {
        double x[3] = {0, 0, 0}, g[3], dir[3] = {0, 0, 0};
        for (int j = 0; j < dim; j++) x[j] = sc_urand(lo, hi);
        for (int j = 0; j < dim; j++) dir[j] = sc_urand(-1, 1);
        double d = dfl_shape_eval1(s, x, g);
        if (check_values) {
            double b = sc_brute_dist(P, npatch, dim, x, 100000);
            if (is_signed && inside(x)) b = -b;
            cr_assert(fabs(d - b) <= 1e-9, "%s: d = %.17g, brute force %.17g at (%g %g %g)",
                      s->ops->kind, d, b, x[0], x[1], x[2]);
        }
        /* gradient */
        const double h = 1e-6;
        double gn = 0;
        for (int j = 0; j < dim; j++) {
            double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]};
            xp[j] += h;
            xm[j] -= h;
            double fd = (dfl_shape_eval1(s, xp, NULL) - dfl_shape_eval1(s, xm, NULL)) / (2 * h);
            cr_assert(fabs(fd - g[j]) <= 1e-6, "%s: grad[%d] = %.17g, FD %.17g", s->ops->kind, j,
                      g[j], fd);
            gn += g[j] * g[j];
        }
        if (unit_grad)
            cr_assert(fabs(sqrt(gn) - 1.0) <= 1e-12, "%s: |grad| = %.17g", s->ops->kind, sqrt(gn));
        /* jets vs FD along the ray */
        dfl_jet jt;
        dfl_err err;
        if (!jets) {
            cr_assert_eq(dfl_shape_jet(s, x, dir, 3, &jt, &err), DFL_E_INPUT, "%s has jets",
                         s->ops->kind);
            continue;
        }
        cr_assert_eq(dfl_shape_jet(s, x, dir, 3, &jt, &err), DFL_OK, "%s", err.msg);
        cr_assert(fabs(dfl_jet_deriv(&jt, 0) - d) <= 1e-12 * (1 + fabs(d)));
        double gd = dfl_vecn_dot(dim, g, dir);
        cr_assert(fabs(dfl_jet_deriv(&jt, 1) - gd) <= 1e-10 * (1 + fabs(gd)),
                  "%s: jet d1 %.17g vs grad.dir %.17g", s->ops->kind, dfl_jet_deriv(&jt, 1), gd);
        for (int k = 1; k <= 3; k++) {
            jet_total++;
            double a = fd_deriv(s, x, dir, k, 1e-2), b = fd_deriv(s, x, dir, k, 5e-3);
            double tol = 1e-5 * (1 + fabs(b));
            if (fabs(a - b) > tol) continue; /* stencil straddles a kink */
            jet_tested++;
            double jk = dfl_jet_deriv(&jt, k);
            cr_assert(fabs(jk - b) <= tol, "%s: jet d%d = %.17g, FD %.17g at (%g %g %g)",
                      s->ops->kind, k, jk, b, x[0], x[1], x[2]);
        }
    }
    if (!jets) return;
    cr_assert(jet_tested >= jet_total / 2, "%s: only %d of %d jet checks were FD-consistent",
              s->ops->kind, jet_tested, jet_total);
}

