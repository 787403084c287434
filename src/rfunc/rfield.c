#include "rfunc/rfield.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/hypot.h"
#include "rfunc/batch.h"
#include "rfunc/domain.h"
#include "rfunc/part.h"
#include "rfunc/region.h"
#include "rfunc/trim.h"

typedef dfl_rfunc_part part;
typedef dfl_rfunc_vertex vertex;

struct dfl_rfield {
    int dim;
    dfl_rfunc_join join;
    int p;
    part *parts;
    size_t n, cap;
    vertex *verts;  /* sorted by hi at finish */
    size_t nv, vcap;
    size_t *vstart; /* n + 1 offsets into verts by hi (after finish) */
    dfl_rfunc_correction corr; /* corrected join: guarded (default) or eq20 */
    double span;           /* max |coordinate| of the parts (domain.h) */
    bool fast;             /* builder option: use the batch evaluator if eligible */
    dfl_rfunc_batch *batch; /* eval's fast path (after finish), or NULL */
    dfl_field slow;         /* the per-point path as a field (ctx = this field, no destroy):
                               the batch's fallback and reference */
};

dfl_status dfl_rfield_new(int dim, dfl_rfunc_join join, int p, dfl_rfield **out, dfl_err *err)
{
    if (dim != 2 && dim != 3)
        return dfl_err_set(err, DFL_E_INPUT, "rfunc field: dimension %d (expected 2 or 3)", dim);
    dfl_status st = dfl_rfunc_join_check(join, p, err);
    if (st != DFL_OK) return st;
    dfl_rfield *r = calloc(1, sizeof *r);
    if (!r) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    r->dim = dim;
    r->join = join;
    r->p = p;
    r->fast = true;
    *out = r;
    return DFL_OK;
}

void dfl_rfield_free(dfl_rfield *r)
{
    if (!r) return;
    for (size_t i = 0; i < r->n; i++)
        if (r->parts[i].kind == DFL_RFUNC_PART_REGION) dfl_rfunc_region_free(&r->parts[i].u.reg);
    free(r->parts);
    free(r->verts);
    free(r->vstart);
    dfl_rfunc_batch_free(r->batch);
    free(r);
}

size_t dfl_rfield_count(const dfl_rfield *r) { return r->n; }

void dfl_rfield_set_fast(dfl_rfield *r, bool on) { r->fast = on; }

void dfl_rfield_set_correction(dfl_rfield *r, dfl_rfunc_correction corr) { r->corr = corr; }

/* The part's coordinates against the domain (domain.h); the span grows. */
static dfl_status take_coords(dfl_rfield *r, const double *x, size_t npts, const char *what,
                              dfl_err *err)
{
    for (size_t i = 0; i < npts; i++) {
        const double *xi = x + i * (size_t)r->dim;
        dfl_status st = dfl_rfunc_domain_coords(r->dim, xi, what, err);
        if (st != DFL_OK) return st;
        for (int j = 0; j < r->dim; j++) r->span = fmax(r->span, fabs(xi[j]));
    }
    return DFL_OK;
}

/* arr (n elements of size bytes, room for *cap) with room for one more:
 * doubled capacity (16 at first) when full.  NULL when out of memory (arr
 * and *cap unchanged). */
static void *grow(void *arr, size_t n, size_t *cap, size_t size)
{
    if (n < *cap) return arr;
    const size_t c = *cap ? 2 * *cap : 16;
    void *p = realloc(arr, c * size);
    if (p) *cap = c;
    return p;
}

static dfl_status push(dfl_rfield *r, const part *pt, dfl_err *err)
{
    part *np = grow(r->parts, r->n, &r->cap, sizeof *np);
    if (!np) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    r->parts = np;
    r->parts[r->n++] = *pt;
    return DFL_OK;
}

dfl_status dfl_rfield_add_segment(dfl_rfield *r, const double *a, const double *b,
                                  dfl_rfunc_trim trim, dfl_err *err)
{
    part pt;
    memset(&pt, 0, sizeof pt);
    pt.kind = DFL_RFUNC_PART_SEGMENT;
    dfl_status st = take_coords(r, a, 1, "segment end point", err);
    if (st == DFL_OK) st = take_coords(r, b, 1, "segment end point", err);
    if (st == DFL_OK) st = dfl_rfunc_seg_init(r->dim, a, b, trim, &pt.u.seg, err);
    if (st != DFL_OK) return st;
    return push(r, &pt, err);
}

dfl_status dfl_rfield_add_triangle(dfl_rfield *r, const double *A, const double *B,
                                   const double *C, const dfl_rfunc_tri_opts *o, dfl_err *err)
{
    if (r->dim != 3)
        return dfl_err_set(err, DFL_E_INPUT, "rfunc field: triangles need dimension 3");
    part pt;
    memset(&pt, 0, sizeof pt);
    pt.kind = DFL_RFUNC_PART_TRIANGLE;
    dfl_status st = take_coords(r, A, 1, "triangle corner", err);
    if (st == DFL_OK) st = take_coords(r, B, 1, "triangle corner", err);
    if (st == DFL_OK) st = take_coords(r, C, 1, "triangle corner", err);
    if (st == DFL_OK) st = dfl_rfunc_tri_init(A, B, C, o, &pt.u.tri, err);
    if (st != DFL_OK) return st;
    return push(r, &pt, err);
}

dfl_status dfl_rfield_add_point(dfl_rfield *r, const double *c, dfl_err *err)
{
    part pt;
    memset(&pt, 0, sizeof pt);
    pt.kind = DFL_RFUNC_PART_POINT;
    dfl_status st = take_coords(r, c, 1, "point part", err);
    if (st == DFL_OK) st = dfl_rfunc_point_init(r->dim, c, &pt.u.pt, err);
    if (st != DFL_OK) return st;
    return push(r, &pt, err);
}

dfl_status dfl_rfield_add_region(dfl_rfield *r, const double *v, size_t n, dfl_err *err)
{
    if (r->dim != 2)
        return dfl_err_set(err, DFL_E_INPUT, "rfunc field: polygon regions need dimension 2");
    part pt;
    memset(&pt, 0, sizeof pt);
    pt.kind = DFL_RFUNC_PART_REGION;
    dfl_status st = take_coords(r, v, n, "region vertex", err);
    if (st != DFL_OK) return st;
    st = dfl_rfunc_region_init(v, n, &pt.u.reg, err);
    if (st != DFL_OK) return st;
    st = push(r, &pt, err);
    if (st != DFL_OK) dfl_rfunc_region_free(&pt.u.reg);
    return st;
}

dfl_status dfl_rfield_add_vertex(dfl_rfield *r, const double *v, size_t i, size_t j,
                                 dfl_err *err)
{
    vertex vx;
    memset(&vx, 0, sizeof vx);
    for (int k = 0; k < r->dim; k++) {
        if (!isfinite(v[k])) return dfl_err_set(err, DFL_E_INPUT, "vertex: non-finite coordinate");
        vx.x[k] = v[k];
    }
    if (i == j) return dfl_err_set(err, DFL_E_INPUT, "vertex: adjacent parts must differ");
    vx.lo = i < j ? i : j;
    vx.hi = i < j ? j : i;
    vertex *nv = grow(r->verts, r->nv, &r->vcap, sizeof *nv);
    if (!nv) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    r->verts = nv;
    r->verts[r->nv++] = vx;
    return DFL_OK;
}

/* ---- field ops --------------------------------------------------------- */

static double part_eval(const part *pt, const double *x, double *g)
{
    switch (pt->kind) {
    case DFL_RFUNC_PART_SEGMENT: return dfl_rfunc_seg_eval(&pt->u.seg, x, g);
    case DFL_RFUNC_PART_TRIANGLE: return dfl_rfunc_tri_eval(&pt->u.tri, x, g);
    case DFL_RFUNC_PART_POINT: return dfl_rfunc_point_eval(&pt->u.pt, x, g);
    case DFL_RFUNC_PART_REGION: return dfl_rfunc_region_eval(&pt->u.reg, x, g);
    }
    assert(0);
    return NAN;
}

static dfl_status part_jet(const part *pt, const double *x, const double *dir, int K,
                           dfl_jet *out, dfl_err *err)
{
    switch (pt->kind) {
    case DFL_RFUNC_PART_SEGMENT: return dfl_rfunc_seg_jet(&pt->u.seg, x, dir, K, out, err);
    case DFL_RFUNC_PART_TRIANGLE: return dfl_rfunc_tri_jet(&pt->u.tri, x, dir, K, out, err);
    case DFL_RFUNC_PART_POINT: return dfl_rfunc_point_jet(&pt->u.pt, x, dir, K, out, err);
    case DFL_RFUNC_PART_REGION: return dfl_rfunc_region_jet(&pt->u.reg, x, dir, K, out, err);
    }
    return dfl_err_set(err, DFL_E_INTERNAL, "rfunc field: unknown part kind");
}

static double vertex_q(int dim, const vertex *v, const double *x, double *g)
{
    double w[3] = {0, 0, 0};
    for (int j = 0; j < dim; j++) w[j] = x[j] - v->x[j];
    const double q = dfl_hypot_vec(dim, w);
    if (g)
        for (int j = 0; j < dim; j++) g[j] = q > 0.0 ? w[j] / q : 0.0;
    return q;
}

/* The per-point path: every part at every point, in part order. */
static void rfield_eval_slow(const void *ctx, size_t m, const double *pts, double *val,
                             double *grad)
{
    const dfl_rfield *r = ctx;
    const int dim = r->dim, want = grad != NULL;
    const int corrected = r->join == DFL_RFUNC_REQUIV_CORRECTED;
    const int eq20 = corrected && r->corr == DFL_RFUNC_CORR_EQ20;
    for (size_t i = 0; i < m; i++) {
        const double *x = pts + i * (size_t)dim;
        dfl_rfunc_acc acc;
        /* current, previous and first part, for the vertex guards */
        double h = 0, hprev = 0, hfirst = 0;
        double g[3] = {0, 0, 0}, gprev[3] = {0, 0, 0}, gfirst[3] = {0, 0, 0};
        dfl_rfunc_acc_begin(&acc, r->join, r->p, dim, want);
        if (eq20) dfl_rfunc_acc_set_correction(&acc, DFL_RFUNC_CORR_EQ20);
        for (size_t k = 0; k < r->n && !dfl_rfunc_acc_is_zero(&acc); k++) {
            if (k > 0) {
                hprev = h;
                memcpy(gprev, g, sizeof g);
            }
            h = part_eval(&r->parts[k], x, want ? g : NULL);
            if (k == 0) {
                hfirst = h;
                memcpy(gfirst, g, sizeof g);
            }
            dfl_rfunc_acc_add(&acc, h, want ? g : NULL);
            if (!corrected) continue;
            for (size_t iv = r->vstart[k]; iv < r->vstart[k + 1]; iv++) {
                const vertex *v = &r->verts[iv];
                double gq[3], glo[3], gt[3];
                if (eq20) {
                    /* bs04's q_v as printed: no guard */
                    const double q = vertex_q(dim, v, x, want ? gq : NULL);
                    dfl_rfunc_acc_add_q(&acc, q, want ? gq : NULL);
                    continue;
                }
                double hlo;
                const double *gl = glo;
                if (v->lo + 1 == k) {
                    hlo = hprev;
                    gl = gprev;
                } else if (v->lo == 0) {
                    hlo = hfirst;
                    gl = gfirst;
                } else {
                    hlo = part_eval(&r->parts[v->lo], x, want ? glo : NULL);
                }
                const double q = vertex_q(dim, v, x, want ? gq : NULL);
                const double qt = dfl_rfunc_guard(dim, q, gq, hlo, gl, h, g, want ? gt : NULL);
                dfl_rfunc_acc_add_q(&acc, qt, want ? gt : NULL);
            }
        }
        val[i] = dfl_rfunc_acc_end(&acc, want ? grad + i * (size_t)dim : NULL);
    }
}

static void rfield_eval(const void *ctx, size_t m, const double *pts, double *val, double *grad)
{
    const dfl_rfield *r = ctx;
    if (r->batch) {
        /* The whole chunk at once: the batch is read-only and allocates
         * nothing (stack scratch), so concurrent calls are safe. */
        dfl_rfunc_batch_eval(r->batch, m, pts, val, grad);
        return;
    }
    rfield_eval_slow(ctx, m, pts, val, grad);
}

static dfl_status domain_check(const dfl_rfield *r, const double *x, bool jet, dfl_err *err)
{
    dfl_status st = dfl_rfunc_domain_point(r->dim, x, jet, err);
    if (st == DFL_OK && jet && r->span > DFL_RFUNC_JET_COORD_MAX)
        st = dfl_err_set(err, DFL_E_INPUT,
                         "the field's parts reach |x| = %.17g, beyond the domain of exact"
                         " derivatives (jets) |x| <= %g",
                         r->span, DFL_RFUNC_JET_COORD_MAX);
    return st;
}

/* A jet direction must be finite and non-zero: u(x + s dir) with dir = 0
 * is a constant, not a derivative anyone asked for. */
static dfl_status dir_check(int dim, const double *dir, dfl_err *err)
{
    double n = 0.0;
    for (int j = 0; j < dim; j++) {
        if (!isfinite(dir[j]))
            return dfl_err_set(err, DFL_E_INPUT, "jet direction: component %d is not finite",
                               j + 1);
        n = fmax(n, fabs(dir[j]));
    }
    if (!(n > 0.0)) return dfl_err_set(err, DFL_E_INPUT, "jet direction is zero");
    if (n > DFL_RFUNC_JET_COORD_MAX || n < 1.0 / DFL_RFUNC_JET_COORD_MAX)
        return dfl_err_set(err, DFL_E_INPUT,
                           "jet direction of size %g outside [%g, %g] (scale it)", n,
                           1.0 / DFL_RFUNC_JET_COORD_MAX, DFL_RFUNC_JET_COORD_MAX);
    return DFL_OK;
}

static dfl_status rfield_jet(const void *ctx, const double *x, const double *dir, int K,
                             dfl_jet *out, dfl_err *err)
{
    const dfl_rfield *r = ctx;
    dfl_status st0 = domain_check(r, x, true, err);
    if (st0 == DFL_OK) st0 = dir_check(r->dim, dir, err);
    if (st0 != DFL_OK) return st0;
    const size_t nq = r->join == DFL_RFUNC_REQUIV_CORRECTED ? r->nv : 0;
    const int eq20 = nq > 0 && r->corr == DFL_RFUNC_CORR_EQ20;
    dfl_jet *jets = malloc((r->n + nq) * sizeof *jets);
    if (!jets) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    dfl_status st = DFL_OK;
    for (size_t k = 0; k < r->n && st == DFL_OK; k++)
        st = part_jet(&r->parts[k], x, dir, K, &jets[k], err);
    for (size_t k = 0; k < nq && st == DFL_OK; k++) {
        const vertex *v = &r->verts[k];
        dfl_rfunc_point pt;
        dfl_jet q;
        st = dfl_rfunc_point_init(r->dim, v->x, &pt, err);
        if (st == DFL_OK) st = dfl_rfunc_point_jet(&pt, x, dir, K, &q, err);
        if (st == DFL_OK) {
            if (eq20) jets[r->n + k] = q;
            else dfl_rfunc_guard_jet(&q, &jets[v->lo], &jets[v->hi], &jets[r->n + k]);
        }
    }
    if (st == DFL_OK)
        st = dfl_rfunc_join_jet_corr(r->join, r->corr, r->p, r->n, jets, nq, jets + r->n, out,
                                     err);
    free(jets);
    return st;
}

static void rfield_destroy(void *ctx) { dfl_rfield_free(ctx); }


/* Stored: the part records and the joining vertices (the parameters the
 * field is evaluated from; the batch path's derived arrays are a cache). */
static size_t rfield_bytes(const void *ctx)
{
    const dfl_rfield *r = ctx;
    return r->n * sizeof(part) + r->nv * sizeof(vertex);
}

static const dfl_field_ops rfield_ops = {"rfunc", rfield_eval, rfield_jet, rfield_destroy,
                                         rfield_bytes};
/* The per-point path of a finished field, borrowed by its batch. */
static const dfl_field_ops rfield_slow_ops = {"rfunc_per_point", rfield_eval_slow, rfield_jet, NULL,
                                              NULL};

dfl_status dfl_rfield_check_point(const dfl_field *f, const double *x, bool jet, dfl_err *err)
{
    if (f->ops != &rfield_ops) return DFL_OK;
    return domain_check(f->ctx, x, jet, err);
}

bool dfl_rfield_nan_is_undefined(const dfl_field *f)
{
    return f->ops == &rfield_ops && ((const dfl_rfield *)f->ctx)->corr == DFL_RFUNC_CORR_EQ20;
}

bool dfl_rfield_is_fast(const dfl_field *f)
{
    return f->ops == &rfield_ops && ((const dfl_rfield *)f->ctx)->batch != NULL;
}

dfl_status dfl_rfield_finish(dfl_rfield **r, dfl_field *out, dfl_err *err)
{
    dfl_rfield *f = *r;
    *r = NULL;
    if (!f) return dfl_err_set(err, DFL_E_INTERNAL, "rfunc field: no builder");
    dfl_status st = DFL_OK;
    if (f->n == 0) st = dfl_err_set(err, DFL_E_INPUT, "rfunc field: no parts");
    for (size_t i = 0; i < f->nv && st == DFL_OK; i++)
        if (f->verts[i].hi >= f->n)
            st = dfl_err_set(err, DFL_E_INPUT, "rfunc field: vertex %zu names part %zu of %zu",
                             i + 1, f->verts[i].hi + 1, f->n);
    /* Counting sort of the vertices by their later part. */
    vertex *sorted = NULL;
    if (st == DFL_OK) {
        f->vstart = calloc(f->n + 1, sizeof *f->vstart);
        sorted = malloc((f->nv ? f->nv : 1) * sizeof *sorted);
        if (!f->vstart || !sorted) st = dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    }
    if (st != DFL_OK) {
        free(sorted);
        dfl_rfield_free(f);
        return st;
    }
    for (size_t i = 0; i < f->nv; i++) f->vstart[f->verts[i].hi + 1]++;
    for (size_t k = 0; k < f->n; k++) f->vstart[k + 1] += f->vstart[k];
    for (size_t i = 0; i < f->nv; i++) {
        size_t *slot = &f->vstart[f->verts[i].hi];
        sorted[(*slot)++] = f->verts[i];
    }
    /* The fill advanced vstart[k] to the start of k+1: shift back. */
    for (size_t k = f->n; k > 0; k--) f->vstart[k] = f->vstart[k - 1];
    f->vstart[0] = 0;
    free(f->verts);
    f->verts = sorted;
    f->vcap = f->nv;
    f->slow.dim = f->dim;
    f->slow.ops = &rfield_slow_ops;
    f->slow.ctx = f;
    /* One part: the join is the identity, which the per-point path keeps
     * exactly (u = h, tests/rfunc/test_segment.c) and a batch only to
     * rounding; there is nothing to vectorize over either. */
    if (f->fast && f->n >= 2) {
        const dfl_rfunc_batch_desc d = {f->dim, f->join, f->p,     f->corr,  f->parts,
                                        f->n,   f->verts, f->nv,   f->vstart, &f->slow};
        st = dfl_rfunc_batch_build(&d, &f->batch, err);
        if (st != DFL_OK) {
            dfl_rfield_free(f);
            return st;
        }
    }
    out->dim = f->dim;
    out->ops = &rfield_ops;
    out->ctx = f;
    return DFL_OK;
}

dfl_status dfl_rfield_polyline(int dim, const double *v, size_t n, bool closed,
                               dfl_rfunc_join join, int p, dfl_rfunc_trim trim, dfl_field *out,
                               dfl_err *err)
{
    return dfl_rfield_polyline_opts(dim, v, n, closed, join, p, trim, true, out, err);
}

/* Size of the polyline: the diagonal of its bounding box. */
static double poly_extent(int dim, const double *v, size_t n)
{
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0}, w[3] = {0, 0, 0};
    for (size_t i = 0; i < n; i++)
        for (int j = 0; j < dim; j++) {
            const double x = v[i * (size_t)dim + j];
            lo[j] = i ? fmin(lo[j], x) : x;
            hi[j] = i ? fmax(hi[j], x) : x;
        }
    for (int j = 0; j < dim; j++) w[j] = hi[j] - lo[j];
    return dfl_hypot_vec(dim, w);
}

/* |a x b| and a . b of two dim-vectors. */
static void cross_dot(int dim, const double *a, const double *b, double *cr, double *dt)
{
    double c[3] = {0, 0, 0};
    if (dim == 2) c[0] = a[0] * b[1] - a[1] * b[0];
    else {
        c[0] = a[1] * b[2] - a[2] * b[1];
        c[1] = a[2] * b[0] - a[0] * b[2];
        c[2] = a[0] * b[1] - a[1] * b[0];
    }
    *cr = dfl_hypot_vec(3, c);
    *dt = 0.0;
    for (int j = 0; j < dim; j++) *dt += a[j] * b[j];
}

/* The degenerate polylines dflab rejects (header): segments shorter than
 * DFL_RFIELD_POLY_TOL of the polyline's size and A-B-A backtracks; a
 * closed polyline with no area (collinear vertices) turns back at its
 * extreme vertices, so the second test catches it. */
static dfl_status poly_check(int dim, const double *v, size_t n, bool closed, dfl_err *err)
{
    const double ext = poly_extent(dim, v, n);
    const size_t nseg = closed ? n : n - 1;
    double e[3][3];
    for (size_t i = 0; i < nseg; i++) {
        const double *a = v + i * (size_t)dim, *b = v + ((i + 1) % n) * (size_t)dim;
        double w[3] = {0, 0, 0};
        for (int j = 0; j < dim; j++) w[j] = b[j] - a[j];
        const double len = dfl_hypot_vec(dim, w);
        if (!(len > DFL_RFIELD_POLY_TOL * ext))
            return dfl_err_set(err, DFL_E_INPUT,
                               "degenerate polyline: segment %zu (vertices %zu and %zu) has length %.3g,"
                               " below %g of the polyline's size %.3g",
                               i + 1, i + 1, (i + 1) % n + 1, len, DFL_RFIELD_POLY_TOL, ext);
    }
    for (size_t i = closed ? 0 : 1; i < (closed ? n : n - 1); i++) {
        const double *a = v + ((i + n - 1) % n) * (size_t)dim, *b = v + i * (size_t)dim,
                     *c = v + ((i + 1) % n) * (size_t)dim;
        for (int j = 0; j < dim; j++) {
            e[0][j] = b[j] - a[j];
            e[1][j] = c[j] - b[j];
        }
        double cr, dt;
        cross_dot(dim, e[0], e[1], &cr, &dt);
        const double l0 = dfl_hypot_vec(dim, e[0]), l1 = dfl_hypot_vec(dim, e[1]);
        if (dt < 0.0 && cr <= DFL_RFIELD_POLY_TOL * l0 * l1)
            return dfl_err_set(err, DFL_E_INPUT,
                               "degenerate polyline: at vertex %zu it turns back on itself"
                               " (segments %zu and %zu overlap)",
                               i + 1, i == 0 ? n : i, i + 1);
    }
    return DFL_OK;
}

dfl_status dfl_rfield_add_polyline(dfl_rfield *r, const double *v, size_t n, bool closed,
                                   dfl_rfunc_trim trim, dfl_err *err)
{
    const int dim = r->dim;
    if (n < (closed ? 3u : 2u))
        return dfl_err_set(err, DFL_E_INPUT, "polyline: %zu vertices (need at least %d%s)", n,
                           closed ? 3 : 2, closed ? " when closed" : "");
    dfl_status st = DFL_OK;
    for (size_t i = 0; i < n && st == DFL_OK; i++) {
        char what[48];
        snprintf(what, sizeof what, "polyline vertex %zu", i + 1);
        st = take_coords(r, v + i * (size_t)dim, 1, what, err);
    }
    if (st == DFL_OK) st = poly_check(dim, v, n, closed, err);
    if (st != DFL_OK) return st;
    const size_t base = r->n, nseg = closed ? n : n - 1;
    for (size_t i = 0; i < nseg && st == DFL_OK; i++) {
        st = dfl_rfield_add_segment(r, v + i * (size_t)dim, v + ((i + 1) % n) * (size_t)dim, trim,
                                    err);
        if (st != DFL_OK)
            dfl_err_prefix(err, "polyline segment %zu (vertices %zu and %zu)", i + 1, i + 1,
                           (i + 1) % n + 1);
    }
    /* Vertex i joins segments i-1 and i (vertex 0 of a closed polyline:
     * the closing segment n-1 and segment 0). */
    for (size_t i = closed ? 0 : 1; i < (closed ? n : n - 1) && st == DFL_OK; i++)
        st = dfl_rfield_add_vertex(r, v + i * (size_t)dim, base + (i == 0 ? n - 1 : i - 1),
                                   base + i, err);
    return st;
}

dfl_status dfl_rfield_polyline_opts(int dim, const double *v, size_t n, bool closed,
                                    dfl_rfunc_join join, int p, dfl_rfunc_trim trim, bool fast,
                                    dfl_field *out, dfl_err *err)
{
    dfl_rfield *r = NULL;
    dfl_status st = dfl_rfield_new(dim, join, p, &r, err);
    if (st != DFL_OK) return st;
    dfl_rfield_set_fast(r, fast);
    st = dfl_rfield_add_polyline(r, v, n, closed, trim, err);
    if (st != DFL_OK) {
        dfl_rfield_free(r);
        return st;
    }
    return dfl_rfield_finish(&r, out, err);
}
