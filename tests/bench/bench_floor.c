/* The floor: this CPU's floating-point throughput, measured at run time
 * (nothing about the machine is assumed).  Per level -- scalar (one double,
 * the sd forms), sse2 (2), avx2 (4), avx512 (8), each only when
 * __builtin_cpu_supports says the CPU and OS run it --
 *
 *   fma      fused multiply-adds (when the CPU has FMA), 2 flops each
 *   muladd   separate multiplies and adds, half each (how dflab's kernels
 *            compute: no contraction, core/isa.h)
 *   div      divisions
 *   sqrt     square roots
 *   divsqrt  two divisions to one root (8 + 4 chains): whether divisions
 *            and roots share one unit (they do on current x86 cores), so
 *            that a kernel's division and root times add up
 *
 * each a loop over NACC independent dependency chains (more than latency x
 * throughput on current x86 cores: FMA latency 4, 2 pipes, 8 in flight),
 * one thread, best of REPS.  Rates are double operations per second (lanes
 * counted); the FMA peak is in flop/s.  bench_floor_fraction turns a
 * kernel's operation count and rate into its fraction of that floor. */
#include <immintrin.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bench.h"

#define NACC 12
#define ITERS 2000000L
#define REPS 5

/* NACC chains a0..a11, the statement S(a) applied to each per iteration. */
#define CHAINS(T, SET1, init)                                                         \
    T a0 = SET1(init), a1 = SET1(init + 0.01), a2 = SET1(init + 0.02),               \
      a3 = SET1(init + 0.03), a4 = SET1(init + 0.04), a5 = SET1(init + 0.05),        \
      a6 = SET1(init + 0.06), a7 = SET1(init + 0.07), a8 = SET1(init + 0.08),        \
      a9 = SET1(init + 0.09), a10 = SET1(init + 0.10), a11 = SET1(init + 0.11)
#define STEP12(S) S(a0); S(a1); S(a2); S(a3); S(a4); S(a5); S(a6); S(a7); S(a8); S(a9); \
    S(a10); S(a11)
#define SUM12(ADD) ADD(ADD(ADD(ADD(a0, a1), ADD(a2, a3)), ADD(ADD(a4, a5), ADD(a6, a7))), \
                       ADD(ADD(a8, a9), ADD(a10, a11)))
/* the mul/add mix: even chains multiply, odd chains add */
#define MIX12(M, A) M(a0); A(a1); M(a2); A(a3); M(a4); A(a5); M(a6); A(a7); M(a8); A(a9); \
    M(a10); A(a11)

/* the division/root mix: two dividing chains to one rooting chain */
#define MIX3(D, R) D(a0); D(a1); R(a2); D(a3); D(a4); R(a5); D(a6); D(a7); R(a8); D(a9); \
    D(a10); R(a11)

/* One loop family per level: T the register type, P the intrinsic prefix,
 * SFX its suffix (pd, sd), TGT the target attribute. */
#define FLOOR_LOOPS(lv, T, P, SFX, TGT, TGTF)                                             \
    TGTF static double fma_##lv(long n)                                                   \
    {                                                                                     \
        CHAINS(T, P##_set1_pd, 1.0);                                                      \
        const T x = P##_set1_pd(0.999999), y = P##_set1_pd(1e-6);                         \
        for (long i = 0; i < n; i++) {                                                    \
            __asm__("" ::: "memory");                                                     \
            STEP12(FMA_S);                                                                \
        }                                                                                 \
        return SUM12(ADD_F)[0];                                                           \
    }                                                                                     \
    TGT static double muladd_##lv(long n)                                                 \
    {                                                                                     \
        CHAINS(T, P##_set1_pd, 1.0);                                                      \
        const T x = P##_set1_pd(0.999999), y = P##_set1_pd(1e-9);                         \
        for (long i = 0; i < n; i++) {                                                    \
            __asm__("" ::: "memory");                                                     \
            MIX12(MUL_S, ADD_S);                                                          \
        }                                                                                 \
        return SUM12(ADD_F)[0];                                                           \
    }                                                                                     \
    TGT static double div_##lv(long n)                                                    \
    {                                                                                     \
        CHAINS(T, P##_set1_pd, 1.3);                                                      \
        const T c = P##_set1_pd(2.0);                                                     \
        for (long i = 0; i < n; i++) {                                                    \
            __asm__("" ::: "memory");                                                     \
            STEP12(DIV_S);                                                                \
        }                                                                                 \
        return SUM12(ADD_F)[0];                                                           \
    }                                                                                     \
    TGT static double divsqrt_##lv(long n)                                                \
    {                                                                                     \
        CHAINS(T, P##_set1_pd, 1.3);                                                      \
        const T c = P##_set1_pd(2.0);                                                     \
        for (long i = 0; i < n; i++) {                                                    \
            __asm__("" ::: "memory");                                                     \
            MIX3(DIV_S, SQRT_S);                                                          \
        }                                                                                 \
        return SUM12(ADD_F)[0];                                                           \
    }                                                                                     \
    TGT static double sqrt_##lv(long n)                                                   \
    {                                                                                     \
        CHAINS(T, P##_set1_pd, 1.7);                                                      \
        const T c = P##_set1_pd(1.9);                                                     \
        for (long i = 0; i < n; i++) {                                                    \
            __asm__("" ::: "memory");                                                     \
            STEP12(SQRT_S);                                                               \
        }                                                                                 \
        return SUM12(ADD_F)[0];                                                           \
    }

/* scalar: the sd forms on the low lane (lane 0 only counts) */
#define FMA_S(a) a = OPF(fmadd)(a, x, y)
#define MUL_S(a) a = OP(mul)(a, x)
#define ADD_S(a) a = OP(add)(a, y)
#define DIV_S(a) a = OP(div)(c, a)
#define SQRT_S(a) a = OP(mul)(SQRT(a), c) /* -> 3.61, a mul beside each root */
#define ADD_F(a, b) OP(add)(a, b)

#define OP(o) _mm_##o##_sd
#define OPF(o) _mm_##o##_sd
#define SQRT(a) _mm_sqrt_sd(a, a)
FLOOR_LOOPS(scalar, __m128d, _mm, sd, , __attribute__((target("fma"))))
#undef OP
#undef OPF
#undef SQRT

#define OP(o) _mm_##o##_pd
#define OPF(o) _mm_##o##_pd
#define SQRT(a) _mm_sqrt_pd(a)
FLOOR_LOOPS(sse2, __m128d, _mm, pd, , __attribute__((target("fma"))))
#undef OP
#undef OPF
#undef SQRT

#define OP(o) _mm256_##o##_pd
#define OPF(o) _mm256_##o##_pd
#define SQRT(a) _mm256_sqrt_pd(a)
FLOOR_LOOPS(avx2, __m256d, _mm256, pd, __attribute__((target("avx2"))),
            __attribute__((target("avx2,fma"))))
#undef OP
#undef OPF
#undef SQRT

#define OP(o) _mm512_##o##_pd
#define OPF(o) _mm512_##o##_pd
#define SQRT(a) _mm512_sqrt_pd(a)
FLOOR_LOOPS(avx512, __m512d, _mm512, pd, __attribute__((target("avx512f"))),
            __attribute__((target("avx512f"))))
#undef OP
#undef OPF
#undef SQRT

typedef double (*loop_fn)(long n);

/* Best-of-REPS seconds of fn(ITERS); *sink keeps the result alive. */
static double time_loop(loop_fn fn, double *sink)
{
    double best = 1e300;
    fn(ITERS / 10); /* warm up: clocks and the upper vector halves */
    for (int r = 0; r < REPS; r++) {
        const double t0 = bench_now();
        *sink += fn(ITERS);
        const double t = bench_now() - t0;
        if (t < best) best = t;
    }
    return best;
}

static const char *const level_names[BENCH_LEVELS] = {"scalar", "sse2", "avx2", "avx512"};
static const int level_lanes[BENCH_LEVELS] = {1, 2, 4, 8};

const char *bench_level_name(int level)
{
    return level >= 0 && level < BENCH_LEVELS ? level_names[level] : "?";
}

void bench_floor_measure(bench_floor *f)
{
    memset(f, 0, sizeof *f);
    __builtin_cpu_init();
    const int fma = __builtin_cpu_supports("fma");
    f->has_fma = fma;
    const loop_fn loops[BENCH_LEVELS][5] = {
        {fma_scalar, muladd_scalar, div_scalar, sqrt_scalar, divsqrt_scalar},
        {fma_sse2, muladd_sse2, div_sse2, sqrt_sse2, divsqrt_sse2},
        {fma_avx2, muladd_avx2, div_avx2, sqrt_avx2, divsqrt_avx2},
        {fma_avx512, muladd_avx512, div_avx512, sqrt_avx512, divsqrt_avx512}};
    const int has[BENCH_LEVELS] = {1, 1, __builtin_cpu_supports("avx2"),
                                   __builtin_cpu_supports("avx512f")};
    double sink = 0;
    printf("# floor: measured on this CPU, one thread, %d independent chains, best of %d\n",
           NACC, REPS);
    char model[256];
    printf("# cpu: %s; sse2 yes, avx2 %s, fma %s, avx512f %s\n",
           bench_cpu_model(model, sizeof model),
           has[2] ? "yes" : "no", fma ? "yes" : "no", has[3] ? "yes" : "no");
    for (int lv = 0; lv < BENCH_LEVELS; lv++) {
        f->has[lv] = has[lv];
        f->fma[lv] = f->muladd[lv] = f->div[lv] = f->sqrt[lv] = NAN;
        if (!has[lv]) continue;
        const double ops = (double)ITERS * NACC * level_lanes[lv];
        if (fma) f->fma[lv] = 2.0 * ops / time_loop(loops[lv][0], &sink);
        f->muladd[lv] = ops / time_loop(loops[lv][1], &sink);
        f->div[lv] = ops / time_loop(loops[lv][2], &sink);
        f->sqrt[lv] = ops / time_loop(loops[lv][3], &sink);
        f->divsqrt[lv] = ops / time_loop(loops[lv][4], &sink);
        /* per op of the mix: 2/3 of a division's time and 1/3 of a root's
         * if they queue on one unit, their max if they do not */
        const double t_one = (2.0 / 3.0) / f->div[lv] + (1.0 / 3.0) / f->sqrt[lv];
        f->one_divider[lv] = 1.0 / f->divsqrt[lv] >= 0.8 * t_one;
        char name[96];
        snprintf(name, sizeof name, "floor.%s.fma", level_names[lv]);
        bench_report(name, f->fma[lv] / 1e9, "GFLOP/s (2 per FMA)");
        snprintf(name, sizeof name, "floor.%s.muladd", level_names[lv]);
        bench_report(name, f->muladd[lv] / 1e9, "G mul-or-add/s");
        snprintf(name, sizeof name, "floor.%s.div", level_names[lv]);
        bench_report(name, f->div[lv] / 1e9, "G div/s");
        snprintf(name, sizeof name, "floor.%s.sqrt", level_names[lv]);
        bench_report(name, f->sqrt[lv] / 1e9, "G sqrt/s");
        snprintf(name, sizeof name, "floor.%s.divsqrt", level_names[lv]);
        bench_report(name, f->divsqrt[lv] / 1e9,
                     f->one_divider[lv] ? "G div-or-sqrt/s (2:1 mix; one unit: times add up)"
                                        : "G div-or-sqrt/s (2:1 mix; separate units)");
        if (!(f->fma_peak >= f->fma[lv])) f->fma_peak = f->fma[lv];
        if (!(f->muladd_peak >= f->muladd[lv])) f->muladd_peak = f->muladd[lv];
    }
    if (!fma) f->fma_peak = f->muladd_peak;
    bench_report("floor.fma_peak", f->fma_peak / 1e9, "GFLOP/s per core (the machine's FP peak)");
    if (sink == 12345.678) printf("#\n");
}

double bench_floor_fraction(const bench_floor *f, int level, double rate, const bench_ops *op,
                            const char **bound)
{
    if (level < 0 || level >= BENCH_LEVELS || !f->has[level]) return NAN;
    const double t_ma = (op->mul + op->add) / f->muladd[level];
    const double t_div = op->div / f->div[level];
    const double t_sqrt = op->sqrt / f->sqrt[level];
    double t = t_ma;
    *bound = "mul+add";
    if (f->one_divider[level] && op->div > 0 && op->sqrt > 0) {
        if (t_div + t_sqrt > t) t = t_div + t_sqrt, *bound = "div+sqrt (one divider)";
        return rate * t;
    }
    if (t_div > t) t = t_div, *bound = "div";
    if (t_sqrt > t) t = t_sqrt, *bound = "sqrt";
    return rate * t;
}

double bench_fma_fraction(const bench_floor *f, double rate, const bench_ops *op)
{
    return rate * (op->mul + op->add + op->div + op->sqrt) / f->fma_peak;
}
