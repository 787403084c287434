/* The process's ISA.  The choice is made once (pthread_once) and never
 * changes: every kernel of a run uses the same variant, and the value is
 * the one piece of process state here, written before any reader sees it.
 * CPU support comes from gcc's __builtin_cpu_supports, which also checks
 * that the OS saves the AVX / AVX-512 registers (XCR0). */
#include "core/isa.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>

DFL_NAMES_DEFINE(dfl_isa, DFL_ISA_LIST, DFL_ISA_COUNT, dfl_isa_names, dfl_isa_name,
                 dfl_isa_parse, "ISA")

#define DFL_ISA_WIDTH(code, name, w) [code] = w,
static const int widths[DFL_ISA_COUNT] = {DFL_ISA_LIST(DFL_ISA_WIDTH)};

bool dfl_isa_cpu_has(dfl_isa isa)
{
    if (isa == DFL_ISA_SSE2) return true;
#if DFL_ISA_MULTI
    __builtin_cpu_init();
    if (isa == DFL_ISA_AVX2) return __builtin_cpu_supports("avx2");
    if (isa == DFL_ISA_AVX512)
        return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
               __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw");
#endif
    return false;
}

dfl_isa dfl_isa_best(void)
{
    dfl_isa best = DFL_ISA_SSE2;
    for (int i = 0; i < DFL_ISA_COUNT; i++)
        if (dfl_isa_cpu_has((dfl_isa)i)) best = (dfl_isa)i;
    return best;
}

int dfl_isa_width(dfl_isa isa)
{
    return (int)isa >= 0 && (int)isa < DFL_ISA_COUNT ? widths[isa] : 2;
}

dfl_status dfl_isa_from_env(dfl_isa *out, dfl_err *err)
{
    const char *s = getenv("DFL_ISA");
    if (!s || !*s) {
        *out = dfl_isa_best();
        return DFL_OK;
    }
    char list[64], esc[96];
    dfl_names_list(dfl_isa_names, DFL_ISA_COUNT, list, sizeof list);
    size_t n = 0;
    for (; s[n] && n + 1 < sizeof esc && n < 80; n++)
        esc[n] = s[n] >= 0x20 && s[n] < 0x7f ? s[n] : '?';
    esc[n] = '\0';
    const int i = dfl_names_find(dfl_isa_names, DFL_ISA_COUNT, s);
    if (i < 0)
        return dfl_err_set(err, DFL_E_INPUT, "environment DFL_ISA='%s': unknown ISA (expected %s)",
                           esc, list);
    const dfl_isa isa = (dfl_isa)i;
    if (!dfl_isa_cpu_has(isa)) {
        char has[64] = "";
        size_t k = 0;
        for (int j = 0; j < DFL_ISA_COUNT && k < sizeof has; j++)
            if (dfl_isa_cpu_has((dfl_isa)j))
                k += (size_t)snprintf(has + k, sizeof has - k, "%s%s", k ? "|" : "",
                                      dfl_isa_names[j]);
        return dfl_err_set(err, DFL_E_INPUT,
                           "environment DFL_ISA='%s': this CPU does not run it (it runs %s)", esc,
                           has);
    }
    *out = isa;
    return DFL_OK;
}

static pthread_once_t once = PTHREAD_ONCE_INIT;
static dfl_isa active = DFL_ISA_SSE2;

static void choose(void)
{
    dfl_isa isa;
    active = dfl_isa_from_env(&isa, NULL) == DFL_OK ? isa : dfl_isa_best();
}

dfl_isa dfl_isa_active(void)
{
    pthread_once(&once, choose);
    return active;
}
