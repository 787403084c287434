/* core/hypot: the plain formula inside the safe range (bit for bit), libm's
 * hypot outside it, and the nested 3D form. */
#include <criterion/criterion.h>
#include <math.h>

#include "core/hypot.h"
#include "core/rng.h"

Test(hypot, plain_formula_in_range_hypot_outside)
{
    uint64_t s = 3;
    for (int it = 0; it < 1000; it++) {
        double a = dfl_rng_splitmix(&s, -10, 10), b = dfl_rng_splitmix(&s, -10, 10);
        cr_assert_eq(dfl_hypot2(a, b), sqrt(a * a + b * b));
    }
    cr_assert_eq(dfl_hypot2(3e200, 4e200), hypot(3e200, 4e200)); /* would overflow */
    cr_assert(isfinite(dfl_hypot2(3e200, 4e200)));
    cr_assert_eq(dfl_hypot2(3e-200, 4e-200), hypot(3e-200, 4e-200)); /* would underflow */
    cr_assert(dfl_hypot2(3e-200, 4e-200) > 0.0);
    cr_assert_eq(dfl_hypot2(0.0, 0.0), 0.0);
    cr_assert_eq(dfl_hypot2(-3.0, 4.0), 5.0);
}

Test(hypot, vectors_nest)
{
    const double w2[2] = {3, 4}, w3[3] = {1, 2, 2}, w[3] = {0.1, 0.7, -0.3};
    cr_assert_eq(dfl_hypot_vec(2, w2), 5.0);
    cr_assert_eq(dfl_hypot_vec(3, w3), 3.0);
    cr_assert_eq(dfl_hypot_vec(3, w), dfl_hypot2(dfl_hypot2(w[0], w[1]), w[2]));
}
