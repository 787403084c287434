/* The analytic shape kinds (shape_analytic.c) against brute force, finite
 * differences and, for circle/sphere jets, the closed-form binomial series
 * of sqrt(A + B s + C s^2) (references: shape_check.h). */
#include <criterion/criterion.h>

#include <math.h>
#include <string.h>

#include "core/vec.h"
#include "geom/shape.h"
#include "geom/shape_check.h"

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

Test(shape_analytic, circle_matches_brute_force)
{
    dfl_shape s;
    cr_assert_eq(dfl_shape_circle(C2, R2, &s, NULL), DFL_OK);
    sc_patch P = {1, {0, 0}, {2 * DFL_PI, 0}, circle_pt, NULL};
    sc_check_shape(&s, &P, 1, circle_in, 1, -1.5, 1.5, 20, 1, 1, 1);
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
    return dfl_vecn_dot(3, u, u) < R3 * R3;
}

Test(shape_analytic, sphere_matches_brute_force)
{
    dfl_shape s;
    cr_assert_eq(dfl_shape_sphere(C3, R3, &s, NULL), DFL_OK);
    sc_patch P = {2, {0, 0}, {DFL_PI, 2 * DFL_PI}, sphere_pt, NULL};
    sc_check_shape(&s, &P, 1, sphere_in, 1, -1.2, 1.2, 20, 1, 1, 1);
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

Test(shape_analytic, circle_sphere_jets_are_the_binomial_series)
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
            for (int j = 0; j < dim; j++) { x[j] = sc_urand(-1, 1); dir[j] = sc_urand(-1, 1); }
            double u[3];
            for (int j = 0; j < dim; j++) u[j] = x[j] - c[j];
            const int K = 12;
            double ref[13];
            binomial_reference(dfl_vecn_dot(dim, u, u), 2 * dfl_vecn_dot(dim, u, dir), dfl_vecn_dot(dim, dir, dir), r, K, ref);
            dfl_jet jt;
            cr_assert_eq(dfl_shape_jet(&s, x, dir, K, &jt, NULL), DFL_OK);
            /* |c_k| ~ sqrt(A) (|dir| / |u|)^k: the singularities of the
             * square root sit at |s| = |u| / |dir| */
            double ratio = sqrt(dfl_vecn_dot(dim, dir, dir) / dfl_vecn_dot(dim, u, u));
            for (int k = 0; k <= K; k++)
                cr_assert(fabs(dfl_jet_coeff(&jt, k) - ref[k]) <=
                              1e-12 * (1 + sqrt(dfl_vecn_dot(dim, u, u))) * pow(ratio, k) + 1e-15,
                          "dim %d coeff %d: %.17g vs %.17g", dim, k, dfl_jet_coeff(&jt, k), ref[k]);
        }
        /* at the centre: d(s) = |dir| s - r exactly (valuation of sqrt) */
        double dir[3] = {0.3, -0.4, 1.2};
        dfl_jet jt;
        cr_assert_eq(dfl_shape_jet(&s, c, dir, 5, &jt, NULL), DFL_OK);
        double dn = sqrt(dfl_vecn_dot(dim, dir, dir));
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
    sc_normalize3(TW);
    sc_perp_basis(TW, TU, TV);
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
    double z = dfl_vecn_dot(3, u, TW), rho = sqrt(dfl_vecn_dot(3, u, u) - z * z);
    return (rho - TR) * (rho - TR) + z * z < Tr * Tr;
}

Test(shape_analytic, torus_matches_brute_force, .init = torus_setup)
{
    dfl_shape s;
    double ax[3] = {1, 2, 2};
    cr_assert_eq(dfl_shape_torus(TC, ax, TR, Tr, &s, NULL), DFL_OK);
    sc_patch P = {2, {0, 0}, {2 * DFL_PI, 2 * DFL_PI}, torus_pt, NULL};
    sc_check_shape(&s, &P, 1, torus_in, 1, -1.2, 1.2, 20, 1, 1, 1);
    dfl_shape_free(&s);
}

/* cylinder: the closest point has the query's axial coordinate, so a window
 * of +-1 around it along the axis is enough */
static const double YP[3] = {0.2, 0.1, -0.1}, Yr = 0.4;
static double YW[3] = {0, -1, 2}, YU[3], YV[3];
static double Yz;
static void cyl_setup(void)
{
    sc_normalize3(YW);
    sc_perp_basis(YW, YU, YV);
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
    double z = dfl_vecn_dot(3, u, YW);
    return dfl_vecn_dot(3, u, u) - z * z < Yr * Yr;
}

Test(shape_analytic, cylinder_matches_brute_force, .init = cyl_setup)
{
    dfl_shape s;
    double ax[3] = {0, -1, 2};
    cr_assert_eq(dfl_shape_cylinder(YP, ax, Yr, &s, NULL), DFL_OK);
    sc_patch P = {2, {0, -1}, {2 * DFL_PI, 1}, cyl_pt, NULL};
    for (int t = 0; t < 15; t++) {
        double x[3] = {sc_urand(-1, 1), sc_urand(-1, 1), sc_urand(-1, 1)};
        double u[3] = {x[0] - YP[0], x[1] - YP[1], x[2] - YP[2]};
        Yz = dfl_vecn_dot(3, u, YW);
        double b = sc_brute_dist(&P, 1, 3, x, 100000);
        if (cyl_in(x)) b = -b;
        double d = dfl_shape_eval1(&s, x, NULL);
        cr_assert(fabs(d - b) <= 1e-9, "cylinder %.17g vs %.17g", d, b);
    }
    sc_check_shape(&s, &P, 1, cyl_in, 1, -1, 1, 20, 0, 1, 1);
    dfl_shape_free(&s);
}

/* plane (3D) and line (2D): window around the plane's point, queries in
 * [-1, 1]^dim, so the foot lies well inside the window */
static const double PP[3] = {0.1, 0.2, -0.3};
static double PN[3] = {1, -2, 0.5}, PU[3], PV[3];
static void plane_setup(void)
{
    sc_normalize3(PN);
    sc_perp_basis(PN, PU, PV);
}
static void plane_pt(const void *ctx, const double *prm, double *p)
{
    (void)ctx;
    for (int j = 0; j < 3; j++) p[j] = PP[j] + prm[0] * PU[j] + prm[1] * PV[j];
}
static int plane_in(const double *x)
{
    double u[3] = {x[0] - PP[0], x[1] - PP[1], x[2] - PP[2]};
    return dfl_vecn_dot(3, u, PN) < 0;
}

Test(shape_analytic, plane_matches_brute_force, .init = plane_setup)
{
    dfl_shape s;
    double n[3] = {1, -2, 0.5};
    cr_assert_eq(dfl_shape_plane(3, PP, n, &s, NULL), DFL_OK);
    sc_patch P = {2, {-4, -4}, {4, 4}, plane_pt, NULL};
    sc_check_shape(&s, &P, 1, plane_in, 1, -1, 1, 15, 1, 1, 1);
    /* jets of a linear function: exact and zero beyond order 1 */
    double x[3] = {0.3, 0.2, 0.1}, dir[3] = {0.5, 0.1, -0.7};
    dfl_jet jt;
    cr_assert_eq(dfl_shape_jet(&s, x, dir, 4, &jt, NULL), DFL_OK);
    cr_assert(fabs(dfl_jet_deriv(&jt, 1) - dfl_vecn_dot(3, dir, PN)) < 1e-15);
    for (int k = 2; k <= 4; k++) cr_assert(fabs(dfl_jet_deriv(&jt, k)) == 0.0);
    dfl_shape_free(&s);
}

/* capped cone: caps (polar discs) and lateral surface */
static const double KA[3] = {0.1, -0.3, -0.4}, KB[3] = {-0.1, 0.3, 0.5};
static double Kra = 0.5, Krb = 0.2, KW[3], KU[3], KV[3], KH;
static void cone_setup(void)
{
    for (int j = 0; j < 3; j++) KW[j] = KB[j] - KA[j];
    KH = sqrt(dfl_vecn_dot(3, KW, KW));
    sc_normalize3(KW);
    sc_perp_basis(KW, KU, KV);
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
    double y = dfl_vecn_dot(3, u, KW), rho = sqrt(dfl_vecn_dot(3, u, u) - y * y);
    return y > 0 && y < KH && rho < Kra + (Krb - Kra) * y / KH;
}

Test(shape_analytic, cone_matches_brute_force, .init = cone_setup)
{
    for (int variant = 0; variant < 3; variant++) {
        /* frustum, pointed cone (rb = 0), flaring frustum (rb > ra) */
        Kra = variant == 2 ? 0.15 : 0.5;
        Krb = variant == 0 ? 0.2 : (variant == 1 ? 0.0 : 0.45);
        dfl_shape s;
        cr_assert_eq(dfl_shape_cone(KA, KB, Kra, Krb, &s, NULL), DFL_OK);
        sc_patch P[3] = {{2, {0, 0}, {Kra, 2 * DFL_PI}, disc_a, NULL},
                      {2, {0, 0}, {Krb, 2 * DFL_PI}, disc_b, NULL},
                      {2, {0, 0}, {1, 2 * DFL_PI}, lateral, NULL}};
        int np = Krb > 0 ? 3 : 2;
        sc_patch Q[3] = {P[0], P[2], P[1]};
        sc_check_shape(&s, np == 3 ? P : Q, np, cone_in, 1, -1, 1, 20, 1, 1, 1);
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

Test(shape_analytic, box_matches_brute_force)
{
    static const int ids[6] = {0, 1, 2, 3, 4, 5};
    dfl_shape s;
    cr_assert_eq(dfl_shape_box(3, BC, BH, &s, NULL), DFL_OK);
    sc_patch P[6];
    for (int f = 0; f < 6; f++) {
        int ax = f / 2, a1 = (ax + 1) % 3, a2 = (ax + 2) % 3;
        sc_patch q = {2, {-BH[a1], -BH[a2]}, {BH[a1], BH[a2]}, box_face, &ids[f]};
        P[f] = q;
    }
    sc_check_shape(&s, P, 6, box_in3, 1, -1, 1, 20, 1, 1, 1);
    dfl_shape_free(&s);
    cr_assert_eq(dfl_shape_box(2, BC, BH, &s, NULL), DFL_OK);
    sc_patch E[4];
    for (int f = 0; f < 4; f++) {
        int a1 = 1 - f / 2;
        sc_patch q = {1, {-BH[a1], 0}, {BH[a1], 0}, rect_edge, &ids[f]};
        E[f] = q;
    }
    sc_check_shape(&s, E, 4, box_in2, 1, -1, 1, 20, 1, 1, 1);
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

Test(shape_analytic, segment_matches_brute_force)
{
    for (seg_dim = 2; seg_dim <= 3; seg_dim++) {
        dfl_shape s;
        cr_assert_eq(dfl_shape_segment(seg_dim, SA, SB, &s, NULL), DFL_OK);
        sc_patch P = {1, {0, 0}, {1, 0}, seg_pt, NULL};
        sc_check_shape(&s, &P, 1, never, 0, -1, 1, 20, 1, 1, 1);
        /* on the segment, moving off it perpendicularly: d(s) = |dir| s */
        double mid[3], dir[3] = {0, 0, 0};
        for (int j = 0; j < seg_dim; j++) mid[j] = 0.5 * (SA[j] + SB[j]);
        dir[0] = -(SB[1] - SA[1]);
        dir[1] = SB[0] - SA[0];
        dfl_jet jt;
        cr_assert_eq(dfl_shape_jet(&s, mid, dir, 3, &jt, NULL), DFL_OK);
        cr_assert(fabs(dfl_jet_coeff(&jt, 1) - sqrt(dfl_vecn_dot(2, dir, dir))) < 1e-14);
        cr_assert(fabs(dfl_jet_coeff(&jt, 2)) < 1e-14 && fabs(dfl_jet_coeff(&jt, 3)) < 1e-14);
        dfl_shape_free(&s);
    }
}

Test(shape_analytic, rejects_degenerate_input)
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
}


/* Inside dflab's domain (|x| <= 1e150, core/domain.h) the circle and the
 * sphere stay finite and exact to a few ulps where the plain square sum
 * would overflow: d = |x - c| - r with |x - c| = 2e150 (or sqrt(3) 2e150). */
Test(shape_analytic, ball_is_finite_across_the_domain)
{
    const double c2[2] = {1e150, -1e150}, x2[2] = {-1e150, -1e150};
    dfl_shape s;
    cr_assert_eq(dfl_shape_circle(c2, 1.0, &s, NULL), DFL_OK);
    double v, g[3];
    s.ops->eval(s.impl, 1, x2, &v, g);
    cr_expect(fabs(v - 2e150) <= 4 * 2e150 * 0x1p-52, "circle: %.17g", v);
    cr_expect(fabs(g[0] + 1.0) < 1e-15 && fabs(g[1]) < 1e-15, "gradient %g %g", g[0], g[1]);
    dfl_shape_free(&s);
    const double c3[3] = {1e150, 1e150, 1e150}, x3[3] = {-1e150, -1e150, -1e150};
    cr_assert_eq(dfl_shape_sphere(c3, 0.5, &s, NULL), DFL_OK);
    s.ops->eval(s.impl, 1, x3, &v, g);
    const double want = sqrt(3.0) * 2e150;
    cr_expect(fabs(v - want) <= 8 * want * 0x1p-52, "sphere: %.17g vs %.17g", v, want);
    dfl_shape_free(&s);
}
