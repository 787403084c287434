/* Tests for geom/curvature.  Expected values are closed forms (sphere 1/r;
 * cylinder 0 and 1/a; torus 1/r and cos(th)/(R + r cos(th)) with the
 * outward normal), hand-derived gradients/Hessians of the defining
 * functions and hand-derived partials of the parametrizations; a graph
 * surface cross-checks the implicit and parametric formulas against each
 * other where F != 0 and the coordinate lines are not principal. */
#include <criterion/criterion.h>

#include <math.h>

#include "core/vec.h"
#include "geom/curvature.h"

static void expect_dir(const double *e, const double *want)
{
    double wn = sqrt(dfl_vec3_dot(want, want));
    cr_assert(fabs(fabs(dfl_vec3_dot(e, want)) / wn - 1.0) < 1e-12, "direction mismatch (|cos| = %.17g)",
              fabs(dfl_vec3_dot(e, want)) / wn);
}

Test(curvature, sphere_implicit_and_parametric)
{
    const double r = 0.7;
    for (int t = 0; t < 10; t++) {
        double u = 0.3 + 0.5 * t, v = -1.2 + 0.25 * t;
        double p[3] = {r * cos(u) * cos(v), r * sin(u) * cos(v), r * sin(v)};
        /* g = |p|^2 - r^2 */
        double G[3] = {2 * p[0], 2 * p[1], 2 * p[2]}, H[9] = {2, 0, 0, 0, 2, 0, 0, 0, 2};
        dfl_curvature c;
        cr_assert_eq(dfl_curvature_implicit(G, H, &c, NULL), DFL_OK);
        cr_assert(fabs(c.k1 - 1 / r) < 1e-14 && fabs(c.k2 - 1 / r) < 1e-14);
        cr_assert(fabs(c.K - 1 / (r * r)) < 1e-13 && fabs(c.H - 1 / r) < 1e-14);
        /* S(u, v) = r (cos u cos v, sin u cos v, sin v) */
        double Su[3] = {-r * sin(u) * cos(v), r * cos(u) * cos(v), 0};
        double Sv[3] = {-r * cos(u) * sin(v), -r * sin(u) * sin(v), r * cos(v)};
        double Suu[3] = {-r * cos(u) * cos(v), -r * sin(u) * cos(v), 0};
        double Suv[3] = {r * sin(u) * sin(v), -r * cos(u) * sin(v), 0};
        double Svv[3] = {-r * cos(u) * cos(v), -r * sin(u) * cos(v), -r * sin(v)};
        cr_assert_eq(dfl_curvature_parametric(Su, Sv, Suu, Suv, Svv, p, &c, NULL), DFL_OK);
        cr_assert(fabs(c.k1 - 1 / r) < 1e-13 && fabs(c.k2 - 1 / r) < 1e-13);
        cr_assert(dfl_vec3_dot(c.n, p) > 0);
        /* the inward normal flips both signs */
        double in[3] = {-p[0], -p[1], -p[2]};
        cr_assert_eq(dfl_curvature_parametric(Su, Sv, Suu, Suv, Svv, in, &c, NULL), DFL_OK);
        cr_assert(fabs(c.k1 + 1 / r) < 1e-13 && fabs(c.k2 + 1 / r) < 1e-13);
        cr_assert(fabs(c.K - 1 / (r * r)) < 1e-12);
    }
}

Test(curvature, cylinder_implicit_and_parametric)
{
    const double a = 0.4;
    for (int t = 0; t < 10; t++) {
        double u = 0.7 * t, z = 0.1 * t - 0.3;
        double p[3] = {a * cos(u), a * sin(u), z};
        double G[3] = {2 * p[0], 2 * p[1], 0}, H[9] = {2, 0, 0, 0, 2, 0, 0, 0, 0};
        double circ[3] = {-sin(u), cos(u), 0}, ax[3] = {0, 0, 1};
        dfl_curvature c;
        cr_assert_eq(dfl_curvature_implicit(G, H, &c, NULL), DFL_OK);
        cr_assert(fabs(c.k1) < 1e-14 && fabs(c.k2 - 1 / a) < 1e-13);
        expect_dir(c.e1, ax);
        expect_dir(c.e2, circ);
        double Su[3] = {-a * sin(u), a * cos(u), 0}, Sv[3] = {0, 0, 1};
        double Suu[3] = {-a * cos(u), -a * sin(u), 0}, Suv[3] = {0, 0, 0}, Svv[3] = {0, 0, 0};
        cr_assert_eq(dfl_curvature_parametric(Su, Sv, Suu, Suv, Svv, G, &c, NULL), DFL_OK);
        cr_assert(fabs(c.k1) < 1e-14 && fabs(c.k2 - 1 / a) < 1e-13);
        expect_dir(c.e1, ax);
        expect_dir(c.e2, circ);
        double cr[3] = {c.e1[1] * c.e2[2] - c.e1[2] * c.e2[1], c.e1[2] * c.e2[0] - c.e1[0] * c.e2[2],
                        c.e1[0] * c.e2[1] - c.e1[1] * c.e2[0]};
        cr_assert(fabs(dfl_vec3_dot(cr, c.n) - 1) < 1e-12, "e1 x e2 = n");
        cr_assert(fabs(c.K) < 1e-14);
    }
}

/* Torus S(phi, th) = ((R + r cos th) cos phi, (R + r cos th) sin phi, r sin th)
 * with outward normal (cos th cos phi, cos th sin phi, sin th): kappa = 1/r
 * along the meridian and cos th / (R + r cos th) along the parallel. */
Test(curvature, torus_closed_forms_and_corrected_gaussian)
{
    const double R = 0.6, r = 0.25;
    int typo_differs = 0;
    for (int t = 0; t < 24; t++) {
        double ph = 0.4 + 0.37 * t, th = -3.0 + 0.26 * t;
        double rr = R + r * cos(th);
        double p[3] = {rr * cos(ph), rr * sin(ph), r * sin(th)};
        double nrm[3] = {cos(th) * cos(ph), cos(th) * sin(ph), sin(th)};
        double km = 1 / r, kp = cos(th) / rr;
        double Sph[3] = {-rr * sin(ph), rr * cos(ph), 0};
        double Sth[3] = {-r * sin(th) * cos(ph), -r * sin(th) * sin(ph), r * cos(th)};
        double Sphph[3] = {-rr * cos(ph), -rr * sin(ph), 0};
        double Sphth[3] = {r * sin(th) * sin(ph), -r * sin(th) * cos(ph), 0};
        double Sthth[3] = {-r * cos(th) * cos(ph), -r * cos(th) * sin(ph), -r * sin(th)};
        /* implicit: g = (|p|^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + y^2) */
        double A = dfl_vec3_dot(p, p) + R * R - r * r;
        double G[3] = {4 * A * p[0] - 8 * R * R * p[0], 4 * A * p[1] - 8 * R * R * p[1], 4 * A * p[2]};
        double H[9] = {8 * p[0] * p[0] + 4 * A - 8 * R * R, 8 * p[0] * p[1], 8 * p[0] * p[2],
                       8 * p[0] * p[1], 8 * p[1] * p[1] + 4 * A - 8 * R * R, 8 * p[1] * p[2],
                       8 * p[0] * p[2], 8 * p[1] * p[2], 8 * p[2] * p[2] + 4 * A};
        dfl_curvature ci, cp;
        cr_assert_eq(dfl_curvature_implicit(G, H, &ci, NULL), DFL_OK);
        cr_assert_eq(dfl_curvature_parametric(Sph, Sth, Sphph, Sphth, Sthth, nrm, &cp, NULL), DFL_OK);
        double lo = fmin(km, kp), hi = fmax(km, kp);
        for (int m = 0; m < 2; m++) {
            const dfl_curvature *c = m ? &cp : &ci;
            cr_assert(fabs(dfl_vec3_dot(c->n, nrm) - 1) < 1e-12);
            cr_assert(fabs(c->k1 - lo) < 1e-12 && fabs(c->k2 - hi) < 1e-12,
                      "%s t %d: k = %.17g %.17g, want %.17g %.17g", m ? "param" : "implicit", t,
                      c->k1, c->k2, lo, hi);
            expect_dir(km < kp ? c->e1 : c->e2, Sth);
            expect_dir(km < kp ? c->e2 : c->e1, Sph);
            cr_assert(fabs(c->K - km * kp) < 1e-12);
            cr_assert(fabs(c->H - 0.5 * (km + kp)) < 1e-12);
        }
        /* the corrected Gaussian curvature (LN - M^2)/(EG - F^2) */
        dfl_fundamental_forms f;
        dfl_fundamental_forms_eval(Sph, Sth, Sphph, Sphth, Sthth, nrm, &f);
        cr_assert(fabs(dfl_gaussian_curvature_ff(&f) - km * kp) < 1e-12);
        cr_assert(fabs(dfl_mean_curvature_ff(&f) - 0.5 * (km + kp)) < 1e-12);
        /* hvb25's printed (LM - N^2)/(EG - F^2) is not it */
        double typo = (f.L * f.M - f.N * f.N) / (f.E * f.G - f.F * f.F);
        if (fabs(typo - km * kp) > 1e-3) typo_differs++;
    }
    cr_assert(typo_differs >= 20);
}

/* Graph z = a x^2 + b x y + c y^2 + e x^3: implicit (g = f - z) and
 * parametric (u, v, f(u, v)) must agree, although F != 0 and the coordinate
 * directions are not principal. */
Test(curvature, graph_implicit_equals_parametric)
{
    const double a = 0.8, b = -0.6, c = 0.3, e = 0.5;
    for (int t = 0; t < 30; t++) {
        double x = -0.9 + 0.06 * t, y = 0.7 - 0.05 * t;
        double fx = 2 * a * x + b * y + 3 * e * x * x, fy = b * x + 2 * c * y;
        double fxx = 2 * a + 6 * e * x, fxy = b, fyy = 2 * c;
        double G[3] = {fx, fy, -1}, H[9] = {fxx, fxy, 0, fxy, fyy, 0, 0, 0, 0};
        double Su[3] = {1, 0, fx}, Sv[3] = {0, 1, fy}, Suu[3] = {0, 0, fxx}, Suv[3] = {0, 0, fxy},
               Svv[3] = {0, 0, fyy};
        dfl_curvature ci, cp;
        cr_assert_eq(dfl_curvature_implicit(G, H, &ci, NULL), DFL_OK);
        cr_assert_eq(dfl_curvature_parametric(Su, Sv, Suu, Suv, Svv, G, &cp, NULL), DFL_OK);
        cr_assert(fabs(ci.k1 - cp.k1) < 1e-12 && fabs(ci.k2 - cp.k2) < 1e-12,
                  "implicit %.17g %.17g param %.17g %.17g", ci.k1, ci.k2, cp.k1, cp.k2);
        if (cp.k2 - cp.k1 > 1e-6) {
            expect_dir(ci.e1, cp.e1);
            expect_dir(ci.e2, cp.e2);
        }
        /* Gaussian curvature of a graph: (fxx fyy - fxy^2) / (1 + fx^2 + fy^2)^2 */
        double K = (fxx * fyy - fxy * fxy) / pow(1 + fx * fx + fy * fy, 2);
        cr_assert(fabs(ci.K - K) < 1e-12 && fabs(cp.K - K) < 1e-12);
        dfl_fundamental_forms ff;
        dfl_fundamental_forms_eval(Su, Sv, Suu, Suv, Svv, cp.n, &ff);
        cr_assert(fabs(dfl_gaussian_curvature_ff(&ff) - K) < 1e-12);
        cr_assert(fabs(dfl_mean_curvature_ff(&ff) - cp.H) < 1e-12);
    }
}

Test(curvature, plane_curves)
{
    const double r = 0.3;
    for (int t = 0; t < 8; t++) {
        double u = 0.8 * t;
        double p[2] = {r * cos(u), r * sin(u)};
        double G[2] = {2 * p[0], 2 * p[1]}, H[4] = {2, 0, 0, 2};
        cr_assert(fabs(dfl_curvature_implicit2(G, H) - 1 / r) < 1e-13);
        double d1[2] = {-r * sin(u), r * cos(u)}, d2[2] = {-r * cos(u), -r * sin(u)};
        double out[2] = {cos(u), sin(u)}, in[2] = {-cos(u), -sin(u)};
        cr_assert(fabs(dfl_curvature_curve2(d1, d2, out) - 1 / r) < 1e-13);
        cr_assert(fabs(dfl_curvature_curve2(d1, d2, in) + 1 / r) < 1e-13);
    }
    double z[2] = {0, 0}, H[4] = {1, 0, 0, 1};
    cr_assert(isnan(dfl_curvature_implicit2(z, H)));
}

Test(curvature, degenerate_input)
{
    double z[3] = {0, 0, 0}, H[9] = {0};
    dfl_curvature c;
    dfl_err err;
    cr_assert_eq(dfl_curvature_implicit(z, H, &c, &err), DFL_E_NUMERIC);
    double Su[3] = {1, 0, 0};
    cr_assert_eq(dfl_curvature_parametric(Su, Su, z, z, z, NULL, &c, &err), DFL_E_NUMERIC);
}
