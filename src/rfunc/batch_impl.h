/* Private to the batched kernels (rfunc/batch*.c): the batch's layout,
 * the arithmetic every kernel shares, and the kernels' entry points.  Why
 * the kernels look the way they do is at the top of batch.c.
 *
 * Index:
 *   struct dfl_rfunc_batch       arrays (structure of arrays) and kind hooks
 *   DFL_INLINE                   forced inlining (kernels: DFL_ISA_KERNEL, core/isa.h)
 *   rsqrt_newton, ipow_sq        1/sqrt without libm, x^k by squaring
 *   pow_term                     h^-p and h^-(p+2) from h^2
 *   DFL_BATCH_SUMS               the lane loop of the R-equivalence kernels
 *   DFL_GEN_CASES                p as a constant for the common orders
 *   dfl_rfunc_batch_alloc        a batch with its arrays
 *   dfl_rfunc_batch_put_seg      a segment into the arrays
 *   dfl_rfunc_batch_accept       u, grad u from the sums, or fall back
 *   dfl_rfunc_batch_sums_*       the built-in kernels' sums (one file each)
 *   dfl_rfunc_batch_try_*        the kinds dfl_rfunc_batch_build tries
 */
#ifndef DFL_RFUNC_BATCH_IMPL_H
#define DFL_RFUNC_BATCH_IMPL_H

#include <stdint.h>
#include <string.h>

#include "core/isa.h"
#include "rfunc/batch.h"

#define LANES 8
/* Points per inner call (stack scratch of the sums path). */
#define SCRATCH 64

struct dfl_rfunc_batch {
    int p;
    int dim;            /* 2 or 3 */
    int strip;          /* 1: strip (slab) trims, 0: disk (sphere) trims; eq. 4 */
    int points;         /* 1: the parts are points c = (ax, ay[, az]) */
    int tris;           /* 1: the parts are triangles (data in kd: batch_tri.c) */
    int cond;           /* triangles: 1 conditional trim (a f^2), 0 prism */
    double ca;          /* triangles: the conditional weight a */
    int regions;        /* 1: the parts are convex regions (2D; data in kd: batch_region.c) */
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
    dfl_field ref;      /* the library's field of the same parts (the public constructors;
                           zero for batches built from a field: dfl_rfunc_batch_build) */
    const dfl_field *fb; /* the fallback and reference: &ref, or the field's per-point path */
    /* Kind hooks (batch_build.c's kinds; NULL for the kinds above):
     * sums_fn replaces the built-in kernels' R-equivalence sums (1 + dim
     * doubles per point, then accept() and the fallback as for those);
     * kernel computes u and grad u itself (joins that are not a sum:
     * R-conjunction, the corrected join), falling back through fb where
     * it cannot trust its arithmetic, and count_fb counts those points
     * (dfl_rfunc_batch_fallbacks); kd is the kind's data, freed by kd_free. */
    void (*sums_fn)(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out);
    void (*kernel)(const dfl_rfunc_batch *b, size_t m, const double *pts, double *val,
                   double *grad);
    size_t (*count_fb)(const dfl_rfunc_batch *b, size_t m, const double *pts);
    void *kd;
    void (*kd_free)(void *kd);
};


/* Arrays of a batch: the 2D disk kernel's eight, then the others. */
#define NARR 17


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

/* The lane loop of the R-equivalence kernels.  Blocks of LANES points (a
 * short last block repeats its last point in the spare lanes) run through
 * every part k = 0..b->n-1 in order; TERM is a statement that adds part
 * k's terms at lane l to S[l], Vx[l], Vy[l] (and Vz[l]) from the point
 * X[l], Y[l] (Z[l]; 0 in 2D).  Writes 1 + dim sums per point to out. */
#define DFL_BATCH_SUMS(b, m, pts, out, dim, TERM)                                              \
    do {                                                                                       \
        const size_t n_ = (b)->n, w_ = (size_t)(dim) + 1;                                      \
        for (size_t i0 = 0; i0 < (m); i0 += LANES) {                                           \
            const size_t c_ = (m) - i0 < LANES ? (m) - i0 : LANES;                             \
            double X[LANES], Y[LANES], Z[LANES] = {0}, S[LANES] = {0}, Vx[LANES] = {0},        \
                   Vy[LANES] = {0}, Vz[LANES] = {0};                                           \
            for (size_t l = 0; l < LANES; l++) {                                               \
                const size_t i_ = i0 + (l < c_ ? l : c_ - 1);                                  \
                X[l] = (pts)[(size_t)(dim) * i_];                                              \
                Y[l] = (pts)[(size_t)(dim) * i_ + 1];                                          \
                if ((dim) == 3) Z[l] = (pts)[3 * i_ + 2];                                      \
            }                                                                                  \
            (void)Z;                                                                           \
            for (size_t k = 0; k < n_; k++) {                                                  \
                _Pragma("omp simd") for (int l = 0; l < LANES; l++) { TERM; }                  \
            }                                                                                  \
            for (size_t l = 0; l < c_; l++) {                                                  \
                (out)[w_ * (i0 + l)] = S[l];                                                   \
                (out)[w_ * (i0 + l) + 1] = Vx[l];                                              \
                (out)[w_ * (i0 + l) + 2] = Vy[l];                                              \
                if ((dim) == 3) (out)[w_ * (i0 + l) + 3] = Vz[l];                              \
            }                                                                                  \
        }                                                                                      \
    } while (0)

/* The order p as a compile-time constant for the common orders (1-4, 7,
 * 12), else the generic loop: calls sums_gen_p(b, m, pts, out, p, dim,
 * strip), which the including file defines. */
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

/* Part k of b's segment arrays from the library's own segment (its frames
 * n1, n2, e from rfunc/segment.c, so that f and the trims' dot products are
 * bitwise the per-point path's), with the disk kernel's hid = 1/(2d) and
 * hid2 = 1/(2d^2). */
void dfl_rfunc_batch_put_seg(dfl_rfunc_batch *b, size_t k, const dfl_rfunc_seg *sg);

/* A batch of n parts of order p and dimension dim with its NARR arrays of
 * n doubles (one allocation), the reference field ref moved in (may be a
 * zero field: then the caller sets b->fb) and fb = &b->ref.  ref is
 * destroyed on failure.  DFL_E_NOMEM. */
dfl_status dfl_rfunc_batch_alloc(int dim, int p, size_t n, dfl_field *ref, dfl_rfunc_batch **out,
                                 dfl_err *err);

/* u and grad u (dim entries) from the sums s (1 + dim doubles) of an
 * R-equivalence of order p, or 0 when they are not trustworthy (then the
 * point falls back): the test the sums path applies (batch.c). */
int dfl_rfunc_batch_accept(int p, int dim, const double *s, double *u, double *g);

/* The built-in kernels' sums, 1 + dim doubles (S, V) per point. */
void dfl_rfunc_batch_sums_seg(const dfl_rfunc_batch *b, size_t m, const double *pts,
                              double *out);                         /* batch_seg.c */
void dfl_rfunc_batch_sums_tri(const dfl_rfunc_batch *b, size_t m, const double *pts,
                              double *out);                         /* batch_tri.c */
void dfl_rfunc_batch_sums_reg(const dfl_rfunc_batch *b, size_t m, const double *pts,
                              double *out);                         /* batch_region.c */
void dfl_rfunc_batch_sums_pts(const dfl_rfunc_batch *b, size_t m, const double *pts,
                              double *out);                         /* batch_point.c */

/* The triangle and region kernels' data for t[0..n-1] (one eq. 4 trim,
 * conditional with k = 2: the caller checks) or the convex regions
 * r[0..n-1] (copied), attached to b as its kind data (tris/regions, kd,
 * kd_free; regions also set kernel and count_fb, which answer points
 * inside a region with u = 0).  b's own arrays are not used.  DFL_E_NOMEM
 * (b unchanged). */
dfl_status dfl_rfunc_batch_tri_attach(dfl_rfunc_batch *b, const dfl_rfunc_tri *t, size_t n,
                                      dfl_err *err); /* batch_tri.c */
dfl_status dfl_rfunc_batch_reg_attach(dfl_rfunc_batch *b, const dfl_rfunc_region *r, size_t n,
                                      dfl_err *err); /* batch_region.c */

/* The kinds dfl_rfunc_batch_build tries after the built-in ones, each in
 * its own file: DFL_OK with *out NULL when the field is not one it
 * computes, DFL_OK with a batch (fb = d->slow) when it is; an error only
 * for what the machine did (DFL_E_NOMEM). */
dfl_status dfl_rfunc_batch_try_smooth(const dfl_rfunc_batch_desc *d, dfl_rfunc_batch **out,
                                      dfl_err *err); /* batch_smooth.c: eq. 5 trims */
dfl_status dfl_rfunc_batch_try_rconj(const dfl_rfunc_batch_desc *d, dfl_rfunc_batch **out,
                                     dfl_err *err); /* batch_rconj.c: R-conjunction */
dfl_status dfl_rfunc_batch_try_corrected(const dfl_rfunc_batch_desc *d, dfl_rfunc_batch **out,
                                         dfl_err *err); /* batch_corrected.c: eq. 20 */
dfl_status dfl_rfunc_batch_try_mixed(const dfl_rfunc_batch_desc *d, dfl_rfunc_batch **out,
                                     dfl_err *err); /* batch_mixed.c: mixed part kinds */

#endif
