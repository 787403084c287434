/* Random Bezier patches: a seed names one surface; the net spans the square. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "geom/surface_random.h"

Test(surface_random, seed_names_one_surface)
{
    dfl_surface_set a, b, c;
    cr_assert_eq(dfl_surface_random_bezier(7, 4, 0.8, 0.4, &a, NULL), DFL_OK);
    cr_assert_eq(dfl_surface_random_bezier(7, 4, 0.8, 0.4, &b, NULL), DFL_OK);
    cr_assert_eq(dfl_surface_random_bezier(8, 4, 0.8, 0.4, &c, NULL), DFL_OK);
    cr_assert_eq(a.npatch, 1);
    cr_assert_eq(memcmp(a.patch[0].cp, b.patch[0].cp, 48 * sizeof(double)), 0);
    cr_assert_neq(memcmp(a.patch[0].cp, c.patch[0].cp, 48 * sizeof(double)), 0);
    for (int k = 0; k < 16; k++) {
        const double *p = a.patch[0].cp + 3 * k;
        cr_assert(fabs(p[0] - (-0.8 + 1.6 * (k % 4) / 3)) < 1e-15);
        cr_assert(fabs(p[1] - (-0.8 + 1.6 * (k / 4) / 3)) < 1e-15);
        cr_assert(fabs(p[2]) <= 0.4);
    }
    dfl_surface_set_free(&a);
    dfl_surface_set_free(&b);
    dfl_surface_set_free(&c);
    dfl_err err;
    cr_assert_eq(dfl_surface_random_bezier(1, 1, 0.8, 0.4, &a, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_surface_random_bezier(1, 4, 0, 0.4, &a, &err), DFL_E_INPUT);
}
