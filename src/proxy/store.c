#include "proxy/store.h"

DFL_NAMES_DEFINE(dfl_proxy_storage, DFL_PROXY_STORAGE_LIST, DFL_PROXY_STORAGE_COUNT,
                 dfl_proxy_storage_names, dfl_proxy_storage_name, dfl_proxy_storage_parse,
                 "storage")
DFL_NAMES_DEFINE(dfl_proxy_position, DFL_PROXY_POSITION_LIST, DFL_PROXY_POSITION_COUNT,
                 dfl_proxy_position_names, dfl_proxy_position_name, dfl_proxy_position_parse,
                 "position")

/* F16C: the half -> float conversion in hardware, 8 lanes; every x86-64
 * CPU with AVX2 has it in practice, but it is its own CPUID bit, checked
 * apart. */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(DFL_NO_ISA)
#include <immintrin.h>

#include "core/isa.h"

__attribute__((target("avx,f16c"))) static void half_block_f16c(const uint16_t *h, size_t n,
                                                                  double *out)
{
    size_t i = 0;
    for (; i + 8 <= n; i += 8) {
        const __m256 f = _mm256_cvtph_ps(_mm_loadu_si128((const __m128i *)(h + i)));
        _mm256_storeu_pd(out + i, _mm256_cvtps_pd(_mm256_castps256_ps128(f)));
        _mm256_storeu_pd(out + i + 4, _mm256_cvtps_pd(_mm256_extractf128_ps(f, 1)));
    }
    for (; i < n; i++) out[i] = _cvtsh_ss(h[i]);
}

int dfl_proxy_store_has_f16c(void)
{
    return dfl_isa_active() != DFL_ISA_SSE2 && __builtin_cpu_supports("f16c");
}
#else
static void half_block_f16c(const uint16_t *h, size_t n, double *out)
{
    for (size_t i = 0; i < n; i++) out[i] = imath_half_to_float(h[i]);
}

int dfl_proxy_store_has_f16c(void) { return 0; }
#endif

void dfl_proxy_store_half_block(int f16c, const uint16_t *h, size_t n, double *out)
{
    if (f16c) {
        half_block_f16c(h, n, out);
        return;
    }
    for (size_t i = 0; i < n; i++) out[i] = imath_half_to_float(h[i]);
}
