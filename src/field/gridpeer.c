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
        f[a] = n >= 2 ? t - fl : 0.0;
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

/* The evaluation loop, compiled per ISA (core/isa.h): same bytes on each. */
DFL_ISA_BODY void points_body(const void *ctx, size_t m, const double *pts, double *val,
                              double *grad)
{
    const gridpeer *g = ctx;
    if (g->kind == DFL_GRIDPEER_TRILINEAR0) {
        for (size_t i = 0; i < m; i++)
            eval_trilinear(g, pts + 3 * i, val + i, grad ? grad + 3 * i : NULL);
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
#pragma omp parallel for schedule(static) num_threads(threads) reduction(min : bad) \
    if (cells > 4096)
    for (long c = 0; c < (long)cells; c++) {
        const int i = (int)(c % n), j = (int)((c / n) % n), k = (int)(c / ((long)n * n));
        const double x[3] = {g->lo[0] + (i + 0.5) * g->h[0], g->lo[1] + (j + 0.5) * g->h[1],
                             g->lo[2] + (k + 0.5) * g->h[2]};
        if (!sample_cell(shape, g, o->storage, x, g->data + (size_t)c * (size_t)g->stride))
            if (c < bad) bad = c;
    }
    if (bad != LONG_MAX) {
        gridpeer_destroy(g);
        return dfl_err_set(err, o->storage == DFL_GRIDPEER_FLOAT16 ? DFL_E_INPUT : DFL_E_NUMERIC,
                           "grid peer: cell %ld: a sample is not finite%s", bad,
                           o->storage == DFL_GRIDPEER_FLOAT16 ? " or overflows a half" : "");
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
