/* Jets of the closed-curve SDF (curve_jet.c) against its closed-form
 * derivatives of orders 0-3 and, at order 4, finite differences of the
 * closed-form third derivative. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/curve_fixtures.h"
#include "geom/footpoint.h"

Test(curve_jet, sdf_jets_match_closed_forms)
{
    dfl_bspline c;
    dfl_curve_sdf *S = cf_blob_sdf(&c);
    unsigned seed = 31;
    int tested = 0;
    for (int q = 0; q < 100 && tested < 30; q++) {
        double x[2] = {-3 + 6 * dfl_rng_lcg(&seed), -2 + 4 * dfl_rng_lcg(&seed)};
        double a = 6.283185307179586 * dfl_rng_lcg(&seed), dir[2] = {cos(a), sin(a)};
        dfl_curve_sdf_val v;
        cr_assert_eq(dfl_curve_sdf_eval(S, x, 3, &v, NULL), DFL_OK);
        if (fabs(1.0 + v.kappa * v.d) < 0.2 || fabs(x[1]) < 0.05) continue;
        tested++;
        dfl_jet j;
        dfl_err err;
        cr_assert_eq(dfl_curve_sdf_jet(S, x, dir, 6, &j, &err), DFL_OK, "%s", err.msg);
        double d1 = v.g[0] * dir[0] + v.g[1] * dir[1];
        double d2 = v.h[0] * dir[0] * dir[0] + 2 * v.h[1] * dir[0] * dir[1] + v.h[2] * dir[1] * dir[1];
        double d3 = v.t3[0] * pow(dir[0], 3) + 3 * v.t3[1] * dir[0] * dir[0] * dir[1] +
                    3 * v.t3[2] * dir[0] * dir[1] * dir[1] + v.t3[3] * pow(dir[1], 3);
        cr_assert(fabs(dfl_jet_deriv(&j, 0) - v.d) < 1e-14);
        cr_assert(fabs(dfl_jet_deriv(&j, 1) - d1) < 1e-12, "%g vs %g", dfl_jet_deriv(&j, 1), d1);
        cr_assert(fabs(dfl_jet_deriv(&j, 2) - d2) < 1e-10 * (1 + fabs(d2)), "%g vs %g",
                  dfl_jet_deriv(&j, 2), d2);
        cr_assert(fabs(dfl_jet_deriv(&j, 3) - d3) < 1e-9 * (1 + fabs(d3)), "%g vs %g",
                  dfl_jet_deriv(&j, 3), d3);
        /* order 4 against FD of the closed-form third derivative along dir */
        const double h = 1e-4;
        double d3s[2];
        for (int sgn = 0; sgn < 2; sgn++) {
            double y[2] = {x[0] + (sgn ? -h : h) * dir[0], x[1] + (sgn ? -h : h) * dir[1]};
            dfl_curve_sdf_val w;
            dfl_curve_sdf_eval(S, y, 3, &w, NULL);
            d3s[sgn] = w.t3[0] * pow(dir[0], 3) + 3 * w.t3[1] * dir[0] * dir[0] * dir[1] +
                       3 * w.t3[2] * dir[0] * dir[1] * dir[1] + w.t3[3] * pow(dir[1], 3);
        }
        double d4 = (d3s[0] - d3s[1]) / (2 * h);
        cr_assert(fabs(dfl_jet_deriv(&j, 4) - d4) < 1e-4 * (1 + fabs(d4)), "d4 %g vs %g",
                  dfl_jet_deriv(&j, 4), d4);
    }
    cr_assert(tested >= 15);
    dfl_curve_sdf_free(S);
    dfl_bspline_free(&c);
}

