/* Small deterministic pseudo-random generators: reproducible sample points
 * for tests, benchmarks and randomized checks (not for statistics or
 * cryptography).  Each takes its whole state by pointer, so generators are
 * independent and thread-safe when each thread owns its state.
 *
 *   dfl_rng_splitmix(s, lo, hi)   SplitMix64 (Steele et al. 2014), 53-bit uniform in [lo, hi)
 *   dfl_rng_xorshift(s, lo, hi)   xorshift64 (13, 7, 17), 53-bit uniform in [lo, hi);
 *                                 the state must not be 0
 *   dfl_rng_lcg(s)                32-bit LCG (1103515245, 12345), 24-bit uniform in [0, 1)
 *
 * The sequences are part of the contract: tests pick their points with them
 * and must see the same points on every machine. */
#ifndef DFL_CORE_RNG_H
#define DFL_CORE_RNG_H

#include <stdint.h>

static inline double dfl_rng_splitmix(uint64_t *s, double lo, double hi)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return lo + (hi - lo) * ((double)(z >> 11) * 0x1.0p-53);
}

static inline double dfl_rng_xorshift(uint64_t *s, double lo, double hi)
{
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    return lo + (hi - lo) * (double)(*s >> 11) * (1.0 / 9007199254740992.0);
}

static inline double dfl_rng_lcg(unsigned *s)
{
    *s = *s * 1103515245u + 12345u;
    return (double)((*s >> 8) & 0xFFFFFF) / (double)0x1000000;
}

#endif
