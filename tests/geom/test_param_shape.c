/* Distance shapes of curves (param_shape.c): the signed shape of a closed
 * curve wraps the SDF and its jets, the unsigned one of an open space curve
 * has the kink |s| |dir_perp| through the curve. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/curve_fixtures.h"
#include "geom/footpoint.h"

Test(param_shape, shapes_wrap_the_distances)
{
    dfl_bspline c;
    cf_make_blob(&c);
    dfl_shape sh;
    dfl_err err;
    cr_assert_eq(dfl_shape_param_curve(&c, NULL, 1, &sh, &err), DFL_OK, "%s", err.msg);
    cr_assert_null(c.cp);
    double x[2] = {0.1, 0.2}, g[2];
    double d = dfl_shape_eval1(&sh, x, g);
    cr_assert(d < 0.0);
    cr_assert(fabs(hypot(g[0], g[1]) - 1.0) < 1e-14);
    dfl_jet j;
    double dir[2] = {1, 0};
    cr_assert_eq(dfl_shape_jet(&sh, x, dir, 3, &j, &err), DFL_OK, "%s", err.msg);
    cr_assert(fabs(dfl_jet_deriv(&j, 0) - d) < 1e-14);
    cr_assert(fabs(dfl_jet_deriv(&j, 1) - g[0]) < 1e-12);
    dfl_shape_free(&sh);

    /* unsigned distance to an open space curve; jet along a ray through
     * the curve: |s| |dir_perp| locally */
    cf_make_space(&c);
    double P[2 * 3];
    dfl_bspline_eval(&c, 2.0, 1, P);
    cr_assert_eq(dfl_shape_param_curve(&c, NULL, 0, &sh, &err), DFL_OK, "%s", err.msg);
    double on[3] = {P[0], P[1], P[2]}, g3[3];
    cr_assert(dfl_shape_eval1(&sh, on, g3) < 1e-12);
    double t[3] = {P[3], P[4], P[5]}, n3[3] = {-t[1], t[0], 0.0};
    double nl = sqrt(n3[0] * n3[0] + n3[1] * n3[1]);
    n3[0] /= nl;
    n3[1] /= nl;
    cr_assert_eq(dfl_shape_jet(&sh, on, n3, 2, &j, &err), DFL_OK, "%s", err.msg);
    cr_assert(fabs(dfl_jet_deriv(&j, 1) - 1.0) < 1e-9, "%g", dfl_jet_deriv(&j, 1));
    dfl_shape_free(&sh);
}
