/* The triangle kernel: R-equivalence of rfunc/tri3d.h triangles with one
 * eq. 4 trim (prism, or conditional with k = 2).
 *
 * Per triangle and point (f = (x - V_0).n, p_i = (x - V_i).m_i computed
 * exactly as tri3d.c does, so they are bitwise the per-point path's) the
 * trim is the left fold t = (p_0 ^ p_1) ^ p_2 of trim.c's conjunction
 * x ^ y = x + y - r, r = sqrt(x^2 + y^2 + c) (c = a f^2 or 0), taken as
 * (2 x y - c)/(x + y + r) when x + y > 0.  The per-point path spends two
 * roots and eight divisions on it and one more on h^-2; this kernel keeps
 * every quotient as a fraction and divides once:
 *
 *     t1 = N1/D1:   s1 = p0 + p1 > 0:  N1 = 2 p0 p1 - c,  D1 = s1 + R1
 *                   else:              N1 = s1 - R1,      D1 = 1
 *                   R1 = sqrt(p0^2 + p1^2 + c)
 *     r2 = RQ/D1,   RQ = sqrt(Q),  Q = N1^2 + (p2^2 + c) D1^2
 *     t = N2/D2:    sD = N1 + p2 D1 (= D1 (t1 + p2)) > 0:
 *                        N2 = 2 N1 p2 - c D1,  D2 = sD + RQ
 *                   else: N2 = sD - RQ,        D2 = D1
 * (both forms of each branch are the per-point ones multiplied by D1, so
 * they are free of cancellation where those are).  With M = |N2| - N2
 * and D = 2 D2 (so that max(-t, 0) = M/D), h^2 = Hd/D^2, Hd = f^2 D^2 + M^2.
 * The partials of the fold, multiplied by R1 RQ:
 *     R1 RQ grad t = (RQ - N1)(R1 - p0) m0 + (RQ - N1)(R1 - p1) m1
 *                    + R1 (RQ - p2 D1) m2 - a f ((RQ - N1) + D1 R1) n
 * (from dx = 1 - x/r, dc = -1/(2r) of trim.h and dc/df = 2 a f), so with
 * E = 1/(Hd R1 RQ) (the one division), 1/Hd = R1 RQ E, 1/(R1 RQ) = Hd E:
 *     1/h^2 = D^2/Hd,  1/h = D sqrt(Hd)/Hd  (odd p: a third root),
 *     w = h^-p,  and h^-(p+2) h grad h = w h^-2 f n - w (M D/Hd) grad t.
 * Operations per triangle at p = 2 (prism): 57 multiplications, 47
 * additions, 2 square roots, 1 division (conditional: 66, 53, 2, 1; odd p
 * a third root); the benchmark quotes them.
 *
 * The roots are the hardware's (correctly rounded, like the per-point
 * path's sqrt): this file is compiled with -fno-math-errno (Makefile), so
 * gcc vectorizes sqrt; the two roots and the division run on the divider
 * beside the multiplications (Newton steps for 1/sqrt would add 26
 * multiplications, the bottleneck).
 *
 * Fallback: the fractions grow like L^6 in the coordinates' scale L, so
 * the kernel trusts a point only while every triangle has p0^2 + p1^2 + c,
 * Q and Hd in [1e-140, 1e140] (then R1 RQ Hd is a normal number and no
 * intermediate under- or overflows); otherwise (a vertex line, where R1 or
 * RQ is 0 and trim.c takes its special partials; points within ~1e-70 of
 * a part; |x| beyond ~1e20), or when S < 1e-140 (V would underflow; far
 * points at large p), S is NaN and the point falls back. */
#include <math.h>
#include <stdlib.h>

#include "rfunc/batch_impl.h"
#include "rfunc/rfield.h"

/* Triangle data as structure of arrays: 21 arrays of n doubles. */
enum {
    T_NX, T_NY, T_NZ,
    T_V0X, T_V0Y, T_V0Z, T_M0X, T_M0Y, T_M0Z,
    T_V1X, T_V1Y, T_V1Z, T_M1X, T_M1Y, T_M1Z,
    T_V2X, T_V2Y, T_V2Z, T_M2X, T_M2Y, T_M2Z,
    T_NARR
};

typedef struct tri_kd {
    const double *a[T_NARR];
    double *mem;
} tri_kd;

static void tri_kd_free(void *p)
{
    tri_kd *kd = p;
    if (!kd) return;
    free(kd->mem);
    free(kd);
}

/* Lanes of a block (points); see DFL_BATCH_SUMS. */
#define TLANES 8
/* The trusted range of the guarded quantities (see the top). */
#define T_LO 1e-140
#define T_HI 1e140
/* The smallest S whose V = sum h^-(p+2) h grad h (~ S^((p+1)/p)) stays a
 * normal number for every p >= 1 (accept() of batch.c allows 1e-280). */
#define T_SMIN 1e-140

/* Triangles per phase chunk: the kernel runs a chunk of KC triangles for a
 * block of TLANES points in three loops (phases), which pass their results
 * through stack scratch.  One loop with the whole triangle would chain two
 * roots and a division (~130 cycles of latency per triangle) and leave the
 * out-of-order window, not the multipliers, as the bound. */
#define KC 16

/* Phase A: f, p_i (bitwise tri3d.c's), t1 = N1/D1 and Q. */
DFL_INLINE void tri_a(double x, double y, double z, const double *const *T, size_t k, double ca,
                      int cond, double *o, double *lo, double *hi)
{
    const double w0x = x - T[T_V0X][k], w0y = y - T[T_V0Y][k], w0z = z - T[T_V0Z][k];
    const double f = w0x * T[T_NX][k] + w0y * T[T_NY][k] + w0z * T[T_NZ][k];     /* 3 */
    const double p0 = w0x * T[T_M0X][k] + w0y * T[T_M0Y][k] + w0z * T[T_M0Z][k]; /* 3 */
    const double p1 = (x - T[T_V1X][k]) * T[T_M1X][k] + (y - T[T_V1Y][k]) * T[T_M1Y][k] +
                      (z - T[T_V1Z][k]) * T[T_M1Z][k];                           /* 3 */
    const double p2 = (x - T[T_V2X][k]) * T[T_M2X][k] + (y - T[T_V2Y][k]) * T[T_M2Y][k] +
                      (z - T[T_V2Z][k]) * T[T_M2Z][k];                           /* 3 */
    /* the conditional term a f^2 as tri3d.c rounds it */
    const double c = cond ? (ca * f) * f : 0.0;                                  /* (2) */
    const double r1sq = cond ? p0 * p0 + p1 * p1 + c : p0 * p0 + p1 * p1;         /* 2 */
    const double R1 = sqrt(r1sq);
    const double s1 = p0 + p1;
    const double pp = (p0 + p0) * p1;                                            /* 1 */
    const double N1a = cond ? pp - c : pp, N1b = s1 - R1, D1a = s1 + R1;
    const double N1 = s1 > 0.0 ? N1a : N1b;
    const double D1 = s1 > 0.0 ? D1a : 1.0;
    const double Q = N1 * N1 + (cond ? p2 * p2 + c : p2 * p2) * (D1 * D1);       /* 4 */
    o[0] = f, o[TLANES] = p0, o[2 * TLANES] = p1, o[3 * TLANES] = p2, o[4 * TLANES] = R1;
    o[5 * TLANES] = N1, o[6 * TLANES] = D1, o[7 * TLANES] = Q;
    *lo = r1sq < *lo ? r1sq : *lo;
    *hi = r1sq > *hi ? r1sq : *hi;
}

/* Phase B: t = N2/D2, Hd, the gradient coefficients (times R1 RQ) and the
 * denominator Z = Hd R1 RQ. */
DFL_INLINE void tri_b(const double *in, double ca, int cond, double *o, double *lo, double *hi)
{
    const double f = in[0], p0 = in[TLANES], p1 = in[2 * TLANES], p2 = in[3 * TLANES],
                 R1 = in[4 * TLANES], N1 = in[5 * TLANES], D1 = in[6 * TLANES],
                 Q = in[7 * TLANES];
    const double c = cond ? (ca * f) * f : 0.0;                                  /* (2) */
    const double RQ = sqrt(Q);
    const double D1p2 = p2 * D1;                                                 /* 1 */
    const double sD = N1 + D1p2;
    const double nn = (N1 + N1) * p2;                                            /* 1 */
    const double N2a = cond ? nn - c * D1 : nn, N2b = sD - RQ, D2a = sD + RQ;    /* (1) */
    const double N2 = sD > 0.0 ? N2a : N2b;
    const double D2 = sD > 0.0 ? D2a : D1;
    /* max(-t, 0) = M / D; h^2 = Hd / D^2 */
    const double D = D2 + D2, M = fabs(N2) - N2;
    const double Hd = (f * f) * (D * D) + M * M;                                 /* 4 */
    const double RR = R1 * RQ;                                                   /* 1 */
    const double u = RQ - N1;
    o[0] = Hd * RR;                                                              /* 1 */
    o[TLANES] = RR, o[2 * TLANES] = D, o[3 * TLANES] = M;
    o[4 * TLANES] = u * (R1 - p0), o[5 * TLANES] = u * (R1 - p1);                /* 2 */
    o[6 * TLANES] = R1 * (RQ - D1p2);                                            /* 1 */
    if (cond) o[7 * TLANES] = (ca * f) * (u + D1 * R1);                          /* (2) */
    o[8 * TLANES] = Hd;
    const double l = Q < Hd ? Q : Hd, g = Q > Hd ? Q : Hd;
    *lo = l < *lo ? l : *lo;
    *hi = g > *hi ? g : *hi;
}

/* Phase C: the one division, h^-p and the sums.  The factors are grouped
 * by scale (1/(R1 RQ) with the partials, mt h^-2 = M D / Hd with h^-p) so
 * that no product under- or overflows before the term itself does. */
DFL_INLINE void tri_c(const double *in, double f, const double *const *T, size_t k, int p,
                      int cond, double *S, double *Vx, double *Vy, double *Vz)
{
    const double Z = in[0], RR = in[TLANES], D = in[2 * TLANES], M = in[3 * TLANES],
                 Hd = in[8 * TLANES];
    const double E = 1.0 / Z;                                                    /* 1 div */
    const double iHd = RR * E, iRR = Hd * E;                                     /* 2 */
    const double r2 = (D * D) * iHd;                                             /* 2: h^-2 */
    double w;
    if (p & 1) {
        const double ih = D * sqrt(Hd) * iHd;                                    /* h^-1 */
        w = p == 1 ? ih : ih * ipow_sq(r2, p / 2);
    } else {
        w = ipow_sq(r2, p / 2);                                                  /* 0 at p = 2 */
    }
    *S += w;
    const double qf = w * (r2 * f);                                              /* 2 */
    const double wm = w * (M * D * iHd);                                         /* 3: h^-(p+2) mt */
    const double b0 = wm * (in[4 * TLANES] * iRR), b1 = wm * (in[5 * TLANES] * iRR),
                 b2 = wm * (in[6 * TLANES] * iRR);                               /* 6 */
    const double bn = cond ? qf + wm * (in[7 * TLANES] * iRR) : qf;
    *Vx += bn * T[T_NX][k] - b0 * T[T_M0X][k] - b1 * T[T_M1X][k] - b2 * T[T_M2X][k]; /* 4 */
    *Vy += bn * T[T_NY][k] - b0 * T[T_M0Y][k] - b1 * T[T_M1Y][k] - b2 * T[T_M2Y][k]; /* 4 */
    *Vz += bn * T[T_NZ][k] - b0 * T[T_M0Z][k] - b1 * T[T_M1Z][k] - b2 * T[T_M2Z][k]; /* 4 */
}

DFL_INLINE void sums_tri_p(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out,
                           const int p, const int cond)
{
    const size_t n = b->n;
    const tri_kd *kd = b->kd;
    const double *const *T = kd->a;
    const double ca = b->ca;
    double A[KC][8][TLANES], B[KC][9][TLANES];
    for (size_t i0 = 0; i0 < m; i0 += TLANES) {
        const size_t c = m - i0 < TLANES ? m - i0 : TLANES;
        double X[TLANES], Y[TLANES], Z[TLANES], S[TLANES] = {0}, Vx[TLANES] = {0},
                                                Vy[TLANES] = {0}, Vz[TLANES] = {0};
        double lo[TLANES], hi[TLANES];
        for (size_t l = 0; l < TLANES; l++) {
            const size_t i = i0 + (l < c ? l : c - 1);
            X[l] = pts[3 * i];
            Y[l] = pts[3 * i + 1];
            Z[l] = pts[3 * i + 2];
            lo[l] = T_HI;
            hi[l] = T_LO;
        }
        for (size_t k0 = 0; k0 < n; k0 += KC) {
            const size_t kc = n - k0 < KC ? n - k0 : KC;
            for (size_t j = 0; j < kc; j++) {
                double *a = &A[j][0][0];
#pragma omp simd
                for (int l = 0; l < TLANES; l++)
                    tri_a(X[l], Y[l], Z[l], T, k0 + j, ca, cond, a + l, &lo[l], &hi[l]);
            }
            for (size_t j = 0; j < kc; j++) {
                const double *a = &A[j][0][0];
                double *bb = &B[j][0][0];
#pragma omp simd
                for (int l = 0; l < TLANES; l++) tri_b(a + l, ca, cond, bb + l, &lo[l], &hi[l]);
            }
            for (size_t j = 0; j < kc; j++) {
                const double *a = &A[j][0][0], *bb = &B[j][0][0];
#pragma omp simd
                for (int l = 0; l < TLANES; l++)
                    tri_c(bb + l, a[l], T, k0 + j, p, cond, &S[l], &Vx[l], &Vy[l], &Vz[l]);
            }
        }
        for (size_t l = 0; l < c; l++) {
            const int ok = lo[l] >= T_LO && hi[l] <= T_HI && S[l] >= T_SMIN;
            out[4 * (i0 + l)] = ok ? S[l] : NAN;
            out[4 * (i0 + l) + 1] = Vx[l];
            out[4 * (i0 + l) + 2] = Vy[l];
            out[4 * (i0 + l) + 3] = Vz[l];
        }
    }
}

#define TRI_CASES(cond)                                              \
    switch (b->p) {                                                  \
    case 1: sums_tri_p(b, m, pts, out, 1, cond); break;              \
    case 2: sums_tri_p(b, m, pts, out, 2, cond); break;              \
    case 3: sums_tri_p(b, m, pts, out, 3, cond); break;              \
    case 4: sums_tri_p(b, m, pts, out, 4, cond); break;              \
    case 5: sums_tri_p(b, m, pts, out, 5, cond); break;              \
    case 6: sums_tri_p(b, m, pts, out, 6, cond); break;              \
    case 7: sums_tri_p(b, m, pts, out, 7, cond); break;              \
    case 8: sums_tri_p(b, m, pts, out, 8, cond); break;              \
    case 12: sums_tri_p(b, m, pts, out, 12, cond); break;            \
    default: sums_tri_p(b, m, pts, out, b->p, cond); break;          \
    }

DFL_INLINE void sums_prism_body(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    TRI_CASES(0)
}
DFL_ISA_KERNEL(sums_prism, (const dfl_rfunc_batch *b, size_t m, const double *pts, double *out), (b, m, pts, out))

DFL_INLINE void sums_cond_body(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    TRI_CASES(1)
}
DFL_ISA_KERNEL(sums_cond, (const dfl_rfunc_batch *b, size_t m, const double *pts, double *out), (b, m, pts, out))

void dfl_rfunc_batch_sums_tri(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    if (b->cond) sums_cond(b, m, pts, out);
    else sums_prism(b, m, pts, out);
}

dfl_status dfl_rfunc_batch_tri_attach(dfl_rfunc_batch *b, const dfl_rfunc_tri *t, size_t n,
                                      dfl_err *err)
{
    tri_kd *kd = calloc(1, sizeof *kd);
    double *mem = malloc(T_NARR * (n ? n : 1) * sizeof *mem);
    if (!kd || !mem) {
        free(kd), free(mem);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory for %zu triangles", n);
    }
    kd->mem = mem;
    for (int j = 0; j < T_NARR; j++) kd->a[j] = mem + (size_t)j * n;
    for (size_t k = 0; k < n; k++)
        for (int j = 0; j < 3; j++) {
            mem[(size_t)(T_NX + j) * n + k] = t[k].n[j];
            for (int i = 0; i < 3; i++) {
                mem[(size_t)(T_V0X + 6 * i + j) * n + k] = t[k].v[i][j];
                mem[(size_t)(T_M0X + 6 * i + j) * n + k] = t[k].m[i][j];
            }
        }
    b->tris = 1;
    b->cond = t[0].o.trim == DFL_RFUNC_TRI_CONDITIONAL;
    b->ca = t[0].o.a;
    b->kd = kd;
    b->kd_free = tri_kd_free;
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
    dfl_rfunc_batch *b;
    if ((st = dfl_rfunc_batch_alloc(3, p, n, &ref, &b, err)) != DFL_OK) return st;
    if ((st = dfl_rfunc_batch_tri_attach(b, t, n, err)) != DFL_OK) {
        dfl_rfunc_batch_free(b);
        return st;
    }
    *out = b;
    return DFL_OK;
}
