/* Batched kernel for R-equivalence of segments with the smooth trims of
 * eq. 5 (DFL_RFUNC_TRIM_DISK_SMOOTH, DFL_RFUNC_TRIM_STRIP_SMOOTH), 2D and
 * 3D.  The segments need not form a chain: each stores its own a, b.
 *
 * Per segment (rfunc/trim.h, rfunc/segment.h): the carrier F = f^2 with
 * f grad f (2D: f = (x - a).n; 3D: F = s1^2 + s2^2 with the two normals),
 * the trim t with grad t (disk: t = -(w.v)/d, grad t = -(w + v)/d with
 * w = x - a, v = x - b; strip: t = 2 p1 p2 / (p1 + p2 + |(p1, p2)|),
 * grad t = (p2 - p1)/|(p1, p2)| e, as the eq. 4 strip kernel), then eq. 5
 *     r = sqrt(t^2 + F^2),  s = r + |t|,
 *     g = sqrt(t^2 + F^2) - t = F^2/s + (|t| - t),
 *     h^2 = F + g^2/4,
 * and, with grad g = (-g grad t + 2 F f grad f)/r (trim.c),
 *     h grad h = f grad f + (g/4) grad g
 *              = A (f grad f) - B grad t,   c = g/(4r), A = 1 + 2 F c, B = c g,
 * the same terms as dfl_rfunc_compose grouped so that the per-component
 * work is two multiplications.  The form of g needs no select: for t > 0
 * it is F^2/(r + t), the library's cancellation-free form; for t <= 0,
 * F^2/(r - t) = r + t and |t| - t = -2t give r - t as a sum of two terms
 * >= 0.  (A select between F^2/s and s would not do: gcc sinks the
 * division into the arm that uses it, and that branch keeps it from
 * vectorizing the lane loop without AVX-512 masks.)  F^2/s is NaN only
 * where s = 0, i.e. t = F = 0, which falls back (Range).
 *
 * Range.  1/r comes from rsqrt_newton (batch_impl.h), valid for normal
 * arguments; the forms above need no scaling while t^2 + F^2 (and, for the
 * strip, p1^2 + p2^2) lie in [1e-290, 1e290] (dfl_hypot2's safe range,
 * which the per-point path also uses unscaled there), and while the
 * largest q = h^-(p+2) over the parts is >= 1e-290 (far away eq. 5 grows
 * like f^2 / 2, and an underflowing q would lose V while S = sum h^-p is
 * still accepted).
 * Outside (points within ~1e-145 of an end point, or very far away) S is
 * set to NaN, and accept() (batch.c) recomputes the point through the
 * per-point path.  (p1^2 + p2^2 <= 1e201 within the domain, rfunc/domain.h,
 * needs no check.)  h^2 = 0 (on a segment) or subnormal overflows h^-p as
 * in the eq. 4 kernels and falls back the same way.
 *
 * Operation counts per segment at p = 2 (2D disk, value and gradient):
 * about 36 multiplications (13 of them in rsqrt_newton), 2 divisions
 * (F^2/s and 1/h^2), ~22 additions; the strip trim adds a second
 * rsqrt_newton and a third division (the conjunction's).  Against the
 * eq. 4 disk kernel (~17 multiplications, 1 division) that is the cost of
 * eq. 5: one root and one division more per part. */
#include <math.h>

#include "rfunc/batch_impl.h"
#include "rfunc/part.h"
#include "rfunc/segment.h"

/* Outside this range of t^2 + F^2 (and p1^2 + p2^2) the point falls back. */
#define SM_LO 1e-290
#define SM_HI 1e290

/* One segment k at one point (x, y, z), first stage: the carrier (f1, f2,
 * F), grad t = *kt (ux, uy, uz), r^2 = t^2 + F^2, *rr = 1/r and g, which
 * ends in the division F^2/s.  dim and strip are compile-time constants.
 *
 * The part's chain (1/sqrt by Newton steps, then F^2/s, then 1/h^2 in
 * pow_term) is longer than the out-of-order window covers at the kernel's
 * throughput, so the lane loop (sums_sm_p) runs this stage one part ahead
 * of smooth_b: the same operations per value, the parts summed in order. */
DFL_INLINE void smooth_a(double x, double y, double z, const dfl_rfunc_batch *b, size_t k,
                         int dim, int strip, double *f1o, double *f2o, double *Fo, double *kto,
                         double *uxo, double *uyo, double *uzo, double *r2o, double *rro,
                         double *go)
{
    const double wx = x - b->ax[k], wy = y - b->ay[k], wz = dim == 3 ? z - b->az[k] : 0.0;
    const double vx = x - b->bx[k], vy = y - b->by[k], vz = dim == 3 ? z - b->bz[k] : 0.0;
    /* carrier: F = f^2; f grad f = f1 n1 (+ f2 n2 in 3D) */
    double f1, f2 = 0.0, F;
    if (dim == 2) {
        f1 = wx * b->nx[k] + wy * b->ny[k];
        F = f1 * f1;
    } else {
        f1 = wx * b->nx[k] + wy * b->ny[k] + wz * b->nz[k];
        f2 = wx * b->mx[k] + wy * b->my[k] + wz * b->mz[k];
        F = f1 * f1 + f2 * f2;
    }
    /* trim: t, and grad t = kt * (ux, uy, uz) */
    double t, kt, ux, uy, uz;
    if (strip) {
        const double p1 = wx * b->ex[k] + wy * b->ey[k] + (dim == 3 ? wz * b->ez[k] : 0.0);
        const double p2 = -(vx * b->ex[k] + vy * b->ey[k] + (dim == 3 ? vz * b->ez[k] : 0.0));
        const double q2 = p1 * p1 + p2 * p2;
        const double rq = rsqrt_newton(q2);
        t = 2.0 * p1 * p2 / (p1 + p2 + q2 * rq);
        kt = (p2 - p1) * rq;
        ux = b->ex[k], uy = b->ey[k], uz = dim == 3 ? b->ez[k] : 0.0;
    } else {
        const double m2 = wx * vx + wy * vy + (dim == 3 ? wz * vz : 0.0);
        t = m2 * b->hid[k]; /* hid holds -1/d here */
        kt = b->hid[k];
        ux = wx + vx, uy = wy + vy, uz = wz + vz;
    }
    /* eq. 5 */
    const double F2 = F * F;
    const double r2 = t * t + F2;
    const double rr = rsqrt_newton(r2);
    const double sg = r2 * rr + fabs(t);
    /* g = F^2/s + (|t| - t): no select (see the top of the file) */
    *go = F2 / sg + (fabs(t) - t);
    *f1o = f1, *f2o = f2, *Fo = F, *kto = kt, *uxo = ux, *uyo = uy, *uzo = uz, *r2o = r2;
    *rro = rr;
}

/* Second stage: adds h^-p to *S and h^-(p+2) h grad h to *Vx, *Vy (*Vz in
 * 3D) from smooth_a's values of segment k.  dim and p are compile-time
 * constants. */
DFL_INLINE void smooth_b(const dfl_rfunc_batch *b, size_t k, int p, int dim, double f1,
                         double f2, double F, double kt, double ux, double uy, double uz,
                         double r2, double rr, double g, double *S, double *Vx, double *Vy,
                         double *Vz, double *r2lo, double *r2hi, double *qhi)
{
    const double qg = 0.25 * g;
    const double h2 = F + qg * g;
    const double c = qg * rr;
    const double A = 1.0 + (F + F) * c;
    const double Bk = c * g * kt;
    const double q = pow_term(h2, p, S);
    /* the range (top of the file), checked once per point after the loop */
    *r2lo = r2 < *r2lo ? r2 : *r2lo;
    *r2hi = r2 > *r2hi ? r2 : *r2hi;
    *qhi = q > *qhi ? q : *qhi;
    const double a1 = A * f1;
    if (dim == 2) {
        *Vx += q * (a1 * b->nx[k] - Bk * ux);
        *Vy += q * (a1 * b->ny[k] - Bk * uy);
    } else {
        const double a2 = A * f2;
        *Vx += q * (a1 * b->nx[k] + a2 * b->mx[k] - Bk * ux);
        *Vy += q * (a1 * b->ny[k] + a2 * b->my[k] - Bk * uy);
        *Vz += q * (a1 * b->nz[k] + a2 * b->mz[k] - Bk * uz);
    }
}

/* The lane loop of DFL_BATCH_SUMS (batch_impl.h) with three more per-lane
 * accumulators: the smallest and largest t^2 + F^2 and the largest
 * h^-(p+2) over the parts.  A point outside the range of the top of the
 * file gets S = NaN, which accept() (batch.c) sends to the per-point path;
 * checking once per point rather than per part keeps selects out of the
 * part loop, and asks only that the largest h^-(p+2) be normal (the
 * parts that dominate V), not every one.  smooth_a runs one part ahead:
 * the lanes keep part k's first-stage values while part k + 1's are
 * computed. */
DFL_INLINE void sums_sm_p(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out,
                          const int p, const int dim, const int strip)
{
    const size_t n = b->n, w = (size_t)dim + 1;
    for (size_t i0 = 0; i0 < m; i0 += LANES) {
        const size_t c = m - i0 < LANES ? m - i0 : LANES;
        double X[LANES], Y[LANES], Z[LANES] = {0}, S[LANES] = {0}, Vx[LANES] = {0},
               Vy[LANES] = {0}, Vz[LANES] = {0}, lo[LANES], hi[LANES], qh[LANES];
        double F1[LANES], F2[LANES], FF[LANES], KT[LANES], UX[LANES], UY[LANES], UZ[LANES],
            R2[LANES], RR[LANES], G[LANES];
        for (size_t l = 0; l < LANES; l++) {
            const size_t i = i0 + (l < c ? l : c - 1);
            X[l] = pts[(size_t)dim * i];
            Y[l] = pts[(size_t)dim * i + 1];
            if (dim == 3) Z[l] = pts[3 * i + 2];
            lo[l] = INFINITY, hi[l] = 0.0, qh[l] = 0.0;
        }
#pragma omp simd
        for (int l = 0; l < LANES; l++)
            smooth_a(X[l], Y[l], Z[l], b, 0, dim, strip, &F1[l], &F2[l], &FF[l], &KT[l], &UX[l],
                     &UY[l], &UZ[l], &R2[l], &RR[l], &G[l]);
        for (size_t k = 0; k + 1 < n; k++) {
#pragma omp simd
            for (int l = 0; l < LANES; l++) {
                const double f1 = F1[l], f2 = F2[l], F = FF[l], kt = KT[l], ux = UX[l],
                             uy = UY[l], uz = UZ[l], r2 = R2[l], rr = RR[l], g = G[l];
                smooth_a(X[l], Y[l], Z[l], b, k + 1, dim, strip, &F1[l], &F2[l], &FF[l], &KT[l],
                         &UX[l], &UY[l], &UZ[l], &R2[l], &RR[l], &G[l]);
                smooth_b(b, k, p, dim, f1, f2, F, kt, ux, uy, uz, r2, rr, g, &S[l], &Vx[l],
                         &Vy[l], &Vz[l], &lo[l], &hi[l], &qh[l]);
            }
        }
#pragma omp simd
        for (int l = 0; l < LANES; l++)
            smooth_b(b, n - 1, p, dim, F1[l], F2[l], FF[l], KT[l], UX[l], UY[l], UZ[l], R2[l],
                     RR[l], G[l], &S[l], &Vx[l], &Vy[l], &Vz[l], &lo[l], &hi[l], &qh[l]);
        for (size_t l = 0; l < c; l++) {
            const int ok = lo[l] >= SM_LO && hi[l] <= SM_HI && qh[l] >= SM_LO;
            out[w * (i0 + l)] = ok ? S[l] : NAN;
            out[w * (i0 + l) + 1] = Vx[l];
            out[w * (i0 + l) + 2] = Vy[l];
            if (dim == 3) out[w * (i0 + l) + 3] = Vz[l];
        }
    }
}

#define SM_CASES(dim, strip)                                      \
    switch (b->p) {                                               \
    case 1: sums_sm_p(b, m, pts, out, 1, dim, strip); break;      \
    case 2: sums_sm_p(b, m, pts, out, 2, dim, strip); break;      \
    case 3: sums_sm_p(b, m, pts, out, 3, dim, strip); break;      \
    case 4: sums_sm_p(b, m, pts, out, 4, dim, strip); break;      \
    case 7: sums_sm_p(b, m, pts, out, 7, dim, strip); break;      \
    case 12: sums_sm_p(b, m, pts, out, 12, dim, strip); break;    \
    default: sums_sm_p(b, m, pts, out, b->p, dim, strip); break;  \
    }

DFL_INLINE void sums_disk_sm2_body(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    SM_CASES(2, 0)
}
DFL_ISA_KERNEL(sums_disk_sm2, (const dfl_rfunc_batch *b, size_t m, const double *pts, double *out), (b, m, pts, out))

DFL_INLINE void sums_strip_sm2_body(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    SM_CASES(2, 1)
}
DFL_ISA_KERNEL(sums_strip_sm2, (const dfl_rfunc_batch *b, size_t m, const double *pts, double *out), (b, m, pts, out))

DFL_INLINE void sums_disk_sm3_body(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    SM_CASES(3, 0)
}
DFL_ISA_KERNEL(sums_disk_sm3, (const dfl_rfunc_batch *b, size_t m, const double *pts, double *out), (b, m, pts, out))

DFL_INLINE void sums_strip_sm3_body(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    SM_CASES(3, 1)
}
DFL_ISA_KERNEL(sums_strip_sm3, (const dfl_rfunc_batch *b, size_t m, const double *pts, double *out), (b, m, pts, out))

/* Takes R-equivalence of segments that all have the same eq. 5 trim. */
dfl_status dfl_rfunc_batch_try_smooth(const dfl_rfunc_batch_desc *d, dfl_rfunc_batch **out,
                                      dfl_err *err)
{
    *out = NULL;
    if (d->join != DFL_RFUNC_REQUIV || d->n < 2 || d->parts[0].kind != DFL_RFUNC_PART_SEGMENT)
        return DFL_OK;
    const dfl_rfunc_trim trim = d->parts[0].u.seg.trim;
    if (!dfl_rfunc_trim_smooth(trim)) return DFL_OK;
    for (size_t k = 0; k < d->n; k++)
        if (d->parts[k].kind != DFL_RFUNC_PART_SEGMENT || d->parts[k].u.seg.trim != trim)
            return DFL_OK;
    dfl_field ref = {0};
    dfl_rfunc_batch *b;
    dfl_status st = dfl_rfunc_batch_alloc(d->dim, d->p, d->n, &ref, &b, err);
    if (st != DFL_OK) return st;
    b->fb = d->slow;
    b->strip = dfl_rfunc_trim_strip(trim);
    for (size_t k = 0; k < d->n; k++) {
        /* the library's own frames (segment.c): the same f and t bitwise
         * up to the reciprocal of d */
        const dfl_rfunc_seg *sg = &d->parts[k].u.seg;
        dfl_rfunc_batch_put_seg(b, k, sg);
        b->hid[k] = -1.0 / sg->d; /* this kernel's own scale of the trim */
        b->hid2[k] = 0.0;
    }
    if (d->dim == 3) b->sums_fn = b->strip ? sums_strip_sm3 : sums_disk_sm3;
    else b->sums_fn = b->strip ? sums_strip_sm2 : sums_disk_sm2;
    *out = b;
    return DFL_OK;
}
