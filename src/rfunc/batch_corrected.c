/* Batched kernel for the corrected join (eq. 20, rfunc/join.h) of segment
 * parts with the disk or strip trim of eq. 4, 2D and 3D, in both forms:
 *
 *   guarded (dflab's):  S = sum_i h_i^-p - sum_v qt_v^-p,
 *                       qt_v = max(q_v, h_lo, h_hi), q_v = |x - v|,
 *                       u = max(S, (2 h_min)^-p)^(-1/p);
 *   eq20 (bs04's):      S = sum_i h_i^-p - sum_v q_v^-p,
 *                       u = S^(-1/p) where S > 0, NaN (value, gradient)
 *                       where S <= 0;
 *   grad u = u^(p+1) (sum_i h_i^-(p+2) h_i grad h_i
 *                     - sum_v qt_v^-(p+2) qt_v grad qt_v).
 *
 * Which fields: every part a segment with one trim (disk or strip); the
 * vertices (sorted by hi, as rfield.c visits them right after part hi) in
 * any number.  eq20 reads no adjacent part.  The guard needs h_lo beside
 * h_hi: lo = hi - 1 (the previous part, the common layout of
 * dfl_rfield_add_polyline: vertex i between segments i-1 and i) or one of
 * at most NSLOT earlier parts whose h the lanes keep (the closing vertex
 * of a closed polyline: lo = its first segment).  Other layouts stay on
 * the per-point path (try_corrected takes no field).
 *
 * Lanes and arithmetic as in batch.c: lanes are points; no branch, root or
 * libm call per part; the guard's max() and the selection of its gradient
 * (q grad q = x - v, or h grad h of part lo or hi, in the order and with
 * the strict > of dfl_rfunc_guard) are blends.  The sums are unscaled; per
 * point (once, not per part) a scalar epilogue reads them.
 *
 * Fallback (b->fb, the per-point path), per point:
 *  - the sums' range: A = sum of |terms| outside [1e-280, 1e280], V not
 *    finite, u^(p+1) above 1e280 (V's terms, ~u^-(p+1), would underflow), the smallest h^2 (eq20: also q^2) below DBL_MIN (on or within
 *    1e-154 of a part or vertex: rsqrt_newton's estimate is invalid there,
 *    and u = 0 on the part);
 *  - guard ties: two of q^2, h_lo^2, h_hi^2 within TIE relative of their
 *    maximum (the per-point path's choice of the gradient depends on
 *    rounding there: the guard is not differentiable on h = q, and
 *    h_lo = h_hi on the bisector of a symmetric vertex);
 *  - cancellation: |S| <= A (p + 2)/(1024 p) (A/|S| >= 341 at p = 1, 512
 *    at p = 2, 796 at p = 7).  The two paths' S differ by a few (p + 2) ulp
 *    of A (each term carries ~p + 2 roundings; the per-point path sums
 *    the parts' and the vertices' terms apart and subtracts at the end),
 *    so u's relative deviation is ~(p + 2)/p eps A/|S|, below 1e-12 by a
 *    margin of 2-4 where the kernel keeps the point (CANCEL_R); the sign
 *    of S, which decides eq20's NaN, is certain there.  eq20 with S below
 *    minus that bound is NaN without fallback;
 *  - guarded floor: S <= (2 h_min)^-p (1 + TIE) (the floor is active or
 *    nearly: rare, closed polylines only, e.g. the centre of a fine
 *    polygon; its gradient 2 grad h_min is the per-point path's).
 *
 * Operation counts per part and lane (p = 2, 2D disk, guarded): segment
 * as batch_seg.c's seg_term (21 mul, 1 div, 17 add/sub), vertex: q^2 and
 * x - v (2 mul, 3 add), max of three with gradient blends (2 cmp, 6
 * blends), ties (1 mul, 4 cmp, 4 adds/ands), power and sums (3 mul, 1 div,
 * 5 add), h_min (1 cmp/blend), plus storing the part's h^2 and h grad h
 * for the vertex loop: ~26 mul, 2 div, ~45 other, 2.5x the disk2 kernel
 * (eq20: ~25 mul, 2 div, ~25 other, fused in one loop).  Measured on the
 * bench curve (1500 segments, one thread, loaded machine): 9.8 cycles per
 * part guarded, 6.0 eq20, beside 3.1-3.6 for the plain disk2 kernel.
 */
#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "rfunc/batch_impl.h"

/* Earlier parts whose h the lanes keep for the guards (closing vertices). */
#define NSLOT 4
/* Guard and floor ties (relative). */
#define TIE 1e-12
/* Cancellation of S against the sum of |terms| (header): |S| > A (p + 2)
 * / (CANCEL_R p), the per-point path's deviation being ~(p + 2)/p eps A/|S|
 * in u (measured on the bench's 1500-segment closed curve, where A/|S| is
 * 64..512 on most nodes: 4.4e-13 at p = 1, 2.4e-13 at p = 2). */
#define CANCEL_R 1024.0
/* Per point out of the lane loop: S, A, Hm, T, V[3]. */
#define NOUT 7

enum { SRC_PREV = -1 };

typedef struct corr_kd {
    int eq20;
    int strip;
    const size_t *vstart; /* n + 1 offsets into the vertex arrays by hi (copy) */
    size_t nv;
    double *vx, *vy, *vz; /* vertex positions */
    int *src;             /* SRC_PREV, or the slot holding part lo */
    int *save;            /* per part: slot to keep its h in, or -1 */
    size_t *mem_vs;
} corr_kd;

static void kd_free(void *p)
{
    corr_kd *kd = p;
    if (!kd) return;
    free(kd->vx);
    free(kd->src);
    free(kd->save);
    free(kd->mem_vs);
    free(kd);
}

/* Segment k at x: h^2 and h grad h (eq. 4; batch_seg.c's seg_term,
 * strip_mt and seg_term3 with the sums left to the caller). */
DFL_INLINE double seg_h2(const dfl_rfunc_batch *b, size_t k, double x, double y, double z,
                         const int dim, const int strip, double *gx, double *gy, double *gz)
{
    const double wx = x - b->ax[k], wy = y - b->ay[k], wz = dim == 3 ? z - b->az[k] : 0.0;
    const double vx = x - b->bx[k], vy = y - b->by[k], vz = dim == 3 ? z - b->bz[k] : 0.0;
    double f2, hx, hy, hz = 0.0, mt;
    if (dim == 2) {
        const double f = wx * b->nx[k] + wy * b->ny[k];
        f2 = f * f;
        hx = f * b->nx[k];
        hy = f * b->ny[k];
    } else {
        const double s1 = wx * b->nx[k] + wy * b->ny[k] + wz * b->nz[k];
        const double s2 = wx * b->mx[k] + wy * b->my[k] + wz * b->mz[k];
        f2 = s1 * s1 + s2 * s2;
        hx = s1 * b->nx[k] + s2 * b->mx[k];
        hy = s1 * b->ny[k] + s2 * b->my[k];
        hz = s1 * b->nz[k] + s2 * b->mz[k];
    }
    if (strip) {
        /* t = 2 p1 p2 / (p1 + p2 + |(p1, p2)|), grad t = (p2 - p1)/r e */
        const double p1 = wx * b->ex[k] + wy * b->ey[k] + (dim == 3 ? wz * b->ez[k] : 0.0);
        const double p2 = -(vx * b->ex[k] + vy * b->ey[k] + (dim == 3 ? vz * b->ez[k] : 0.0));
        const double r2 = p1 * p1 + p2 * p2;
        const double rr = rsqrt_newton(r2);
        const double t = 2.0 * p1 * p2 / (p1 + p2 + r2 * rr);
        mt = 0.5 * (fabs(t) - t);
        const double kk = mt * (p2 - p1) * rr;
        hx -= kk * b->ex[k];
        hy -= kk * b->ey[k];
        if (dim == 3) hz -= kk * b->ez[k];
    } else {
        const double m2 = wx * vx + wy * vy + (dim == 3 ? wz * vz : 0.0);
        const double mp = m2 + fabs(m2);
        mt = mp * b->hid[k];
        const double mi = mp * b->hid2[k];
        hx += mi * (wx + vx);
        hy += mi * (wy + vy);
        if (dim == 3) hz += mi * (wz + vz);
    }
    *gx = hx;
    *gy = hy;
    *gz = hz;
    return f2 + mt * mt;
}

/* Adds sign x^-p to *S, x^-p to *A and sign x^-(p+2) (x grad x) to V. */
DFL_INLINE void add_term(double x2, double gx, double gy, double gz, int p, int dim,
                         double sign, double *S, double *A, double *Vx, double *Vy, double *Vz)
{
    double w = 0.0;
    const double q = pow_term(x2, p, &w);
    *S += sign * w;
    *A += w;
    *Vx += sign * q * gx;
    *Vy += sign * q * gy;
    if (dim == 3) *Vz += sign * q * gz;
}

/* The guard (dfl_rfunc_guard: q, then lo, then hi, each taken when
 * strictly larger) on squares, with its gradient x grad x; *tie += 1 when
 * two of the three are within TIE of the maximum. */
DFL_INLINE double guard2(double q2, double wx, double wy, double wz, double hl, double lx,
                         double ly, double lz, double hh, double cx, double cy, double cz,
                         int dim, double *gx, double *gy, double *gz, double *tie)
{
    const double M1 = hl > q2 ? hl : q2;
    double ax = hl > q2 ? lx : wx, ay = hl > q2 ? ly : wy;
    double az = dim == 3 ? (hl > q2 ? lz : wz) : 0.0;
    const double M = hh > M1 ? hh : M1;
    *gx = hh > M1 ? cx : ax;
    *gy = hh > M1 ? cy : ay;
    *gz = dim == 3 ? (hh > M1 ? cz : az) : 0.0;
    const double Mt = M * (1.0 - TIE);
    const double c = (q2 > Mt ? 1.0 : 0.0) + (hl > Mt ? 1.0 : 0.0) + (hh > Mt ? 1.0 : 0.0);
    *tie += c > 1.5 ? 1.0 : 0.0;
    return M;
}

/* Vertex v after part hi (h^2 hh, h grad h c), with lo (hl, l): its
 * term into the sums of one lane. */
DFL_INLINE void vert_term(double x, double y, double z, double vx, double vy, double vz,
                          double hl, double lx, double ly, double lz, double hh, double cx,
                          double cy, double cz, int p, int dim, int eq20, double *S, double *A,
                          double *Vx, double *Vy, double *Vz, double *Hm, double *T)
{
    const double wx = x - vx, wy = y - vy, wz = dim == 3 ? z - vz : 0.0;
    const double q2 = wx * wx + wy * wy + (dim == 3 ? wz * wz : 0.0);
    if (eq20) {
        *Hm = q2 < *Hm ? q2 : *Hm;
        add_term(q2, wx, wy, wz, p, dim, -1.0, S, A, Vx, Vy, Vz);
        return;
    }
    double gx, gy, gz;
    const double M = guard2(q2, wx, wy, wz, hl, lx, ly, lz, hh, cx, cy, cz, dim, &gx, &gy, &gz, T);
    add_term(M, gx, gy, gz, p, dim, -1.0, S, A, Vx, Vy, Vz);
}

/* The lanes of m <= LANES points through every part and vertex; NOUT
 * doubles per point into out.  Per lane: the sums, the smallest h^2, the
 * tie count, and h^2, h grad h of the current (C), previous (P) and kept
 * (slot) parts. */
DFL_INLINE void block_p(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out,
                        const int p, const int dim, const int strip, const int eq20)
{
    const corr_kd *kd = b->kd;
    double X[LANES], Y[LANES], Z[LANES], S[LANES], A[LANES], Vx[LANES], Vy[LANES], Vz[LANES];
    double Hm[LANES], T[LANES], Hc[LANES], Cx[LANES], Cy[LANES], Cz[LANES];
    double Hp[LANES], Px[LANES], Py[LANES], Pz[LANES];
    double Hs[NSLOT][LANES], Sx[NSLOT][LANES], Sy[NSLOT][LANES], Sz[NSLOT][LANES];
    for (int l = 0; l < LANES; l++) {
        const size_t i = (size_t)l < m ? (size_t)l : m - 1;
        X[l] = pts[(size_t)dim * i];
        Y[l] = pts[(size_t)dim * i + 1];
        Z[l] = dim == 3 ? pts[(size_t)dim * i + 2] : 0.0;
        S[l] = A[l] = Vx[l] = Vy[l] = Vz[l] = T[l] = 0.0;
        Hm[l] = INFINITY;
        Hp[l] = Px[l] = Py[l] = Pz[l] = 0.0;
        Hc[l] = Cx[l] = Cy[l] = Cz[l] = 0.0;
    }
    for (size_t k = 0; k < b->n; k++) {
        const size_t v0 = kd->vstart[k], v1 = kd->vstart[k + 1];
        if (eq20 && v1 == v0 + 1) {
            /* eq20's common case: one vertex, fused (gcc does not if-convert
             * the guard's blends beside two power terms in one loop: the
             * guarded form runs the part and vertex loops apart) */
            const double vx = kd->vx[v0], vy = kd->vy[v0], vz = kd->vz[v0];
#pragma omp simd
            for (int l = 0; l < LANES; l++) {
                double gx, gy, gz;
                const double h2 = seg_h2(b, k, X[l], Y[l], Z[l], dim, strip, &gx, &gy, &gz);
                add_term(h2, gx, gy, gz, p, dim, 1.0, &S[l], &A[l], &Vx[l], &Vy[l], &Vz[l]);
                Hm[l] = h2 < Hm[l] ? h2 : Hm[l];
                vert_term(X[l], Y[l], Z[l], vx, vy, vz, 0.0, 0.0, 0.0, 0.0, h2, gx, gy, gz, p,
                          dim, 1, &S[l], &A[l], &Vx[l], &Vy[l], &Vz[l], &Hm[l], &T[l]);
            }
            continue;
        }
#pragma omp simd
        for (int l = 0; l < LANES; l++) {
            double gx, gy, gz;
            const double h2 = seg_h2(b, k, X[l], Y[l], Z[l], dim, strip, &gx, &gy, &gz);
            add_term(h2, gx, gy, gz, p, dim, 1.0, &S[l], &A[l], &Vx[l], &Vy[l], &Vz[l]);
            Hm[l] = h2 < Hm[l] ? h2 : Hm[l];
            Hc[l] = h2;
            Cx[l] = gx;
            Cy[l] = gy;
            Cz[l] = gz;
        }
        for (size_t iv = v0; iv < v1; iv++) {
            const double vx = kd->vx[iv], vy = kd->vy[iv], vz = kd->vz[iv];
            const int s = eq20 ? SRC_PREV : kd->src[iv];
            const double *H = s == SRC_PREV ? Hp : Hs[s];
            const double *GX = s == SRC_PREV ? Px : Sx[s];
            const double *GY = s == SRC_PREV ? Py : Sy[s];
            const double *GZ = s == SRC_PREV ? Pz : Sz[s];
            for (int l = 0; l < LANES; l++)
                vert_term(X[l], Y[l], Z[l], vx, vy, vz, H[l], GX[l], GY[l], GZ[l], Hc[l], Cx[l],
                          Cy[l], Cz[l], p, dim, eq20, &S[l], &A[l], &Vx[l], &Vy[l], &Vz[l],
                          &Hm[l], &T[l]);
        }
        memcpy(Hp, Hc, sizeof Hp);
        memcpy(Px, Cx, sizeof Px);
        memcpy(Py, Cy, sizeof Py);
        memcpy(Pz, Cz, sizeof Pz);
        const int sv = eq20 ? -1 : kd->save[k];
        if (sv >= 0) {
            memcpy(Hs[sv], Hc, sizeof Hc);
            memcpy(Sx[sv], Cx, sizeof Cx);
            memcpy(Sy[sv], Cy, sizeof Cy);
            memcpy(Sz[sv], Cz, sizeof Cz);
        }
    }
    for (size_t l = 0; l < m; l++) {
        double *o = out + NOUT * l;
        o[0] = S[l], o[1] = A[l], o[2] = Hm[l], o[3] = T[l];
        o[4] = Vx[l], o[5] = Vy[l], o[6] = Vz[l];
    }
}

#define CORR_CASES(dim, strip, eq20)                                   \
    switch (b->p) {                                                    \
    case 1: block_p(b, m, pts, out, 1, dim, strip, eq20); break;       \
    case 2: block_p(b, m, pts, out, 2, dim, strip, eq20); break;       \
    case 3: block_p(b, m, pts, out, 3, dim, strip, eq20); break;       \
    case 4: block_p(b, m, pts, out, 4, dim, strip, eq20); break;       \
    case 7: block_p(b, m, pts, out, 7, dim, strip, eq20); break;       \
    case 12: block_p(b, m, pts, out, 12, dim, strip, eq20); break;     \
    default: block_p(b, m, pts, out, b->p, dim, strip, eq20); break;   \
    }

#define CORR_FN(name, dim, strip, eq20)                                                     \
    DFL_INLINE void name##_body(const dfl_rfunc_batch *b, size_t m, const double *pts,      \
                                double *out)                                                \
    {                                                                                       \
        CORR_CASES(dim, strip, eq20)                                                        \
    }                                                                                       \
    DFL_ISA_KERNEL(name, (const dfl_rfunc_batch *b, size_t m, const double *pts, double *out), \
                   (b, m, pts, out))
CORR_FN(blk_d2g, 2, 0, 0)
CORR_FN(blk_d2e, 2, 0, 1)
CORR_FN(blk_s2g, 2, 1, 0)
CORR_FN(blk_s2e, 2, 1, 1)
CORR_FN(blk_d3g, 3, 0, 0)
CORR_FN(blk_d3e, 3, 0, 1)
CORR_FN(blk_s3g, 3, 1, 0)
CORR_FN(blk_s3e, 3, 1, 1)

typedef void (*blk_fn)(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out);

static blk_fn block_of(const dfl_rfunc_batch *b)
{
    static const blk_fn fns[2][2][2] = {{{blk_d2g, blk_d2e}, {blk_s2g, blk_s2e}},
                                        {{blk_d3g, blk_d3e}, {blk_s3g, blk_s3e}}};
    const corr_kd *kd = b->kd;
    return fns[b->dim == 3][kd->strip][kd->eq20];
}

/* y^(-1/p) for y > 0 (join.c's inv_root). */
static double inv_root(double y, int p)
{
    return p == 1 ? 1.0 / y : p == 2 ? 1.0 / sqrt(y) : pow(y, -1.0 / p);
}

/* u and grad u from one point's sums o (NOUT doubles): 1 when computed
 * (eq20's undefined points included: NaN), 0 when the point falls back. */
static int finish(int p, int dim, int eq20, const double *o, double *u, double *g)
{
    const double S = o[0], A = o[1], Hm = o[2];
    if (!(A >= 1e-280 && A <= 1e280) || !(Hm >= DBL_MIN) || o[3] != 0.0) return 0;
    for (int j = 0; j < dim; j++)
        if (!isfinite(o[4 + j])) return 0;
    if (!(fabs(S) * (CANCEL_R * p) > A * (p + 2))) return 0;
    if (S < 0.0) {
        if (!eq20) return 0;
        *u = NAN;
        for (int j = 0; j < dim; j++) g[j] = NAN;
        return 1;
    }
    if (!eq20) {
        /* the floor (2 h_min)^-p with h_min^2 = Hm */
        const double fl = dfl_rfunc_ipow(inv_root(4.0 * Hm, 2), p);
        if (!(S > fl * (1.0 + TIE))) return 0;
    }
    const double w = inv_root(S, p);
    const double wp1 = dfl_rfunc_ipow(w, p + 1);
    /* wp1 <= 1e280: the dominant terms of V, ~1/wp1, are far from underflow */
    if (!(wp1 >= 1e-290 && wp1 <= 1e280)) return 0;
    for (int j = 0; j < dim; j++) {
        g[j] = wp1 * o[4 + j];
        if (!isfinite(g[j])) return 0;
    }
    *u = w;
    return 1;
}

static void kernel(const dfl_rfunc_batch *b, size_t m, const double *pts, double *val,
                   double *grad)
{
    const corr_kd *kd = b->kd;
    const blk_fn blk = block_of(b);
    const size_t dim = (size_t)b->dim;
    double o[NOUT * LANES];
    for (size_t i0 = 0; i0 < m; i0 += LANES) {
        const size_t c = m - i0 < LANES ? m - i0 : LANES;
        blk(b, c, pts + dim * i0, o);
        for (size_t l = 0; l < c; l++) {
            const size_t i = i0 + l;
            double u, g[3];
            if (!finish(b->p, b->dim, kd->eq20, o + NOUT * l, &u, g))
                u = dfl_field_eval1(b->fb, pts + dim * i, g);
            val[i] = u;
            if (grad)
                for (size_t j = 0; j < dim; j++) grad[dim * i + j] = g[j];
        }
    }
}

static size_t count_fb(const dfl_rfunc_batch *b, size_t m, const double *pts)
{
    const corr_kd *kd = b->kd;
    const blk_fn blk = block_of(b);
    const size_t dim = (size_t)b->dim;
    double o[NOUT * LANES];
    size_t cnt = 0;
    for (size_t i0 = 0; i0 < m; i0 += LANES) {
        const size_t c = m - i0 < LANES ? m - i0 : LANES;
        blk(b, c, pts + dim * i0, o);
        for (size_t l = 0; l < c; l++) {
            double u, g[3];
            cnt += !finish(b->p, b->dim, kd->eq20, o + NOUT * l, &u, g);
        }
    }
    return cnt;
}

/* The vertices' sources and the parts' slots (header); 0 when a guard's
 * lo is neither hi - 1 nor one of NSLOT kept parts. */
static int plan_slots(const dfl_rfunc_batch_desc *d, corr_kd *kd)
{
    int nslot = 0;
    for (size_t k = 0; k < d->n; k++) kd->save[k] = -1;
    for (size_t i = 0; i < d->nv; i++) {
        const dfl_rfunc_vertex *v = &d->verts[i];
        if (kd->eq20 || v->lo + 1 == v->hi) {
            kd->src[i] = SRC_PREV;
            continue;
        }
        if (kd->save[v->lo] < 0) {
            if (nslot == NSLOT) return 0;
            kd->save[v->lo] = nslot++;
        }
        kd->src[i] = kd->save[v->lo];
    }
    return 1;
}

dfl_status dfl_rfunc_batch_try_corrected(const dfl_rfunc_batch_desc *d, dfl_rfunc_batch **out,
                                         dfl_err *err)
{
    *out = NULL;
    if (d->join != DFL_RFUNC_REQUIV_CORRECTED || d->n < 2 || (d->dim != 2 && d->dim != 3))
        return DFL_OK;
    if (d->parts[0].kind != DFL_RFUNC_PART_SEGMENT) return DFL_OK;
    const dfl_rfunc_trim trim = d->parts[0].u.seg.trim;
    if (trim != DFL_RFUNC_TRIM_DISK && trim != DFL_RFUNC_TRIM_STRIP) return DFL_OK;
    for (size_t k = 0; k < d->n; k++)
        if (d->parts[k].kind != DFL_RFUNC_PART_SEGMENT || d->parts[k].u.seg.trim != trim)
            return DFL_OK;
    for (size_t i = 0; i < d->nv; i++)
        if (d->verts[i].hi >= d->n || d->verts[i].lo >= d->verts[i].hi) return DFL_OK;
    corr_kd *kd = calloc(1, sizeof *kd);
    const size_t nv1 = d->nv ? d->nv : 1;
    if (kd) {
        kd->vx = malloc(3 * nv1 * sizeof *kd->vx);
        kd->src = malloc(nv1 * sizeof *kd->src);
        kd->save = malloc(d->n * sizeof *kd->save);
        kd->mem_vs = malloc((d->n + 1) * sizeof *kd->mem_vs);
    }
    if (!kd || !kd->vx || !kd->src || !kd->save || !kd->mem_vs) {
        kd_free(kd);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    }
    kd->eq20 = d->corr == DFL_RFUNC_CORR_EQ20;
    kd->strip = trim == DFL_RFUNC_TRIM_STRIP;
    kd->nv = d->nv;
    kd->vy = kd->vx + nv1;
    kd->vz = kd->vy + nv1;
    memcpy(kd->mem_vs, d->vstart, (d->n + 1) * sizeof *kd->mem_vs);
    kd->vstart = kd->mem_vs;
    for (size_t i = 0; i < d->nv; i++) {
        kd->vx[i] = d->verts[i].x[0];
        kd->vy[i] = d->verts[i].x[1];
        kd->vz[i] = d->dim == 3 ? d->verts[i].x[2] : 0.0;
    }
    if (!plan_slots(d, kd)) {
        kd_free(kd);
        return DFL_OK;
    }
    dfl_field ref = {0};
    dfl_rfunc_batch *b;
    dfl_status st = dfl_rfunc_batch_alloc(d->dim, d->p, d->n, &ref, &b, err);
    if (st != DFL_OK) {
        kd_free(kd);
        return st;
    }
    b->fb = d->slow;
    b->strip = kd->strip;
    b->kd = kd;
    b->kd_free = kd_free;
    b->kernel = kernel;
    b->count_fb = count_fb;
    /* the segments' own frames (segment.c): f and the trims' dot products
     * are then bitwise the per-point path's */
    for (size_t k = 0; k < d->n; k++) {
        dfl_rfunc_batch_put_seg(b, k, &d->parts[k].u.seg);
    }
    *out = b;
    return DFL_OK;
}
