/* Tests for geom/shape.  References never come from a previous run:
 *  - distances: brute-force closest point over a dense sampling of each
 *    shape's boundary (>= 1e5 samples per shape and query, then a local
 *    pattern search in the patch parameters), signed by an independent
 *    closed-form inside test;
 *  - gradients: central finite differences of the SDF;
 *  - jets: 7-point finite-difference stencils along the ray (orders 1-3),
 *    used only where two step sizes agree (the stencil does not straddle a
 *    curvature jump such as a box's face/edge region boundary), and for
 *    circle/sphere the closed-form binomial series of sqrt(A + B s + C s^2). */
#include <criterion/criterion.h>

#include <math.h>
#include <string.h>

#include "geom/shape.h"

#define PI 3.14159265358979323846

/* ------------------------------------------------------------ helpers */

static unsigned long long rng_state = 88172645463325252ULL;
static double urand(double lo, double hi)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return lo + (hi - lo) * (double)(rng_state >> 11) * (1.0 / 9007199254740992.0);
}

static double dot(int n, const double *a, const double *b)
{
    double s = 0;
    for (int j = 0; j < n; j++) s += a[j] * b[j];
    return s;
}

static void normalize3(double *a)
{
    double l = sqrt(dot(3, a, a));
    for (int j = 0; j < 3; j++) a[j] /= l;
}

/* Orthonormal u, v perpendicular to unit w (Gram-Schmidt from e_x or e_y). */
static void perp_basis(const double w[3], double u[3], double v[3])
{
    double t[3] = {1, 0, 0};
    if (fabs(w[0]) > 0.8) { t[0] = 0; t[1] = 1; }
    double tw = dot(3, t, w);
    for (int j = 0; j < 3; j++) u[j] = t[j] - tw * w[j];
    normalize3(u);
    v[0] = w[1] * u[2] - w[2] * u[1];
    v[1] = w[2] * u[0] - w[0] * u[2];
    v[2] = w[0] * u[1] - w[1] * u[0];
}

/* A boundary patch: point(ctx, params) over the box [lo, hi] (np params). */
typedef struct patch {
    int np;
    double lo[2], hi[2];
    void (*point)(const void *ctx, const double *prm, double *p);
    const void *ctx;
} patch;

static double pdist(const patch *P, int dim, const double *x, const double *prm)
{
    double p[3];
    P->point(P->ctx, prm, p);
    double d2 = 0;
    for (int j = 0; j < dim; j++) d2 += (x[j] - p[j]) * (x[j] - p[j]);
    return sqrt(d2);
}

/* Pattern search from prm with initial steps st (clamped to the box). */
static double refine(const patch *P, int dim, const double *x, double *prm, const double *st0)
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
static double brute_dist(const patch *P, int npatch, int dim, const double *x, long nsamp)
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

/* Checks value vs brute force (signed by inside()), gradient vs central
 * FD and jets of orders 1-3 vs FD, at npts random points in [lo, hi]^dim. */
typedef int (*inside_fn)(const double *x);

static void check_shape(const dfl_shape *s, const patch *P, int npatch, inside_fn inside,
                        int is_signed, double lo, double hi, int npts, int check_values,
                        int unit_grad)
{
    const int dim = s->dim;
    int jet_tested = 0, jet_total = 0;
    for (int t = 0; t < npts; t++) {
        double x[3] = {0, 0, 0}, g[3], dir[3] = {0, 0, 0};
        for (int j = 0; j < dim; j++) x[j] = urand(lo, hi);
        for (int j = 0; j < dim; j++) dir[j] = urand(-1, 1);
        double d = dfl_shape_eval1(s, x, g);
        if (check_values) {
            double b = brute_dist(P, npatch, dim, x, 100000);
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
        if (unit_grad) cr_assert(fabs(sqrt(gn) - 1.0) <= 1e-12, "%s: |grad| = %.17g", s->ops->kind, sqrt(gn));
        /* jets vs FD along the ray */
        dfl_jet jt;
        dfl_err err;
        cr_assert_eq(dfl_shape_jet(s, x, dir, 3, &jt, &err), DFL_OK, "%s", err.msg);
        cr_assert(fabs(dfl_jet_deriv(&jt, 0) - d) <= 1e-12 * (1 + fabs(d)));
        double gd = dot(dim, g, dir);
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
    cr_assert(jet_tested >= jet_total / 2, "%s: only %d of %d jet checks were FD-consistent",
              s->ops->kind, jet_tested, jet_total);
}

/* ------------------------------------------------------------ shapes */

static const double C2[2] = {0.1, -0.2}, R2 = 0.7;
static void circle_pt(const void *ctx, const double *prm, double *p)
{
    (void)ctx;
    p[0] = C2[0] + R2 * cos(prm[0]);
    p[1] = C2[1] + R2 * sin(prm[0]);
}
static int circle_in(const double *x)
{
    return hypot(x[0] - C2[0], x[1] - C2[1]) < R2;
}

Test(shape, circle_matches_brute_force)
{
    dfl_shape s;
    cr_assert_eq(dfl_shape_circle(C2, R2, &s, NULL), DFL_OK);
    patch P = {1, {0, 0}, {2 * PI, 0}, circle_pt, NULL};
    check_shape(&s, &P, 1, circle_in, 1, -1.5, 1.5, 20, 1, 1);
    dfl_shape_free(&s);
    cr_assert_null(s.impl);
}

static const double C3[3] = {0.1, -0.2, 0.05}, R3 = 0.6;
static void sphere_pt(const void *ctx, const double *prm, double *p)
{
    (void)ctx;
    p[0] = C3[0] + R3 * sin(prm[0]) * cos(prm[1]);
    p[1] = C3[1] + R3 * sin(prm[0]) * sin(prm[1]);
    p[2] = C3[2] + R3 * cos(prm[0]);
}
static int sphere_in(const double *x)
{
    double u[3] = {x[0] - C3[0], x[1] - C3[1], x[2] - C3[2]};
    return dot(3, u, u) < R3 * R3;
}

Test(shape, sphere_matches_brute_force)
{
    dfl_shape s;
    cr_assert_eq(dfl_shape_sphere(C3, R3, &s, NULL), DFL_OK);
    patch P = {2, {0, 0}, {PI, 2 * PI}, sphere_pt, NULL};
    check_shape(&s, &P, 1, sphere_in, 1, -1.2, 1.2, 20, 1, 1);
    dfl_shape_free(&s);
}

/* Closed form: d(s) = sqrt(A + B s + C s^2) - r = sqrt(A) sum_m C(1/2, m) z^m - r,
 * z = (B s + C s^2)/A, collected with plain truncated polynomial products. */
static void binomial_reference(double A, double B, double Cc, double r, int K, double *coef)
{
    double z[32] = {0}, zm[32] = {0};
    z[1] = B / A;
    z[2] = Cc / A;
    zm[0] = 1;
    memset(coef, 0, (size_t)(K + 1) * sizeof *coef);
    double bin = 1;
    for (int m = 0; m <= K; m++) {
        for (int k = 0; k <= K; k++) coef[k] += bin * zm[k];
        double t[32] = {0};
        for (int k = 0; k <= K; k++)
            for (int i = 0; i <= k; i++) t[k] += zm[i] * z[k - i];
        memcpy(zm, t, sizeof t);
        bin *= (0.5 - m) / (m + 1);
    }
    for (int k = 0; k <= K; k++) coef[k] *= sqrt(A);
    coef[0] -= r;
}

Test(shape, circle_sphere_jets_are_the_binomial_series)
{
    for (int dim = 2; dim <= 3; dim++) {
        dfl_shape s;
        cr_assert_eq(dim == 2 ? dfl_shape_circle(C2, R2, &s, NULL)
                              : dfl_shape_sphere(C3, R3, &s, NULL),
                     DFL_OK);
        const double *c = dim == 2 ? C2 : C3;
        double r = dim == 2 ? R2 : R3;
        for (int t = 0; t < 10; t++) {
            double x[3], dir[3];
            for (int j = 0; j < dim; j++) { x[j] = urand(-1, 1); dir[j] = urand(-1, 1); }
            double u[3];
            for (int j = 0; j < dim; j++) u[j] = x[j] - c[j];
            const int K = 12;
            double ref[13];
            binomial_reference(dot(dim, u, u), 2 * dot(dim, u, dir), dot(dim, dir, dir), r, K, ref);
            dfl_jet jt;
            cr_assert_eq(dfl_shape_jet(&s, x, dir, K, &jt, NULL), DFL_OK);
            /* |c_k| ~ sqrt(A) (|dir| / |u|)^k: the singularities of the
             * square root sit at |s| = |u| / |dir| */
            double ratio = sqrt(dot(dim, dir, dir) / dot(dim, u, u));
            for (int k = 0; k <= K; k++)
                cr_assert(fabs(dfl_jet_coeff(&jt, k) - ref[k]) <=
                              1e-12 * (1 + sqrt(dot(dim, u, u))) * pow(ratio, k) + 1e-15,
                          "dim %d coeff %d: %.17g vs %.17g", dim, k, dfl_jet_coeff(&jt, k), ref[k]);
        }
        /* at the centre: d(s) = |dir| s - r exactly (valuation of sqrt) */
        double dir[3] = {0.3, -0.4, 1.2};
        dfl_jet jt;
        cr_assert_eq(dfl_shape_jet(&s, c, dir, 5, &jt, NULL), DFL_OK);
        double dn = sqrt(dot(dim, dir, dir));
        cr_assert(fabs(dfl_jet_coeff(&jt, 0) + r) < 1e-15);
        cr_assert(fabs(dfl_jet_coeff(&jt, 1) - dn) < 1e-15);
        for (int k = 2; k <= 5; k++) cr_assert(fabs(dfl_jet_coeff(&jt, k)) < 1e-15);
        dfl_shape_free(&s);
    }
}

/* torus */
static double TW[3] = {1, 2, 2}, TU[3], TV[3];
static const double TC[3] = {0.1, -0.1, 0.2}, TR = 0.6, Tr = 0.25;
static void torus_setup(void)
{
    normalize3(TW);
    perp_basis(TW, TU, TV);
}
static void torus_pt(const void *ctx, const double *prm, double *p)
{
    (void)ctx;
    double rr = TR + Tr * cos(prm[1]);
    for (int j = 0; j < 3; j++)
        p[j] = TC[j] + rr * (cos(prm[0]) * TU[j] + sin(prm[0]) * TV[j]) + Tr * sin(prm[1]) * TW[j];
}
static int torus_in(const double *x)
{
    double u[3] = {x[0] - TC[0], x[1] - TC[1], x[2] - TC[2]};
    double z = dot(3, u, TW), rho = sqrt(dot(3, u, u) - z * z);
    return (rho - TR) * (rho - TR) + z * z < Tr * Tr;
}

Test(shape, torus_matches_brute_force, .init = torus_setup)
{
    dfl_shape s;
    double ax[3] = {1, 2, 2};
    cr_assert_eq(dfl_shape_torus(TC, ax, TR, Tr, &s, NULL), DFL_OK);
    patch P = {2, {0, 0}, {2 * PI, 2 * PI}, torus_pt, NULL};
    check_shape(&s, &P, 1, torus_in, 1, -1.2, 1.2, 20, 1, 1);
    dfl_shape_free(&s);
}

/* cylinder: the closest point has the query's axial coordinate, so a window
 * of +-1 around it along the axis is enough */
static const double YP[3] = {0.2, 0.1, -0.1}, Yr = 0.4;
static double YW[3] = {0, -1, 2}, YU[3], YV[3];
static double Yz;
static void cyl_setup(void)
{
    normalize3(YW);
    perp_basis(YW, YU, YV);
}
static void cyl_pt(const void *ctx, const double *prm, double *p)
{
    (void)ctx;
    for (int j = 0; j < 3; j++)
        p[j] = YP[j] + (Yz + prm[1]) * YW[j] + Yr * (cos(prm[0]) * YU[j] + sin(prm[0]) * YV[j]);
}
static int cyl_in(const double *x)
{
    double u[3] = {x[0] - YP[0], x[1] - YP[1], x[2] - YP[2]};
    double z = dot(3, u, YW);
    return dot(3, u, u) - z * z < Yr * Yr;
}

Test(shape, cylinder_matches_brute_force, .init = cyl_setup)
{
    dfl_shape s;
    double ax[3] = {0, -1, 2};
    cr_assert_eq(dfl_shape_cylinder(YP, ax, Yr, &s, NULL), DFL_OK);
    patch P = {2, {0, -1}, {2 * PI, 1}, cyl_pt, NULL};
    for (int t = 0; t < 15; t++) {
        double x[3] = {urand(-1, 1), urand(-1, 1), urand(-1, 1)};
        double u[3] = {x[0] - YP[0], x[1] - YP[1], x[2] - YP[2]};
        Yz = dot(3, u, YW);
        double b = brute_dist(&P, 1, 3, x, 100000);
        if (cyl_in(x)) b = -b;
        double d = dfl_shape_eval1(&s, x, NULL);
        cr_assert(fabs(d - b) <= 1e-9, "cylinder %.17g vs %.17g", d, b);
    }
    check_shape(&s, &P, 1, cyl_in, 1, -1, 1, 20, 0, 1);
    dfl_shape_free(&s);
}

/* plane (3D) and line (2D): window around the plane's point, queries in
 * [-1, 1]^dim, so the foot lies well inside the window */
static const double PP[3] = {0.1, 0.2, -0.3};
static double PN[3] = {1, -2, 0.5}, PU[3], PV[3];
static void plane_setup(void)
{
    normalize3(PN);
    perp_basis(PN, PU, PV);
}
static void plane_pt(const void *ctx, const double *prm, double *p)
{
    (void)ctx;
    for (int j = 0; j < 3; j++) p[j] = PP[j] + prm[0] * PU[j] + prm[1] * PV[j];
}
static int plane_in(const double *x)
{
    double u[3] = {x[0] - PP[0], x[1] - PP[1], x[2] - PP[2]};
    return dot(3, u, PN) < 0;
}

Test(shape, plane_matches_brute_force, .init = plane_setup)
{
    dfl_shape s;
    double n[3] = {1, -2, 0.5};
    cr_assert_eq(dfl_shape_plane(3, PP, n, &s, NULL), DFL_OK);
    patch P = {2, {-4, -4}, {4, 4}, plane_pt, NULL};
    check_shape(&s, &P, 1, plane_in, 1, -1, 1, 15, 1, 1);
    /* jets of a linear function: exact and zero beyond order 1 */
    double x[3] = {0.3, 0.2, 0.1}, dir[3] = {0.5, 0.1, -0.7};
    dfl_jet jt;
    cr_assert_eq(dfl_shape_jet(&s, x, dir, 4, &jt, NULL), DFL_OK);
    cr_assert(fabs(dfl_jet_deriv(&jt, 1) - dot(3, dir, PN)) < 1e-15);
    for (int k = 2; k <= 4; k++) cr_assert(fabs(dfl_jet_deriv(&jt, k)) == 0.0);
    dfl_shape_free(&s);
}

/* capped cone: caps (polar discs) and lateral surface */
static const double KA[3] = {0.1, -0.3, -0.4}, KB[3] = {-0.1, 0.3, 0.5};
static double Kra = 0.5, Krb = 0.2, KW[3], KU[3], KV[3], KH;
static void cone_setup(void)
{
    for (int j = 0; j < 3; j++) KW[j] = KB[j] - KA[j];
    KH = sqrt(dot(3, KW, KW));
    normalize3(KW);
    perp_basis(KW, KU, KV);
}
static void disc_a(const void *ctx, const double *prm, double *p)
{
    (void)ctx;
    for (int j = 0; j < 3; j++) p[j] = KA[j] + prm[0] * (cos(prm[1]) * KU[j] + sin(prm[1]) * KV[j]);
}
static void disc_b(const void *ctx, const double *prm, double *p)
{
    (void)ctx;
    for (int j = 0; j < 3; j++) p[j] = KB[j] + prm[0] * (cos(prm[1]) * KU[j] + sin(prm[1]) * KV[j]);
}
static void lateral(const void *ctx, const double *prm, double *p)
{
    (void)ctx;
    double t = prm[0], rr = Kra + t * (Krb - Kra);
    for (int j = 0; j < 3; j++)
        p[j] = KA[j] + t * KH * KW[j] + rr * (cos(prm[1]) * KU[j] + sin(prm[1]) * KV[j]);
}
static int cone_in(const double *x)
{
    double u[3] = {x[0] - KA[0], x[1] - KA[1], x[2] - KA[2]};
    double y = dot(3, u, KW), rho = sqrt(dot(3, u, u) - y * y);
    return y > 0 && y < KH && rho < Kra + (Krb - Kra) * y / KH;
}

Test(shape, cone_matches_brute_force, .init = cone_setup)
{
    for (int variant = 0; variant < 3; variant++) {
        /* frustum, pointed cone (rb = 0), flaring frustum (rb > ra) */
        Kra = variant == 2 ? 0.15 : 0.5;
        Krb = variant == 0 ? 0.2 : (variant == 1 ? 0.0 : 0.45);
        dfl_shape s;
        cr_assert_eq(dfl_shape_cone(KA, KB, Kra, Krb, &s, NULL), DFL_OK);
        patch P[3] = {{2, {0, 0}, {Kra, 2 * PI}, disc_a, NULL},
                      {2, {0, 0}, {Krb, 2 * PI}, disc_b, NULL},
                      {2, {0, 0}, {1, 2 * PI}, lateral, NULL}};
        int np = Krb > 0 ? 3 : 2;
        patch Q[3] = {P[0], P[2], P[1]};
        check_shape(&s, np == 3 ? P : Q, np, cone_in, 1, -1, 1, 20, 1, 1);
        dfl_shape_free(&s);
    }
}

/* box: faces */
static const double BC[3] = {0.1, -0.1, 0.05}, BH[3] = {0.5, 0.3, 0.4};
static void box_face(const void *ctx, const double *prm, double *p)
{
    int f = *(const int *)ctx, ax = f / 2, a1 = (ax + 1) % 3, a2 = (ax + 2) % 3;
    p[ax] = BC[ax] + (f % 2 ? BH[ax] : -BH[ax]);
    p[a1] = BC[a1] + prm[0];
    p[a2] = BC[a2] + prm[1];
}
static void rect_edge(const void *ctx, const double *prm, double *p)
{
    int f = *(const int *)ctx, ax = f / 2, a1 = 1 - ax;
    p[ax] = BC[ax] + (f % 2 ? BH[ax] : -BH[ax]);
    p[a1] = BC[a1] + prm[0];
}
static int box_in3(const double *x)
{
    for (int j = 0; j < 3; j++)
        if (fabs(x[j] - BC[j]) >= BH[j]) return 0;
    return 1;
}
static int box_in2(const double *x)
{
    for (int j = 0; j < 2; j++)
        if (fabs(x[j] - BC[j]) >= BH[j]) return 0;
    return 1;
}

Test(shape, box_matches_brute_force)
{
    static const int ids[6] = {0, 1, 2, 3, 4, 5};
    dfl_shape s;
    cr_assert_eq(dfl_shape_box(3, BC, BH, &s, NULL), DFL_OK);
    patch P[6];
    for (int f = 0; f < 6; f++) {
        int ax = f / 2, a1 = (ax + 1) % 3, a2 = (ax + 2) % 3;
        patch q = {2, {-BH[a1], -BH[a2]}, {BH[a1], BH[a2]}, box_face, &ids[f]};
        P[f] = q;
    }
    check_shape(&s, P, 6, box_in3, 1, -1, 1, 20, 1, 1);
    dfl_shape_free(&s);
    cr_assert_eq(dfl_shape_box(2, BC, BH, &s, NULL), DFL_OK);
    patch E[4];
    for (int f = 0; f < 4; f++) {
        int a1 = 1 - f / 2;
        patch q = {1, {-BH[a1], 0}, {BH[a1], 0}, rect_edge, &ids[f]};
        E[f] = q;
    }
    check_shape(&s, E, 4, box_in2, 1, -1, 1, 20, 1, 1);
    dfl_shape_free(&s);
}

/* segment: unsigned */
static const double SA[3] = {-0.3, 0.2, 0.1}, SB[3] = {0.4, -0.1, 0.3};
static int seg_dim;
static void seg_pt(const void *ctx, const double *prm, double *p)
{
    (void)ctx;
    for (int j = 0; j < seg_dim; j++) p[j] = SA[j] + prm[0] * (SB[j] - SA[j]);
}
static int never(const double *x)
{
    (void)x;
    return 0;
}

Test(shape, segment_matches_brute_force)
{
    for (seg_dim = 2; seg_dim <= 3; seg_dim++) {
        dfl_shape s;
        cr_assert_eq(dfl_shape_segment(seg_dim, SA, SB, &s, NULL), DFL_OK);
        patch P = {1, {0, 0}, {1, 0}, seg_pt, NULL};
        check_shape(&s, &P, 1, never, 0, -1, 1, 20, 1, 1);
        /* on the segment, moving off it perpendicularly: d(s) = |dir| s */
        double mid[3], dir[3] = {0, 0, 0};
        for (int j = 0; j < seg_dim; j++) mid[j] = 0.5 * (SA[j] + SB[j]);
        dir[0] = -(SB[1] - SA[1]);
        dir[1] = SB[0] - SA[0];
        dfl_jet jt;
        cr_assert_eq(dfl_shape_jet(&s, mid, dir, 3, &jt, NULL), DFL_OK);
        cr_assert(fabs(dfl_jet_coeff(&jt, 1) - sqrt(dot(2, dir, dir))) < 1e-14);
        cr_assert(fabs(dfl_jet_coeff(&jt, 2)) < 1e-14 && fabs(dfl_jet_coeff(&jt, 3)) < 1e-14);
        dfl_shape_free(&s);
    }
}

/* ------------------------------------------------------------ CSG */

Test(shape, csg_exact_ops_are_min_max)
{
    const double ca[2] = {-0.2, 0}, cb[2] = {0.25, 0.1};
    for (int op = DFL_CSG_UNION; op <= DFL_CSG_DIFFERENCE; op++) {
        dfl_shape a, b, s, ra, rb;
        dfl_shape_circle(ca, 0.5, &a, NULL);
        dfl_shape_circle(cb, 0.4, &b, NULL);
        dfl_shape_circle(ca, 0.5, &ra, NULL);
        dfl_shape_circle(cb, 0.4, &rb, NULL);
        cr_assert_eq(dfl_shape_csg((dfl_csg_op)op, 0, &a, &b, &s, NULL), DFL_OK);
        cr_assert_null(a.impl);
        cr_assert_null(b.impl);
        for (int t = 0; t < 200; t++) {
            double x[2] = {urand(-1, 1), urand(-1, 1)};
            double da = dfl_shape_eval1(&ra, x, NULL), db = dfl_shape_eval1(&rb, x, NULL);
            double want = op == DFL_CSG_UNION ? fmin(da, db)
                        : op == DFL_CSG_INTERSECTION ? fmax(da, db) : fmax(da, -db);
            cr_assert(dfl_shape_eval1(&s, x, NULL) == want);
        }
        /* gradients and jets vs FD (values need no brute force: min/max) */
        check_shape(&s, NULL, 0, NULL, 1, -1, 1, 20, 0, 1);
        dfl_shape_free(&s);
        dfl_shape_free(&ra);
        dfl_shape_free(&rb);
    }
}

Test(shape, csg_smooth_ops)
{
    /* smin closed-form properties */
    cr_assert(fabs(dfl_csg_smin(0.3, 0.3, 0.2) - (0.3 - 0.2 / 4)) < 1e-16);
    cr_assert(dfl_csg_smin(0.0, 0.5, 0.2) == 0.0);
    cr_assert(dfl_csg_smin(0.5, 0.0, 0.2) == 0.0);
    for (int t = 0; t < 1000; t++) {
        double a = urand(-1, 1), b = urand(-1, 1), k = urand(0.01, 0.5);
        double m = dfl_csg_smin(a, b, k);
        cr_assert(m <= fmin(a, b) + 1e-16 && m >= fmin(a, b) - k / 4 - 1e-16);
    }
    const double ca[3] = {-0.2, 0, 0.1}, cb[3] = {0.25, 0.1, -0.1};
    for (int op = DFL_CSG_SMOOTH_UNION; op <= DFL_CSG_SMOOTH_DIFFERENCE; op++) {
        dfl_shape a, b, s, ra, rb;
        dfl_shape_sphere(ca, 0.5, &a, NULL);
        dfl_shape_sphere(cb, 0.4, &b, NULL);
        dfl_shape_sphere(ca, 0.5, &ra, NULL);
        dfl_shape_sphere(cb, 0.4, &rb, NULL);
        cr_assert_eq(dfl_shape_csg((dfl_csg_op)op, 0.3, &a, &b, &s, NULL), DFL_OK);
        for (int t = 0; t < 200; t++) {
            double x[3] = {urand(-1, 1), urand(-1, 1), urand(-1, 1)};
            double da = dfl_shape_eval1(&ra, x, NULL), db = dfl_shape_eval1(&rb, x, NULL);
            double want = op == DFL_CSG_SMOOTH_UNION ? dfl_csg_smin(da, db, 0.3)
                        : op == DFL_CSG_SMOOTH_INTERSECTION ? -dfl_csg_smin(-da, -db, 0.3)
                                                            : -dfl_csg_smin(-da, db, 0.3);
            cr_assert(fabs(dfl_shape_eval1(&s, x, NULL) - want) < 1e-15);
        }
        check_shape(&s, NULL, 0, NULL, 1, -1, 1, 30, 0, 0);
        dfl_shape_free(&s);
        dfl_shape_free(&ra);
        dfl_shape_free(&rb);
    }
}

/* ------------------------------------------------------------ misc */

Test(shape, footpoint_of_sdf_input)
{
    dfl_shape s;
    double ax[3] = {1, 2, 2};
    cr_assert_eq(dfl_shape_torus(TC, ax, TR, Tr, &s, NULL), DFL_OK);
    for (int t = 0; t < 50; t++) {
        double x[3] = {urand(-1, 1), urand(-1, 1), urand(-1, 1)}, p[3], g[3];
        dfl_err err;
        cr_assert_eq(dfl_shape_footpoint(&s, x, p, &err), DFL_OK, "%s", err.msg);
        double d = dfl_shape_eval1(&s, x, g);
        double u[3] = {x[0] - p[0], x[1] - p[1], x[2] - p[2]};
        cr_assert(fabs(dfl_shape_eval1(&s, p, NULL)) < 1e-13);
        cr_assert(fabs(sqrt(dot(3, u, u)) - fabs(d)) < 1e-12);
    }
    dfl_shape_free(&s);
}

Test(shape, rejects_degenerate_input)
{
    dfl_shape s = {0};
    dfl_err err;
    double c[3] = {0, 0, 0}, z[3] = {0, 0, 0}, ax[3] = {0, 0, 1}, h[3] = {1, 0, 1};
    cr_assert_eq(dfl_shape_circle(c, 0.0, &s, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "radius"));
    cr_assert_eq(dfl_shape_sphere(c, -1.0, &s, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_shape_torus(c, z, 1, 0.2, &s, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "axis"));
    cr_assert_eq(dfl_shape_torus(c, ax, 0.2, 0.3, &s, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_shape_cylinder(c, ax, 0, &s, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_shape_plane(3, c, z, &s, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_shape_cone(c, c, 1, 1, &s, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_shape_cone(c, ax, 0, 0, &s, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_shape_box(3, c, h, &s, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_shape_segment(2, c, c, &s, &err), DFL_E_INPUT);
    cr_assert_null(s.impl);
    dfl_shape a, b;
    dfl_shape_circle(c, 1, &a, NULL);
    dfl_shape_sphere(c, 1, &b, NULL);
    cr_assert_eq(dfl_shape_csg(DFL_CSG_UNION, 0, &a, &b, &s, &err), DFL_E_INPUT);
    cr_assert_null(a.impl); /* ownership taken even on failure */
    dfl_shape_circle(c, 1, &a, NULL);
    dfl_shape_circle(c, 2, &b, NULL);
    cr_assert_eq(dfl_shape_csg(DFL_CSG_SMOOTH_UNION, 0, &a, &b, &s, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "k"));
}

/* Hermite data of a sphere: H = (I - n n^T)/|u|, d_xyz = 3 u_x u_y u_z/|u|^5
 * (differentiate x/|u| in y, then -x y/|u|^3 in z); of a circle likewise. */
Test(shape, hermite_derivatives_closed_form)
{
    dfl_shape s;
    cr_assert_eq(dfl_shape_sphere(C3, R3, &s, NULL), DFL_OK);
    for (int t = 0; t < 20; t++) {
        double x[3] = {urand(-1, 1), urand(-1, 1), urand(-1, 1)};
        double u[3] = {x[0] - C3[0], x[1] - C3[1], x[2] - C3[2]}, l = sqrt(dot(3, u, u));
        dfl_shape_derivs D;
        cr_assert_eq(dfl_shape_derivs_at(&s, x, &D, NULL), DFL_OK);
        cr_assert(fabs(D.d - (l - R3)) < 1e-15);
        for (int i = 0; i < 3; i++) {
            cr_assert(fabs(D.g[i] - u[i] / l) < 1e-15);
            for (int j = 0; j < 3; j++) {
                double want = ((i == j) - u[i] * u[j] / (l * l)) / l;
                cr_assert(fabs(D.H[3 * i + j] - want) < 1e-13 * (1 + fabs(want)), "H%d%d", i, j);
            }
        }
        double want = 3 * u[0] * u[1] * u[2] / pow(l, 5);
        cr_assert(fabs(D.dxyz - want) < 1e-12 * (1 + fabs(want)), "%.17g vs %.17g", D.dxyz, want);
    }
    dfl_shape_free(&s);
    cr_assert_eq(dfl_shape_circle(C2, R2, &s, NULL), DFL_OK);
    double x[2] = {0.4, 0.9}, u[2] = {x[0] - C2[0], x[1] - C2[1]}, l = hypot(u[0], u[1]);
    dfl_shape_derivs D;
    cr_assert_eq(dfl_shape_derivs_at(&s, x, &D, NULL), DFL_OK);
    cr_assert(fabs(D.H[1] + u[0] * u[1] / (l * l * l)) < 1e-14);
    cr_assert(fabs(D.H[0] - u[1] * u[1] / (l * l * l)) < 1e-14);
    dfl_shape_free(&s);
}
