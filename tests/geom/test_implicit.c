/* Tests for geom/implicit.  References:
 *  - the implicit torus quartic against the closed-form torus SDF of
 *    geom/shape (itself checked against brute force in test_shape.c);
 *  - Goursat's and the genus-2 surface against a dense brute-force sampling
 *    of the zero set made here by bisection on sign changes along grid lines
 *    (independent of the solver's own projected samples);
 *  - derivatives of g and of the SDF against central finite differences and
 *    against the curvature closed form Hess d = sum k_i/(1 + k_i d) e_i e_i^T. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/curvature.h"
#include "geom/implicit.h"
#include "geom/shape.h"

static unsigned long long rng_state = 0x9E3779B97F4A7C15ULL;
static double urand(double lo, double hi)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return lo + (hi - lo) * (double)(rng_state >> 11) * (1.0 / 9007199254740992.0);
}

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static const double TC[3] = {0.1, -0.2, 0.05}, TAX[3] = {1, -1, 2}, TR = 0.5, Tr = 0.2;

static dfl_implicit *make_torus(dfl_foot_backend b)
{
    dfl_implicit_options opt;
    dfl_implicit_options_default(&opt);
    opt.backend = b;
    dfl_implicit *s = NULL;
    dfl_err err;
    cr_assert_eq(dfl_implicit_torus(TC, TAX, TR, Tr, &opt, &s, &err), DFL_OK, "%s", err.msg);
    return s;
}

/* A point at local cylindrical coordinates (rho, phi, z) of the torus frame. */
static void torus_point(double rho, double phi, double z, double x[3])
{
    double w[3], u[3], v[3], l = sqrt(dot3(TAX, TAX));
    for (int j = 0; j < 3; j++) w[j] = TAX[j] / l;
    double t[3] = {1, 0, 0}, tw = dot3(t, w);
    for (int j = 0; j < 3; j++) u[j] = t[j] - tw * w[j];
    l = sqrt(dot3(u, u));
    for (int j = 0; j < 3; j++) u[j] /= l;
    v[0] = w[1] * u[2] - w[2] * u[1];
    v[1] = w[2] * u[0] - w[0] * u[2];
    v[2] = w[0] * u[1] - w[1] * u[0];
    for (int j = 0; j < 3; j++)
        x[j] = TC[j] + rho * (cos(phi) * u[j] + sin(phi) * v[j]) + z * w[j];
}

Test(implicit, g_derivatives_match_finite_differences)
{
    dfl_implicit *s = make_torus(DFL_FOOT_NEWTON);
    for (int t = 0; t < 20; t++) {
        double x[3] = {urand(-1, 1), urand(-1, 1), urand(-1, 1)}, G[3], H[9], T[27];
        dfl_implicit_g(s, x, G, H);
        dfl_implicit_g3(s, x, T);
        const double h = 1e-5;
        for (int j = 0; j < 3; j++) {
            double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]}, Gp[3], Gm[3], Hp[9], Hm[9];
            xp[j] += h;
            xm[j] -= h;
            double fd = (dfl_implicit_g(s, xp, Gp, Hp) - dfl_implicit_g(s, xm, Gm, Hm)) / (2 * h);
            cr_assert(fabs(fd - G[j]) < 1e-8 * (1 + fabs(G[j])));
            for (int i = 0; i < 3; i++) {
                cr_assert(fabs((Gp[i] - Gm[i]) / (2 * h) - H[3 * i + j]) < 1e-7 * (1 + fabs(H[3 * i + j])));
                for (int k = 0; k < 3; k++)
                    cr_assert(fabs((Hp[3 * i + k] - Hm[3 * i + k]) / (2 * h) - T[9 * i + 3 * k + j]) <
                              1e-6 * (1 + fabs(T[9 * i + 3 * k + j])));
            }
        }
    }
    dfl_implicit_free(s);
}

/* The implicit torus' footpoint SDF equals the closed-form torus SDF. */
Test(implicit, torus_footpoint_sdf_is_exact)
{
    dfl_implicit *s = make_torus(DFL_FOOT_NEWTON);
    dfl_shape ex;
    cr_assert_eq(dfl_shape_torus(TC, TAX, TR, Tr, &ex, NULL), DFL_OK);
    double worst = 0;
    for (int t = 0; t < 400; t++) {
        double x[3];
        if (t < 300)
            for (int j = 0; j < 3; j++) x[j] = TC[j] + urand(-1, 1);
        else /* far away */
            for (int j = 0; j < 3; j++) x[j] = TC[j] + urand(-50, 50);
        dfl_footpoint f;
        dfl_err err;
        cr_assert_eq(dfl_implicit_footpoint(s, x, &f, &err), DFL_OK, "%s", err.msg);
        double g[3], d = dfl_shape_eval1(&ex, x, g);
        worst = fmax(worst, fabs(f.d - d));
        cr_assert(fabs(f.d - d) <= 1e-10 * (1 + fabs(d)), "x = (%g %g %g): %.17g vs exact %.17g",
                  x[0], x[1], x[2], f.d, d);
        if (!f.medial)
            for (int j = 0; j < 3; j++) cr_assert(fabs(f.n[j] - g[j]) < 1e-8);
    }
    cr_log_info("implicit torus vs exact: max |error| %.3g", worst);
    dfl_shape_free(&ex);
    dfl_implicit_free(s);
}

/* Hard points: near the axis (the medial axis outside the tube's ring and
 * the centres of the major curvature), near the centre circle (centres of
 * the minor curvature, medial axis of the solid), far away.  Both backends
 * must agree with each other and with the exact SDF to 1e-10. */
Test(implicit, newton_and_ceres_agree_on_hard_points)
{
    dfl_implicit *s = make_torus(DFL_FOOT_NEWTON);
    dfl_shape ex;
    cr_assert_eq(dfl_shape_torus(TC, TAX, TR, Tr, &ex, NULL), DFL_OK);
    double pts[][3] = {
        {1e-3, 0.3, 0.0},  {1e-6, 1.0, 0.1},  {1e-4, 2.0, -0.3}, {2e-3, 4.0, 0.5},  /* near axis */
        {TR + 1e-3, 0.2, 0.0}, {TR - 1e-4, 1.3, 1e-4}, {TR, 2.5, 1e-3},           /* centre circle */
        {TR + 1e-6, 5.0, -1e-6},
        {80.0, 0.7, 30.0}, {3.0, 2.0, -60.0}, {0.01, 0.0, 100.0},                 /* far away */
        {TR + Tr - 1e-9, 0.4, 0.0}, {TR - Tr + 1e-9, 0.4, 0.0}};                  /* on surface */
    int np = sizeof pts / sizeof pts[0];
    double worst = 0;
    for (int i = 0; i < np; i++) {
        double x[3];
        torus_point(pts[i][0], pts[i][1], pts[i][2], x);
        dfl_footpoint fn, fc;
        dfl_err err;
        cr_assert_eq(dfl_implicit_footpoint_with(s, DFL_FOOT_NEWTON, x, &fn, &err), DFL_OK, "%s",
                     err.msg);
        cr_assert_eq(dfl_implicit_footpoint_with(s, DFL_FOOT_CERES, x, &fc, &err), DFL_OK, "%s",
                     err.msg);
        double d = dfl_shape_eval1(&ex, x, NULL);
        worst = fmax(worst, fabs(fn.d - fc.d));
        cr_assert(fabs(fn.d - fc.d) <= 1e-10, "point %d: newton %.17g ceres %.17g", i, fn.d, fc.d);
        cr_assert(fabs(fn.d - d) <= 1e-10, "point %d: newton %.17g exact %.17g", i, fn.d, d);
        cr_assert(fabs(fc.d - d) <= 1e-10, "point %d: ceres %.17g exact %.17g", i, fc.d, d);
    }
    cr_log_info("newton vs ceres on %d hard points: max |diff| %.3g", np, worst);
    dfl_shape_free(&ex);
    dfl_implicit_free(s);
}

Test(implicit, medial_axis_is_flagged_and_deterministic)
{
    dfl_implicit *s = make_torus(DFL_FOOT_NEWTON);
    double x[3];
    torus_point(0.0, 0.0, 0.1, x); /* on the axis: a whole circle of footpoints */
    dfl_footpoint a, b;
    cr_assert_eq(dfl_implicit_footpoint(s, x, &a, NULL), DFL_OK);
    cr_assert_eq(dfl_implicit_footpoint(s, x, &b, NULL), DFL_OK);
    cr_assert(a.medial == 1);
    cr_assert(memcmp(a.p, b.p, sizeof a.p) == 0);
    double want = sqrt(TR * TR + 0.1 * 0.1) - Tr;
    cr_assert(fabs(a.d - want) < 1e-10);
    torus_point(0.3, 1.0, 0.05, x);
    cr_assert_eq(dfl_implicit_footpoint(s, x, &a, NULL), DFL_OK);
    cr_assert(a.medial == 0);
    dfl_implicit_free(s);
}

/* Jets of the implicit torus SDF equal the jets of the closed form. */
Test(implicit, torus_jets_match_closed_form)
{
    dfl_implicit *s = make_torus(DFL_FOOT_NEWTON);
    dfl_shape ex;
    cr_assert_eq(dfl_shape_torus(TC, TAX, TR, Tr, &ex, NULL), DFL_OK);
    for (int t = 0; t < 30; t++) {
        double x[3], dir[3];
        torus_point(urand(0.1, 1.0), urand(0, 6.3), urand(-0.5, 0.5), x);
        for (int j = 0; j < 3; j++) dir[j] = urand(-1, 1);
        dfl_footpoint f;
        cr_assert_eq(dfl_implicit_footpoint(s, x, &f, NULL), DFL_OK);
        if (f.medial) continue;
        const int K = 6;
        dfl_jet a, b;
        dfl_err err;
        cr_assert_eq(dfl_implicit_jet(s, &f, x, dir, K, &a, &err), DFL_OK, "%s", err.msg);
        cr_assert_eq(dfl_shape_jet(&ex, x, dir, K, &b, NULL), DFL_OK);
        for (int k = 0; k <= K; k++) {
            double ca = dfl_jet_coeff(&a, k), cb = dfl_jet_coeff(&b, k);
            cr_assert(fabs(ca - cb) <= 1e-8 * (1 + fabs(cb)) * pow(5.0, k),
                      "t %d coeff %d: implicit %.17g closed form %.17g", t, k, ca, cb);
        }
    }
    dfl_shape_free(&ex);
    dfl_implicit_free(s);
}

/* ---- brute force over the zero set ----------------------------------- */

typedef struct cloud {
    size_t n, cap;
    double *p;
} cloud;

static void cloud_add(cloud *c, const double p[3])
{
    if (c->n == c->cap) {
        c->cap = c->cap ? 2 * c->cap : 4096;
        c->p = realloc(c->p, c->cap * 3 * sizeof *c->p);
        cr_assert_not_null(c->p);
    }
    memcpy(c->p + 3 * c->n++, p, 3 * sizeof *p);
}

/* Roots of g along all grid lines (three directions) of a grid of spacing
 * about hb over [lo, hi], by bisection to 1e-13. */
static cloud zero_set(const dfl_implicit *s, const double lo[3], const double hi[3], double hb)
{
    cloud c = {0, 0, NULL};
    int n[3];
    for (int a = 0; a < 3; a++) n[a] = (int)ceil((hi[a] - lo[a]) / hb);
    for (int ax = 0; ax < 3; ax++) {
        int a1 = (ax + 1) % 3, a2 = (ax + 2) % 3;
        double step = (hi[ax] - lo[ax]) / n[ax];
        for (int i = 0; i <= n[a1]; i++)
            for (int j = 0; j <= n[a2]; j++) {
                double p[3];
                p[a1] = lo[a1] + (hi[a1] - lo[a1]) * i / n[a1];
                p[a2] = lo[a2] + (hi[a2] - lo[a2]) * j / n[a2];
                p[ax] = lo[ax];
                double gprev = dfl_implicit_g(s, p, NULL, NULL);
                for (int k = 1; k <= n[ax]; k++) {
                    double q[3] = {p[0], p[1], p[2]};
                    q[ax] = lo[ax] + step * k;
                    double g = dfl_implicit_g(s, q, NULL, NULL);
                    if ((g < 0) != (gprev < 0)) {
                        double a = q[ax] - step, b = q[ax], ga = gprev;
                        while (b - a > 1e-13) {
                            double m = 0.5 * (a + b);
                            q[ax] = m;
                            double gm = dfl_implicit_g(s, q, NULL, NULL);
                            if ((gm < 0) == (ga < 0)) { a = m; ga = gm; } else b = m;
                        }
                        q[ax] = 0.5 * (a + b);
                        cloud_add(&c, q);
                    }
                    gprev = g;
                }
            }
    }
    return c;
}

static void check_against_cloud(const dfl_implicit *s, const double lo[3], const double hi[3],
                                double hb, int npts)
{
    cloud c = zero_set(s, lo, hi, hb);
    cr_assert(c.n > 1000);
    double worst_excess = 0;
    for (int t = 0; t < npts; t++) {
        double x[3];
        for (int a = 0; a < 3; a++) {
            double m = 0.5 * (lo[a] + hi[a]), r = 0.75 * (hi[a] - lo[a]);
            x[a] = urand(m - r, m + r);
        }
        dfl_footpoint f;
        dfl_err err;
        cr_assert_eq(dfl_implicit_footpoint(s, x, &f, &err), DFL_OK, "%s", err.msg);
        double best = HUGE_VAL;
        for (size_t i = 0; i < c.n; i++) {
            double u[3] = {x[0] - c.p[3 * i], x[1] - c.p[3 * i + 1], x[2] - c.p[3 * i + 2]};
            best = fmin(best, dot3(u, u));
        }
        best = sqrt(best);
        /* the solver's footpoint is on the surface, so no sample can be
         * closer; and the true footpoint has a sample within ~hb */
        cr_assert(best >= fabs(f.d) - 1e-12, "x (%g %g %g): sample closer (%.17g) than solver (%.17g)",
                  x[0], x[1], x[2], best, fabs(f.d));
        cr_assert(best - fabs(f.d) <= 2 * hb, "x (%g %g %g): solver %.17g, samples %.17g",
                  x[0], x[1], x[2], fabs(f.d), best);
        worst_excess = fmax(worst_excess, best - fabs(f.d));
        double g = dfl_implicit_g(s, x, NULL, NULL);
        cr_assert(g == 0 || (g < 0) == (f.d < 0));
        cr_assert(fabs(dfl_implicit_g(s, f.p, NULL, NULL)) < 1e-10);
    }
    cr_log_info("cloud of %zu points, spacing %.3g: max sample excess %.3g", c.n, hb, worst_excess);
    free(c.p);
}

Test(implicit, goursat_distance_matches_brute_force)
{
    const double c[3] = {0, 0, 0};
    dfl_implicit *s = NULL;
    dfl_err err;
    cr_assert_eq(dfl_implicit_goursat(c, 0, -5, 11.8, NULL, &s, &err), DFL_OK, "%s", err.msg);
    double lo[3] = {-2.5, -2.5, -2.5}, hi[3] = {2.5, 2.5, 2.5};
    check_against_cloud(s, lo, hi, 0.02, 100);
    dfl_implicit_free(s);
}

Test(implicit, genus2_distance_matches_brute_force)
{
    const double c[3] = {0.1, 0, -0.1};
    dfl_implicit *s = NULL;
    dfl_err err;
    cr_assert_eq(dfl_implicit_genus2(c, 0.1, NULL, &s, &err), DFL_OK, "%s", err.msg);
    double lo[3] = {-1.2 + 0.1, -0.6, -0.12 - 0.1}, hi[3] = {1.2 + 0.1, 0.6, 0.12 - 0.1};
    check_against_cloud(s, lo, hi, 0.006, 100);
    dfl_implicit_free(s);
}

/* ---- SDF derivatives for Hermite data ---------------------------------- */

static double sdf(const dfl_implicit *s, const double *x, double *g)
{
    dfl_footpoint f;
    cr_assert_eq(dfl_implicit_footpoint(s, x, &f, NULL), DFL_OK);
    if (g) memcpy(g, f.n, sizeof f.n);
    return f.d;
}

static void check_derivs(const dfl_implicit *s, const double *x)
{
    dfl_sdf_derivs D;
    dfl_err err;
    cr_assert_eq(dfl_implicit_sdf_derivs(s, x, &D, &err), DFL_OK, "%s", err.msg);
    cr_assert(!D.foot.medial);
    const double h = 2e-5;
    /* Hessian by central differences of the gradient */
    for (int j = 0; j < 3; j++) {
        double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]}, gp[3], gm[3];
        xp[j] += h;
        xm[j] -= h;
        sdf(s, xp, gp);
        sdf(s, xm, gm);
        for (int i = 0; i < 3; i++) {
            double fd = (gp[i] - gm[i]) / (2 * h);
            cr_assert(fabs(fd - D.H[3 * i + j]) < 1e-6 * (1 + fabs(fd)),
                      "x (%.17g, %.17g, %.17g): H[%d][%d] = %.12g, FD %.12g", x[0], x[1], x[2],
                      i, j, D.H[3 * i + j], fd);
        }
    }
    /* d_xyz = d/dy d/dz (d/dx d): mixed difference of the gradient's x */
    const double h3 = 1e-3;
    double acc = 0;
    for (int sy = -1; sy <= 1; sy += 2)
        for (int sz = -1; sz <= 1; sz += 2) {
            double xq[3] = {x[0], x[1] + sy * h3, x[2] + sz * h3}, g[3];
            sdf(s, xq, g);
            acc += sy * sz * g[0];
        }
    double fd3 = acc / (4 * h3 * h3);
    cr_assert(fabs(fd3 - D.dxyz) < 1e-4 * (1 + fabs(fd3)), "dxyz = %.12g, FD %.12g", D.dxyz, fd3);
    /* closed form through the principal curvatures at the footpoint */
    double G[3], Hg[9];
    dfl_implicit_g(s, D.foot.p, G, Hg);
    dfl_curvature cv;
    cr_assert_eq(dfl_curvature_implicit(G, Hg, &cv, NULL), DFL_OK);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double want = cv.k1 / (1 + cv.k1 * D.d) * cv.e1[i] * cv.e1[j] +
                          cv.k2 / (1 + cv.k2 * D.d) * cv.e2[i] * cv.e2[j];
            cr_assert(fabs(want - D.H[3 * i + j]) < 1e-9 * (1 + fabs(want)),
                      "H[%d][%d] = %.15g, curvature form %.15g", i, j, D.H[3 * i + j], want);
        }
}

Test(implicit, sdf_derivatives_match_finite_differences)
{
    dfl_implicit *s = make_torus(DFL_FOOT_NEWTON);
    for (int t = 0; t < 12; t++) {
        /* finite differences need room: stay 0.08 away from the centre
         * circle, where the Hessian grows like 1/distance */
        double rho, z;
        do {
            rho = urand(0.15, 0.9);
            z = urand(-0.4, 0.4);
        } while (hypot(rho - TR, z) < 0.08);
        double x[3];
        torus_point(rho, urand(0, 6.3), z, x);
        check_derivs(s, x);
    }
    dfl_implicit_free(s);
    const double c[3] = {0, 0, 0};
    cr_assert_eq(dfl_implicit_goursat(c, 0, -5, 11.8, NULL, &s, NULL), DFL_OK);
    double x1[3] = {2.2, 0.3, -0.4}, x2[3] = {1.6, 1.5, 0.2}, x3[3] = {0.5, 2.0, 2.1};
    check_derivs(s, x1);
    check_derivs(s, x2);
    check_derivs(s, x3);
    dfl_implicit_free(s);
}

Test(implicit, as_shape_and_bad_input)
{
    dfl_implicit *s = make_torus(DFL_FOOT_NEWTON);
    dfl_shape sh;
    cr_assert_eq(dfl_implicit_shape(&s, &sh, NULL), DFL_OK);
    cr_assert_null(s);
    cr_assert_not_null(dfl_implicit_of_shape(&sh));
    double x[3], g[3];
    torus_point(0.9, 0.2, 0.1, x);
    double d = dfl_shape_eval1(&sh, x, g);
    double want = sqrt(0.4 * 0.4 + 0.1 * 0.1) - Tr;
    cr_assert(fabs(d - want) < 1e-12);
    dfl_shape_free(&sh);
    dfl_err err;
    double c[3] = {0, 0, 0}, z[3] = {0, 0, 0};
    cr_assert_eq(dfl_implicit_torus(c, z, 1, 0.2, NULL, &s, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_implicit_torus(c, TAX, 0.2, 0.3, NULL, &s, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_implicit_genus2(c, 0.3, NULL, &s, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_implicit_goursat(c, -0.5, 0, -1, NULL, &s, &err), DFL_E_INPUT);
    /* x^2 + y^2 + z^2 + 1 = 0 has no real point */
    dfl_monomial t[4] = {{1, {2, 0, 0}}, {1, {0, 2, 0}}, {1, {0, 0, 2}}, {1, {0, 0, 0}}};
    double lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};
    cr_assert_eq(dfl_implicit_new(4, t, NULL, NULL, lo, hi, NULL, &s, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "empty"));
}
