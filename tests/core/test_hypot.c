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

/* Below 1e-290 the square sum has lost bits to underflow, which is why
 * dfl_hypot2 is libm's hypot there (hypot.h): 3e-160 and 4e-160 square to
 * about 2.5e-319, a subnormal with a few significant digits, while the
 * length is 5e-160 to within rounding. */
Test(hypot, subnormal_square_sum_uses_hypot)
{
    const double a = 3e-160, b = 4e-160, s = a * a + b * b;
    cr_assert(s > 0.0 && s < 1e-290, "the premise: a tiny non-zero square sum");
    cr_assert_eq(dfl_hypot2(a, b), hypot(a, b));
    cr_assert(fabs(dfl_hypot2(a, b) - 5e-160) <= 4e-16 * 5e-160, "%.17g", dfl_hypot2(a, b));
}

/* dfl_hypot_vec(3, w) rounds the inner length first (hypot.h), which is not
 * always the three-term square root: over random vectors it must equal the
 * nested form every time, and the two forms must differ for some of them
 * (else this test could not tell them apart). */
Test(hypot, vectors_nest_bit_for_bit)
{
    uint64_t s = 11;
    int differ = 0;
    for (int it = 0; it < 2000; it++) {
        double w[3];
        for (int j = 0; j < 3; j++) w[j] = dfl_rng_splitmix(&s, -10, 10);
        const double nested = dfl_hypot2(dfl_hypot2(w[0], w[1]), w[2]);
        cr_assert_eq(dfl_hypot_vec(3, w), nested, "it %d", it);
        differ += nested != sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    }
    cr_assert_gt(differ, 0);
}
