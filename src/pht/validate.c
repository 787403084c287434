/* Validation errors and the medial band (validate.h).  Points are handled
 * in fixed chunks of CHUNK, in parallel; each chunk's partial statistics go
 * to its own slot and are combined in chunk order, so the result does not
 * depend on the thread count. */
#include "pht/validate.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CHUNK 256

typedef struct part {
    size_t n, noff, band, skipped;
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
        if (!isfinite(e)) e = INFINITY;
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
