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
 *  - DFL_ISA_KERNEL (core/isa.h) compiles each kernel for AVX-512, AVX2
 *    and the baseline; the process's ISA picks one (DFL_ISA forces it), and
 *    every variant computes the same bytes (the Makefile builds for
 *    baseline x86-64 with -ffp-contract=off).
 */
#include "rfunc/batch.h"

#include <assert.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "rfunc/batch_impl.h"
#include "rfunc/join.h"
#include "rfunc/rfield.h"

/* 1 + dim sums per point: the kernel of the batch's parts, dimension and trim. */
static void sums(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    if (b->sums_fn) b->sums_fn(b, m, pts, out);
    else if (b->regions) dfl_rfunc_batch_sums_reg(b, m, pts, out);
    else if (b->tris) dfl_rfunc_batch_sums_tri(b, m, pts, out);
    else if (b->points) dfl_rfunc_batch_sums_pts(b, m, pts, out);
    else dfl_rfunc_batch_sums_seg(b, m, pts, out);
}

int dfl_rfunc_batch_simd_width(void)
{
    return dfl_isa_width(dfl_isa_active());
}

/* u and grad u (dim entries) from the sums, or 0 when they are not
 * trustworthy. */
static int accept(int p, int dim, const double *s, double *u, double *g)
{
    const double S = s[0];
    if (!(S >= 1e-280 && S <= 1e280)) return 0;
    for (int j = 1; j <= dim; j++)
        if (!isfinite(s[j])) return 0;
    const double w = p == 1 ? 1.0 / S : p == 2 ? 1.0 / sqrt(S) : pow(S, -1.0 / p);
    /* V's terms h^-(p+2) h grad h: the significant ones (h near u) are
     * about u^-(p+2) = S / u^2, which must not underflow (far away, e.g.
     * |x| ~ 1e50 for p = 2, V would be 0 while S is fine). */
    if (!(S / (w * w) >= 1e-290)) return 0;
    const double wp1 = dfl_rfunc_ipow(w, p + 1);
    if (!(wp1 >= 1e-290) || !isfinite(wp1)) return 0;
    for (int j = 0; j < dim; j++) {
        g[j] = wp1 * s[1 + j];
        if (!isfinite(g[j])) return 0;
    }
    *u = w;
    return 1;
}

int dfl_rfunc_batch_accept(int p, int dim, const double *s, double *u, double *g)
{
    return accept(p, dim, s, u, g);
}

static void eval_block(const dfl_rfunc_batch *b, size_t m, const double *pts, double *val,
                       double *grad)
{
    double s[4 * SCRATCH];
    const size_t dim = (size_t)b->dim;
    assert(m <= SCRATCH);
    if (b->kernel) {
        b->kernel(b, m, pts, val, grad);
        return;
    }
    sums(b, m, pts, s);
    for (size_t i = 0; i < m; i++) {
        double u, g[3];
        if (!accept(b->p, b->dim, s + (dim + 1) * i, &u, g))
            u = dfl_field_eval1(b->fb, pts + dim * i, g);
        val[i] = u;
        if (grad)
            for (size_t j = 0; j < dim; j++) grad[dim * i + j] = g[j];
    }
}

void dfl_rfunc_batch_eval(const dfl_rfunc_batch *b, size_t m, const double *pts, double *val,
                          double *grad)
{
    const size_t dim = (size_t)b->dim;
    for (size_t i = 0; i < m; i += SCRATCH) {
        const size_t c = m - i < SCRATCH ? m - i : SCRATCH;
        eval_block(b, c, pts + dim * i, val + i, grad ? grad + dim * i : NULL);
    }
}

size_t dfl_rfunc_batch_fallbacks(const dfl_rfunc_batch *b, size_t m, const double *pts)
{
    double s[4 * SCRATCH];
    const size_t dim = (size_t)b->dim;
    size_t cnt = 0;
    if (b->kernel) return b->count_fb ? b->count_fb(b, m, pts) : 0;
    for (size_t i = 0; i < m; i += SCRATCH) {
        const size_t c = m - i < SCRATCH ? m - i : SCRATCH;
        sums(b, c, pts + dim * i, s);
        for (size_t j = 0; j < c; j++) {
            double u, g[3];
            cnt += !accept(b->p, b->dim, s + (dim + 1) * j, &u, g);
        }
    }
    return cnt;
}

/* ---- construction -------------------------------------------------------- */

/* A batch of n parts of order p and dimension dim with its arrays (one
 * allocation) and the reference field ref (moved in; destroyed on failure). */
void dfl_rfunc_batch_put_seg(dfl_rfunc_batch *b, size_t k, const dfl_rfunc_seg *sg)
{
    assert(k < b->n);
    b->ax[k] = sg->a[0], b->ay[k] = sg->a[1], b->az[k] = sg->a[2];
    b->bx[k] = sg->b[0], b->by[k] = sg->b[1], b->bz[k] = sg->b[2];
    b->nx[k] = sg->n1[0], b->ny[k] = sg->n1[1], b->nz[k] = sg->n1[2];
    b->mx[k] = sg->n2[0], b->my[k] = sg->n2[1], b->mz[k] = sg->n2[2];
    b->ex[k] = sg->e[0], b->ey[k] = sg->e[1], b->ez[k] = sg->e[2];
    b->hid[k] = 0.5 / sg->d;
    b->hid2[k] = 0.5 / (sg->d * sg->d);
}

dfl_status dfl_rfunc_batch_alloc(int dim, int p, size_t n, dfl_field *ref, dfl_rfunc_batch **out,
                                 dfl_err *err)
{
    dfl_rfunc_batch *b = calloc(1, sizeof *b);
    double *mem = malloc(NARR * (n ? n : 1) * sizeof *mem);
    if (!b || !mem) {
        free(b);
        free(mem);
        dfl_field_destroy(ref);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory for %zu parts", n);
    }
    b->p = p;
    b->dim = dim;
    b->n = n;
    b->mem = mem;
    double **arr[NARR] = {&b->ax, &b->ay, &b->bx, &b->by, &b->nx, &b->ny, &b->hid, &b->hid2,
                          &b->az, &b->bz, &b->nz, &b->mx, &b->my, &b->mz,
                          &b->ex, &b->ey, &b->ez};
    for (int j = 0; j < NARR; j++) *arr[j] = mem + (size_t)j * n;
    b->ref = *ref;
    b->fb = &b->ref;
    *out = b;
    return DFL_OK;
}

/* ---- from a field -------------------------------------------------------- */

/* The built-in kernels' cases: R-equivalence of point parts only, of
 * convex regions only, of triangles only (one eq. 4 trim), or of 2D or 3D
 * segments, all with the same eq. 4 trim (disk or strip), forming a chain
 * (segment k starts exactly where k-1 ends).  Then the segments are those
 * of the open polyline a_0, ..., a_{n-1}, b_{n-1} (a closed polyline is
 * the open one with b_{n-1} = a_0, and the R-equivalence ignores the
 * vertices), which the batch is built from: NULL (no error) when the
 * field is not eligible, or when the polyline checks of the batch's
 * reference field reject the chain (segments added one by one may
 * backtrack). */
static dfl_status try_builtin(const dfl_rfunc_batch_desc *f, dfl_rfunc_batch **out, dfl_err *err)
{
    *out = NULL;
    if (f->join != DFL_RFUNC_REQUIV || f->n < 2) return DFL_OK;
    const int dim = f->dim;
    size_t npt = 0, ntri = 0, nreg = 0;
    for (size_t k = 0; k < f->n; k++) {
        npt += f->parts[k].kind == DFL_RFUNC_PART_POINT;
        ntri += f->parts[k].kind == DFL_RFUNC_PART_TRIANGLE;
        nreg += f->parts[k].kind == DFL_RFUNC_PART_REGION;
    }
    if (nreg == f->n) {
        /* only convex regions: the region kernel */
        dfl_rfunc_region *rg = malloc(f->n * sizeof *rg);
        if (!rg) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
        for (size_t k = 0; k < f->n; k++) rg[k] = f->parts[k].u.reg;
        dfl_status st = dfl_rfunc_batch_regions(rg, f->n, f->p, out, err);
        free(rg);
        return st;
    }
    if (ntri == f->n) {
        /* only triangles: the triangle kernel, when their trims allow */
        dfl_rfunc_tri *t = malloc(f->n * sizeof *t);
        if (!t) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
        for (size_t k = 0; k < f->n; k++) t[k] = f->parts[k].u.tri;
        dfl_err e2;
        dfl_status st = dfl_rfunc_batch_triangles(t, f->n, f->p, out, &e2);
        free(t);
        if (st == DFL_E_INPUT) {
            *out = NULL;
            return DFL_OK;
        }
        if (st != DFL_OK) *err = e2;
        return st;
    }
    if (npt == f->n) {
        /* only points: the point kernel */
        double *c = malloc((size_t)dim * f->n * sizeof *c);
        if (!c) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
        for (size_t k = 0; k < f->n; k++)
            memcpy(c + (size_t)dim * k, f->parts[k].u.pt.c, (size_t)dim * sizeof *c);
        dfl_status st = dfl_rfunc_batch_points(dim, c, f->n, f->p, out, err);
        free(c);
        return st;
    }
    const dfl_rfunc_trim trim = f->parts[0].u.seg.trim;
    if (f->parts[0].kind != DFL_RFUNC_PART_SEGMENT ||
        (trim != DFL_RFUNC_TRIM_DISK && trim != DFL_RFUNC_TRIM_STRIP))
        return DFL_OK;
    for (size_t k = 0; k < f->n; k++) {
        const dfl_rfunc_part *pt = &f->parts[k];
        if (pt->kind != DFL_RFUNC_PART_SEGMENT || pt->u.seg.trim != trim) return DFL_OK;
        if (k > 0) {
            const double *e = f->parts[k - 1].u.seg.b, *a = pt->u.seg.a;
            for (int j = 0; j < dim; j++)
                if (e[j] != a[j]) return DFL_OK;
        }
    }
    const size_t d = (size_t)dim;
    double *v = malloc(d * (f->n + 1) * sizeof *v);
    if (!v) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    for (size_t k = 0; k < f->n; k++) memcpy(v + d * k, f->parts[k].u.seg.a, d * sizeof *v);
    memcpy(v + d * f->n, f->parts[f->n - 1].u.seg.b, d * sizeof *v);
    dfl_err e2;
    dfl_status st = dfl_rfunc_batch_new_opts(dim, v, f->n + 1, false, f->p, trim, out, &e2);
    free(v);
    if (st == DFL_E_INPUT) {
        *out = NULL;
        return DFL_OK;
    }
    if (st != DFL_OK) *err = e2;
    return st;
}

typedef dfl_status (*try_fn)(const dfl_rfunc_batch_desc *d, dfl_rfunc_batch **out, dfl_err *err);

dfl_status dfl_rfunc_batch_build(const dfl_rfunc_batch_desc *d, dfl_rfunc_batch **out,
                                 dfl_err *err)
{
    /* In order: the first kind that takes the field computes it. */
    static const try_fn tries[] = {try_builtin, dfl_rfunc_batch_try_smooth,
                                   dfl_rfunc_batch_try_rconj, dfl_rfunc_batch_try_corrected,
                                   dfl_rfunc_batch_try_mixed};
    *out = NULL;
    if (d->n < 2) return DFL_OK;
    for (size_t i = 0; i < sizeof tries / sizeof tries[0]; i++) {
        dfl_status st = tries[i](d, out, err);
        if (st != DFL_OK) {
            dfl_rfunc_batch_free(*out);
            *out = NULL;
            return st;
        }
        if (*out) return DFL_OK;
    }
    return DFL_OK;
}

void dfl_rfunc_batch_free(dfl_rfunc_batch *b)
{
    if (!b) return;
    if (b->kd_free) b->kd_free(b->kd);
    dfl_field_destroy(&b->ref);
    free(b->mem);
    free(b);
}

size_t dfl_rfunc_batch_segments(const dfl_rfunc_batch *b) { return b->n; }
int dfl_rfunc_batch_order(const dfl_rfunc_batch *b) { return b->p; }
const dfl_field *dfl_rfunc_batch_reference(const dfl_rfunc_batch *b) { return b->fb; }

/* ---- as a field ---------------------------------------------------------- */

static void field_eval(const void *ctx, size_t m, const double *pts, double *val, double *grad)
{
    dfl_rfunc_batch_eval(ctx, m, pts, val, grad);
}

static dfl_status field_jet(const void *ctx, const double *x, const double *dir, int K,
                            dfl_jet *out, dfl_err *err)
{
    const dfl_rfunc_batch *b = ctx;
    return dfl_field_jet(b->fb, x, dir, K, out, err);
}

static void field_destroy(void *ctx) { dfl_rfunc_batch_free(ctx); }

/* Stored: the segments' end points (everything else is derived from them). */
static size_t field_bytes(const void *ctx)
{
    const dfl_rfunc_batch *b = ctx;
    return b->n * 2 * (size_t)b->dim * sizeof(double);
}

static const dfl_field_ops batch_ops = {"rfunc_batch", field_eval, field_jet, field_destroy,
                                        field_bytes};

dfl_status dfl_rfunc_batch_field(const double *v, size_t n, bool closed, int p, dfl_field *out,
                                 dfl_err *err)
{
    dfl_rfunc_batch *b;
    dfl_status st = dfl_rfunc_batch_new(v, n, closed, p, &b, err);
    if (st != DFL_OK) return st;
    out->dim = b->dim;
    out->ops = &batch_ops;
    out->ctx = b;
    return DFL_OK;
}
