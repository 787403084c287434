/* Proxy storage: the scalar type every stored proxy scalar has, and what
 * the footpoint's three scalars mean.
 *
 * Function index
 *   DFL_PROXY_STORAGE_LIST      double | float | half (X-macro, core/names.h)
 *   DFL_PROXY_POSITION_LIST     displacement | absolute
 *   dfl_proxy_storage_name/parse, dfl_proxy_position_name/parse
 *   dfl_proxy_storage_size      bytes per stored scalar (8, 4, 2)
 *   dfl_proxy_store_put         round a double to the storage type, store it
 *   dfl_proxy_store_get         load a stored scalar as double (exact)
 *   dfl_proxy_store_half_block  load n halves as double (F16C where it runs)
 *   dfl_proxy_store_has_f16c    the process may use F16C
 *
 * Rounding: float is the C conversion (round to nearest even); half goes
 * double -> float -> half (Imath's imath_float_to_half, round to nearest
 * even), so a value within half a float ulp of a half tie may round
 * differently from a direct double -> half rounding; |v| >= 65520 becomes
 * +-inf.  Loading is exact for all three types.  No allocation, no state.
 *
 * Position (the footpoint's 3 scalars): `displacement` stores p - x_c (x_c
 * the cell centre; the paper's order-1 encoding), `absolute` stores p.  In
 * double both decode to the same p up to one rounding of the sum; in half
 * the displacement keeps its relative precision near the surface, where
 * the absolute footpoint loses the normal direction p - x_c (see proxy.h).
 * Measured (torus R = 0.6, r = 0.25 from the analytic SDF input, errors on
 * a 101^3 lattice over [-1, 1]^3 within 0.1 of the surface, half storage):
 * order 2 at 32^3, max error nearest 2.0e-4 (displacement) vs 5.2e-3
 * (absolute), Hermite 8.3e-5 vs 2.7e-3; at 64^3 nearest 4.3e-5 vs 1.2e-2;
 * order 1 at 64^3 nearest 1.6e-3 vs 1.2e-2.  In float and double the two
 * agree to the digits shown.  Hence displacement is the default.
 *
 * Range: no stored proxy may decode to a non-finite value, so the grid
 * builder (proxy.c) caps what the storage cannot hold finite, with F_s the
 * largest finite value (DBL_MAX, FLT_MAX, 65504): a displacement longer
 * than F_s in some component is shortened along itself (its direction, the
 * normal, survives; the footpoint moves along its ray), an absolute
 * coordinate is clamped to +-F_s, and each curvature to +-min(F_s, 2^64/h)
 * (h the cell size; 2^64/h keeps every product in the decoding finite for
 * points of the box).  kappa_r and kappa_R share the cap, so |kappa_r| >=
 * |kappa_R| still holds.  A half curvature above 65504 is a radius below
 * 1.5e-5: the capped proxy is a sphere or torus of that radius, not inf.
 * Each capped cell is counted in the grid's stats.clamped (proxy.h).
 * Displacements shorter than the storage's smallest normal value (half:
 * 2^-14) count as centres on the surface (proxy.h) and move.
 */
#ifndef DFL_PROXY_STORE_H
#define DFL_PROXY_STORE_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <Imath/half.h>

#include "core/names.h"
#include "core/status.h"

#define DFL_PROXY_STORAGE_LIST(X)                                  \
    X(DFL_PROXY_DOUBLE, "double", "IEEE binary64, 8 bytes")        \
    X(DFL_PROXY_FLOAT, "float", "IEEE binary32, 4 bytes")          \
    X(DFL_PROXY_HALF, "half", "IEEE binary16 (Imath), 2 bytes")
typedef enum dfl_proxy_storage { DFL_PROXY_STORAGE_LIST(DFL_NAMES_CODE) } dfl_proxy_storage;
enum { DFL_PROXY_STORAGE_COUNT = 0 DFL_PROXY_STORAGE_LIST(DFL_NAMES_ONE) };
extern const char *const dfl_proxy_storage_names[DFL_PROXY_STORAGE_COUNT];
const char *dfl_proxy_storage_name(dfl_proxy_storage s);
dfl_status dfl_proxy_storage_parse(const char *s, dfl_proxy_storage *out, dfl_err *err);

#define DFL_PROXY_POSITION_LIST(X)                                         \
    X(DFL_PROXY_DISPLACEMENT, "displacement", "p - cell centre")           \
    X(DFL_PROXY_ABSOLUTE, "absolute", "the footpoint p itself")
typedef enum dfl_proxy_position { DFL_PROXY_POSITION_LIST(DFL_NAMES_CODE) } dfl_proxy_position;
enum { DFL_PROXY_POSITION_COUNT = 0 DFL_PROXY_POSITION_LIST(DFL_NAMES_ONE) };
extern const char *const dfl_proxy_position_names[DFL_PROXY_POSITION_COUNT];
const char *dfl_proxy_position_name(dfl_proxy_position s);
dfl_status dfl_proxy_position_parse(const char *s, dfl_proxy_position *out, dfl_err *err);

/* 8, 4 or 2. */
static inline size_t dfl_proxy_storage_size(dfl_proxy_storage s)
{
    return s == DFL_PROXY_DOUBLE ? 8 : s == DFL_PROXY_FLOAT ? 4 : 2;
}

/* Stores v rounded to s at base[i] (base points to an array of s's type). */
static inline void dfl_proxy_store_put(dfl_proxy_storage s, void *base, size_t i, double v)
{
    switch (s) {
    case DFL_PROXY_DOUBLE: ((double *)base)[i] = v; break;
    case DFL_PROXY_FLOAT: ((float *)base)[i] = (float)v; break;
    default: ((uint16_t *)base)[i] = imath_float_to_half((float)v); break;
    }
}

/* base[i] as double (exact). */
static inline double dfl_proxy_store_get(dfl_proxy_storage s, const void *base, size_t i)
{
    switch (s) {
    case DFL_PROXY_DOUBLE: return ((const double *)base)[i];
    case DFL_PROXY_FLOAT: return ((const float *)base)[i];
    default: return imath_half_to_float(((const uint16_t *)base)[i]);
    }
}

/* n halves h[0..n) as double into out, each what dfl_proxy_store_get
 * gives (Imath's imath_half_to_float, then exact widening), bit for bit
 * for all 65536 halves.  With f16c != 0 the CPU's F16C conversion runs
 * 8 at a time (the caller checked dfl_proxy_store_has_f16c(); F16C quiets
 * a signalling NaN where Imath keeps it, but widening to double quiets it
 * in both, so the doubles agree); f16c == 0 is Imath's, one at a time.
 * No allocation. */
void dfl_proxy_store_half_block(int f16c, const uint16_t *h, size_t n, double *out);

/* 1 when the process's ISA (core/isa.h) is avx2 or avx512 and the CPU has
 * F16C: DFL_ISA=sse2 keeps to the baseline instructions. */
int dfl_proxy_store_has_f16c(void);

/* The value dfl_proxy_store_put then dfl_proxy_store_get give back. */
static inline double dfl_proxy_store_round(dfl_proxy_storage s, double v)
{
    switch (s) {
    case DFL_PROXY_DOUBLE: return v;
    case DFL_PROXY_FLOAT: return (float)v;
    default: return imath_half_to_float(imath_float_to_half((float)v));
    }
}

#endif
