/* The robust implicit footpoint's fast path: the square-system Newton
 * reaches the sphere's exact footpoint, the fast path answers away from the
 * centre, and at the centre (every point a footpoint) the cap test hands
 * the point to the full search. */
#include <criterion/criterion.h>
#include <math.h>

#include "core/vec.h"
#include "proxy/input_implicit_fast.h"

Test(input_implicit_fast, sphere)
{
    const double c[3] = {0, 0, 0};
    dfl_implicit *s;
    cr_assert_eq(dfl_implicit_sphere(c, 0.5, NULL, &s, NULL), DFL_OK);
    double x[3] = {0.6, 0.3, -0.2}, p[3] = {0.45, 0.2, -0.1}, d;
    cr_assert(dfl_imp_square_newton(s, x, p, dfl_implicit_scale(s)));
    double l = dfl_vec3_norm(x);
    for (int j = 0; j < 3; j++) cr_assert(fabs(p[j] - 0.5 * x[j] / l) < 1e-14);
    dfl_imp_index *ix = dfl_imp_index_new(s);
    cr_assert_not_null(ix);
    cr_assert(dfl_imp_fast_foot(ix, x, p, &d));
    cr_assert(fabs(d - (l - 0.5)) < 1e-14);
    /* near the centre the far side is nearly as close: if the fast path
     * answers at all, it answers right */
    double y[3] = {0.01, -0.02, 0.005};
    if (dfl_imp_fast_foot(ix, y, p, &d)) cr_assert(fabs(d - (dfl_vec3_norm(y) - 0.5)) < 1e-14);
    double o[3] = {0, 0, 0};
    cr_assert(!dfl_imp_fast_foot(ix, o, p, &d));
    dfl_imp_index_free(ix);
    dfl_implicit_free(s);
}
