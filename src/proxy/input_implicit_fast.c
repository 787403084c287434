/* The robust implicit footpoint's fast path (see input_implicit_fast.h). */
#include "proxy/input_implicit_fast.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/linalg.h"
#include "core/vec.h"
#include "proxy/input_implicit.h"

struct dfl_imp_index {
    const dfl_implicit *s;
    size_t ns;
    double *pts, *nrm;      /* sorted by bucket: ns points and unit normals */
    double *soa;            /* the same by coordinate: x y z of the points, then
                               of the normals, ns each (the cap test's lanes) */
    size_t *start;          /* nb[0] nb[1] nb[2] + 1 bucket starts */
    double *bbox;           /* per bucket: lo[3], hi[3] of its samples (exact) */
    double lo[3], cell, h;
    int nb[3];
};

static void bucket_of(const dfl_imp_index *ix, const double q[3], int b[3])
{
    for (int a = 0; a < 3; a++) {
        /* clamped as a double: the cast of NaN or of one beyond int's range
         * is undefined (x86 gives INT_MIN, so +inf went to bucket 0) */
        const double f = floor((q[a] - ix->lo[a]) / ix->cell);
        b[a] = !(f >= 0.0) ? 0 : (f >= ix->nb[a] ? ix->nb[a] - 1 : (int)f);
    }
}

static size_t bucket_id(const dfl_imp_index *ix, int i, int j, int k)
{
    return ((size_t)k * ix->nb[1] + j) * ix->nb[0] + i;
}

dfl_imp_index *dfl_imp_index_new(const dfl_implicit *s)
{
    dfl_imp_index *ix = calloc(1, sizeof *ix);
    if (!ix) return NULL;
    size_t ns;
    const double *sp = dfl_implicit_samples(s, &ns);
    ix->s = s;
    ix->ns = ns;
    ix->h = dfl_implicit_spacing(s);
    /* coarse buckets: far queries visit few, and buckets are pruned by
     * their distance to the query */
    ix->cell = 6 * ix->h;
    double hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (int a = 0; a < 3; a++) ix->lo[a] = HUGE_VAL;
    for (size_t t = 0; t < ns; t++)
        for (int a = 0; a < 3; a++) {
            ix->lo[a] = fmin(ix->lo[a], sp[3 * t + a]);
            hi[a] = fmax(hi[a], sp[3 * t + a]);
        }
    size_t nbt = 1;
    for (int a = 0; a < 3; a++) {
        ix->nb[a] = 1 + (int)((hi[a] - ix->lo[a]) / ix->cell);
        nbt *= (size_t)ix->nb[a];
    }
    ix->pts = malloc(3 * ns * sizeof *ix->pts);
    ix->nrm = malloc(3 * ns * sizeof *ix->nrm);
    ix->start = calloc(nbt + 1, sizeof *ix->start);
    size_t *fill = malloc((nbt + 1) * sizeof *fill), *bid = malloc(ns * sizeof *bid);
    if (!ix->pts || !ix->nrm || !ix->start || !fill || !bid) {
        free(fill);
        free(bid);
        dfl_imp_index_free(ix);
        return NULL;
    }
    for (size_t t = 0; t < ns; t++) {
        int b[3];
        bucket_of(ix, sp + 3 * t, b);
        bid[t] = bucket_id(ix, b[0], b[1], b[2]);
        ix->start[bid[t] + 1]++;
    }
    for (size_t b = 0; b < nbt; b++) ix->start[b + 1] += ix->start[b];
    memcpy(fill, ix->start, (nbt + 1) * sizeof *fill);
    for (size_t t = 0; t < ns; t++) {
        size_t w = fill[bid[t]]++;
        double G[3];
        dfl_implicit_g(s, sp + 3 * t, G, NULL);
        double gn = dfl_vec3_norm(G);
        for (int a = 0; a < 3; a++) {
            ix->pts[3 * w + a] = sp[3 * t + a];
            ix->nrm[3 * w + a] = gn > 0 ? G[a] / gn : 0.0;
        }
    }
    free(fill);
    free(bid);
    if (!(ix->soa = malloc((6 * ns + 1) * sizeof *ix->soa)) ||
        !(ix->bbox = malloc(6 * nbt * sizeof *ix->bbox))) {
        dfl_imp_index_free(ix);
        return NULL;
    }
    for (size_t b = 0; b < nbt; b++) {
        double *bx = ix->bbox + 6 * b;
        for (int a = 0; a < 3; a++) bx[a] = bx[3 + a] = NAN; /* empty: never looked at */
        for (size_t t = ix->start[b]; t < ix->start[b + 1]; t++)
            for (int a = 0; a < 3; a++) {
                const double v = ix->pts[3 * t + a];
                bx[a] = t == ix->start[b] ? v : fmin(bx[a], v);
                bx[3 + a] = t == ix->start[b] ? v : fmax(bx[3 + a], v);
            }
    }
    for (size_t t = 0; t < ns; t++)
        for (int a = 0; a < 3; a++) {
            ix->soa[a * ns + t] = ix->pts[3 * t + a];
            ix->soa[(3 + a) * ns + t] = ix->nrm[3 * t + a];
        }
    return ix;
}

void dfl_imp_index_free(dfl_imp_index *ix)
{
    if (!ix) return;
    free(ix->pts);
    free(ix->nrm);
    free(ix->soa);
    free(ix->bbox);
    free(ix->start);
    free(ix);
}

/* Squared distance from x to bucket (i, j, k)'s box. */
static double box_d2(const dfl_imp_index *ix, const double x[3], int i, int j, int k)
{
    const int b[3] = {i, j, k};
    double s = 0;
    for (int a = 0; a < 3; a++) {
        double lo = ix->lo[a] + b[a] * ix->cell, hi = lo + ix->cell;
        double o = x[a] < lo ? lo - x[a] : (x[a] > hi ? x[a] - hi : 0.0);
        s += o * o;
    }
    return s;
}

/* A lower bound of d2(x, s) over the samples s of bucket b, in floating
 * point too: per axis the gap to the samples' box is no larger in
 * magnitude than x - s (rounding is monotone and symmetric), and squares
 * and the same left-to-right sum are monotone (0 + o^2 is o^2).  So a
 * bucket is passed over only when each of its samples would be, one at a
 * time.  NaN (x not finite): no comparison holds, nothing is passed over. */
static double tight_d2(const dfl_imp_index *ix, const double x[3], size_t b)
{
    const double *bx = ix->bbox + 6 * b;
    double s = 0;
    for (int a = 0; a < 3; a++) {
        double o = x[a] < bx[a] ? bx[a] - x[a] : (x[a] > bx[3 + a] ? x[a] - bx[3 + a] : 0.0);
        s += o * o;
    }
    return s;
}

static double d2(const double *a, const double *b)
{
    double u[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return dfl_vec3_dot(u, u);
}

/* Index of the nearest sample (rings of buckets until the ring's lower
 * bound exceeds the best). */
static size_t nearest(const dfl_imp_index *ix, const double x[3])
{
    int c0[3];
    bucket_of(ix, x, c0);
    double best = HUGE_VAL, lb = 0;
    size_t bi = 0;
    for (int a = 0; a < 3; a++) {
        double o = x[a] < ix->lo[a] ? ix->lo[a] - x[a]
                                    : fmax(0.0, x[a] - (ix->lo[a] + ix->nb[a] * ix->cell));
        lb += o * o;
    }
    int rmax = ix->nb[0] + ix->nb[1] + ix->nb[2];
    for (int r = 0; r <= rmax; r++) {
        for (int k = c0[2] - r; k <= c0[2] + r; k++) {
            if (k < 0 || k >= ix->nb[2]) continue;
            for (int j = c0[1] - r; j <= c0[1] + r; j++) {
                if (j < 0 || j >= ix->nb[1]) continue;
                /* a row through the ring's inside holds two of its buckets
                 * (the same buckets in the same order, fewer steps) */
                const int step = abs(j - c0[1]) < r && abs(k - c0[2]) < r ? 2 * r : 1;
                for (int i = c0[0] - r; i <= c0[0] + r; i += i == c0[0] - r ? step : 1) {
                    if (i < 0 || i >= ix->nb[0]) continue;
                    if (abs(i - c0[0]) < r && abs(j - c0[1]) < r && abs(k - c0[2]) < r) continue;
                    size_t b = bucket_id(ix, i, j, k);
                    if (ix->start[b] == ix->start[b + 1] || box_d2(ix, x, i, j, k) >= best ||
                        tight_d2(ix, x, b) >= best) /* no sample would win */
                        continue;
                    for (size_t t = ix->start[b]; t < ix->start[b + 1]; t++) {
                        double e = d2(x, ix->pts + 3 * t);
                        if (e < best) { best = e; bi = t; }
                    }
                }
            }
        }
        double ring = r * ix->cell;
        if (best < HUGE_VAL && sqrt(best) <= sqrt(lb) + ring) break;
    }
    return bi;
}

int dfl_imp_square_newton(const dfl_implicit *s, const double x[3], double p[3], double scale)
{
    double G[3], H[9];
    dfl_implicit_g(s, p, G, NULL);
    double gg = dfl_vec3_dot(G, G);
    if (!(gg > 0)) return 0;
    double t = ((x[0] - p[0]) * G[0] + (x[1] - p[1]) * G[1] + (x[2] - p[2]) * G[2]) / gg;
    for (int it = 0; it < 30; it++) {
        double g = dfl_implicit_g(s, p, G, H), gn = dfl_vec3_norm(G);
        double F[4], J[16];
        for (int i = 0; i < 3; i++) {
            F[i] = p[i] - x[i] + t * G[i];
            for (int j = 0; j < 3; j++) J[4 * i + j] = (i == j) + t * H[3 * i + j];
            J[4 * i + 3] = G[i];
            J[12 + i] = G[i];
        }
        F[3] = g;
        J[15] = 0;
        if (gn > 0 && sqrt(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]) <= 1e-13 * scale &&
            fabs(g) / gn <= 1e-13 * scale)
            return 1;
        int piv[4];
        if (dfl_lu_factor(4, J, piv, 1e-14, NULL) != DFL_OK) return 0;
        for (int i = 0; i < 4; i++) F[i] = -F[i];
        dfl_lu_solve(4, J, piv, F);
        for (int i = 0; i < 3; i++) p[i] += F[i];
        t += F[3];
        if (!isfinite(p[0] + p[1] + p[2] + t)) return 0;
    }
    return 0;
}

/* The cap test of samples t0..t1-1 (the reference's loop: any one that
 * fails fails the test, so the answer does not depend on the order the
 * samples are looked at): a pass without branches over chunks of them,
 * which vectorizes (the file is compiled without errno and trapping math,
 * the Makefile), in the reference's operations for each sample (vector
 * add, mul and sqrt round as the scalar ones do).  Per lane 0.0 or 1.0,
 * whole numbers summed: exact in any order. */
#define CAP_CHUNK 64
static int cap_run(const dfl_imp_index *ix, size_t t0, size_t t1, const double x[3],
                   const double p[3], double rb2, double near2)
{
    const size_t ns = ix->ns;
    const double *sx = ix->soa, *sy = sx + ns, *sz = sy + ns;
    const double *nx = sz + ns, *ny = nx + ns, *nz = ny + ns;
    const double x0 = x[0], x1 = x[1], x2 = x[2], p0 = p[0], p1 = p[1], p2 = p[2];
    for (size_t c0 = t0; c0 < t1; c0 += CAP_CHUNK) {
        const int m = t1 - c0 < CAP_CHUNK ? (int)(t1 - c0) : CAP_CHUNK;
        double fl[CAP_CHUNK];
        const double *restrict ax = sx + c0, *restrict ay = sy + c0, *restrict az = sz + c0;
        const double *restrict bx = nx + c0, *restrict by = ny + c0, *restrict bz = nz + c0;
#pragma omp simd
        for (int t = 0; t < m; t++) {
            /* d2(x, s), d2(p, s); u, un, tt, q, |tt|, |q| and the test as in
             * dfl_vec3_dot and dfl_vec3_norm */
            const double u0 = x0 - ax[t], u1 = x1 - ay[t], u2 = x2 - az[t];
            const double q0 = p0 - ax[t], q1 = p1 - ay[t], q2 = p2 - az[t];
            const double dx = u0 * u0 + u1 * u1 + u2 * u2, Q = q0 * q0 + q1 * q1 + q2 * q2;
            const double un = u0 * bx[t] + u1 * by[t] + u2 * bz[t];
            const double e0 = u0 - un * bx[t], e1 = u1 - un * by[t], e2 = u2 - un * bz[t];
            const double tl = sqrt(e0 * e0 + e1 * e1 + e2 * e2), ql = sqrt(Q);
            const double look = (dx > rb2 ? 0.0 : 1.0) * (Q <= near2 ? 0.0 : 1.0);
            const double ok = (e0 * q0 + e1 * q1 + e2 * q2 >= 0.5 * tl * ql ? 1.0 : 0.0) *
                              (tl > 0 ? 1.0 : 0.0);
            fl[t] = look * (1.0 - ok);
        }
        double fail = 0;
        for (int t = 0; t < m; t++) fail += fl[t];
        if (fail > 0) return 0;
    }
    return 1;
}

static int cap_test(const dfl_imp_index *ix, const double x[3], const double p[3], double ad)
{
    const double rb = ad + 2 * ix->h, near2 = 4 * ix->h * ix->h;
    double lo[3] = {x[0] - rb, x[1] - rb, x[2] - rb}, hi[3] = {x[0] + rb, x[1] + rb, x[2] + rb};
    int bl[3], bh[3];
    bucket_of(ix, lo, bl);
    bucket_of(ix, hi, bh);
    for (int k = bl[2]; k <= bh[2]; k++)
        for (int j = bl[1]; j <= bh[1]; j++)
            for (int i = bl[0]; i <= bh[0]; i++) {
                size_t b = bucket_id(ix, i, j, k);
                if (ix->start[b] == ix->start[b + 1] || box_d2(ix, x, i, j, k) > rb * rb ||
                    tight_d2(ix, x, b) > rb * rb) /* no sample in the ball */
                    continue;
                if (!cap_run(ix, ix->start[b], ix->start[b + 1], x, p, rb * rb, near2)) return 0;
            }
    return 1;
}

int dfl_imp_fast_foot(const dfl_imp_index *ix, const double x[3], double p[3], double *d)
{
    if (ix->ns == 0) return 0;
    const double scale = dfl_implicit_scale(ix->s);
    size_t t = nearest(ix, x);
    memcpy(p, ix->pts + 3 * t, 3 * sizeof *p);
    if (!dfl_imp_square_newton(ix->s, x, p, scale)) return 0;
    double G[3];
    double gx = dfl_implicit_g(ix->s, x, NULL, NULL);
    dfl_implicit_g(ix->s, p, G, NULL);
    double u[3] = {x[0] - p[0], x[1] - p[1], x[2] - p[2]}, gn = dfl_vec3_norm(G);
    if (!(gn > 0)) return 0;
    double dd = dfl_vec3_dot(u, G) / gn;
    if (fabs(dd) > 1e-12 * scale && (gx > 0) != (dd > 0)) return 0;
    if (!dfl_proxy_implicit_certify(ix->s, x, p, dd)) return 0;
    if (!cap_test(ix, x, p, fabs(dd))) return 0;
    *d = dd;
    return 1;
}
