#include "field/gridpeer.h"

#include <math.h>
#include <stdlib.h>
#include <limits.h>
#include <string.h>

#include <Imath/half.h>
#include <omp.h>

#include "core/isa.h"

DFL_NAMES_DEFINE(dfl_gridpeer_kind, DFL_GRIDPEER_KIND_LIST, DFL_GRIDPEER_KIND_COUNT,
                 dfl_gridpeer_kind_names, dfl_gridpeer_kind_name, dfl_gridpeer_kind_parse,
                 "grid peer kind")
DFL_NAMES_DEFINE(dfl_gridpeer_storage, DFL_GRIDPEER_STORAGE_LIST, DFL_GRIDPEER_STORAGE_COUNT,
                 dfl_gridpeer_storage_names, dfl_gridpeer_storage_name,
                 dfl_gridpeer_storage_parse, "grid peer storage")

#define X_SCALARS(code, name, k) [code] = k,
static const int kind_scalars[DFL_GRIDPEER_KIND_COUNT] = {DFL_GRIDPEER_KIND_LIST(X_SCALARS)};
#undef X_SCALARS

/* The decoded scalars are kept as doubles even for float16 storage: each
 * is the half's exact value, so decoding equals decoding from the halves
 * (what is stored decides the error; the byte count is reported apart). */
typedef struct gridpeer {
    dfl_gridpeer_opts opts;  /* as built (threads as given) */
    dfl_gridpeer_kind kind;
    int n, stride;
    double lo[3], h[3];
    double *data;   /* n^3 cells x stride, cell index i + n (j + n k) */
    /* tricubic: the (n + 2)^3 coefficients with the ghosts the stored ones
     * determine (not-a-knot), index (i + 1) + (n + 2) ((j + 1) + (n + 2)
     * (k + 1)) for i, j, k in -1 .. n; NULL for the other kinds */
    double *ext;
} gridpeer;

size_t dfl_gridpeer_scalars(dfl_gridpeer_kind kind, int n)
{
    return (size_t)n * (size_t)n * (size_t)n * (size_t)kind_scalars[kind];
}

/* Cell index along one axis of the cell holding x (clamped into the box). */
DFL_ISA_BODY int cell_of(const gridpeer *g, int a, double x)
{
    double t = floor((x - g->lo[a]) / g->h[a]);
    if (!(t >= 0.0)) return 0;  /* also NaN: decodes cell 0, the value stays NaN */
    if (t > g->n - 1) return g->n - 1;
    return (int)t;
}

DFL_ISA_BODY void eval_taylor(const gridpeer *g, const double *x, double *val, double *grad)
{
    const int n = g->n;
    int c[3];
    double r[3];
    for (int a = 0; a < 3; a++) {
        c[a] = cell_of(g, a, x[a]);
        r[a] = x[a] - (g->lo[a] + (c[a] + 0.5) * g->h[a]);
    }
    const double *s = g->data + (size_t)g->stride * ((size_t)c[0] + (size_t)n * ((size_t)c[1] +
                                                                              (size_t)n * c[2]));
    double gr[3] = {s[1], s[2], s[3]};
    double u = s[0] + s[1] * r[0] + s[2] * r[1] + s[3] * r[2];
    if (g->kind == DFL_GRIDPEER_TAYLOR2) {
        /* s[4..9] = Hxx Hxy Hxz Hyy Hyz Hzz */
        const double Hr[3] = {s[4] * r[0] + s[5] * r[1] + s[6] * r[2],
                              s[5] * r[0] + s[7] * r[1] + s[8] * r[2],
                              s[6] * r[0] + s[8] * r[1] + s[9] * r[2]};
        u += 0.5 * (r[0] * Hr[0] + r[1] * Hr[1] + r[2] * Hr[2]);
        for (int a = 0; a < 3; a++) gr[a] += Hr[a];
    }
    *val = u;
    if (grad) memcpy(grad, gr, sizeof gr);
}

DFL_ISA_BODY void eval_trilinear(const gridpeer *g, const double *x, double *val, double *grad)
{
    const int n = g->n;
    int i0[3];
    double f[3];
    for (int a = 0; a < 3; a++) {
        const double t = (x[a] - g->lo[a]) / g->h[a] - 0.5;
        double fl = floor(t);
        if (!(fl >= 0.0)) fl = 0.0;  /* also NaN: the value stays NaN through f */
        if (fl > n - 2) fl = n >= 2 ? n - 2 : 0;
        i0[a] = (int)fl;
        f[a] = n >= 2 ? t - fl : isnan(t) ? t : 0.0; /* one cell: a constant, NaN for NaN */
    }
    const int s1 = n >= 2 ? 1 : 0;
    double v[8];
    for (int k = 0; k < 8; k++) {
        const size_t ix = (size_t)(i0[0] + (k & 1 ? s1 : 0)),
                     iy = (size_t)(i0[1] + (k & 2 ? s1 : 0)),
                     iz = (size_t)(i0[2] + (k & 4 ? s1 : 0));
        v[k] = g->data[ix + (size_t)n * (iy + (size_t)n * iz)];
    }
    const double x00 = v[0] + f[0] * (v[1] - v[0]), x10 = v[2] + f[0] * (v[3] - v[2]),
                 x01 = v[4] + f[0] * (v[5] - v[4]), x11 = v[6] + f[0] * (v[7] - v[6]);
    const double y0 = x00 + f[1] * (x10 - x00), y1 = x01 + f[1] * (x11 - x01);
    *val = y0 + f[2] * (y1 - y0);
    if (!grad) return;
    /* d/df of the trilinear form per axis, then d f / dx = 1/h. */
    double dfx = 0, dfy = 0, dfz = 0;
    for (int k = 0; k < 8; k++) {
        const double wx = k & 1 ? f[0] : 1 - f[0], wy = k & 2 ? f[1] : 1 - f[1],
                     wz = k & 4 ? f[2] : 1 - f[2];
        dfx += (k & 1 ? 1.0 : -1.0) * wy * wz * v[k];
        dfy += (k & 2 ? 1.0 : -1.0) * wx * wz * v[k];
        dfz += (k & 4 ? 1.0 : -1.0) * wx * wy * v[k];
    }
    grad[0] = n >= 2 ? dfx / g->h[0] : 0.0;
    grad[1] = n >= 2 ? dfy / g->h[1] : 0.0;
    grad[2] = n >= 2 ? dfz / g->h[2] : 0.0;
}

/* The uniform cubic B-spline weights of the piece at local u (u in [0, 1]
 * on the piece, beyond it when extrapolating) and their derivatives in u. */
DFL_ISA_BODY void bspline_weights(double u, double *w, double *dw)
{
    const double v = 1.0 - u, u2 = u * u, u3 = u2 * u;
    w[0] = v * v * v / 6.0;
    w[1] = (3.0 * u3 - 6.0 * u2 + 4.0) / 6.0;
    w[2] = (-3.0 * u3 + 3.0 * u2 + 3.0 * u + 1.0) / 6.0;
    w[3] = u3 / 6.0;
    dw[0] = -0.5 * v * v;
    dw[1] = 0.5 * (3.0 * u2 - 4.0 * u);
    dw[2] = 0.5 * (-3.0 * u2 + 2.0 * u + 1.0);
    dw[3] = 0.5 * u2;
}

/* The tensor spline at x: per axis the piece between centres i and i + 1
 * (i clamped to 0 .. n - 2: the end pieces extend over the outer half
 * cells and beyond the box), its 4^3 extended coefficients contracted
 * axis by axis. */
DFL_ISA_BODY void eval_tricubic(const gridpeer *g, const double *x, double *val, double *grad)
{
    const int n = g->n;
    const size_t m = (size_t)n + 2;
    int i0[3];
    double w[3][4], dw[3][4];
    for (int a = 0; a < 3; a++) {
        const double t = (x[a] - g->lo[a]) / g->h[a] - 0.5;
        double fl = floor(t);
        if (!(fl >= 0.0)) fl = 0.0;  /* also NaN: the value stays NaN through u */
        if (fl > n - 2) fl = n - 2;
        i0[a] = (int)fl;
        bspline_weights(t - fl, w[a], dw[a]);
    }
    /* ext index of coefficient i0 - 1 + a is i0 + a */
    const double *c0 = g->ext + (size_t)i0[0] + m * ((size_t)i0[1] + m * (size_t)i0[2]);
    double v = 0, gx = 0, gy = 0, gz = 0;
    for (int c = 0; c < 4; c++) {
        double sy = 0, sdx = 0, sdy = 0;
        for (int b = 0; b < 4; b++) {
            const double *r = c0 + m * ((size_t)b + m * (size_t)c);
            const double sx = w[0][0] * r[0] + w[0][1] * r[1] + w[0][2] * r[2] + w[0][3] * r[3];
            const double dx =
                dw[0][0] * r[0] + dw[0][1] * r[1] + dw[0][2] * r[2] + dw[0][3] * r[3];
            sy += w[1][b] * sx;
            sdx += w[1][b] * dx;
            sdy += dw[1][b] * sx;
        }
        v += w[2][c] * sy;
        gx += w[2][c] * sdx;
        gy += w[2][c] * sdy;
        gz += dw[2][c] * sy;
    }
    *val = v;
    if (!grad) return;
    grad[0] = gx / g->h[0];
    grad[1] = gy / g->h[1];
    grad[2] = gz / g->h[2];
}

/* The evaluation loop, compiled per ISA (core/isa.h): same bytes on each. */
DFL_ISA_BODY void points_body(const void *ctx, size_t m, const double *pts, double *val,
                              double *grad)
{
    const gridpeer *g = ctx;
    if (g->kind == DFL_GRIDPEER_TRILINEAR0) {
        for (size_t i = 0; i < m; i++)
            eval_trilinear(g, pts + 3 * i, val + i, grad ? grad + 3 * i : NULL);
    } else if (g->kind == DFL_GRIDPEER_TRICUBIC) {
        for (size_t i = 0; i < m; i++)
            eval_tricubic(g, pts + 3 * i, val + i, grad ? grad + 3 * i : NULL);
    } else {
        for (size_t i = 0; i < m; i++)
            eval_taylor(g, pts + 3 * i, val + i, grad ? grad + 3 * i : NULL);
    }
}
DFL_ISA_KERNEL(points,
               (const void *ctx, size_t m, const double *pts, double *val, double *grad),
               (ctx, m, pts, val, grad))

static void gridpeer_eval(const void *ctx, size_t m, const double *pts, double *val, double *grad)
{
    points(ctx, m, pts, val, grad);
}

static void gridpeer_destroy(void *ctx)
{
    gridpeer *g = ctx;
    free(g->data);
    free(g->ext);
    free(g);
}

/* Stored: the scalars in their storage (float16: 2 bytes each, although
 * the decoder keeps their exact values as doubles). */
static size_t gridpeer_bytes(const void *ctx)
{
    const gridpeer *g = ctx;
    const size_t each = g->opts.storage == DFL_GRIDPEER_FLOAT16 ? 2 : 8;
    return dfl_gridpeer_scalars(g->kind, g->n) * each;
}

static const dfl_field_ops gridpeer_ops = {"gridpeer", gridpeer_eval, NULL, gridpeer_destroy,
                                           gridpeer_bytes};

/* Rounds v to the storage; 0 when it does not fit (a half overflows). */
static int store(dfl_gridpeer_storage st, double v, double *out)
{
    if (st == DFL_GRIDPEER_FLOAT64) {
        *out = v;
        return 1;
    }
    const float h = imath_half_to_float(imath_float_to_half((float)v));
    *out = h;
    return isfinite(h);
}

/* The samples of one cell centre x into s[0..stride-1]; 0 on a non-finite
 * or unstorable sample or a failed jet. */
static int sample_cell(const dfl_shape *shape, const gridpeer *g, dfl_gridpeer_storage st,
                       const double *x, double *s)
{
    double raw[10];
    if (g->kind == DFL_GRIDPEER_TAYLOR2) {
        dfl_shape_derivs d;
        if (dfl_shape_derivs_at(shape, x, &d, NULL) != DFL_OK) return 0;
        raw[0] = d.d;
        memcpy(raw + 1, d.g, 3 * sizeof *raw);
        raw[4] = d.H[0], raw[5] = d.H[1], raw[6] = d.H[2];
        raw[7] = d.H[4], raw[8] = d.H[5], raw[9] = d.H[8];
    } else {
        dfl_shape_eval(shape, 1, x, raw, raw + 1);
    }
    for (int j = 0; j < g->stride; j++)
        if (!isfinite(raw[j]) || !store(st, raw[j], s + j)) return 0;
    return 1;
}

/* Not-a-knot prefilter of one line of n >= 4 samples f[k * stride] into
 * the coefficients c_k (in place): the c_k with c_{k-1} + 4 c_k + c_{k+1}
 * = 6 f_k for k = 0 .. n - 1, the ghosts c_{-1}, c_n given by the fourth
 * differences c_{-1} - 4 c_0 + 6 c_1 - 4 c_2 + c_3 = 0 (and its mirror).
 * Eliminating the ghost from row 0 and combining rows 0, 1, 2 leaves
 * c_1 = (8 f_1 - f_0 - f_2) / 6 (one cubic through f_0, f_1, f_2 has
 * second derivative f_0 - 2 f_1 + f_2 at centre 1, and c = f - f'' / 6
 * there); likewise c_{n-2}.  Rows 2 .. n - 3 are then a strictly diagonally
 * dominant tridiagonal system in c_2 .. c_{n-3} (Thomas' algorithm, no
 * pivoting needed), and rows 1, n - 2 give c_0, c_{n-1}.  work: 3n doubles. */
static void prefilter_line(int n, double *f, size_t stride, double *work)
{
    double *in = work, *c = work + n, *cp = work + 2 * (size_t)n;
    for (int k = 0; k < n; k++) in[k] = f[(size_t)k * stride];
    c[1] = (8.0 * in[1] - in[0] - in[2]) / 6.0;
    c[n - 2] = (8.0 * in[n - 2] - in[n - 3] - in[n - 1]) / 6.0;
    /* forward sweep over rows 2 .. n - 3 (none for n = 4); c holds the
     * swept right-hand sides until the back substitution */
    for (int k = 2; k <= n - 3; k++) {
        double d = 6.0 * in[k];
        if (k == 2) d -= c[1];
        if (k == n - 3) d -= c[n - 2];
        const double den = k == 2 ? 4.0 : 4.0 - cp[k - 1];
        cp[k] = 1.0 / den;
        c[k] = (k == 2 ? d : d - c[k - 1]) / den;
    }
    for (int k = n - 4; k >= 2; k--) c[k] -= cp[k] * c[k + 1];
    c[0] = 6.0 * in[1] - 4.0 * c[1] - c[2];
    c[n - 1] = 6.0 * in[n - 2] - 4.0 * c[n - 2] - c[n - 3];
    for (int k = 0; k < n; k++) f[(size_t)k * stride] = c[k];
}

/* The not-a-knot prefilter of the n^3 samples in data, in place, along
 * each axis in turn (the tensor interpolant: the per-axis operators
 * commute).  Lines are independent, so the result does not depend on the
 * thread count.  0 when out of memory. */
static int prefilter(double *data, int n, int threads)
{
    const size_t nn = (size_t)n * (size_t)n;
    const size_t strides[3] = {1, (size_t)n, nn};
    double *work = malloc((size_t)threads * 3 * (size_t)n * sizeof *work);
    if (!work) return 0;
    for (int a = 0; a < 3; a++) {
#pragma omp parallel for schedule(static) num_threads(threads) if (nn > 64)
        for (long l = 0; l < (long)nn; l++) {
            /* the line's first sample: the two other axes' indices */
            const size_t p = (size_t)l % (size_t)n, q = (size_t)l / (size_t)n;
            const size_t start = a == 0 ? p * n + q * nn : a == 1 ? p + q * nn : p + q * n;
            prefilter_line(n, data + start, strides[a],
                           work + (size_t)omp_get_thread_num() * 3 * (size_t)n);
        }
    }
    free(work);
    return 1;
}

/* The tricubic coefficients from the samples in g->data: prefiltered, each
 * rounded to the storage (in place: g->data then holds what is stored),
 * and the extended array with the not-a-knot ghosts of the stored ones. */
static dfl_status tricubic_coeffs(gridpeer *g, dfl_gridpeer_storage st, int threads,
                                  dfl_err *err)
{
    const int n = g->n;
    const size_t cells = (size_t)n * (size_t)n * (size_t)n, m = (size_t)n + 2;
    if (!prefilter(g->data, n, threads))
        return dfl_err_set(err, DFL_E_NOMEM, "grid peer: out of memory for the prefilter");
    for (size_t c = 0; c < cells; c++) {
        const double v = g->data[c];
        if (!isfinite(v))
            return dfl_err_set(err, DFL_E_NUMERIC, "grid peer: coefficient %zu is not finite", c);
        if (!store(st, v, g->data + c))
            return dfl_err_set(err, DFL_E_INPUT, "grid peer: coefficient %zu overflows a half",
                               c);
    }
    g->ext = malloc(m * m * m * sizeof *g->ext);
    if (!g->ext) return dfl_err_set(err, DFL_E_NOMEM, "grid peer: out of memory for %zu cells", cells);
    double *e = g->ext;
    for (size_t k = 0; k < (size_t)n; k++)
        for (size_t j = 0; j < (size_t)n; j++)
            memcpy(e + 1 + m * (j + 1 + m * (k + 1)), g->data + (size_t)n * (j + (size_t)n * k),
                   (size_t)n * sizeof *e);
    /* ghosts axis by axis, each from the (already extended) lines of the
     * previous axes, so edges and corners are the tensor rule's too:
     * c_{-1} = 4 c_0 - 6 c_1 + 4 c_2 - c_3, c_n = 4 c_{n-1} - 6 c_{n-2} +
     * 4 c_{n-3} - c_{n-4} */
    const size_t stride[3] = {1, m, m * m};
    for (int a = 0; a < 3; a++) {
        /* the other two axes b < c: those before a are extended already
         * (indices 0 .. m - 1), those after a not yet (1 .. m - 2) */
        const int b = a == 0 ? 1 : 0, c = a == 2 ? 1 : 2;
        const size_t s = stride[a];
        for (size_t v = c > a; v < m - (c > a); v++)
            for (size_t u = b > a; u < m - (b > a); u++) {
                double *l = e + u * stride[b] + v * stride[c];
                l[0] = 4.0 * l[s] - 6.0 * l[2 * s] + 4.0 * l[3 * s] - l[4 * s];
                l[(m - 1) * s] = 4.0 * l[(m - 2) * s] - 6.0 * l[(m - 3) * s] +
                                 4.0 * l[(m - 4) * s] - l[(m - 5) * s];
            }
    }
    return DFL_OK;
}

static dfl_status check_opts(const dfl_shape *shape, const dfl_gridpeer_opts *o, dfl_err *err)
{
    if (!shape || !shape->ops || shape->dim != 3)
        return dfl_err_set(err, DFL_E_INPUT, "grid peer: a 3D shape is required");
    if ((int)o->kind < 0 || (int)o->kind >= DFL_GRIDPEER_KIND_COUNT || (int)o->storage < 0 ||
        (int)o->storage >= DFL_GRIDPEER_STORAGE_COUNT)
        return dfl_err_set(err, DFL_E_INPUT, "grid peer: unknown kind or storage");
    if (o->n < 1 || o->n > 1024)
        return dfl_err_set(err, DFL_E_INPUT, "grid peer: expected 1 <= n <= 1024, got %d", o->n);
    for (int a = 0; a < 3; a++)
        if (!(isfinite(o->lo[a]) && isfinite(o->hi[a]) && o->lo[a] < o->hi[a]))
            return dfl_err_set(err, DFL_E_INPUT, "grid peer: expected lo < hi on axis %d", a);
    if (o->kind == DFL_GRIDPEER_TAYLOR2 && !shape->ops->jet)
        return dfl_err_set(err, DFL_E_INPUT,
                           "grid peer: taylor2 needs the Hessian, and shape '%s' has no jets",
                           shape->ops->kind);
    if (o->kind == DFL_GRIDPEER_TRICUBIC && o->n < 4)
        return dfl_err_set(err, DFL_E_INPUT,
                           "grid peer: tricubic needs n >= 4 (its not-a-knot ends), got %d",
                           o->n);
    return DFL_OK;
}

dfl_status dfl_gridpeer_new(const dfl_shape *shape, const dfl_gridpeer_opts *o, dfl_field *out,
                            dfl_err *err)
{
    dfl_status st = check_opts(shape, o, err);
    if (st != DFL_OK) return st;
    gridpeer *g = calloc(1, sizeof *g);
    if (!g) return dfl_err_set(err, DFL_E_NOMEM, "grid peer: out of memory");
    g->opts = *o;
    g->kind = o->kind;
    g->n = o->n;
    g->stride = kind_scalars[o->kind];
    for (int a = 0; a < 3; a++) {
        g->lo[a] = o->lo[a];
        g->h[a] = (o->hi[a] - o->lo[a]) / o->n;
    }
    const size_t cells = (size_t)o->n * (size_t)o->n * (size_t)o->n;
    g->data = malloc(cells * (size_t)g->stride * sizeof *g->data);
    if (!g->data) {
        free(g);
        return dfl_err_set(err, DFL_E_NOMEM, "grid peer: out of memory for %zu cells", cells);
    }
    long bad = LONG_MAX; /* the smallest failing cell: the message is thread-count independent */
    const int n = o->n;
    const int threads = o->threads > 0 ? o->threads : omp_get_max_threads();
    /* tricubic rounds its coefficients, not its samples */
    const dfl_gridpeer_storage sample_st =
        o->kind == DFL_GRIDPEER_TRICUBIC ? DFL_GRIDPEER_FLOAT64 : o->storage;
#pragma omp parallel for schedule(static) num_threads(threads) reduction(min : bad) \
    if (cells > 4096)
    for (long c = 0; c < (long)cells; c++) {
        const int i = (int)(c % n), j = (int)((c / n) % n), k = (int)(c / ((long)n * n));
        const double x[3] = {g->lo[0] + (i + 0.5) * g->h[0], g->lo[1] + (j + 0.5) * g->h[1],
                             g->lo[2] + (k + 0.5) * g->h[2]};
        if (!sample_cell(shape, g, sample_st, x, g->data + (size_t)c * (size_t)g->stride))
            if (c < bad) bad = c;
    }
    if (bad != LONG_MAX) {
        gridpeer_destroy(g);
        return dfl_err_set(err, sample_st == DFL_GRIDPEER_FLOAT16 ? DFL_E_INPUT : DFL_E_NUMERIC,
                           "grid peer: cell %ld: a sample is not finite%s", bad,
                           sample_st == DFL_GRIDPEER_FLOAT16 ? " or overflows a half" : "");
    }
    if (o->kind == DFL_GRIDPEER_TRICUBIC && (st = tricubic_coeffs(g, o->storage, threads, err))) {
        gridpeer_destroy(g);
        return st;
    }
    out->dim = 3;
    out->ops = &gridpeer_ops;
    out->ctx = g;
    return DFL_OK;
}

int dfl_gridpeer_field_info(const dfl_field *f, dfl_gridpeer_opts *out)
{
    if (!f || f->ops != &gridpeer_ops) return 0;
    *out = ((const gridpeer *)f->ctx)->opts;
    return 1;
}

const double *dfl_gridpeer_stored(const dfl_field *f, size_t *count)
{
    if (!f || f->ops != &gridpeer_ops) return NULL;
    const gridpeer *g = f->ctx;
    *count = dfl_gridpeer_scalars(g->kind, g->n);
    return g->data;
}
