/* The segment kernels: 2D disk (the reference kernel, see batch.c), 2D
 * strip, 3D disk and strip trims of eq. 4, R-equivalence. */
#include <math.h>
#include <stdlib.h>

#include "rfunc/batch_impl.h"
#include "rfunc/rfield.h"

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

/* The strip trim of eq. 4 (rfunc/segment.h) and the power terms, for a
 * carrier F2 = f^2 (3D: s1^2 + s2^2): p1 = (x - a).e, p2 = (b - x).e,
 * r = |(p1, p2)|, t = 2 p1 p2 / (p1 + p2 + r) (trim.h's conjunction
 * without cancellation), mt = max(-t, 0), grad t = (p2 - p1)/r e.
 *
 * Why it looks like this.  Newton steps for 1/sqrt (batch.c) cost 13
 * multiplications, a third of the kernel's, on the multiply pipes while
 * the divider idles; so r comes from sqrt() (vectorized: this file is
 * compiled with -fno-math-errno, see the Makefile), and 1/r and 1/h^2
 * share one division, R = 1/(r h^2): 1/r = h^2 R, 1/h^2 = r R (odd p:
 * R = 1/(r h), 1/h = r R).  r, t and mt are the per-point path's own
 * expressions (the same roundings; merging t's division into R as well
 * rounds mt differently and made u exceed min h by an ulp at a node of
 * tests/e2e/bs04/test_bs04_fields.c, which checks u <= min h).
 * r h^2 below 1e-300 (a point on the segment, h^2 near the double range)
 * poisons *S with NaN so that the point falls back.
 *
 * The term runs in two stages: strip_t (r and t: a root, then a division
 * that waits on it) and strip_term (mt, h^2, then the division R that
 * waits on t).  Per part that is a root and two divisions in series, ~80
 * cycles of latency against ~11 cycles of divider work per vector, more
 * than the out-of-order window covers; so the lane loops (strip_lanes
 * below) run strip_t one part ahead of strip_term: each stage's chain
 * then overlaps the other's, with the same operations per value. */
DFL_INLINE double strip_t(double p1, double p2, double *r)
{
    *r = sqrt(p1 * p1 + p2 * p2);                 /* 2, 1; sqrt */
    const double P = p1 * p2;                     /* 1, 0 */
    return (P + P) / ((p1 + p2) + *r);            /* 0, 3; div */
}

/* Adds h^-p to *S; returns q = h^-(p+2) (the factor of the carrier's
 * f grad f) and *qe (the factor of -e), from strip_t's r and t.  Counts
 * (mul, add; div, sqrt). */
DFL_INLINE double strip_term(double F2, double p1, double p2, double r, double t, int p,
                             double *S, double *qe)
{
    const double mt = 0.5 * (fabs(t) - t);        /* 1, 1: max(-t, 0) exactly */
    const double h2 = F2 + mt * mt;               /* 1, 1 */
    double rr, r2i, w;
    if (p & 1) {
        const double h = sqrt(h2);                /* odd p: sqrt */
        const double rh = r * h;
        const double R = 1.0 / rh;                /* div */
        *S += rh >= 1e-300 ? 0.0 : NAN;
        const double hm1 = r * R;                 /* 1/h */
        rr = h * R;
        r2i = hm1 * hm1;
        w = p == 1 ? hm1 : hm1 * ipow_sq(r2i, p / 2);
    } else {
        const double rh2 = r * h2;                /* 1, 0 */
        const double R = 1.0 / rh2;               /* div */
        *S += rh2 >= 1e-300 ? 0.0 : NAN;          /* 0, 1; compare */
        rr = h2 * R;                              /* 1, 0 */
        r2i = r * R;                              /* 1, 0 */
        w = ipow_sq(r2i, p / 2);                  /* muls of ipow_sq(p/2) */
    }
    const double q = w * r2i;                     /* 1, 0 */
    *S += w;                                      /* 0, 1 */
    *qe = q * (mt * (p2 - p1) * rr);              /* 3, 1 */
    return q;
}

/* 2D segment with the strip trim, first stage: the carrier f and the
 * trim's p1, p2, r, t of part k at (x, y). */
DFL_INLINE void strip2_a(double x, double y, const dfl_rfunc_batch *b, size_t k, double *f,
                         double *p1, double *p2, double *r, double *t)
{
    const double wx = x - b->ax[k], wy = y - b->ay[k];                   /* 0, 2 */
    const double vx = x - b->bx[k], vy = y - b->by[k];                   /* 0, 2 */
    *f = wx * b->nx[k] + wy * b->ny[k];                                  /* 2, 1 */
    *p1 = wx * b->ex[k] + wy * b->ey[k];                                 /* 2, 1 */
    *p2 = -(vx * b->ex[k] + vy * b->ey[k]);                              /* 2, 1 */
    *t = strip_t(*p1, *p2, r);
}

/* Second stage: adds part k's terms to *S, *Vx, *Vy. */
DFL_INLINE void strip2_b(const dfl_rfunc_batch *b, size_t k, int p, double f, double p1,
                         double p2, double r, double t, double *S, double *Vx, double *Vy)
{
    double qe;
    const double q = strip_term(f * f, p1, p2, r, t, p, S, &qe);         /* 1 + above */
    const double qf = q * f;                                             /* 1, 0 */
    *Vx += qf * b->nx[k] - qe * b->ex[k];                                /* 2, 2 */
    *Vy += qf * b->ny[k] - qe * b->ey[k];                                /* 2, 2 */
}

/* 3D segment (space curves): f^2 = s1^2 + s2^2 with the two normals, the
 * sphere (strip = 0) or slab (strip = 1) trim. */
DFL_INLINE void seg_term3(double x, double y, double z, const dfl_rfunc_batch *b, size_t k,
                          int p, double *S, double *Vx, double *Vy, double *Vz)
{
    const double wx = x - b->ax[k], wy = y - b->ay[k], wz = z - b->az[k];
    const double vx = x - b->bx[k], vy = y - b->by[k], vz = z - b->bz[k];
    const double s1 = wx * b->nx[k] + wy * b->ny[k] + wz * b->nz[k];
    const double s2 = wx * b->mx[k] + wy * b->my[k] + wz * b->mz[k];
    double gx = s1 * b->nx[k] + s2 * b->mx[k], gy = s1 * b->ny[k] + s2 * b->my[k],
           gz = s1 * b->nz[k] + s2 * b->mz[k];
    const double m2 = wx * vx + wy * vy + wz * vz;
    const double mp = m2 + fabs(m2);
    const double mt = mp * b->hid[k];
    const double mi = mp * b->hid2[k];
    gx += mi * (wx + vx);
    gy += mi * (wy + vy);
    gz += mi * (wz + vz);
    const double q = pow_term(s1 * s1 + s2 * s2 + mt * mt, p, S);
    *Vx += q * gx;
    *Vy += q * gy;
    *Vz += q * gz;
}

/* 3D segment with the slab trim, first stage: the carrier's s1, s2 and
 * the trim's p1, p2, r, t of part k at (x, y, z). */
DFL_INLINE void strip3_a(double x, double y, double z, const dfl_rfunc_batch *b, size_t k,
                         double *s1, double *s2, double *p1, double *p2, double *r, double *t)
{
    const double wx = x - b->ax[k], wy = y - b->ay[k], wz = z - b->az[k];
    const double vx = x - b->bx[k], vy = y - b->by[k], vz = z - b->bz[k];
    *s1 = wx * b->nx[k] + wy * b->ny[k] + wz * b->nz[k];
    *s2 = wx * b->mx[k] + wy * b->my[k] + wz * b->mz[k];
    *p1 = wx * b->ex[k] + wy * b->ey[k] + wz * b->ez[k];
    *p2 = -(vx * b->ex[k] + vy * b->ey[k] + vz * b->ez[k]);
    *t = strip_t(*p1, *p2, r);
}

/* Second stage: adds part k's terms to *S, *Vx, *Vy, *Vz. */
DFL_INLINE void strip3_b(const dfl_rfunc_batch *b, size_t k, int p, double s1, double s2,
                         double p1, double p2, double r, double t, double *S, double *Vx,
                         double *Vy, double *Vz)
{
    const double gx = s1 * b->nx[k] + s2 * b->mx[k], gy = s1 * b->ny[k] + s2 * b->my[k],
                 gz = s1 * b->nz[k] + s2 * b->mz[k];
    double qe;
    const double q = strip_term(s1 * s1 + s2 * s2, p1, p2, r, t, p, S, &qe);
    *Vx += q * gx - qe * b->ex[k];
    *Vy += q * gy - qe * b->ey[k];
    *Vz += q * gz - qe * b->ez[k];
}

/* The strip kernels' lane loop: DFL_BATCH_SUMS (batch_impl.h) with the
 * first stage one part ahead (see strip_term).  Lane l keeps part k's
 * first-stage values (C1 = f or s1, C2 = s2, P1, P2, R, T) while the loop
 * computes part k + 1's and adds part k's terms, so each point still sums
 * its parts in order with the same operations. */
DFL_INLINE void strip_lanes(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out,
                            const int p, const int dim)
{
    const size_t n = b->n, w = (size_t)dim + 1;
    for (size_t i0 = 0; i0 < m; i0 += LANES) {
        const size_t c = m - i0 < LANES ? m - i0 : LANES;
        double X[LANES], Y[LANES], Z[LANES] = {0}, S[LANES] = {0}, Vx[LANES] = {0},
               Vy[LANES] = {0}, Vz[LANES] = {0};
        double C1[LANES], C2[LANES] = {0}, P1[LANES], P2[LANES], R[LANES], T[LANES];
        /* a short last block repeats its last point in the spare lanes */
        for (size_t l = 0; l < LANES; l++) {
            const size_t i = i0 + (l < c ? l : c - 1);
            X[l] = pts[(size_t)dim * i];
            Y[l] = pts[(size_t)dim * i + 1];
            if (dim == 3) Z[l] = pts[3 * i + 2];
        }
#pragma omp simd
        for (int l = 0; l < LANES; l++) {
            if (dim == 2) strip2_a(X[l], Y[l], b, 0, &C1[l], &P1[l], &P2[l], &R[l], &T[l]);
            else strip3_a(X[l], Y[l], Z[l], b, 0, &C1[l], &C2[l], &P1[l], &P2[l], &R[l], &T[l]);
        }
        for (size_t k = 0; k + 1 < n; k++) {
#pragma omp simd
            for (int l = 0; l < LANES; l++) {
                const double c1 = C1[l], c2 = C2[l], p1 = P1[l], p2 = P2[l], r = R[l], t = T[l];
                if (dim == 2) {
                    strip2_a(X[l], Y[l], b, k + 1, &C1[l], &P1[l], &P2[l], &R[l], &T[l]);
                    strip2_b(b, k, p, c1, p1, p2, r, t, &S[l], &Vx[l], &Vy[l]);
                } else {
                    strip3_a(X[l], Y[l], Z[l], b, k + 1, &C1[l], &C2[l], &P1[l], &P2[l], &R[l],
                             &T[l]);
                    strip3_b(b, k, p, c1, c2, p1, p2, r, t, &S[l], &Vx[l], &Vy[l], &Vz[l]);
                }
            }
        }
#pragma omp simd
        for (int l = 0; l < LANES; l++) {
            if (dim == 2)
                strip2_b(b, n - 1, p, C1[l], P1[l], P2[l], R[l], T[l], &S[l], &Vx[l], &Vy[l]);
            else
                strip3_b(b, n - 1, p, C1[l], C2[l], P1[l], P2[l], R[l], T[l], &S[l], &Vx[l],
                         &Vy[l], &Vz[l]);
        }
        for (size_t l = 0; l < c; l++) {
            out[w * (i0 + l)] = S[l];
            out[w * (i0 + l) + 1] = Vx[l];
            out[w * (i0 + l) + 2] = Vy[l];
            if (dim == 3) out[w * (i0 + l) + 3] = Vz[l];
        }
    }
}

/* The strip and 3D kernels' sums: 1 + dim doubles per point (S, V). */
DFL_INLINE void sums_gen_p(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out,
                           const int p, const int dim, const int strip)
{
    if (strip) strip_lanes(b, m, pts, out, p, dim);
    else
        DFL_BATCH_SUMS(b, m, pts, out, 3,
                       seg_term3(X[l], Y[l], Z[l], b, k, p, &S[l], &Vx[l], &Vy[l], &Vz[l]));
}

DFL_INLINE void sums_strip2_body(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    DFL_GEN_CASES(2, 1)
}
DFL_ISA_KERNEL(sums_strip2, (const dfl_rfunc_batch *b, size_t m, const double *pts, double *out), (b, m, pts, out))

DFL_INLINE void sums_disk3_body(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    DFL_GEN_CASES(3, 0)
}
DFL_ISA_KERNEL(sums_disk3, (const dfl_rfunc_batch *b, size_t m, const double *pts, double *out), (b, m, pts, out))

DFL_INLINE void sums_strip3_body(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    DFL_GEN_CASES(3, 1)
}
DFL_ISA_KERNEL(sums_strip3, (const dfl_rfunc_batch *b, size_t m, const double *pts, double *out), (b, m, pts, out))

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

DFL_INLINE void sums_disk2_body(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
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
DFL_ISA_KERNEL(sums_disk2, (const dfl_rfunc_batch *b, size_t m, const double *pts, double *out), (b, m, pts, out))

void dfl_rfunc_batch_sums_seg(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    if (b->dim == 3) {
        if (b->strip) sums_strip3(b, m, pts, out);
        else sums_disk3(b, m, pts, out);
    } else if (b->strip) {
        sums_strip2(b, m, pts, out);
    } else {
        sums_disk2(b, m, pts, out);
    }
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
    if ((st = dfl_rfunc_batch_alloc(dim, p, ns, &ref, &b, err)) != DFL_OK) return st;
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
            dfl_rfunc_batch_put_seg(b, k, &sg);
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

