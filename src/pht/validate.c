/* Validation errors and the medial band (validate.h).  Points are handled
 * in fixed chunks of CHUNK, in parallel; each chunk's partial statistics go
 * to its own slot and are combined in chunk order, so the result does not
 * depend on the thread count. */
#include "pht/validate.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"

#define CHUNK 256

typedef struct part {
    size_t n, noff, band, skipped, nonfinite;
    double max, sum, sq, gmax, gsum;
    double omax, osum, osq, ogmax, ogsum;
} part;

/* Band flags of n points (n <= CHUNK); d, g: the exact SDF there. */
static void band_chunk(const dfl_shape *s, size_t n, const double *pts, const double *d,
                       const double *g, double w, unsigned char *near)
{
    const int dim = s->dim;
    double y[CHUNK * 3] = {0}, dy[CHUNK];
    if (w <= 0.0 || n == 0) {
        memset(near, 0, n);
        return;
    }
    for (size_t i = 0; i < n; i++) {
        double sg = d[i] < 0.0 ? -1.0 : 1.0;
        for (int j = 0; j < dim; j++)
            y[i * dim + j] = pts[i * dim + j] + w * sg * g[i * dim + j];
    }
    dfl_shape_eval(s, n, y, dy, NULL);
    for (size_t i = 0; i < n; i++) {
        double r = 0.0;
        for (int j = 0; j < dim; j++) r += pts[i * dim + j] * pts[i * dim + j];
        double defect = fabs(d[i]) + w - fabs(dy[i]);
        near[i] = !(defect <= 1e-6 * w + 1e-12 * (1.0 + sqrt(r)));
    }
}

dfl_status dfl_pht_medial_band(const dfl_shape *shape, size_t m, const double *pts, double w,
                               unsigned char *near, dfl_err *err)
{
    (void)err;
    const int dim = shape->dim;
    size_t nch = (m + CHUNK - 1) / CHUNK;
#pragma omp parallel for schedule(dynamic, 1) if (nch > 1)
    for (size_t c = 0; c < nch; c++) {
        size_t i0 = c * CHUNK, n = m - i0 < CHUNK ? m - i0 : CHUNK;
        double d[CHUNK], g[CHUNK * 3];
        dfl_shape_eval(shape, n, pts + i0 * dim, d, g);
        band_chunk(shape, n, pts + i0 * dim, d, g, w, near + i0);
    }
    return DFL_OK;
}

static void add(double e, double ge, double *max, double *sum, double *sq, double *gmax,
                double *gsum)
{
    if (e > *max) *max = e;
    *sum += e;
    *sq += e * e;
    if (ge > *gmax) *gmax = ge;
    *gsum += ge;
}

static void chunk_stats(const dfl_field *f, const dfl_shape *s, size_t n, const double *pts,
                        double w, part *p)
{
    const int dim = s->dim;
    double fv[CHUNK], fg[CHUNK * 3], d[CHUNK], g[CHUNK * 3];
    unsigned char near[CHUNK];
    f->ops->eval(f->ctx, n, pts, fv, fg);
    dfl_shape_eval(s, n, pts, d, g);
    band_chunk(s, n, pts, d, g, w, near);
    memset(p, 0, sizeof *p);
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(d[i])) {
            p->skipped++;
            continue;
        }
        double e = fabs(fv[i] - d[i]), ge = 0.0;
        for (int j = 0; j < dim; j++) {
            double dj = fg[i * dim + j] - g[i * dim + j];
            ge += dj * dj;
        }
        ge = sqrt(ge);
        /* a NaN must not vanish from a maximum (fmax and > drop it) */
        if (!isfinite(e) || !isfinite(ge)) p->nonfinite++;
        if (!isfinite(e)) e = INFINITY;
        if (!isfinite(ge)) ge = INFINITY;
        p->n++;
        add(e, ge, &p->max, &p->sum, &p->sq, &p->gmax, &p->gsum);
        if (near[i]) {
            p->band++;
            continue;
        }
        p->noff++;
        add(e, ge, &p->omax, &p->osum, &p->osq, &p->ogmax, &p->ogsum);
    }
}

static void finish(const part *parts, size_t np, dfl_pht_val *out)
{
    part t;
    memset(&t, 0, sizeof t);
    for (size_t c = 0; c < np; c++) {
        const part *p = &parts[c];
        t.n += p->n;
        t.noff += p->noff;
        t.band += p->band;
        t.skipped += p->skipped;
        t.nonfinite += p->nonfinite;
        t.sum += p->sum;
        t.sq += p->sq;
        t.gsum += p->gsum;
        t.osum += p->osum;
        t.osq += p->osq;
        t.ogsum += p->ogsum;
        t.max = fmax(t.max, p->max);
        t.gmax = fmax(t.gmax, p->gmax);
        t.omax = fmax(t.omax, p->omax);
        t.ogmax = fmax(t.ogmax, p->ogmax);
    }
    memset(out, 0, sizeof *out);
    out->band = t.band;
    out->skipped = t.skipped;
    out->nonfinite = t.nonfinite;
    out->all.n = t.n;
    out->off.n = t.noff;
    if (t.n) {
        out->all.max = t.max;
        out->all.mean = t.sum / (double)t.n;
        out->all.rms = sqrt(t.sq / (double)t.n);
        out->all.gmax = t.gmax;
        out->all.gmean = t.gsum / (double)t.n;
    }
    if (t.noff) {
        out->off.max = t.omax;
        out->off.mean = t.osum / (double)t.noff;
        out->off.rms = sqrt(t.osq / (double)t.noff);
        out->off.gmax = t.ogmax;
        out->off.gmean = t.ogsum / (double)t.noff;
    }
}

dfl_status dfl_pht_validate_points(const dfl_field *f, const dfl_shape *shape, size_t m,
                                   const double *pts, double w, dfl_pht_val *out, dfl_err *err)
{
    size_t nch = (m + CHUNK - 1) / CHUNK;
    part *parts = calloc(nch ? nch : 1, sizeof *parts);
    if (!parts) return dfl_err_set(err, DFL_E_NOMEM, "PHT validation: out of memory");
    const int dim = shape->dim;
#pragma omp parallel for schedule(dynamic, 1) if (nch > 1)
    for (size_t c = 0; c < nch; c++) {
        size_t i0 = c * CHUNK, n = m - i0 < CHUNK ? m - i0 : CHUNK;
        chunk_stats(f, shape, n, pts + i0 * dim, w, &parts[c]);
    }
    finish(parts, nch, out);
    free(parts);
    return DFL_OK;
}

/* Point k of the protocol: nodes first (x fastest), then midpoints. */
static void grid_point(const dfl_pht_val_opts *o, int dim, size_t nodes, size_t k, double *x)
{
    size_t n = (size_t)o->n, r;
    double off = 0.0;
    if (k < nodes) {
        r = k;
    } else {
        r = k - nodes;
        n -= 1;
        off = 0.5;
    }
    for (int j = 0; j < dim; j++) {
        size_t i = r % n;
        r /= n;
        double t = ((double)i + off) / (double)(o->n - 1);
        x[j] = o->lo[j] + (o->hi[j] - o->lo[j]) * t;
    }
}

dfl_status dfl_pht_validate_grid(const dfl_field *f, const dfl_shape *shape,
                                 const dfl_pht_val_opts *o, dfl_pht_val *out, dfl_err *err)
{
    const int dim = shape->dim;
    if (o->n < 2 || o->n > 100000)
        return dfl_err_set(err, DFL_E_INPUT, "PHT validation: n = %d (expected 2..100000)", o->n);
    for (int j = 0; j < dim; j++)
        if (!isfinite(o->lo[j]) || !isfinite(o->hi[j]) || !(o->lo[j] < o->hi[j]))
            return dfl_err_set(err, DFL_E_INPUT,
                               "PHT validation: box side %d is [%g, %g] (expected lo < hi)", j,
                               o->lo[j], o->hi[j]);
    size_t nodes = 1, mids = 1;
    for (int j = 0; j < dim; j++) {
        nodes *= (size_t)o->n;
        mids *= (size_t)(o->n - 1);
    }
    size_t m = nodes + mids, nch = (m + CHUNK - 1) / CHUNK;
    part *parts = calloc(nch, sizeof *parts);
    if (!parts) return dfl_err_set(err, DFL_E_NOMEM, "PHT validation: out of memory");
#pragma omp parallel for schedule(dynamic, 4)
    for (size_t c = 0; c < nch; c++) {
        size_t i0 = c * CHUNK, n = m - i0 < CHUNK ? m - i0 : CHUNK;
        double pts[CHUNK * 3];
        for (size_t i = 0; i < n; i++) grid_point(o, dim, nodes, i0 + i, pts + i * dim);
        chunk_stats(f, shape, n, pts, o->band, &parts[c]);
    }
    finish(parts, nch, out);
    free(parts);
    return DFL_OK;
}

/* ---- the per-cell protocol ---- */

void dfl_pht_cellval_opts_default(int dim, dfl_pht_cellval_opts *o)
{
    memset(o, 0, sizeof *o);
    o->eps = NAN;
    o->random = 4;
    o->seed = 1;
    o->dense = dim == 2 ? 5 : 4;
    o->scales = 8;
}

/* One cell's partial results (combined in cell order). */
typedef struct cpart {
    size_t n, skipped, band, off, medial, above, nonfinite;
    double max, gmax, band_max, off_max, medial_max;
    int medial_cell, nomem;
} cpart;

typedef struct cbuf {
    size_t cap;
    double *x, *d, *g, *f, *fg;
    unsigned char *near, *kind; /* kind: 1 = near-medial point */
} cbuf;

static void cbuf_free(cbuf *b)
{
    free(b->x), free(b->d), free(b->g), free(b->f), free(b->fg), free(b->near), free(b->kind);
    memset(b, 0, sizeof *b);
}

static int cbuf_init(cbuf *b, size_t cap, int dim)
{
    memset(b, 0, sizeof *b);
    b->cap = cap;
    b->x = malloc(cap * (size_t)dim * sizeof *b->x);
    b->d = malloc(cap * sizeof *b->d);
    b->g = malloc(cap * (size_t)dim * sizeof *b->g);
    b->f = malloc(cap * sizeof *b->f);
    b->fg = malloc(cap * (size_t)dim * sizeof *b->fg);
    b->near = malloc(cap);
    b->kind = malloc(cap);
    return b->x && b->d && b->g && b->f && b->fg && b->near && b->kind ? 0 : -1;
}

/* Band flags of n points in pieces of CHUNK (band_chunk's bound). */
static void band_all(const dfl_shape *s, size_t n, const double *x, const double *d,
                     const double *g, double w, unsigned char *near)
{
    const int dim = s->dim;
    for (size_t a = 0; a < n; a += CHUNK) {
        size_t k = n - a < CHUNK ? n - a : CHUNK;
        band_chunk(s, k, x + a * dim, d + a, g + a * dim, w, near + a);
    }
}

/* The medial axis on x's normal line (d, g: the exact SDF at x): the
 * defect of the band criterion, |d(x)| + t - |d(x + t sigma g)|, is 0 while
 * the footpoint stays x's and positive once the line has crossed the medial
 * axis; t is bisected in [0, w] (the defect positive at w), at most 60
 * halvings, down to 1e-6 w.  Returns 1 and the crossing in xm, 0 if the
 * defect at w is not positive. */
static int bisect_medial(const dfl_shape *s, const double *x, double d, const double *g, double w,
                         double *xm)
{
    const int dim = s->dim;
    const double sg = d < 0.0 ? -1.0 : 1.0;
    double r = 0.0;
    for (int j = 0; j < dim; j++) r += x[j] * x[j];
    const double tol0 = 1e-12 * (1.0 + sqrt(r));
    double lo = 0.0, hi = w, y[3], dy;
    for (int j = 0; j < dim; j++) y[j] = x[j] + hi * sg * g[j];
    dfl_shape_eval(s, 1, y, &dy, NULL);
    if (!(fabs(d) + hi - fabs(dy) > 1e-6 * hi + tol0)) return 0;
    for (int it = 0; it < 60 && hi - lo > 1e-6 * w; it++) {
        const double t = 0.5 * (lo + hi);
        for (int j = 0; j < dim; j++) y[j] = x[j] + t * sg * g[j];
        dfl_shape_eval(s, 1, y, &dy, NULL);
        if (fabs(d) + t - fabs(dy) > 1e-6 * t + tol0) hi = t;
        else lo = t;
    }
    for (int j = 0; j < dim; j++) xm[j] = x[j] + 0.5 * (lo + hi) * sg * g[j];
    return 1;
}

static uint64_t vmix(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* Lattice node i of q^dim nodes of [lo, hi] into x. */
static void sub_node(int dim, int q, size_t i, const double *lo, const double *hi, double *x)
{
    for (int j = 0; j < dim; j++) {
        size_t ij = i % (size_t)q;
        i /= (size_t)q;
        double t = (double)ij / (double)(q - 1);
        x[j] = ij == (size_t)(q - 1) ? hi[j] : lo[j] + (hi[j] - lo[j]) * t;
    }
}

static void one_cell(const dfl_pht_spline *sp, const dfl_shape *s, const dfl_pht_cellval_opts *o,
                     size_t ci, cbuf *b, cpart *p)
{
    const int dim = s->dim;
    double lo[3], hi[3], diag = 0.0;
    int level;
    dfl_pht_spline_cell(sp, ci, lo, hi, &level);
    for (int j = 0; j < dim; j++) diag += (hi[j] - lo[j]) * (hi[j] - lo[j]);
    diag = sqrt(diag);
    memset(p, 0, sizeof *p);
    /* the halving's nodes and the random points */
    size_t n = 0, n3 = dim == 2 ? 9 : 27;
    for (size_t i = 0; i < n3; i++, n++) sub_node(dim, 3, i, lo, hi, b->x + n * dim);
    uint64_t st = vmix(o->seed ^ 0xD1B54A32D192ED03ull * (uint64_t)(level + 1));
    for (int j = 0; j < dim; j++) {
        uint64_t bits;
        memcpy(&bits, &lo[j], sizeof bits);
        st = vmix(st ^ (bits + 0x8CB92BA72F3D8DD7ull * (uint64_t)(j + 1)));
    }
    for (int r = 0; r < o->random; r++, n++)
        for (int j = 0; j < dim; j++) b->x[n * dim + j] = dfl_rng_splitmix(&st, lo[j], hi[j]);
    dfl_shape_eval(s, n, b->x, b->d, b->g);
    band_all(s, n, b->x, b->d, b->g, 2.0 * diag, b->near);
    int med = 0;
    for (size_t i = 0; i < n; i++) med |= b->near[i] && isfinite(b->d[i]);
    memset(b->kind, 0, n);
    if (med) {
        p->medial_cell = 1;
        const int q = o->dense;
        size_t qn = 1, n0 = n;
        for (int j = 0; j < dim; j++) qn *= (size_t)q;
        for (size_t i = 0; i < qn; i++) sub_node(dim, q, i, lo, hi, b->x + (n0 + i) * dim);
        dfl_shape_eval(s, qn, b->x + n0 * dim, b->d + n0, b->g + n0 * dim);
        memset(b->kind + n0, 0, qn);
        n = n0 + qn;
        /* normal-line bisection from the sub-grid nodes that see the medial
         * axis within 2 diag (at most dim q^(dim-1) of them, in node order) */
        band_all(s, qn, b->x + n0 * dim, b->d + n0, b->g + n0 * dim, 2.0 * diag, b->near + n0);
        double e = hi[0] - lo[0];
        for (int j = 1; j < dim; j++) e = fmin(e, hi[j] - lo[j]);
        const size_t cap = (size_t)(q + 1) / 2;
        size_t nf = 0;
        for (size_t i = 0; i < qn; i++) nf += b->near[n0 + i] && isfinite(b->d[n0 + i]);
        /* the flagged nodes j nf / cap, j = 0..cap-1: spread over the cell */
        for (size_t i = 0, seen = 0, next = 0, nb = 0; i < qn && nb < cap; i++) {
            const size_t ia = n0 + i;
            if (!b->near[ia] || !isfinite(b->d[ia])) continue;
            if (seen++ != next) continue;
            nb++;
            next = nb * nf / cap;
            if (next < seen) next = seen;
            double xm[3], nrm[3];
            memcpy(nrm, b->g + ia * dim, dim * sizeof *nrm);
            if (!bisect_medial(s, b->x + ia * dim, b->d[ia], nrm, 2.0 * diag, xm)) continue;
            int in = 1;
            for (int j = 0; j < dim; j++) in &= xm[j] >= lo[j] && xm[j] <= hi[j];
            size_t m0 = n;
            if (in) memcpy(b->x + n++ * dim, xm, dim * sizeof *xm);
            /* two offsets per octave: e 2^-k and 3/4 e 2^-k (the maximum of
             * |f - d| next to a point kink sits at a fraction of e) */
            for (int k = 1; k <= o->scales; k++)
                for (int h = 0; h < 4; h++) {
                    const double t = (h & 1 ? 0.75 : 1.0) * ldexp(e, -k) * (h & 2 ? -1.0 : 1.0);
                    double *y = b->x + n * dim;
                    int inside = 1;
                    for (int j = 0; j < dim; j++) {
                        y[j] = xm[j] + t * nrm[j];
                        inside &= y[j] >= lo[j] && y[j] <= hi[j];
                    }
                    n += (size_t)inside;
                }
            dfl_shape_eval(s, n - m0, b->x + m0 * dim, b->d + m0, b->g + m0 * dim);
            memset(b->kind + m0, 1, n - m0);
        }
    }
    assert(n <= b->cap);
    dfl_pht_eval_cell(sp, ci, n, b->x, b->f, b->fg, NULL);
    /* near-medial points lie within e of the medial axis along a normal
     * line: in the band whenever w > 0 (no second SDF for them) */
    size_t nplain = n;
    while (nplain > 0 && b->kind[nplain - 1]) nplain--;
    band_all(s, nplain, b->x, b->d, b->g, o->band, b->near);
    memset(b->near + nplain, o->band > 0.0, n - nplain);
    const int count_above = o->eps > 0;
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(b->d[i])) {
            p->skipped++;
            continue;
        }
        double e = fabs(b->f[i] - b->d[i]), ge = 0.0;
        if (!isfinite(e)) e = INFINITY;
        for (int j = 0; j < dim; j++) {
            double dj = b->fg[i * dim + j] - b->g[i * dim + j];
            ge += dj * dj;
        }
        ge = isfinite(ge) ? sqrt(ge) : INFINITY;
        p->nonfinite += !isfinite(e) || !isfinite(ge);
        p->n++;
        p->max = fmax(p->max, e);
        p->gmax = fmax(p->gmax, ge);
        if (b->near[i]) {
            p->band++;
            p->band_max = fmax(p->band_max, e);
        } else {
            p->off++;
            p->off_max = fmax(p->off_max, e);
        }
        if (b->kind[i]) {
            p->medial++;
            p->medial_max = fmax(p->medial_max, e);
        }
        if (count_above && e > o->eps) p->above++;
    }
}

dfl_status dfl_pht_validate_cells(const dfl_pht_spline *s, const dfl_shape *shape,
                                  const dfl_pht_cellval_opts *o, dfl_pht_cellval *out,
                                  dfl_err *err)
{
    const int dim = shape->dim;
    assert(dim == dfl_pht_spline_dim(s));
    memset(out, 0, sizeof *out);
    if (o->random < 0 || o->random > 256 || o->dense < 2 || o->dense > 33 || o->scales < 0 ||
        o->scales > 40 || !(o->band >= 0.0) || !isfinite(o->band))
        return dfl_err_set(err, DFL_E_INPUT,
                           "PHT cell validation: random %d (0..256), dense %d (2..33), scales %d "
                           "(0..40), band %g (>= 0)",
                           o->random, o->dense, o->scales, o->band);
    const size_t nc = dfl_pht_spline_ncells(s);
    size_t qn = 1;
    for (int j = 0; j < dim; j++) qn *= (size_t)o->dense;
    const size_t cap = 27 + (size_t)o->random + qn + (size_t)o->dense * (1 + 4 * (size_t)o->scales);
    cpart *parts = calloc(nc ? nc : 1, sizeof *parts);
    if (!parts) return dfl_err_set(err, DFL_E_NOMEM, "PHT cell validation: out of memory");
    int fail = 0;
#pragma omp parallel reduction(| : fail)
    {
        cbuf b;
        if (cbuf_init(&b, cap, dim) != 0) fail = 1;
#pragma omp for schedule(dynamic, 8)
        for (size_t i = 0; i < nc; i++)
            if (!fail) one_cell(s, shape, o, i, &b, &parts[i]);
        cbuf_free(&b);
    }
    if (fail) {
        free(parts);
        return dfl_err_set(err, DFL_E_NOMEM, "PHT cell validation: out of memory");
    }
    for (size_t i = 0; i < nc; i++) {
        const cpart *p = &parts[i];
        out->n += p->n;
        out->skipped += p->skipped;
        out->band += p->band;
        out->off += p->off;
        out->medial += p->medial;
        out->above += p->above;
        out->nonfinite += p->nonfinite;
        out->medial_cells += (size_t)p->medial_cell;
        out->max = fmax(out->max, p->max);
        out->gmax = fmax(out->gmax, p->gmax);
        out->band_max = fmax(out->band_max, p->band_max);
        out->off_max = fmax(out->off_max, p->off_max);
        out->medial_max = fmax(out->medial_max, p->medial_max);
    }
    /* a maximum over no point is no number: NaN, not 0 (0 would read as an
     * exact fit, e.g. cv_band_max of a band of width 0 or of a box the
     * medial axis misses) */
    if (!out->n) out->max = out->gmax = NAN;
    if (!out->band) out->band_max = NAN;
    if (!out->off) out->off_max = NAN;
    if (!out->medial) out->medial_max = NAN;
    free(parts);
    return DFL_OK;
}
