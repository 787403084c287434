/* The implicit SDF beyond its value (implicit_sdf.c): jets against the
 * closed-form torus, SDF Hessian and d_xyz against central finite
 * differences and against the curvature form
 * Hess d = sum k_i / (1 + k_i d) e_i e_i^T (geom/curvature.h), and the
 * shape wrapper. */
#include <string.h>

#include "geom/curvature.h"
#include "geom/shape.h"
#include "geom/implicit_fixtures.h"

/* Jets of the implicit torus SDF equal the jets of the closed form. */
Test(implicit_sdf, torus_jets_match_closed_form)
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

Test(implicit_sdf, sdf_derivatives_match_finite_differences)
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

Test(implicit_sdf, as_shape)
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
}
