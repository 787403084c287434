/* Why the kernel looks the way it does:
 *
 *  - Vector lanes are points: a block of LANES points runs through all
 *    segments, whose data (structure of arrays: a, b, n, 1/2d, 1/2d^2) is
 *    broadcast, with one accumulator per lane.  The lane loop vectorizes
 *    without reassociating a reduction (ISO C forbids that; gcc would need
 *    -ffast-math), each point sums its segments in order, and the segment
 *    data is loaded once per block instead of once per point.
 *  - No branch, no sqrt, no libm call in the lane loop: max(-t, 0) is
 *    (|t| - t)/2; even p need 1/h^2 only (one division); odd p need 1/h,
 *    a Newton iteration for 1/sqrt(h^2) from the classic exponent-halving
 *    bit estimate (relative error < 3.5%, quadratic convergence: 1.8e-3,
 *    4.9e-6, 3.6e-11, then rounding level after 4 steps).  gcc does not
 *    vectorize sqrt() under the default -fmath-errno.  The estimate is
 *    valid for normal h^2 >= DBL_MIN; below it (and for h^2 = 0) the
 *    result is > 4e153, its cube overflows, V becomes inf/NaN and the point
 *    falls back (see accept()); with the division, h^2 = 0 or subnormal
 *    gives inf the same way.
 *  - Multiplications are the bottleneck (two multiply pipes on current x86
 *    cores, while the adds have their own), so the layout stores what saves
 *    multiplications (normals, 1/2d, 1/2d^2) and powers use repeated
 *    squaring; FMA would not help: it runs on the multiply pipes.
 *  - The order p is a compile-time constant in the common cases (1..8, 12)
 *    so that the powers are straight-line multiplications.
 *  - target_clones compiles the kernel for AVX-512, AVX2 and the baseline
 *    and lets the loader pick (the Makefile builds for baseline x86-64).
 */
#include "rfunc/batch.h"

#include <assert.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "rfunc/join.h"
#include "rfunc/rfield.h"
#include "rfunc/region.h"
#include "rfunc/segment.h"
#include "rfunc/tri3d.h"

#define LANES 8
/* Points per inner call when the caller wants no gradient (stack scratch). */
#define SCRATCH 64

struct dfl_rfunc_batch {
    int p;
    int dim;            /* 2 or 3 */
    int strip;          /* 1: strip (slab) trims, 0: disk (sphere) trims; eq. 4 */
    int points;         /* 1: the parts are points c = (ax, ay[, az]) */
    int tris;           /* 1: the parts are triangles (tri below) */
    int cond;           /* triangles: 1 conditional trim (a f^2), 0 prism */
    double ca;          /* triangles: the conditional weight a */
    double *tri;        /* triangles: 24 doubles each: n, then V_i, m_i (i = 0..2) */
    int regions;        /* 1: the parts are convex regions (2D) */
    size_t *roff;       /* regions: n + 1 offsets into rv/rm (edges) */
    double *rv, *rm;    /* regions: edge start points and inward normals, 2 each */
    size_t n;           /* segments */
    double *ax, *ay;    /* start points a */
    double *bx, *by;    /* end points b */
    double *nx, *ny;    /* unit normals n = (b_y - a_y, -(b_x - a_x)) / d (eq. 2);
                           3D: the first normal n1 (rfunc/segment.c) */
    double *hid;        /* 1 / (2 d) */
    double *hid2;       /* 1 / (2 d^2) */
    double *az, *bz;    /* 3D: z of a and b */
    double *nz;         /* 3D: z of n1 */
    double *mx, *my, *mz; /* 3D: the second normal n2 */
    double *ex, *ey, *ez; /* unit direction (b - a) / d (strip trims, 3D) */
    double *mem;        /* one allocation for the arrays */
    dfl_field ref;      /* the library's field of the same polyline */
};

/* Arrays of a batch: the 2D disk kernel's eight, then the others. */
#define NARR 17

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) && \
    !defined(DFL_NO_CLONES)
#define DFL_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define DFL_CLONES
#endif

#if defined(__GNUC__)
#define DFL_INLINE static inline __attribute__((always_inline))
#else
#define DFL_INLINE static inline
#endif

/* 1/sqrt(x) for normal x > 0 to ~1 ulp; see the top of the file. */
DFL_INLINE double rsqrt_newton(double x)
{
    uint64_t i;
    double y;
    memcpy(&i, &x, sizeof i);
    i = UINT64_C(0x5FE6EB50C7B537A9) - (i >> 1);
    memcpy(&y, &i, sizeof y);
    const double hx = 0.5 * x;
    y = y * (1.5 - hx * y * y);
    y = y * (1.5 - hx * y * y);
    y = y * (1.5 - hx * y * y);
    y = y * (1.5 - hx * y * y);
    return y;
}

/* x^k (k >= 1) by repeated squaring; with k a compile-time constant this
 * unrolls into floor(log2 k) + popcount(k) - 1 multiplications. */
DFL_INLINE double ipow_sq(double x, int k)
{
    while (!(k & 1)) {
        x *= x;
        k >>= 1;
    }
    double r = x;
    for (k >>= 1; k; k >>= 1) {
        x *= x;
        if (k & 1) r *= x;
    }
    return r;
}

/* One segment at one point: adds h^-p to *S and h^-(p+2) h grad h to *Vx,
 * *Vy.  Operation counts per line (mul, add; fabs is a logic op) are
 * summed by the benchmark (tests/bench/bench_rfunc.c, kernel_ops): keep
 * them in step with the code. */
DFL_INLINE void seg_term(double x, double y, const dfl_rfunc_batch *b, size_t k, int p,
                         double *S, double *Vx, double *Vy)
{
    const double wx = x - b->ax[k], wy = y - b->ay[k];   /* x - a       0, 2 */
    const double vx = x - b->bx[k], vy = y - b->by[k];   /* x - b       0, 2 */
    const double f = wx * b->nx[k] + wy * b->ny[k];      /* eq. 2       2, 1 */
    const double m2 = wx * vx + wy * vy;                 /* -t d        2, 1 */
    const double mp = m2 + fabs(m2);                     /* 2 max(.,0)  0, 1 */
    const double mt = mp * b->hid[k];                    /* max(-t, 0)  1, 0 */
    const double mi = mp * b->hid2[k];                   /* mt / d      1, 0 */
    const double h2 = f * f + mt * mt;                   /* eq. 4^2     2, 1 */
    const double gx = f * b->nx[k] + mi * (wx + vx);     /* h grad h    2, 2 */
    const double gy = f * b->ny[k] + mi * (wy + vy);     /*             2, 2 */
    double r2, w;
    if (p & 1) {
        const double r = rsqrt_newton(h2);                /* 13, 4 */
        r2 = r * r;                                       /* 1, 0 */
        w = p == 1 ? r : r * ipow_sq(r2, p / 2);          /* muls of ipow_sq(p/2) + 1, 0 */
    } else {
        r2 = 1.0 / h2;                                    /* 1 division */
        w = ipow_sq(r2, p / 2);                           /* muls of ipow_sq(p/2), 0 */
    }
    const double q = w * r2;                             /* 1, 0 */
    *S += w;                                             /* 0, 1 */
    *Vx += q * gx;                                       /* 1, 1 */
    *Vy += q * gy;                                       /* 1, 1 */
}

/* The power part shared by the kernels below: adds h^-p to *S and returns
 * h^-(p+2) (the factor of h grad h in V). */
DFL_INLINE double pow_term(double h2, int p, double *S)
{
    double r2, w;
    if (p & 1) {
        const double r = rsqrt_newton(h2);
        r2 = r * r;
        w = p == 1 ? r : r * ipow_sq(r2, p / 2);
    } else {
        r2 = 1.0 / h2;
        w = ipow_sq(r2, p / 2);
    }
    *S += w;
    return w * r2;
}

/* The strip trim of eq. 4 (rfunc/segment.h): p1 = (x - a).e, p2 = (b - x).e,
 * t = 2 p1 p2 / (p1 + p2 + r), r = |(p1, p2)| (rfunc/trim.h's conjunction
 * without cancellation; p1 + p2 = d > 0), grad t = (p2 - p1)/r e, so with
 * mt = max(-t, 0): h grad h = f grad f - mt (p2 - p1)/r e.  Returns mt and
 * the factor k = mt (p2 - p1)/r of -e. */
DFL_INLINE double strip_mt(double p1, double p2, double *k)
{
    const double r2 = p1 * p1 + p2 * p2;
    const double rr = rsqrt_newton(r2);
    const double t = 2.0 * p1 * p2 / (p1 + p2 + r2 * rr);
    const double mt = 0.5 * (fabs(t) - t);
    *k = mt * (p2 - p1) * rr;
    return mt;
}

/* 2D segment with the strip trim. */
DFL_INLINE void seg_term_strip2(double x, double y, const dfl_rfunc_batch *b, size_t k, int p,
                                double *S, double *Vx, double *Vy)
{
    const double wx = x - b->ax[k], wy = y - b->ay[k];
    const double vx = x - b->bx[k], vy = y - b->by[k];
    const double f = wx * b->nx[k] + wy * b->ny[k];
    const double p1 = wx * b->ex[k] + wy * b->ey[k], p2 = -(vx * b->ex[k] + vy * b->ey[k]);
    double kk;
    const double mt = strip_mt(p1, p2, &kk);
    const double q = pow_term(f * f + mt * mt, p, S);
    *Vx += q * (f * b->nx[k] - kk * b->ex[k]);
    *Vy += q * (f * b->ny[k] - kk * b->ey[k]);
}

/* 3D segment (space curves): f^2 = s1^2 + s2^2 with the two normals, the
 * sphere (strip = 0) or slab (strip = 1) trim. */
DFL_INLINE void seg_term3(double x, double y, double z, const dfl_rfunc_batch *b, size_t k,
                          int p, int strip, double *S, double *Vx, double *Vy, double *Vz)
{
    const double wx = x - b->ax[k], wy = y - b->ay[k], wz = z - b->az[k];
    const double vx = x - b->bx[k], vy = y - b->by[k], vz = z - b->bz[k];
    const double s1 = wx * b->nx[k] + wy * b->ny[k] + wz * b->nz[k];
    const double s2 = wx * b->mx[k] + wy * b->my[k] + wz * b->mz[k];
    double gx = s1 * b->nx[k] + s2 * b->mx[k], gy = s1 * b->ny[k] + s2 * b->my[k],
           gz = s1 * b->nz[k] + s2 * b->mz[k];
    double mt;
    if (strip) {
        const double p1 = wx * b->ex[k] + wy * b->ey[k] + wz * b->ez[k];
        const double p2 = -(vx * b->ex[k] + vy * b->ey[k] + vz * b->ez[k]);
        double kk;
        mt = strip_mt(p1, p2, &kk);
        gx -= kk * b->ex[k];
        gy -= kk * b->ey[k];
        gz -= kk * b->ez[k];
    } else {
        const double m2 = wx * vx + wy * vy + wz * vz;
        const double mp = m2 + fabs(m2);
        mt = mp * b->hid[k];
        const double mi = mp * b->hid2[k];
        gx += mi * (wx + vx);
        gy += mi * (wy + vy);
        gz += mi * (wz + vz);
    }
    const double q = pow_term(s1 * s1 + s2 * s2 + mt * mt, p, S);
    *Vx += q * gx;
    *Vy += q * gy;
    *Vz += q * gz;
}

/* A point part: h^2 = |x - c|^2, h grad h = x - c. */
DFL_INLINE void point_term(double x, double y, double z, const dfl_rfunc_batch *b, size_t k,
                           int p, int dim, double *S, double *Vx, double *Vy, double *Vz)
{
    const double wx = x - b->ax[k], wy = y - b->ay[k], wz = dim == 3 ? z - b->az[k] : 0.0;
    const double q = pow_term(wx * wx + wy * wy + wz * wz, p, S);
    *Vx += q * wx;
    *Vy += q * wy;
    *Vz += q * wz;
}

/* Rvachev's R0-conjunction x ^ y = x + y - sqrt(x^2 + y^2 + c) as
 * rfunc/trim.c's dfl_rfunc_conj0 computes it (without cancellation for
 * x + y > 0), with its partials.  r^2 below 1e-280 (a point on a vertex
 * line of the prism, where the reciprocal square root estimate is not
 * valid) poisons *bad so that the point falls back. */
DFL_INLINE double conj0_l(double x, double y, double c, double *dx, double *dy, double *dc,
                          double *bad)
{
    const double r2 = x * x + y * y + c;
    const double rr = rsqrt_newton(r2);
    const double r = r2 * rr, s = x + y;
    *bad += r2 < 1e-280 ? NAN : 0.0;
    *dx = 1.0 - x * rr;
    *dy = 1.0 - y * rr;
    *dc = -0.5 * rr;
    return s > 0.0 ? (2.0 * x * y - c) / (s + r) : s - r;
}

/* A triangle of rfunc/tri3d.h with eq. 4: f = (x - V_0).n, p_i = (x - V_i).m_i,
 * t = (p_0 ^ p_1) ^ p_2 (conditional: c = a f^2 under both roots), h grad h
 * = f n - mt grad t. */
DFL_INLINE void tri_term(double x, double y, double z, const dfl_rfunc_batch *b, size_t k,
                         int p, int cond, double *S, double *Vx, double *Vy, double *Vz)
{
    const double *T = b->tri + 24 * k;
    const double *n = T, *V0 = T + 3, *m0 = T + 6, *V1 = T + 9, *m1 = T + 12, *V2 = T + 15,
                 *m2 = T + 18;
    const double f = (x - V0[0]) * n[0] + (y - V0[1]) * n[1] + (z - V0[2]) * n[2];
    const double p0 = (x - V0[0]) * m0[0] + (y - V0[1]) * m0[1] + (z - V0[2]) * m0[2];
    const double p1 = (x - V1[0]) * m1[0] + (y - V1[1]) * m1[1] + (z - V1[2]) * m1[2];
    const double p2 = (x - V2[0]) * m2[0] + (y - V2[1]) * m2[1] + (z - V2[2]) * m2[2];
    const double c = cond ? b->ca * f * f : 0.0, dcdf = cond ? 2.0 * b->ca * f : 0.0;
    double ax, ay, ac, bx, by, bc, bad = 0.0;
    const double t1 = conj0_l(p0, p1, c, &ax, &ay, &ac, &bad);
    const double t = conj0_l(t1, p2, c, &bx, &by, &bc, &bad);
    const double cn = (bx * ac + bc) * dcdf;
    const double mt = 0.5 * (fabs(t) - t);
    const double q = pow_term(f * f + mt * mt, p, S);
    *S += bad;
    for (int j = 0; j < 3; j++) {
        const double gt = bx * (ax * m0[j] + ay * m1[j]) + by * m2[j] + cn * n[j];
        const double g = f * n[j] - mt * gt;
        if (j == 0) *Vx += q * g;
        else if (j == 1) *Vy += q * g;
        else *Vz += q * g;
    }
}

DFL_INLINE void sums_tri_p(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out,
                           const int p, const int cond)
{
    const size_t n = b->n;
    for (size_t i0 = 0; i0 < m; i0 += LANES) {
        const size_t c = m - i0 < LANES ? m - i0 : LANES;
        double X[LANES], Y[LANES], Z[LANES], S[LANES] = {0}, Vx[LANES] = {0}, Vy[LANES] = {0},
                                             Vz[LANES] = {0};
        for (size_t l = 0; l < LANES; l++) {
            const size_t i = i0 + (l < c ? l : c - 1);
            X[l] = pts[3 * i];
            Y[l] = pts[3 * i + 1];
            Z[l] = pts[3 * i + 2];
        }
        for (size_t k = 0; k < n; k++) {
#pragma omp simd
            for (int l = 0; l < LANES; l++)
                tri_term(X[l], Y[l], Z[l], b, k, p, cond, &S[l], &Vx[l], &Vy[l], &Vz[l]);
        }
        for (size_t l = 0; l < c; l++) {
            out[4 * (i0 + l)] = S[l];
            out[4 * (i0 + l) + 1] = Vx[l];
            out[4 * (i0 + l) + 2] = Vy[l];
            out[4 * (i0 + l) + 3] = Vz[l];
        }
    }
}

DFL_CLONES
static void sums_tri(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    switch (b->p * 2 + b->cond) {
    case 4: sums_tri_p(b, m, pts, out, 2, 0); break;
    case 5: sums_tri_p(b, m, pts, out, 2, 1); break;
    default:
        if (b->cond) sums_tri_p(b, m, pts, out, b->p, 1);
        else sums_tri_p(b, m, pts, out, b->p, 0);
        break;
    }
}

/* A convex region of rfunc/region.h: h^2 = sum_i max(-p_i, 0)^2 over its
 * edges, p_i = (x - V_i).m_i, h grad h = -sum_i max(-p_i, 0) m_i (0 inside,
 * where the point falls back: h^-p is infinite). */
DFL_INLINE void region_term(double x, double y, const dfl_rfunc_batch *b, size_t k, int p,
                            double *S, double *Vx, double *Vy)
{
    double h2 = 0.0, gx = 0.0, gy = 0.0;
    for (size_t e = b->roff[k]; e < b->roff[k + 1]; e++) {
        const double q = -((x - b->rv[2 * e]) * b->rm[2 * e] + (y - b->rv[2 * e + 1]) * b->rm[2 * e + 1]);
        const double mq = 0.5 * (q + fabs(q));
        h2 += mq * mq;
        gx -= mq * b->rm[2 * e];
        gy -= mq * b->rm[2 * e + 1];
    }
    const double q = pow_term(h2, p, S);
    *Vx += q * gx;
    *Vy += q * gy;
}

/* The strip, 3D, point (strip = -1) and region (strip = -2) kernels' sums:
 * 1 + dim doubles per point (S, V). */
DFL_INLINE void sums_gen_p(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out,
                           const int p, const int dim, const int strip)
{
    const size_t n = b->n, w = (size_t)dim + 1;
    for (size_t i0 = 0; i0 < m; i0 += LANES) {
        const size_t c = m - i0 < LANES ? m - i0 : LANES;
        double X[LANES], Y[LANES], Z[LANES] = {0}, S[LANES] = {0}, Vx[LANES] = {0},
                                   Vy[LANES] = {0}, Vz[LANES] = {0};
        for (size_t l = 0; l < LANES; l++) {
            const size_t i = i0 + (l < c ? l : c - 1);
            X[l] = pts[(size_t)dim * i];
            Y[l] = pts[(size_t)dim * i + 1];
            if (dim == 3) Z[l] = pts[3 * i + 2];
        }
        for (size_t k = 0; k < n; k++) {
            if (strip == -2) {
#pragma omp simd
                for (int l = 0; l < LANES; l++)
                    region_term(X[l], Y[l], b, k, p, &S[l], &Vx[l], &Vy[l]);
            } else if (strip < 0) {
#pragma omp simd
                for (int l = 0; l < LANES; l++)
                    point_term(X[l], Y[l], Z[l], b, k, p, dim, &S[l], &Vx[l], &Vy[l], &Vz[l]);
            } else if (dim == 2) {
#pragma omp simd
                for (int l = 0; l < LANES; l++)
                    seg_term_strip2(X[l], Y[l], b, k, p, &S[l], &Vx[l], &Vy[l]);
            } else {
#pragma omp simd
                for (int l = 0; l < LANES; l++)
                    seg_term3(X[l], Y[l], Z[l], b, k, p, strip, &S[l], &Vx[l], &Vy[l], &Vz[l]);
            }
        }
        for (size_t l = 0; l < c; l++) {
            out[w * (i0 + l)] = S[l];
            out[w * (i0 + l) + 1] = Vx[l];
            out[w * (i0 + l) + 2] = Vy[l];
            if (dim == 3) out[w * (i0 + l) + 3] = Vz[l];
        }
    }
}

#define DFL_GEN_CASES(dim, strip)                                  \
    switch (b->p) {                                                \
    case 1: sums_gen_p(b, m, pts, out, 1, dim, strip); break;      \
    case 2: sums_gen_p(b, m, pts, out, 2, dim, strip); break;      \
    case 3: sums_gen_p(b, m, pts, out, 3, dim, strip); break;      \
    case 4: sums_gen_p(b, m, pts, out, 4, dim, strip); break;      \
    case 7: sums_gen_p(b, m, pts, out, 7, dim, strip); break;      \
    case 12: sums_gen_p(b, m, pts, out, 12, dim, strip); break;    \
    default: sums_gen_p(b, m, pts, out, b->p, dim, strip); break;  \
    }

DFL_CLONES
static void sums_strip2(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    DFL_GEN_CASES(2, 1)
}

DFL_CLONES
static void sums_disk3(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    DFL_GEN_CASES(3, 0)
}

DFL_CLONES
static void sums_strip3(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    DFL_GEN_CASES(3, 1)
}

/* Sums S and V (3 doubles per point) for m points. */
DFL_INLINE void sums_p(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out,
                       const int p)
{
    const size_t n = b->n;
    for (size_t i0 = 0; i0 < m; i0 += LANES) {
        const size_t c = m - i0 < LANES ? m - i0 : LANES;
        double X[LANES], Y[LANES], S[LANES] = {0}, Vx[LANES] = {0}, Vy[LANES] = {0};
        /* a short last block repeats its last point in the spare lanes */
        for (size_t l = 0; l < LANES; l++) {
            const size_t i = i0 + (l < c ? l : c - 1);
            X[l] = pts[2 * i];
            Y[l] = pts[2 * i + 1];
        }
        for (size_t k = 0; k < n; k++) {
#pragma omp simd
            for (int l = 0; l < LANES; l++)
                seg_term(X[l], Y[l], b, k, p, &S[l], &Vx[l], &Vy[l]);
        }
        for (size_t l = 0; l < c; l++) {
            out[3 * (i0 + l)] = S[l];
            out[3 * (i0 + l) + 1] = Vx[l];
            out[3 * (i0 + l) + 2] = Vy[l];
        }
    }
}

DFL_CLONES
static void sums_disk2(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    switch (b->p) {
    case 1: sums_p(b, m, pts, out, 1); break;
    case 2: sums_p(b, m, pts, out, 2); break;
    case 3: sums_p(b, m, pts, out, 3); break;
    case 4: sums_p(b, m, pts, out, 4); break;
    case 5: sums_p(b, m, pts, out, 5); break;
    case 6: sums_p(b, m, pts, out, 6); break;
    case 7: sums_p(b, m, pts, out, 7); break;
    case 8: sums_p(b, m, pts, out, 8); break;
    case 12: sums_p(b, m, pts, out, 12); break;
    default: sums_p(b, m, pts, out, b->p); break;
    }
}

DFL_CLONES
static void sums_reg(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    DFL_GEN_CASES(2, -2)
}

DFL_CLONES
static void sums_points2(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    DFL_GEN_CASES(2, -1)
}

DFL_CLONES
static void sums_points3(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    DFL_GEN_CASES(3, -1)
}

/* 1 + dim sums per point: the kernel of the batch's parts, dimension and trim. */
static void sums(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    if (b->regions) {
        sums_reg(b, m, pts, out);
    } else if (b->tris) {
        sums_tri(b, m, pts, out);
    } else if (b->points) {
        if (b->dim == 3) sums_points3(b, m, pts, out);
        else sums_points2(b, m, pts, out);
    } else if (b->dim == 3) {
        if (b->strip) sums_strip3(b, m, pts, out);
        else sums_disk3(b, m, pts, out);
    } else if (b->strip) {
        sums_strip2(b, m, pts, out);
    } else {
        sums_disk2(b, m, pts, out);
    }
}

int dfl_rfunc_batch_simd_width(void)
{
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) && \
    !defined(DFL_NO_CLONES)
    /* The dispatcher's order: x86-64-v4, then v3, then the baseline. */
    __builtin_cpu_init();
    if (__builtin_cpu_supports("x86-64-v4")) return 8;
    if (__builtin_cpu_supports("x86-64-v3")) return 4;
#endif
    return 2;
}

/* u and grad u (dim entries) from the sums, or 0 when they are not
 * trustworthy. */
static int accept(int p, int dim, const double *s, double *u, double *g)
{
    const double S = s[0];
    if (!(S >= 1e-280 && S <= 1e280)) return 0;
    for (int j = 1; j <= dim; j++)
        if (!isfinite(s[j])) return 0;
    const double w = p == 1 ? 1.0 / S : p == 2 ? 1.0 / sqrt(S) : pow(S, -1.0 / p);
    const double wp1 = dfl_rfunc_ipow(w, p + 1);
    if (!(wp1 >= 1e-290) || !isfinite(wp1)) return 0;
    for (int j = 0; j < dim; j++) {
        g[j] = wp1 * s[1 + j];
        if (!isfinite(g[j])) return 0;
    }
    *u = w;
    return 1;
}

static void eval_block(const dfl_rfunc_batch *b, size_t m, const double *pts, double *val,
                       double *grad)
{
    double s[4 * SCRATCH];
    const size_t dim = (size_t)b->dim;
    assert(m <= SCRATCH);
    sums(b, m, pts, s);
    for (size_t i = 0; i < m; i++) {
        double u, g[3];
        if (!accept(b->p, b->dim, s + (dim + 1) * i, &u, g))
            u = dfl_field_eval1(&b->ref, pts + dim * i, g);
        val[i] = u;
        if (grad)
            for (size_t j = 0; j < dim; j++) grad[dim * i + j] = g[j];
    }
}

void dfl_rfunc_batch_eval(const dfl_rfunc_batch *b, size_t m, const double *pts, double *val,
                          double *grad)
{
    const size_t dim = (size_t)b->dim;
    for (size_t i = 0; i < m; i += SCRATCH) {
        const size_t c = m - i < SCRATCH ? m - i : SCRATCH;
        eval_block(b, c, pts + dim * i, val + i, grad ? grad + dim * i : NULL);
    }
}

size_t dfl_rfunc_batch_fallbacks(const dfl_rfunc_batch *b, size_t m, const double *pts)
{
    double s[4 * SCRATCH];
    const size_t dim = (size_t)b->dim;
    size_t cnt = 0;
    for (size_t i = 0; i < m; i += SCRATCH) {
        const size_t c = m - i < SCRATCH ? m - i : SCRATCH;
        sums(b, c, pts + dim * i, s);
        for (size_t j = 0; j < c; j++) {
            double u, g[3];
            cnt += !accept(b->p, b->dim, s + (dim + 1) * j, &u, g);
        }
    }
    return cnt;
}

/* ---- construction -------------------------------------------------------- */

/* A batch of n parts of order p and dimension dim with its arrays (one
 * allocation) and the reference field ref (moved in; destroyed on failure). */
static dfl_status batch_alloc(int dim, int p, size_t n, dfl_field *ref, dfl_rfunc_batch **out,
                              dfl_err *err)
{
    dfl_rfunc_batch *b = calloc(1, sizeof *b);
    double *mem = malloc(NARR * n * sizeof *mem);
    if (!b || !mem) {
        free(b);
        free(mem);
        dfl_field_destroy(ref);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory for %zu parts", n);
    }
    b->p = p;
    b->dim = dim;
    b->n = n;
    b->mem = mem;
    double **arr[NARR] = {&b->ax, &b->ay, &b->bx, &b->by, &b->nx, &b->ny, &b->hid, &b->hid2,
                          &b->az, &b->bz, &b->nz, &b->mx, &b->my, &b->mz,
                          &b->ex, &b->ey, &b->ez};
    for (int j = 0; j < NARR; j++) *arr[j] = mem + (size_t)j * n;
    b->ref = *ref;
    *out = b;
    return DFL_OK;
}

dfl_status dfl_rfunc_batch_new(const double *v, size_t n, bool closed, int p,
                               dfl_rfunc_batch **out, dfl_err *err)
{
    return dfl_rfunc_batch_new_opts(2, v, n, closed, p, DFL_RFUNC_TRIM_DISK, out, err);
}

dfl_status dfl_rfunc_batch_new_opts(int dim, const double *v, size_t n, bool closed, int p,
                                    dfl_rfunc_trim trim, dfl_rfunc_batch **out, dfl_err *err)
{
    dfl_field ref = {0};
    if (trim != DFL_RFUNC_TRIM_DISK && trim != DFL_RFUNC_TRIM_STRIP)
        return dfl_err_set(err, DFL_E_INPUT,
                           "batch: trim '%s' has no batched kernel (disk and strip only)",
                           dfl_rfunc_trim_name(trim));
    /* The library validates everything (counts, p, degenerate segments). */
    dfl_status st = dfl_rfield_polyline_opts(dim, v, n, closed, DFL_RFUNC_REQUIV, p, trim, false,
                                             &ref, err);
    if (st != DFL_OK) return st;
    const size_t ns = closed ? n : n - 1;
    dfl_rfunc_batch *b;
    if ((st = batch_alloc(dim, p, ns, &ref, &b, err)) != DFL_OK) return st;
    b->strip = trim == DFL_RFUNC_TRIM_STRIP;
    if (dim == 3 || b->strip) {
        /* the library's own segment frames (rfunc/segment.c): the same n1,
         * n2, e as the per-point path */
        for (size_t k = 0; k < ns; k++) {
            dfl_rfunc_seg sg;
            const double *a = v + (size_t)dim * k, *e = v + (size_t)dim * ((k + 1) % n);
            st = dfl_rfunc_seg_init(dim, a, e, trim, &sg, err);
            if (st != DFL_OK) {
                dfl_rfunc_batch_free(b);
                return st;
            }
            b->ax[k] = sg.a[0], b->ay[k] = sg.a[1], b->az[k] = sg.a[2];
            b->bx[k] = sg.b[0], b->by[k] = sg.b[1], b->bz[k] = sg.b[2];
            b->nx[k] = sg.n1[0], b->ny[k] = sg.n1[1], b->nz[k] = sg.n1[2];
            b->mx[k] = sg.n2[0], b->my[k] = sg.n2[1], b->mz[k] = sg.n2[2];
            b->ex[k] = sg.e[0], b->ey[k] = sg.e[1], b->ez[k] = sg.e[2];
            b->hid[k] = 0.5 / sg.d;
            b->hid2[k] = 0.5 / (sg.d * sg.d);
        }
        *out = b;
        return DFL_OK;
    }
    for (size_t k = 0; k < ns; k++) {
        const double *a = v + 2 * k, *e = v + 2 * ((k + 1) % n);
        /* d and the normal exactly as rfunc/segment.c computes them (not
         * hypot): then f = (x - a) . n is bitwise the library's, and u
         * agrees with rfield's per-point path to rounding even where f is
         * itself a rounding residue (points on a segment up to the
         * rounding of their coordinates, 1e-9 off it). */
        const double dx = e[0] - a[0], dy = e[1] - a[1];
        const double d = sqrt(dx * dx + dy * dy);
        b->ax[k] = a[0];
        b->ay[k] = a[1];
        b->bx[k] = e[0];
        b->by[k] = e[1];
        b->nx[k] = (e[1] - a[1]) / d;
        b->ny[k] = -(e[0] - a[0]) / d;
        b->hid[k] = 0.5 / d;
        b->hid2[k] = 0.5 / (d * d);
    }
    *out = b;
    return DFL_OK;
}

dfl_status dfl_rfunc_batch_points(int dim, const double *c, size_t n, int p,
                                  dfl_rfunc_batch **out, dfl_err *err)
{
    if (n < 2) return dfl_err_set(err, DFL_E_INPUT, "batch: %zu points (need at least 2)", n);
    dfl_rfield *r;
    dfl_status st = dfl_rfield_new(dim, DFL_RFUNC_REQUIV, p, &r, err);
    if (st != DFL_OK) return st;
    dfl_rfield_set_fast(r, false);
    for (size_t i = 0; i < n && st == DFL_OK; i++) st = dfl_rfield_add_point(r, c + (size_t)dim * i, err);
    dfl_field ref = {0};
    if (st == DFL_OK) st = dfl_rfield_finish(&r, &ref, err);
    else dfl_rfield_free(r);
    if (st != DFL_OK) return st;
    dfl_rfunc_batch *b;
    if ((st = batch_alloc(dim, p, n, &ref, &b, err)) != DFL_OK) return st;
    b->points = 1;
    for (size_t k = 0; k < n; k++) {
        b->ax[k] = c[(size_t)dim * k];
        b->ay[k] = c[(size_t)dim * k + 1];
        b->az[k] = dim == 3 ? c[3 * k + 2] : 0.0;
    }
    *out = b;
    return DFL_OK;
}

dfl_status dfl_rfunc_batch_triangles(const dfl_rfunc_tri *t, size_t n, int p,
                                     dfl_rfunc_batch **out, dfl_err *err)
{
    if (n < 2) return dfl_err_set(err, DFL_E_INPUT, "batch: %zu triangles (need at least 2)", n);
    const dfl_rfunc_tri_opts o = t[0].o;
    for (size_t k = 0; k < n; k++)
        if (t[k].o.smooth || t[k].o.trim != o.trim || t[k].o.a != o.a ||
            (o.trim == DFL_RFUNC_TRI_CONDITIONAL && t[k].o.k != 2))
            return dfl_err_set(err, DFL_E_INPUT,
                               "batch: triangles need one eq. 4 trim (conditional with k = 2)");
    dfl_rfield *r;
    dfl_status st = dfl_rfield_new(3, DFL_RFUNC_REQUIV, p, &r, err);
    if (st != DFL_OK) return st;
    dfl_rfield_set_fast(r, false);
    for (size_t k = 0; k < n && st == DFL_OK; k++)
        st = dfl_rfield_add_triangle(r, t[k].v[0], t[k].v[1], t[k].v[2], &t[k].o, err);
    dfl_field ref = {0};
    if (st == DFL_OK) st = dfl_rfield_finish(&r, &ref, err);
    else dfl_rfield_free(r);
    if (st != DFL_OK) return st;
    double *tri = malloc(24 * n * sizeof *tri);
    if (!tri) {
        dfl_field_destroy(&ref);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory for %zu triangles", n);
    }
    dfl_rfunc_batch *b;
    if ((st = batch_alloc(3, p, n, &ref, &b, err)) != DFL_OK) {
        free(tri);
        return st;
    }
    b->tris = 1;
    b->cond = o.trim == DFL_RFUNC_TRI_CONDITIONAL;
    b->ca = o.a;
    b->tri = tri;
    for (size_t k = 0; k < n; k++) {
        double *T = tri + 24 * k;
        memcpy(T, t[k].n, 3 * sizeof *T);
        for (int i = 0; i < 3; i++) {
            memcpy(T + 3 + 6 * i, t[k].v[i], 3 * sizeof *T);
            memcpy(T + 6 + 6 * i, t[k].m[i], 3 * sizeof *T);
        }
    }
    *out = b;
    return DFL_OK;
}

dfl_status dfl_rfunc_batch_regions(const dfl_rfunc_region *r, size_t n, int p,
                                   dfl_rfunc_batch **out, dfl_err *err)
{
    if (n < 2) return dfl_err_set(err, DFL_E_INPUT, "batch: %zu regions (need at least 2)", n);
    dfl_rfield *rf;
    dfl_status st = dfl_rfield_new(2, DFL_RFUNC_REQUIV, p, &rf, err);
    if (st != DFL_OK) return st;
    dfl_rfield_set_fast(rf, false);
    size_t ne = 0;
    for (size_t k = 0; k < n && st == DFL_OK; k++) {
        st = dfl_rfield_add_region(rf, r[k].v, r[k].n, err);
        ne += r[k].n;
    }
    dfl_field ref = {0};
    if (st == DFL_OK) st = dfl_rfield_finish(&rf, &ref, err);
    else dfl_rfield_free(rf);
    if (st != DFL_OK) return st;
    size_t *off = malloc((n + 1) * sizeof *off);
    double *ev = malloc(4 * ne * sizeof *ev);
    dfl_rfunc_batch *b = NULL;
    if (!off || !ev) {
        free(off), free(ev);
        dfl_field_destroy(&ref);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory for %zu regions", n);
    }
    if ((st = batch_alloc(2, p, n, &ref, &b, err)) != DFL_OK) {
        free(off), free(ev);
        return st;
    }
    b->regions = 1;
    b->roff = off;
    b->rv = ev;
    b->rm = ev + 2 * ne;
    off[0] = 0;
    for (size_t k = 0; k < n; k++) {
        memcpy(b->rv + 2 * off[k], r[k].v, 2 * r[k].n * sizeof *ev);
        memcpy(b->rm + 2 * off[k], r[k].m, 2 * r[k].n * sizeof *ev);
        off[k + 1] = off[k] + r[k].n;
    }
    *out = b;
    return DFL_OK;
}

void dfl_rfunc_batch_free(dfl_rfunc_batch *b)
{
    if (!b) return;
    free(b->tri);
    free(b->roff);
    free(b->rv);
    dfl_field_destroy(&b->ref);
    free(b->mem);
    free(b);
}

size_t dfl_rfunc_batch_segments(const dfl_rfunc_batch *b) { return b->n; }
int dfl_rfunc_batch_order(const dfl_rfunc_batch *b) { return b->p; }
const dfl_field *dfl_rfunc_batch_reference(const dfl_rfunc_batch *b) { return &b->ref; }

/* ---- as a field ---------------------------------------------------------- */

static void field_eval(const void *ctx, size_t m, const double *pts, double *val, double *grad)
{
    dfl_rfunc_batch_eval(ctx, m, pts, val, grad);
}

static dfl_status field_jet(const void *ctx, const double *x, const double *dir, int K,
                            dfl_jet *out, dfl_err *err)
{
    const dfl_rfunc_batch *b = ctx;
    return dfl_field_jet(&b->ref, x, dir, K, out, err);
}

static void field_destroy(void *ctx) { dfl_rfunc_batch_free(ctx); }

static const dfl_field_ops batch_ops = {"rfunc_batch", field_eval, field_jet, field_destroy};

dfl_status dfl_rfunc_batch_field(const double *v, size_t n, bool closed, int p, dfl_field *out,
                                 dfl_err *err)
{
    dfl_rfunc_batch *b;
    dfl_status st = dfl_rfunc_batch_new(v, n, closed, p, &b, err);
    if (st != DFL_OK) return st;
    out->dim = b->dim;
    out->ops = &batch_ops;
    out->ctx = b;
    return DFL_OK;
}
