/* Storage types: names, sizes, rounding and exact loads. */
#include <criterion/criterion.h>
#include <math.h>

#include "proxy/store.h"

Test(proxy_store, names)
{
    dfl_proxy_storage s;
    cr_expect_eq(dfl_proxy_storage_parse("half", &s, NULL), DFL_OK);
    cr_expect_eq(s, DFL_PROXY_HALF);
    cr_expect_eq(dfl_proxy_storage_parse("int8", &s, NULL), DFL_E_INPUT);
    cr_expect_str_eq(dfl_proxy_storage_name(DFL_PROXY_FLOAT), "float");
    dfl_proxy_position p;
    cr_expect_eq(dfl_proxy_position_parse("absolute", &p, NULL), DFL_OK);
    cr_expect_eq(p, DFL_PROXY_ABSOLUTE);
    cr_expect_str_eq(dfl_proxy_position_name(DFL_PROXY_DISPLACEMENT), "displacement");
}

Test(proxy_store, rounding)
{
    unsigned char buf[64];
    const double v = 0.1234567890123;
    for (int s = 0; s < DFL_PROXY_STORAGE_COUNT; s++) {
        dfl_proxy_store_put((dfl_proxy_storage)s, buf, 3, v);
        const double r = dfl_proxy_store_get((dfl_proxy_storage)s, buf, 3);
        cr_expect_eq(r, dfl_proxy_store_round((dfl_proxy_storage)s, v));
        /* relative error within half an ulp of the type */
        const double ulp = s == DFL_PROXY_DOUBLE ? 0x1p-53 : s == DFL_PROXY_FLOAT ? 0x1p-24 : 0x1p-11;
        cr_expect_leq(fabs(r - v), ulp * fabs(v), "%s", dfl_proxy_storage_name(s));
    }
    cr_expect_eq(dfl_proxy_storage_size(DFL_PROXY_HALF), 2);
    /* half: exact for representable values, 1 + 2^-10 is the next after 1 */
    dfl_proxy_store_put(DFL_PROXY_HALF, buf, 0, 1.0 + 0x1p-10);
    cr_expect_eq(dfl_proxy_store_get(DFL_PROXY_HALF, buf, 0), 1.0 + 0x1p-10);
    dfl_proxy_store_put(DFL_PROXY_HALF, buf, 0, 1.0 + 0x1p-12);
    cr_expect_eq(dfl_proxy_store_get(DFL_PROXY_HALF, buf, 0), 1.0);
    dfl_proxy_store_put(DFL_PROXY_HALF, buf, 0, 70000.0);
    cr_expect(isinf(dfl_proxy_store_get(DFL_PROXY_HALF, buf, 0)));
}

/* dfl_proxy_store_half_block is dfl_proxy_store_get (Imath) bit for bit on
 * all 65536 halves (zeros, subnormals, infinities, quiet and signalling
 * NaNs), on both paths (F16C where this CPU has it), in blocks of 8 and in
 * a short tail. */
Test(proxy_store, half_blocks_equal_imath_on_every_half)
{
    enum { N = 65536 };
    static uint16_t h[N];
    static double want[N], got[N];
    for (size_t i = 0; i < N; i++) {
        h[i] = (uint16_t)i;
        want[i] = dfl_proxy_store_get(DFL_PROXY_HALF, h, i);
    }
    cr_assert(isnan(want[0x7c01]) && isinf(want[0x7c00]) && want[1] > 0, "Imath's reference");
    for (int f16c = 0; f16c <= 1; f16c++) {
        if (f16c && !__builtin_cpu_supports("f16c")) continue;
        memset(got, 0, sizeof got);
        dfl_proxy_store_half_block(f16c, h, N, got);
        for (size_t i = 0; i < N; i++)
            cr_assert(memcmp(&got[i], &want[i], sizeof got[i]) == 0,
                      "f16c %d half 0x%04zx: %a vs %a", f16c, i, got[i], want[i]);
        for (size_t at = 0x7bf9; at < 0x7c11; at++) { /* lengths 1..13 around the NaNs */
            double t[13];
            size_t len = 1 + at % 13;
            dfl_proxy_store_half_block(f16c, h + at, len, t);
            cr_assert(memcmp(t, want + at, len * sizeof *t) == 0, "f16c %d tail at 0x%zx", f16c, at);
        }
    }
}
