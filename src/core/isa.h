/* The instruction set of the hot kernels, chosen once per process.
 *
 * dflab is built for baseline x86-64 (SSE2).  The hot kernels (the bs04
 * batched kernels rfunc/batch_*.c, PHT evaluation pht/spline.c, the proxy
 * filters proxy/filter.c (decoding inline from proxy/decode.h), the grid
 * peers field/gridpeer.c) are compiled
 * once per ISA below (DFL_ISA_KERNEL) and the process's ISA picks the
 * variant at run time.  All variants compute the same bytes: vector add,
 * mul, div and sqrt round correctly like their scalar forms, every object
 * is compiled with -ffp-contract=off (no FMA contraction; the Makefile),
 * no variant reassociates a sum, and no math library call is vectorized
 * (glibc's vector math needs -ffast-math).  So DFL_ISA changes speed, never
 * a result.
 *
 * The environment variable DFL_ISA forces one:
 *   DFL_ISA=sse2     baseline x86-64: SSE2, 2 doubles per vector
 *   DFL_ISA=avx2     AVX2 (FMA not used), 4 doubles per vector
 *   DFL_ISA=avx512   AVX-512 F/DQ/VL/BW (FMA not used), 8 doubles per vector
 * unset or empty: the widest the CPU and OS support.  A name that is not
 * one of these, or an ISA this CPU does not run, is bad input:
 * dfl_isa_from_env fails with one line, and dflab exits 2 before doing
 * anything.  Other compilers and machines (clang, non-x86-64): one variant,
 * reported as sse2 on x86-64.
 *
 *   DFL_ISA_LIST                       the ISAs (X-macro: code, name, doubles)
 *   dfl_isa_name, dfl_isa_parse        names (core/names.h)
 *   dfl_isa_cpu_has(isa)               this CPU and OS run isa
 *   dfl_isa_best()                     the widest isa the CPU runs
 *   dfl_isa_width(isa)                 doubles per vector
 *   dfl_isa_from_env(&isa, err)        DFL_ISA checked against the CPU
 *   dfl_isa_active()                   the process's ISA (read once)
 *   DFL_ISA_BODY                       a body compiled into each variant
 *   DFL_ISA_KERNEL(name, params, args) per-ISA variants and their dispatch
 */
#ifndef DFL_CORE_ISA_H
#define DFL_CORE_ISA_H

#include <stdbool.h>

#include "core/names.h"
#include "core/status.h"

#define DFL_ISA_LIST(X)           \
    X(DFL_ISA_SSE2, "sse2", 2)    \
    X(DFL_ISA_AVX2, "avx2", 4)    \
    X(DFL_ISA_AVX512, "avx512", 8)

typedef enum dfl_isa { DFL_ISA_LIST(DFL_NAMES_CODE) } dfl_isa;
enum { DFL_ISA_COUNT = 0 DFL_ISA_LIST(DFL_NAMES_ONE) };

extern const char *const dfl_isa_names[DFL_ISA_COUNT];
/* The name of isa ("?" outside the list). */
const char *dfl_isa_name(dfl_isa isa);
/* An ISA by its exact name; DFL_E_INPUT "unknown ISA ..." otherwise. */
dfl_status dfl_isa_parse(const char *s, dfl_isa *out, dfl_err *err);

/* True when this CPU (and the OS, which must save the vector registers)
 * runs the variant compiled for isa; sse2 is always true on x86-64. */
bool dfl_isa_cpu_has(dfl_isa isa);

/* The widest ISA with dfl_isa_cpu_has. */
dfl_isa dfl_isa_best(void);

/* Doubles per vector register of isa (2, 4, 8). */
int dfl_isa_width(dfl_isa isa);

/* The ISA the environment asks for: DFL_ISA unset or empty gives
 * dfl_isa_best(); a listed name the CPU runs gives that one.  DFL_E_INPUT
 * with one line naming the variable, the value and what was expected, for
 * an unknown name or one the CPU does not run (*out unchanged). */
dfl_status dfl_isa_from_env(dfl_isa *out, dfl_err *err);

/* The process's ISA: dfl_isa_from_env on the first call (thread-safe, once
 * per process; later changes of DFL_ISA are not seen), dfl_isa_best() when
 * that fails (programs check dfl_isa_from_env first and reject bad input). */
dfl_isa dfl_isa_active(void);

/* A function compiled into every variant that inlines it (kernel bodies
 * and their helpers). */
#if defined(__GNUC__)
#define DFL_ISA_BODY static inline __attribute__((always_inline))
#else
#define DFL_ISA_BODY static inline
#endif

/* Per-ISA kernels.  After `DFL_ISA_BODY void name##_body params` (its
 * body is compiled in each variant),
 *     DFL_ISA_KERNEL(name, (params), (args))
 * defines `static void name params`, which runs the body compiled for
 * dfl_isa_active().  The variant is picked per call (one switch), so call
 * it per batch of points, never per point. */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(DFL_NO_ISA)
#define DFL_ISA_MULTI 1
#define DFL_ISA_TARGET_AVX2 __attribute__((target("avx2")))
#define DFL_ISA_TARGET_AVX512 \
    __attribute__((target("avx512f,avx512dq,avx512vl,avx512bw,prefer-vector-width=512")))
#define DFL_ISA_KERNEL(name, params, args)                              \
    DFL_ISA_TARGET_AVX512 static void name##_avx512 params              \
    {                                                                   \
        name##_body args;                                               \
    }                                                                   \
    DFL_ISA_TARGET_AVX2 static void name##_avx2 params { name##_body args; } \
    static void name##_sse2 params { name##_body args; }                \
    static void name params                                             \
    {                                                                   \
        switch (dfl_isa_active()) {                                     \
        case DFL_ISA_AVX512: name##_avx512 args; break;                 \
        case DFL_ISA_AVX2: name##_avx2 args; break;                     \
        default: name##_sse2 args; break;                               \
        }                                                               \
    }
#else
#define DFL_ISA_MULTI 0
#define DFL_ISA_KERNEL(name, params, args) \
    static void name params { name##_body args; }
#endif

#endif
