/* core/isa.h: the names, widths and the DFL_ISA rules (unset or empty: the
 * best; a name the CPU runs: it; unknown or not run: DFL_E_INPUT naming the
 * variable, *out unchanged). */
#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>

#include "core/isa.h"

Test(core_isa, names_and_widths)
{
    cr_expect_str_eq(dfl_isa_name(DFL_ISA_SSE2), "sse2");
    cr_expect_str_eq(dfl_isa_name(DFL_ISA_AVX2), "avx2");
    cr_expect_str_eq(dfl_isa_name(DFL_ISA_AVX512), "avx512");
    cr_expect_eq(dfl_isa_width(DFL_ISA_SSE2), 2);
    cr_expect_eq(dfl_isa_width(DFL_ISA_AVX2), 4);
    cr_expect_eq(dfl_isa_width(DFL_ISA_AVX512), 8);
    dfl_isa i;
    cr_expect_eq(dfl_isa_parse("avx2", &i, NULL), DFL_OK);
    cr_expect_eq(i, DFL_ISA_AVX2);
    cr_expect_eq(dfl_isa_parse("AVX2", &i, NULL), DFL_E_INPUT);
}

Test(core_isa, best_is_the_widest_the_cpu_runs)
{
    cr_expect(dfl_isa_cpu_has(DFL_ISA_SSE2));
    const dfl_isa b = dfl_isa_best();
    cr_expect(dfl_isa_cpu_has(b));
    for (int i = (int)b + 1; i < DFL_ISA_COUNT; i++) cr_expect(!dfl_isa_cpu_has((dfl_isa)i));
    /* AVX-512 machines run AVX2 */
    if (dfl_isa_cpu_has(DFL_ISA_AVX512)) cr_expect(dfl_isa_cpu_has(DFL_ISA_AVX2));
}

Test(core_isa, environment)
{
    dfl_isa i = DFL_ISA_AVX512;
    unsetenv("DFL_ISA");
    cr_expect_eq(dfl_isa_from_env(&i, NULL), DFL_OK);
    cr_expect_eq(i, dfl_isa_best());
    setenv("DFL_ISA", "", 1);
    i = DFL_ISA_AVX512;
    cr_expect_eq(dfl_isa_from_env(&i, NULL), DFL_OK);
    cr_expect_eq(i, dfl_isa_best());
    for (int k = 0; k < DFL_ISA_COUNT; k++) {
        setenv("DFL_ISA", dfl_isa_names[k], 1);
        dfl_err err;
        i = (dfl_isa)((k + 1) % DFL_ISA_COUNT);
        const dfl_status st = dfl_isa_from_env(&i, &err);
        if (dfl_isa_cpu_has((dfl_isa)k)) {
            cr_expect_eq(st, DFL_OK);
            cr_expect_eq(i, (dfl_isa)k);
        } else {
            cr_expect_eq(st, DFL_E_INPUT);
            cr_expect_eq(i, (dfl_isa)((k + 1) % DFL_ISA_COUNT), "unchanged on failure");
            cr_expect(strstr(err.msg, "DFL_ISA") && strstr(err.msg, "does not run"), "%s",
                      err.msg);
        }
    }
    setenv("DFL_ISA", "avx", 1);
    dfl_err err;
    i = DFL_ISA_AVX2;
    cr_expect_eq(dfl_isa_from_env(&i, &err), DFL_E_INPUT);
    cr_expect_eq(i, DFL_ISA_AVX2);
    cr_expect(strstr(err.msg, "DFL_ISA='avx'") && strstr(err.msg, "sse2|avx2|avx512"), "%s",
              err.msg);
    unsetenv("DFL_ISA");
}
