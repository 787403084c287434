/* Batched kernel for R-conjunction (eq. 7) of segment parts: 2D or 3D,
 * all with the disk or all with the strip trim of eq. 4, in any order and
 * arrangement (the fold needs no chain).
 *
 * The join is a left fold in part order, u_1 = h_1, u_k = u_(k-1) ^ h_k,
 *     a ^ b = lo - hi ((1 + r^p)^(1/p) - 1),  lo = min, hi = max, r = lo/hi
 * (rfunc/join.h), so it is sequential over parts, but lanes are points: a
 * block of RC_LANES points runs through the parts in order, each lane with its
 * own u and grad u, and the gradient is carried forward,
 *     grad u_k = F_a grad u_(k-1) + F_b grad h_k,
 * with the partials of join.c's dfl_rfunc_rconj2: 1 - (hi/N)^(p-1) for the
 * larger argument and 1 - (lo/N)^(p-1) for the smaller, N = hi w,
 * w = (1 + r^p)^(1/p).  Each part needs h itself (not a power of h^2 as
 * R-equivalence does): one reciprocal square root by Newton steps
 * (batch_impl.h), h = h^2 / h, grad h = (h grad h) / h.
 *
 * The root w, without libm in the lane loop and without cancellation in
 * w - 1 when r^p is tiny:
 *  - p = 2: w - 1 = x / (1 + w), x = r^2, w = y / sqrt(y), y = 1 + x, by
 *    one more reciprocal square root (Newton steps) and a division.
 *  - p >= 3: w - 1 = x g(x), x = r^p in [0, 1], with
 *        g(x) = ((1 + x)^(1/p) - 1) / x,
 *    analytic on [0, 1] with its only singularity at x = -1 (t = -3 in
 *    t = 2x - 1), so its Chebyshev interpolant converges like
 *    (3 + sqrt 8)^-D and the Taylor coefficients in t decay like 3^-j:
 *    the monomial form in t is well conditioned (sum |a_j| <= 1.25 g(0)
 *    for every p).  Degree D = 20 reaches 2.2e-16 relative for p = 3..64
 *    (checked against 40-digit arithmetic; tests/rfunc/test_batch_rconj.c
 *    checks the kernel against join.c's expm1(log1p(x)/p)).  The
 *    coefficients are computed when the batch is built, from long-double
 *    values at the Chebyshev nodes (libm there, never in the lane loop).
 * Then F = lo - hi (w - 1), and the partials without the cancellation of
 * join.c's 1 - (1/w)^(p-1): 1 - w^(1-p) = (x - (w - 1)) / w^p (w^(p-1) =
 * (1 + x)/w), which for p = 2 is (w - 1)/w; 1/w by a division from w - 1
 * for p >= 3, from the Newton root for p = 2.  These gradients are closer
 * to a long-double fold than the per-point path's: at 700 parts (2D,
 * disk trims, 3600 points) 1e-14 against 5.7e-12 for p = 2 and 2.1e-12
 * against 7.1e-11 for p = 12 (absolute, |grad u| ~ 1); the values agree
 * with both to 1e-14 relative.
 * F = lo (1 - (w - 1)/r) with (w - 1)/r <= 2^(1/p) - 1 < 0.42: the fold
 * step has no cancellation, and its relative error factors a F_a / F and
 * b F_b / F are non-negative and sum to 1 (F is homogeneous of degree 1),
 * so rounding does not grow along the fold.
 *
 * Orders: p = 2, 3, 4, 7 and 12 are compile-time constants; every other
 * p >= 2 runs the same lane loop with p at run time (powers by seven
 * squarings and selects), still vectorized.
 *
 * Fallback through b->fb (the field's per-point path), per point: h^2
 * outside [1e-280, 1e280] for some part (on a part, where u = 0 and the
 * gradient is 0 by the library's convention; subnormal or overflowing
 * squares near the domain's edge; non-finite input), u < 1e-280, or a
 * non-finite gradient.
 *
 * Operation counts per part (2D disk, p = 2, value + gradient; counted in
 * gcc's AVX2 code): 49 multiplications, 28 additions, 2 divisions (lo/hi,
 * x/(1 + w)) and ~15 compares, blends and logic ops: the segment's h^2
 * and h grad h 12 multiplications, its reciprocal root 13 (Newton) + 1,
 * the fold's root 13, the rest 10.  Two multiply pipes and 4 doubles per
 * vector: >= 6.1 cycles per part per core, 8.0e8/s on two cores at
 * 2.45 GHz (the R-equivalence kernel needs 15 multiplications).  Measured
 * (one thread, CPU time, machine under load ~8): 16 cycles per part for
 * p = 2 (1.5e8 part-evaluations per CPU-second) beside 3.5 for the
 * R-equivalence kernel; p = 7, 12: 27 cycles.  Splitting the fold from
 * the parts' h into separate lane passes, or blocks of 16 to 64 points,
 * did not change the rate.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "rfunc/batch_impl.h"

/* Coefficients of g in t = 2x - 1 (see the top), degree NCOEF - 1. */
#define NCOEF 21

typedef struct rconj_kd {
    double a[NCOEF];
} rconj_kd;

/* h^2 and h grad h (into *g0, *g1, *g2; scalars, so that the lane loop
 * vectorizes) of segment k at (x, y, z): the
 * carrier f^2 (2D: f = (x - a).n; 3D: s1^2 + s2^2 with the library's two
 * normals) plus mt^2, mt = max(-t, 0) of the disk trim -t = (w.v)/d or the
 * strip trim t = 2 p1 p2 / (p1 + p2 + |(p1, p2)|) (rfunc/segment.c). */
DFL_INLINE double seg_h2(double x, double y, double z, const dfl_rfunc_batch *b, size_t k,
                         int dim, int strip, double *g0, double *g1, double *g2)
{
    const double wx = x - b->ax[k], wy = y - b->ay[k], wz = dim == 3 ? z - b->az[k] : 0.0;
    const double vx = x - b->bx[k], vy = y - b->by[k], vz = dim == 3 ? z - b->bz[k] : 0.0;
    double s1 = wx * b->nx[k] + wy * b->ny[k], s2 = 0.0;
    if (dim == 3) {
        s1 += wz * b->nz[k];
        s2 = wx * b->mx[k] + wy * b->my[k] + wz * b->mz[k];
    }
    double gx = s1 * b->nx[k], gy = s1 * b->ny[k], gz = 0.0;
    if (dim == 3) {
        gx += s2 * b->mx[k];
        gy += s2 * b->my[k];
        gz = s1 * b->nz[k] + s2 * b->mz[k];
    }
    double mt;
    if (strip) {
        const double p1 = wx * b->ex[k] + wy * b->ey[k] + wz * b->ez[k];
        const double p2 = -(vx * b->ex[k] + vy * b->ey[k] + vz * b->ez[k]);
        const double q2 = p1 * p1 + p2 * p2;
        const double rq = rsqrt_newton(q2);
        const double t = 2.0 * p1 * p2 / (p1 + p2 + q2 * rq);
        mt = 0.5 * (fabs(t) - t);
        /* grad t = (p2 - p1)/r e, grad mt = -grad t where t < 0 */
        const double kk = mt * (p2 - p1) * rq;
        gx -= kk * b->ex[k];
        gy -= kk * b->ey[k];
        if (dim == 3) gz -= kk * b->ez[k];
    } else {
        const double m2 = wx * vx + wy * vy + wz * vz;
        const double mp = m2 + fabs(m2);
        mt = mp * b->hid[k];
        const double mi = mp * b->hid2[k];
        gx += mi * (wx + vx);
        gy += mi * (wy + vy);
        if (dim == 3) gz += mi * (wz + vz);
    }
    *g0 = gx;
    *g1 = gy;
    *g2 = gz;
    return s1 * s1 + s2 * s2 + mt * mt;
}

/* g(x) of the top by Horner in t = 2x - 1 (written out: straight-line code). */
DFL_INLINE double g_poly(const double *a, double x)
{
    const double t = 2.0 * x - 1.0;
    double s = a[20];
    s = s * t + a[19], s = s * t + a[18], s = s * t + a[17], s = s * t + a[16];
    s = s * t + a[15], s = s * t + a[14], s = s * t + a[13], s = s * t + a[12];
    s = s * t + a[11], s = s * t + a[10], s = s * t + a[9], s = s * t + a[8];
    s = s * t + a[7], s = s * t + a[6], s = s * t + a[5], s = s * t + a[4];
    s = s * t + a[3], s = s * t + a[2], s = s * t + a[1], s = s * t + a[0];
    return s;
}

/* x^k, 1 <= k <= 127, as straight-line code: squarings and selects by
 * the bits of k.  With k a compile-time constant the selects fold and
 * the unused squarings vanish (floor(log2 k) + popcount(k) - 1
 * multiplications, as ipow_sq); with k at run time there is no loop whose
 * trip count depends on k, which would keep the lane loop from
 * vectorizing (gcc -O2 does not peel such loops, not even ipow_sq's with
 * a constant k). */
DFL_INLINE double pick(int bit, double x)
{
    /* bit ? x : 1.0 by masks: a select gcc keeps as a branch when bit is
     * not a compile-time constant */
    const double one = 1.0;
    uint64_t xb, ob;
    memcpy(&xb, &x, sizeof xb);
    memcpy(&ob, &one, sizeof ob);
    const uint64_t m = (uint64_t)0 - (uint64_t)(bit != 0);
    const uint64_t rb = (xb & m) | (ob & ~m);
    double r;
    memcpy(&r, &rb, sizeof r);
    return r;
}

DFL_INLINE double ipow_k(double x, int k)
{
    double r = pick(k & 1, x);
    x *= x;
    r *= pick(k & 2, x);
    x *= x;
    r *= pick(k & 4, x);
    x *= x;
    r *= pick(k & 8, x);
    x *= x;
    r *= pick(k & 16, x);
    x *= x;
    r *= pick(k & 32, x);
    x *= x;
    r *= pick(k & 64, x);
    return r;
}

/* One fold step u ^ h at one lane: the new u, and the partials F_u, F_h. */
DFL_INLINE double fold(double u, double h, int p, const double *a,
                       double *Fu, double *Fh)
{
    const int u_hi = u >= h;
    const double hi = u_hi ? u : h, lo = u_hi ? h : u;
    const double r = lo / hi;
    const double x = ipow_k(r, p);
    double wm1, d_hi, d_lo; /* w - 1 = (1 + x)^(1/p) - 1, the partials */
    if (__builtin_constant_p(p) && p == 2) {
        /* p = 2 has its case (RCONJ_CASES): w - 1 = x / (1 + w) and, with
         * iw = 1/w from the Newton root, d_hi = 1 - 1/w = (w - 1) iw (no
         * cancellation) and d_lo = 1 - r iw */
        const double y = 1.0 + x, iw = rsqrt_newton(y);
        wm1 = x / (1.0 + y * iw);
        d_hi = wm1 * iw;
        d_lo = 1.0 - r * iw;
    } else {
        wm1 = x * g_poly(a, x);
        /* d_hi = 1 - w^(1-p) = (w^(p-1) - 1)/w^(p-1), w^(p-1) = (1 + x)/w:
         * (x - (w - 1))/(1 + x) = (x - (w - 1)) / w^p, without the
         * cancellation of 1 - w^(1-p) (w - 1 <= x/p: no cancellation in
         * x - (w - 1) either) */
        const double iw = 1.0 / (1.0 + wm1);
        d_hi = (x - wm1) * ipow_k(iw, p);
        d_lo = 1.0 - ipow_k(r * iw, p - 1);
    }
    const double F = lo - hi * wm1;
    *Fu = u_hi ? d_hi : d_lo;
    *Fh = u_hi ? d_lo : d_hi;
    return F;
}

/* Points per block: two AVX-512 vectors.  The fold is one chain per
 * point through the parts, so a block runs as many chains side by side as
 * it has lanes; with the int flags below, 16 lanes also let gcc pick
 * 512-bit vectors (16 ints fill one; with 8 it vectorized the whole lane
 * loop at 256 bits, half the AVX-512 width), while AVX2 and SSE2 keep
 * their 8 and 4 lanes per vector of ints. */
#define RC_LANES 16

/* The fast values of m <= SCRATCH points and, per point, whether it must
 * fall back (ok[i] = 0); grad gets dim doubles per point. */
DFL_INLINE void run_p(const dfl_rfunc_batch *b, size_t m, const double *pts, double *val,
                      double *grad, int *ok, const int p, const int dim, const int strip)
{
    const rconj_kd *kd = b->kd;
    const size_t n = b->n, D = (size_t)dim;
    for (size_t i0 = 0; i0 < m; i0 += RC_LANES) {
        const size_t c = m - i0 < RC_LANES ? m - i0 : RC_LANES;
        double X[RC_LANES], Y[RC_LANES], Z[RC_LANES] = {0}, U[RC_LANES], G0[RC_LANES],
            G1[RC_LANES], G2[RC_LANES] = {0};
        int bad[RC_LANES] = {0};
        /* a short last block repeats its last point in the spare lanes */
        for (size_t l = 0; l < RC_LANES; l++) {
            const size_t i = i0 + (l < c ? l : c - 1);
            X[l] = pts[D * i];
            Y[l] = pts[D * i + 1];
            if (dim == 3) Z[l] = pts[D * i + 2];
        }
#pragma omp simd
        for (int l = 0; l < RC_LANES; l++) {
            double g0, g1, g2;
            const double h2 = seg_h2(X[l], Y[l], Z[l], b, 0, dim, strip, &g0, &g1, &g2);
            const double rh = rsqrt_newton(h2);
            bad[l] |= !(h2 >= 1e-280) | !(h2 <= 1e280);
            U[l] = h2 * rh;
            G0[l] = g0 * rh;
            G1[l] = g1 * rh;
            if (dim == 3) G2[l] = g2 * rh;
        }
        for (size_t k = 1; k < n; k++) {
#pragma omp simd
            for (int l = 0; l < RC_LANES; l++) {
                double g0, g1, g2, Fu, Fh;
                const double h2 = seg_h2(X[l], Y[l], Z[l], b, k, dim, strip, &g0, &g1, &g2);
                const double rh = rsqrt_newton(h2);
                bad[l] |= !(h2 >= 1e-280) | !(h2 <= 1e280);
                const double h = h2 * rh, u = U[l];
                U[l] = fold(u, h, p, kd->a, &Fu, &Fh);
                const double c = Fh * rh; /* F_h / h: grad h = (h grad h) / h */
                G0[l] = Fu * G0[l] + c * g0;
                G1[l] = Fu * G1[l] + c * g1;
                if (dim == 3) G2[l] = Fu * G2[l] + c * g2;
            }
        }
        for (size_t l = 0; l < c; l++) {
            const size_t i = i0 + l;
            val[i] = U[l];
            grad[D * i] = G0[l];
            grad[D * i + 1] = G1[l];
            if (dim == 3) grad[D * i + 2] = G2[l];
            ok[i] = !bad[l] && U[l] >= 1e-280 && isfinite(U[l]) && isfinite(G0[l]) &&
                    isfinite(G1[l]) && isfinite(G2[l]);
        }
    }
}

#define RCONJ_CASES(dim, strip)                                                  \
    switch (b->p) {                                                              \
    case 2: run_p(b, m, pts, val, grad, ok, 2, dim, strip); break;               \
    case 3: run_p(b, m, pts, val, grad, ok, 3, dim, strip); break;               \
    case 4: run_p(b, m, pts, val, grad, ok, 4, dim, strip); break;               \
    case 7: run_p(b, m, pts, val, grad, ok, 7, dim, strip); break;               \
    case 12: run_p(b, m, pts, val, grad, ok, 12, dim, strip); break;             \
    default: run_p(b, m, pts, val, grad, ok, b->p, dim, strip); break;           \
    }

DFL_INLINE void run_disk2_body(const dfl_rfunc_batch *b, size_t m, const double *pts, double *val,
                      double *grad, int *ok)
{
    RCONJ_CASES(2, 0)
}
DFL_ISA_KERNEL(run_disk2, (const dfl_rfunc_batch *b, size_t m, const double *pts, double *val, double *grad, int *ok), (b, m, pts, val, grad, ok))

DFL_INLINE void run_strip2_body(const dfl_rfunc_batch *b, size_t m, const double *pts, double *val,
                       double *grad, int *ok)
{
    RCONJ_CASES(2, 1)
}
DFL_ISA_KERNEL(run_strip2, (const dfl_rfunc_batch *b, size_t m, const double *pts, double *val, double *grad, int *ok), (b, m, pts, val, grad, ok))

DFL_INLINE void run_disk3_body(const dfl_rfunc_batch *b, size_t m, const double *pts, double *val,
                      double *grad, int *ok)
{
    RCONJ_CASES(3, 0)
}
DFL_ISA_KERNEL(run_disk3, (const dfl_rfunc_batch *b, size_t m, const double *pts, double *val, double *grad, int *ok), (b, m, pts, val, grad, ok))

DFL_INLINE void run_strip3_body(const dfl_rfunc_batch *b, size_t m, const double *pts, double *val,
                       double *grad, int *ok)
{
    RCONJ_CASES(3, 1)
}
DFL_ISA_KERNEL(run_strip3, (const dfl_rfunc_batch *b, size_t m, const double *pts, double *val, double *grad, int *ok), (b, m, pts, val, grad, ok))

static void run(const dfl_rfunc_batch *b, size_t m, const double *pts, double *val,
                double *grad, int *ok)
{
    if (b->dim == 3) {
        if (b->strip) run_strip3(b, m, pts, val, grad, ok);
        else run_disk3(b, m, pts, val, grad, ok);
    } else if (b->strip) {
        run_strip2(b, m, pts, val, grad, ok);
    } else {
        run_disk2(b, m, pts, val, grad, ok);
    }
}

static void kernel(const dfl_rfunc_batch *b, size_t m, const double *pts, double *val,
                   double *grad)
{
    double g[3 * SCRATCH];
    int ok[SCRATCH];
    const size_t D = (size_t)b->dim;
    run(b, m, pts, val, g, ok);
    for (size_t i = 0; i < m; i++) {
        if (!ok[i]) val[i] = dfl_field_eval1(b->fb, pts + D * i, g + D * i);
        if (grad)
            for (size_t j = 0; j < D; j++) grad[D * i + j] = g[D * i + j];
    }
}

static size_t count_fb(const dfl_rfunc_batch *b, size_t m, const double *pts)
{
    double v[SCRATCH], g[3 * SCRATCH];
    int ok[SCRATCH];
    size_t cnt = 0;
    for (size_t i = 0; i < m; i += SCRATCH) {
        const size_t c = m - i < SCRATCH ? m - i : SCRATCH;
        run(b, c, pts + (size_t)b->dim * i, v, g, ok);
        for (size_t j = 0; j < c; j++) cnt += !ok[j];
    }
    return cnt;
}

/* The Horner coefficients a[0..NCOEF-1] of g in t (top): Chebyshev
 * interpolation at the NCOEF Chebyshev nodes of [0, 1] in long double
 * (node values to ~1e-19 where long double is the x87 format; with a
 * 53-bit long double the kernel is still good to ~1e-14), then the
 * Chebyshev series summed into monomials by T_(j+1) = 2t T_j - T_(j-1). */
static void g_coeffs(int p, double *a)
{
    enum { N = NCOEF };
    const long double pi = 3.141592653589793238462643383279502884L;
    long double f[N], c[N], T0[N] = {0}, T1[N] = {0}, T2[N], A[N] = {0};
    for (int j = 0; j < N; j++) {
        const long double x = (cosl((2 * j + 1) * pi / (2 * N)) + 1.0L) / 2.0L;
        f[j] = expm1l(log1pl(x) / p) / x;
    }
    for (int k = 0; k < N; k++) {
        long double s = 0.0L;
        for (int j = 0; j < N; j++) s += f[j] * cosl(k * (2 * j + 1) * pi / (2 * N));
        c[k] = (k ? 2.0L : 1.0L) * s / N;
    }
    T0[0] = 1.0L;
    T1[1] = 1.0L;
    A[0] = c[0];
    for (int j = 0; j < N; j++) A[j] += c[1] * T1[j];
    for (int k = 2; k < N; k++) {
        for (int j = 0; j < N; j++) T2[j] = (j ? 2.0L * T1[j - 1] : 0.0L) - T0[j];
        for (int j = 0; j < N; j++) {
            A[j] += c[k] * T2[j];
            T0[j] = T1[j];
            T1[j] = T2[j];
        }
    }
    for (int j = 0; j < N; j++) a[j] = (double)A[j];
}

/* R-conjunction of segments that all carry the same eq. 4 trim (disk or
 * strip); the segment data are the library's own (rfunc/segment.c), so h
 * is the per-point path's to rounding. */
dfl_status dfl_rfunc_batch_try_rconj(const dfl_rfunc_batch_desc *d, dfl_rfunc_batch **out,
                                     dfl_err *err)
{
    *out = NULL;
    if (d->join != DFL_RFUNC_RCONJ || d->n < 2 || d->p < 2) return DFL_OK;
    const dfl_rfunc_trim trim = d->parts[0].u.seg.trim;
    for (size_t k = 0; k < d->n; k++) {
        const dfl_rfunc_part *pt = &d->parts[k];
        if (pt->kind != DFL_RFUNC_PART_SEGMENT || pt->u.seg.trim != trim) return DFL_OK;
    }
    if (trim != DFL_RFUNC_TRIM_DISK && trim != DFL_RFUNC_TRIM_STRIP) return DFL_OK;
    rconj_kd *kd = malloc(sizeof *kd);
    if (!kd) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    dfl_field ref = {0};
    dfl_rfunc_batch *b;
    dfl_status st = dfl_rfunc_batch_alloc(d->dim, d->p, d->n, &ref, &b, err);
    if (st != DFL_OK) {
        free(kd);
        return st;
    }
    /* p = 2 too: the general step is its fallback where p is not known
     * to be a compile-time constant (unoptimized builds) */
    g_coeffs(d->p, kd->a);
    b->kd = kd;
    b->kd_free = free;
    b->fb = d->slow;
    b->strip = trim == DFL_RFUNC_TRIM_STRIP;
    b->kernel = kernel;
    b->count_fb = count_fb;
    for (size_t k = 0; k < d->n; k++) {
        dfl_rfunc_batch_put_seg(b, k, &d->parts[k].u.seg);
    }
    *out = b;
    return DFL_OK;
}
