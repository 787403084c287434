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

#define LANES 8
/* Points per inner call when the caller wants no gradient (stack scratch). */
#define SCRATCH 64

struct dfl_rfunc_batch {
    int p;
    size_t n;           /* segments */
    double *ax, *ay;    /* start points a */
    double *bx, *by;    /* end points b */
    double *nx, *ny;    /* unit normals n = (b_y - a_y, -(b_x - a_x)) / d (eq. 2) */
    double *hid;        /* 1 / (2 d) */
    double *hid2;       /* 1 / (2 d^2) */
    double *mem;        /* one allocation for the eight arrays */
    dfl_field ref;      /* the library's field of the same polyline */
};

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
static void sums(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
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

/* u and grad u from the sums, or 0 when they are not trustworthy. */
static int accept(int p, const double *s, double *u, double *g)
{
    const double S = s[0];
    if (!(S >= 1e-280 && S <= 1e280) || !isfinite(s[1]) || !isfinite(s[2])) return 0;
    const double w = p == 1 ? 1.0 / S : p == 2 ? 1.0 / sqrt(S) : pow(S, -1.0 / p);
    const double wp1 = dfl_rfunc_ipow(w, p + 1);
    if (!(wp1 >= 1e-290) || !isfinite(wp1)) return 0;
    g[0] = wp1 * s[1];
    g[1] = wp1 * s[2];
    if (!isfinite(g[0]) || !isfinite(g[1])) return 0;
    *u = w;
    return 1;
}

static void eval_block(const dfl_rfunc_batch *b, size_t m, const double *pts, double *val,
                       double *grad)
{
    double s[3 * SCRATCH];
    assert(m <= SCRATCH);
    sums(b, m, pts, s);
    for (size_t i = 0; i < m; i++) {
        double u, g[2];
        if (!accept(b->p, s + 3 * i, &u, g)) u = dfl_field_eval1(&b->ref, pts + 2 * i, g);
        val[i] = u;
        if (grad) {
            grad[2 * i] = g[0];
            grad[2 * i + 1] = g[1];
        }
    }
}

void dfl_rfunc_batch_eval(const dfl_rfunc_batch *b, size_t m, const double *pts, double *val,
                          double *grad)
{
    for (size_t i = 0; i < m; i += SCRATCH) {
        const size_t c = m - i < SCRATCH ? m - i : SCRATCH;
        eval_block(b, c, pts + 2 * i, val + i, grad ? grad + 2 * i : NULL);
    }
}

size_t dfl_rfunc_batch_fallbacks(const dfl_rfunc_batch *b, size_t m, const double *pts)
{
    double s[3 * SCRATCH];
    size_t cnt = 0;
    for (size_t i = 0; i < m; i += SCRATCH) {
        const size_t c = m - i < SCRATCH ? m - i : SCRATCH;
        sums(b, c, pts + 2 * i, s);
        for (size_t j = 0; j < c; j++) {
            double u, g[2];
            cnt += !accept(b->p, s + 3 * j, &u, g);
        }
    }
    return cnt;
}

/* ---- construction -------------------------------------------------------- */

dfl_status dfl_rfunc_batch_new(const double *v, size_t n, bool closed, int p,
                               dfl_rfunc_batch **out, dfl_err *err)
{
    dfl_field ref = {0};
    /* The library validates everything (counts, p, degenerate segments). */
    dfl_status st = dfl_rfield_polyline_opts(2, v, n, closed, DFL_RFUNC_REQUIV, p,
                                             DFL_RFUNC_TRIM_DISK, false, &ref, err);
    if (st != DFL_OK) return st;
    dfl_rfunc_batch *b = calloc(1, sizeof *b);
    const size_t ns = closed ? n : n - 1;
    double *mem = malloc(8 * ns * sizeof *mem);
    if (!b || !mem) {
        free(b);
        free(mem);
        dfl_field_destroy(&ref);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory for %zu segments", ns);
    }
    b->p = p;
    b->n = ns;
    b->mem = mem;
    double **arr[8] = {&b->ax, &b->ay, &b->bx, &b->by, &b->nx, &b->ny, &b->hid, &b->hid2};
    for (int j = 0; j < 8; j++) *arr[j] = mem + (size_t)j * ns;
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
    b->ref = ref;
    *out = b;
    return DFL_OK;
}

void dfl_rfunc_batch_free(dfl_rfunc_batch *b)
{
    if (!b) return;
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
    out->dim = 2;
    out->ops = &batch_ops;
    out->ctx = b;
    return DFL_OK;
}
