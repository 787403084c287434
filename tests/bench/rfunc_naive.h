/* The naive baseline of the bs04 rfunc benchmark (bench_rfunc.c), which
 * tests/rfunc/test_batch.c also checks against brute force: the 2D
 * polyline field of rfunc/batch.h (disk trim, eq. 4; R-equivalence of
 * order p, eq. 6) as a plain scalar loop that calls a (non-inlined)
 * function per segment and uses pow() for every power, with no scaling
 * (so it overflows where the fast path falls back; fine at the benchmark's
 * distances).  Where some h_i = 0 it returns 0 and gradient 0, like the
 * library; its trim, written about the centre c as (d/2)^2 - |x - c|^2, is
 * 0 only to rounding at the end points, so there u is of the order of the
 * rounding of the coordinates.
 *
 * Header-only (static) as the test helpers are: the benchmark and the
 * tests are separate programs.  The segments are stored as the fast path
 * stores them (structure of arrays), so the two read the same memory.
 */
#ifndef DFL_TESTS_BENCH_RFUNC_NAIVE_H
#define DFL_TESTS_BENCH_RFUNC_NAIVE_H

#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdlib.h>

typedef struct rfunc_naive {
    int p;
    size_t n;                 /* segments */
    double *ax, *ay, *bx, *by; /* segment k from a to b; one allocation at ax */
} rfunc_naive;

/* The polyline v[0..n-1] (closed adds v[n-1] -> v[0]) with order p, as
 * dfl_rfunc_batch_new takes it (the caller validates it there).  Returns
 * 0, or -1 when out of memory. */
static inline int rfunc_naive_init(rfunc_naive *nv, const double *v, size_t n, bool closed, int p)
{
    const size_t ns = closed ? n : n - 1;
    double *mem = malloc(4 * (ns ? ns : 1) * sizeof *mem);
    if (!mem) return -1;
    nv->p = p;
    nv->n = ns;
    nv->ax = mem, nv->ay = mem + ns, nv->bx = mem + 2 * ns, nv->by = mem + 3 * ns;
    for (size_t k = 0; k < ns; k++) {
        const double *a = v + 2 * k, *e = v + 2 * ((k + 1) % n);
        nv->ax[k] = a[0];
        nv->ay[k] = a[1];
        nv->bx[k] = e[0];
        nv->by[k] = e[1];
    }
    return 0;
}

static inline void rfunc_naive_free(rfunc_naive *nv) { free(nv->ax); }

/* h and grad h of segment k, eq. 4 with the disk trim, written the obvious
 * way: the normal and the trim from scratch, a branch on the trim sign.
 * Not inlined: the baseline pays a call per segment ("unused": not every
 * file that includes this header calls it). */
__attribute__((noinline, unused)) static double rfunc_naive_seg(const rfunc_naive *b, size_t k,
                                                                double x, double y, double *gx,
                                                                double *gy)
{
    const double axk = b->ax[k], ayk = b->ay[k];
    const double bxk = b->bx[k], byk = b->by[k];
    const double d = sqrt(pow(bxk - axk, 2) + pow(byk - ayk, 2));
    const double nx = (byk - ayk) / d, ny = -(bxk - axk) / d;
    const double f = (x - axk) * nx + (y - ayk) * ny;
    const double cx = 0.5 * (axk + bxk), cy = 0.5 * (ayk + byk);
    const double t = (pow(d / 2, 2) - pow(x - cx, 2) - pow(y - cy, 2)) / d;
    if (t >= 0) {
        *gx = f >= 0 ? nx : -nx;
        *gy = f >= 0 ? ny : -ny;
        return fabs(f);
    }
    const double h = sqrt(pow(f, 2) + pow(t, 2));
    if (h == 0) {
        *gx = *gy = 0;
        return 0;
    }
    /* grad t = -2 (x - c) / d */
    *gx = (f * nx + t * (-2 * (x - cx) / d)) / h;
    *gy = (f * ny + t * (-2 * (y - cy) / d)) / h;
    return h;
}

/* u at m points pts[2i], pts[2i+1] into val[i] and, when grad is not NULL,
 * its gradient into grad[2i], grad[2i+1]. */
static inline void rfunc_naive_eval(const rfunc_naive *b, size_t m, const double *pts,
                                    double *val, double *grad)
{
    const int p = b->p;
    for (size_t i = 0; i < m; i++) {
        const double x = pts[2 * i], y = pts[2 * i + 1];
        double S = 0, Vx = 0, Vy = 0;
        int zero = 0;
        for (size_t k = 0; k < b->n; k++) {
            double gx, gy;
            const double h = rfunc_naive_seg(b, k, x, y, &gx, &gy);
            if (h == 0) {
                zero = 1;
                break;
            }
            S += pow(h, -p);
            Vx += pow(h, -(p + 1)) * gx;
            Vy += pow(h, -(p + 1)) * gy;
        }
        const double u = zero ? 0.0 : pow(S, -1.0 / p);
        val[i] = u;
        if (grad) {
            grad[2 * i] = zero ? 0.0 : pow(u, p + 1) * Vx;
            grad[2 * i + 1] = zero ? 0.0 : pow(u, p + 1) * Vy;
        }
    }
}

#endif
