/* The implicit surface object (implicit.c): g and its derivatives in world
 * coordinates against central finite differences, and construction
 * errors. */
#include <string.h>

#include "geom/implicit_fixtures.h"

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

Test(implicit, empty_surface_is_rejected)
{
    dfl_implicit *s = NULL;
    dfl_err err;
    /* x^2 + y^2 + z^2 + 1 = 0 has no real point */
    dfl_monomial t[4] = {{1, {2, 0, 0}}, {1, {0, 2, 0}}, {1, {0, 0, 2}}, {1, {0, 0, 0}}};
    double lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};
    cr_assert_eq(dfl_implicit_new(4, t, NULL, NULL, lo, hi, NULL, &s, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "empty"));
}
