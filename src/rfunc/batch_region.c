/* The convex-region kernel: R-equivalence of 2D convex polygons
 * (rfunc/region.h): h^2 = sum_i max(-p_i, 0)^2 over the edges,
 * p_i = (x - V_i).m_i (computed exactly as region.c does, so bitwise the
 * per-point path's), h grad h = -sum_i max(-p_i, 0) m_i.
 *
 * Regions have different edge counts, which would give the lane loop an
 * inner loop of varying length.  The batch groups the regions by edge
 * count (structure of arrays per group and edge), and runs each chunk of
 * KR regions of a group for a block of LANES points in two loops: the
 * edges (h^2 and h grad h, with the edge count a compile-time constant for
 * 3..8 edges, so the edge loop unrolls into straight-line code) and then
 * the join (h^-p, the order a compile-time constant).  Per region and
 * point at p = 2: 5 multiplications per edge, then 3 and 1 division (a
 * square: 23 multiplications, 1 division).  The sums run over the groups
 * in order, each in the field's order (rounding differs from the field's
 * order only in the last bits).
 *
 * Points inside a region get u = 0 and grad u = 0 directly (the per-point
 * path's value; a third of the benchmark's grid lies inside its squares),
 * recognised exactly by sum_i min(p_i, 0) = 0 (h^2 may underflow), so the
 * kind uses the kernel hook (batch_impl.h) rather than the sums path.
 * Points within ~1e-140 of a region fall back (h^-p overflows, see
 * pow_term). */
#include <math.h>
#include <stdlib.h>

#include "rfunc/batch_impl.h"
#include "rfunc/join.h"
#include "rfunc/rfield.h"

/* Regions with e edges: for edge j the arrays V_x, V_y, m_x, m_y of nr
 * doubles at d + (4 j + 0..3) nr, region k of the group at index k. */
typedef struct reg_group {
    size_t e, nr;
    const double *d;
} reg_group;

typedef struct reg_kd {
    size_t ng;
    reg_group *g;
    double *mem;
} reg_kd;

static void reg_kd_free(void *p)
{
    reg_kd *kd = p;
    if (!kd) return;
    free(kd->g);
    free(kd->mem);
    free(kd);
}

/* Regions per chunk. */
#define KR 32

/* h^2 and h grad h of region k of a group at one point (e edges). */
DFL_INLINE void reg_edges(double x, double y, const double *d, size_t nr, size_t k,
                          const size_t e, double *h2o, double *gxo, double *gyo, double *zo)
{
    double h2 = 0.0, gx = 0.0, gy = 0.0, z = 0.0;
    for (size_t j = 0; j < e; j++) {
        const double *dj = d + 4 * j * nr;
        const double mx = dj[2 * nr + k], my = dj[3 * nr + k];
        /* s = -q of region.c, ms = min(s, 0) = -max(q, 0) (no negation) */
        const double s = (x - dj[k]) * mx + (y - dj[nr + k]) * my;      /* 2 */
        const double ms = s < 0.0 ? s : 0.0;
        z += ms;     /* 0 exactly when the point is inside (h^2 may underflow) */
        h2 += ms * ms;                                                  /* 1 */
        gx += ms * mx;                                                  /* 1 */
        gy += ms * my;                                                  /* 1 */
    }
    *h2o = h2;
    *gxo = gx;
    *gyo = gy;
    *zo = z;
}

DFL_INLINE void edges_e(const reg_group *g, size_t k0, size_t kc, const double *X,
                        const double *Y, double (*H)[LANES], double (*GX)[LANES],
                        double (*GY)[LANES], double (*ZS)[LANES], const size_t e)
{
    for (size_t j = 0; j < kc; j++) {
#pragma omp simd
        for (int l = 0; l < LANES; l++)
            reg_edges(X[l], Y[l], g->d, g->nr, k0 + j, e, &H[j][l], &GX[j][l], &GY[j][l],
                      &ZS[j][l]);
    }
}

/* The edge loop of a chunk (kc <= KR regions of group g from k0). */
DFL_INLINE void reg_phase_edges_body(const reg_group *g, size_t k0, size_t kc, const double *X,
                            const double *Y, double (*H)[LANES], double (*GX)[LANES],
                            double (*GY)[LANES], double (*ZS)[LANES])
{
    switch (g->e) {
    case 3: edges_e(g, k0, kc, X, Y, H, GX, GY, ZS, 3); break;
    case 4: edges_e(g, k0, kc, X, Y, H, GX, GY, ZS, 4); break;
    case 5: edges_e(g, k0, kc, X, Y, H, GX, GY, ZS, 5); break;
    case 6: edges_e(g, k0, kc, X, Y, H, GX, GY, ZS, 6); break;
    case 7: edges_e(g, k0, kc, X, Y, H, GX, GY, ZS, 7); break;
    case 8: edges_e(g, k0, kc, X, Y, H, GX, GY, ZS, 8); break;
    default: edges_e(g, k0, kc, X, Y, H, GX, GY, ZS, g->e); break;
    }
}
DFL_ISA_KERNEL(reg_phase_edges,
               (const reg_group *g, size_t k0, size_t kc, const double *X, const double *Y,
                double (*H)[LANES], double (*GX)[LANES], double (*GY)[LANES],
                double (*ZS)[LANES]),
               (g, k0, kc, X, Y, H, GX, GY, ZS))

DFL_INLINE void join_p(size_t kc, double (*H)[LANES], double (*GX)[LANES], double (*GY)[LANES],
                       double (*ZS)[LANES], double *S, double *Vx, double *Vy, double *I,
                       const int p)
{
    for (size_t j = 0; j < kc; j++) {
#pragma omp simd
        for (int l = 0; l < LANES; l++) {
            const double q = pow_term(H[j][l], p, &S[l]);  /* p = 2: 1 division, 1 */
            Vx[l] += q * GX[j][l];                          /* 1 */
            Vy[l] += q * GY[j][l];                          /* 1 */
            I[l] += ZS[j][l] == 0.0 ? 1.0 : 0.0;
        }
    }
}

/* The join loop of a chunk: adds h^-p to S, h^-(p+2) h grad h to V. */
DFL_INLINE void reg_phase_join_body(int p, size_t kc, double (*H)[LANES], double (*GX)[LANES],
                           double (*GY)[LANES], double (*ZS)[LANES], double *S, double *Vx,
                           double *Vy, double *I)
{
    switch (p) {
    case 1: join_p(kc, H, GX, GY, ZS, S, Vx, Vy, I, 1); break;
    case 2: join_p(kc, H, GX, GY, ZS, S, Vx, Vy, I, 2); break;
    case 3: join_p(kc, H, GX, GY, ZS, S, Vx, Vy, I, 3); break;
    case 4: join_p(kc, H, GX, GY, ZS, S, Vx, Vy, I, 4); break;
    case 5: join_p(kc, H, GX, GY, ZS, S, Vx, Vy, I, 5); break;
    case 6: join_p(kc, H, GX, GY, ZS, S, Vx, Vy, I, 6); break;
    case 7: join_p(kc, H, GX, GY, ZS, S, Vx, Vy, I, 7); break;
    case 8: join_p(kc, H, GX, GY, ZS, S, Vx, Vy, I, 8); break;
    case 12: join_p(kc, H, GX, GY, ZS, S, Vx, Vy, I, 12); break;
    default: join_p(kc, H, GX, GY, ZS, S, Vx, Vy, I, p); break;
    }
}
DFL_ISA_KERNEL(reg_phase_join,
               (int p, size_t kc, double (*H)[LANES], double (*GX)[LANES], double (*GY)[LANES],
                double (*ZS)[LANES], double *S, double *Vx, double *Vy, double *I),
               (p, kc, H, GX, GY, ZS, S, Vx, Vy, I))

/* S, V and the number of regions containing the point (4 doubles per point). */
static void reg_sums(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    const reg_kd *kd = b->kd;
    double H[KR][LANES], GX[KR][LANES], GY[KR][LANES], ZS[KR][LANES];
    for (size_t i0 = 0; i0 < m; i0 += LANES) {
        const size_t c = m - i0 < LANES ? m - i0 : LANES;
        double X[LANES], Y[LANES], S[LANES] = {0}, Vx[LANES] = {0}, Vy[LANES] = {0},
                                   I[LANES] = {0};
        for (size_t l = 0; l < LANES; l++) {
            const size_t i = i0 + (l < c ? l : c - 1);
            X[l] = pts[2 * i];
            Y[l] = pts[2 * i + 1];
        }
        for (size_t ig = 0; ig < kd->ng; ig++) {
            const reg_group *g = &kd->g[ig];
            for (size_t k0 = 0; k0 < g->nr; k0 += KR) {
                const size_t kc = g->nr - k0 < KR ? g->nr - k0 : KR;
                reg_phase_edges(g, k0, kc, X, Y, H, GX, GY, ZS);
                reg_phase_join(b->p, kc, H, GX, GY, ZS, S, Vx, Vy, I);
            }
        }
        for (size_t l = 0; l < c; l++) {
            out[4 * (i0 + l)] = S[l];
            out[4 * (i0 + l) + 1] = Vx[l];
            out[4 * (i0 + l) + 2] = Vy[l];
            out[4 * (i0 + l) + 3] = I[l];
        }
    }
}

/* u and grad u from the sums s (S, V), or 0 when they are not trustworthy:
 * the rules of batch.c's accept (the same ranges, the same roots). */
static int reg_accept(int p, const double *s, double *u, double *g)
{
    const double S = s[0];
    if (!(S >= 1e-140 && S <= 1e280) || !isfinite(s[1]) || !isfinite(s[2])) return 0;
    const double w = p == 1 ? 1.0 / S : p == 2 ? 1.0 / sqrt(S) : pow(S, -1.0 / p);
    const double wp1 = dfl_rfunc_ipow(w, p + 1);
    if (!(wp1 >= 1e-290) || !isfinite(wp1)) return 0;
    g[0] = wp1 * s[1];
    g[1] = wp1 * s[2];
    if (!isfinite(g[0]) || !isfinite(g[1])) return 0;
    *u = w;
    return 1;
}

/* The kind's kernel (batch_impl.h): a point inside a region has u = 0 and
 * grad u = 0, as the per-point path's accumulator gives (join.c), without
 * the fallback; the rest as the sums kernels. */
static void reg_kernel(const dfl_rfunc_batch *b, size_t m, const double *pts, double *val,
                       double *grad)
{
    double s[4 * SCRATCH];
    for (size_t i0 = 0; i0 < m; i0 += SCRATCH) {
        const size_t c = m - i0 < SCRATCH ? m - i0 : SCRATCH;
        reg_sums(b, c, pts + 2 * i0, s);
        for (size_t i = 0; i < c; i++) {
            double u = 0.0, g[2] = {0.0, 0.0};
            if (!(s[4 * i + 3] > 0.0) && !reg_accept(b->p, s + 4 * i, &u, g))
                u = dfl_field_eval1(b->fb, pts + 2 * (i0 + i), g);
            val[i0 + i] = u;
            if (grad) grad[2 * (i0 + i)] = g[0], grad[2 * (i0 + i) + 1] = g[1];
        }
    }
}

static size_t reg_count_fb(const dfl_rfunc_batch *b, size_t m, const double *pts)
{
    double s[4 * SCRATCH];
    size_t cnt = 0;
    for (size_t i0 = 0; i0 < m; i0 += SCRATCH) {
        const size_t c = m - i0 < SCRATCH ? m - i0 : SCRATCH;
        reg_sums(b, c, pts + 2 * i0, s);
        for (size_t i = 0; i < c; i++) {
            double u, g[2];
            cnt += !(s[4 * i + 3] > 0.0) && !reg_accept(b->p, s + 4 * i, &u, g);
        }
    }
    return cnt;
}

void dfl_rfunc_batch_sums_reg(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    /* S and V only (3 doubles per point), for callers of the sums interface */
    double s[4 * SCRATCH];
    for (size_t i0 = 0; i0 < m; i0 += SCRATCH) {
        const size_t c = m - i0 < SCRATCH ? m - i0 : SCRATCH;
        reg_sums(b, c, pts + 2 * i0, s);
        for (size_t i = 0; i < c; i++)
            for (int j = 0; j < 3; j++) out[3 * (i0 + i) + j] = s[4 * i + j];
    }
}

/* The regions grouped by edge count (ascending), each group in the
 * field's order. */
static dfl_status reg_kd_new(const dfl_rfunc_region *r, size_t n, reg_kd **out, dfl_err *err)
{
    size_t emax = 0, ne = 0;
    for (size_t k = 0; k < n; k++) {
        emax = r[k].n > emax ? r[k].n : emax;
        ne += r[k].n;
    }
    reg_kd *kd = calloc(1, sizeof *kd);
    size_t *cnt = calloc(emax + 1, sizeof *cnt);
    double *mem = malloc(4 * ne * sizeof *mem);
    reg_group *g = NULL;
    size_t ng = 0;
    if (kd && cnt && mem) {
        for (size_t k = 0; k < n; k++) cnt[r[k].n]++;
        for (size_t e = 0; e <= emax; e++) ng += cnt[e] > 0;
        g = malloc(ng * sizeof *g);
    }
    if (!kd || !cnt || !mem || !g) {
        free(kd), free(cnt), free(mem), free(g);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory for %zu regions", n);
    }
    size_t off = 0, ig = 0;
    for (size_t e = 0; e <= emax; e++) {
        if (!cnt[e]) continue;
        double *d = mem + off;
        size_t k = 0;
        for (size_t i = 0; i < n; i++) {
            if (r[i].n != e) continue;
            for (size_t j = 0; j < e; j++) {
                d[(4 * j + 0) * cnt[e] + k] = r[i].v[2 * j];
                d[(4 * j + 1) * cnt[e] + k] = r[i].v[2 * j + 1];
                d[(4 * j + 2) * cnt[e] + k] = r[i].m[2 * j];
                d[(4 * j + 3) * cnt[e] + k] = r[i].m[2 * j + 1];
            }
            k++;
        }
        g[ig++] = (reg_group){e, cnt[e], d};
        off += 4 * e * cnt[e];
    }
    free(cnt);
    kd->ng = ng;
    kd->g = g;
    kd->mem = mem;
    *out = kd;
    return DFL_OK;
}

dfl_status dfl_rfunc_batch_reg_attach(dfl_rfunc_batch *b, const dfl_rfunc_region *r, size_t n,
                                      dfl_err *err)
{
    reg_kd *kd = NULL;
    dfl_status st = reg_kd_new(r, n, &kd, err);
    if (st != DFL_OK) return st;
    b->regions = 1;
    b->kd = kd;
    b->kd_free = reg_kd_free;
    b->kernel = reg_kernel;
    b->count_fb = reg_count_fb;
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
    for (size_t k = 0; k < n && st == DFL_OK; k++) st = dfl_rfield_add_region(rf, r[k].v, r[k].n, err);
    dfl_field ref = {0};
    if (st == DFL_OK) st = dfl_rfield_finish(&rf, &ref, err);
    else dfl_rfield_free(rf);
    if (st != DFL_OK) return st;
    dfl_rfunc_batch *b;
    if ((st = dfl_rfunc_batch_alloc(2, p, n, &ref, &b, err)) != DFL_OK) return st;
    if ((st = dfl_rfunc_batch_reg_attach(b, r, n, err)) != DFL_OK) {
        dfl_rfunc_batch_free(b);
        return st;
    }
    *out = b;
    return DFL_OK;
}
