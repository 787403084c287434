/* core/rng: ranges, determinism, and the first values of each sequence
 * (pinned: tests choose their points with these generators). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>

#include "core/rng.h"

Test(rng, ranges_and_determinism)
{
    uint64_t a = 1, b = 1, x = 88172645463325252ULL;
    unsigned l = 5;
    double mean = 0;
    for (int i = 0; i < 10000; i++) {
        double u = dfl_rng_splitmix(&a, -2, 3);
        cr_assert(u >= -2 && u < 3);
        cr_assert_eq(u, dfl_rng_splitmix(&b, -2, 3));
        double v = dfl_rng_xorshift(&x, 0, 1);
        cr_assert(v >= 0 && v < 1);
        double w = dfl_rng_lcg(&l);
        cr_assert(w >= 0 && w < 1);
        mean += v;
    }
    cr_assert(fabs(mean / 10000 - 0.5) < 0.02);
}

Test(rng, pinned_first_values)
{
    uint64_t s = 0;
    /* SplitMix64 from 0: first output 0xE220A8397B1DCDAF */
    dfl_rng_splitmix(&s, 0, 1);
    uint64_t z = s;
    cr_assert_eq(z, 0x9E3779B97F4A7C15ull);
    uint64_t t = 0;
    cr_assert_eq(dfl_rng_splitmix(&t, 0, 1), (double)(0xE220A8397B1DCDAFull >> 11) * 0x1.0p-53);
    uint64_t x = 1;
    dfl_rng_xorshift(&x, 0, 1);
    /* xorshift64 (13, 7, 17) from 1: 1 ^ 1 << 13 = 8193; ^ >> 7 = 8257; ^ << 17 */
    cr_assert_eq(x, 8257ull ^ (8257ull << 17));
    unsigned l = 0;
    dfl_rng_lcg(&l);
    cr_assert_eq(l, 12345u);
}
