/* Untrimmed offsets: sampling, cusps and crossing counts.
 *
 * Why a sweep for the crossings: offsets of the sjp10 studies are sampled
 * with thousands of points and counted for several delta; all pairs would
 * be quadratic, while segments of a smooth curve overlap in x with few
 * others. */
#include "geom/offset.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void dfl_offset_free(dfl_offset *o)
{
    if (!o) return;
    free(o->t);
    free(o->pts);
    free(o->foot);
    free(o->speed);
    memset(o, 0, sizeof *o);
}

dfl_status dfl_offset_curve(const dfl_bspline *c, int orient, double delta, size_t n,
                            dfl_offset *out, dfl_err *err)
{
    memset(out, 0, sizeof *out);
    if (c->dim != 2 || !dfl_bspline_is_closed(c, 1e-12))
        return dfl_err_set(err, DFL_E_INPUT, "offset: a closed planar curve is required");
    if (n < 8 || n > 100000000)
        return dfl_err_set(err, DFL_E_INPUT, "offset: samples must be in 8..1e8, got %zu", n);
    if (orient != 1 && orient != -1)
        return dfl_err_set(err, DFL_E_INPUT, "offset: orientation must be +1 or -1");
    if (!isfinite(delta)) return dfl_err_set(err, DFL_E_INPUT, "offset: delta is not finite");
    out->t = malloc(n * sizeof *out->t);
    out->pts = malloc(2 * n * sizeof *out->pts);
    out->foot = malloc(2 * n * sizeof *out->foot);
    out->speed = malloc(n * sizeof *out->speed);
    if (!out->t || !out->pts || !out->foot || !out->speed) {
        dfl_offset_free(out);
        return dfl_err_set(err, DFL_E_NOMEM, "offset: out of memory");
    }
    out->n = n;
    out->delta = delta;
    const double T = c->t1 - c->t0;
    for (size_t i = 0; i < n; i++) {
        const double t = c->t0 + T * (double)i / (double)n;
        double d[6];
        dfl_bspline_eval(c, t, 2, d);
        const double sp = hypot(d[2], d[3]);
        const double tx = d[2] / sp, ty = d[3] / sp;
        const double nx = orient * ty, ny = -orient * tx;
        /* kappa for the outward normal: dN/ds = kappa T, so
         * kappa = (dN/dt . C') / |C'|^2 = orient (C' x C'') / |C'|^3 */
        const double kappa = orient * (d[2] * d[5] - d[3] * d[4]) / (sp * sp * sp);
        out->t[i] = t;
        out->foot[2 * i] = d[0];
        out->foot[2 * i + 1] = d[1];
        out->pts[2 * i] = d[0] + delta * nx;
        out->pts[2 * i + 1] = d[1] + delta * ny;
        out->speed[i] = 1.0 + kappa * delta;
    }
    return DFL_OK;
}

/* Orientation of (a, b, c): > 0 left turn. */
static double orient2(const double *a, const double *b, const double *c)
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

static int proper_cross(const double *a, const double *b, const double *c, const double *d)
{
    const double o1 = orient2(a, b, c), o2 = orient2(a, b, d);
    const double o3 = orient2(c, d, a), o4 = orient2(c, d, b);
    return ((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0));
}

typedef struct seg_ref {
    double xmin, xmax;
    size_t i;
} seg_ref;

static int cmp_seg(const void *x, const void *y)
{
    const seg_ref *a = x, *b = y;
    if (a->xmin != b->xmin) return a->xmin < b->xmin ? -1 : 1;
    return a->i < b->i ? -1 : a->i > b->i;
}

dfl_status dfl_polyline_crossings(const double *p, size_t n, size_t *count, dfl_err *err)
{
    *count = 0;
    if (n < 4) return DFL_OK;
    seg_ref *s = malloc(n * sizeof *s);
    if (!s) return dfl_err_set(err, DFL_E_NOMEM, "offset: out of memory");
    for (size_t i = 0; i < n; i++) {
        const double *a = p + 2 * i, *b = p + 2 * ((i + 1) % n);
        s[i].xmin = fmin(a[0], b[0]);
        s[i].xmax = fmax(a[0], b[0]);
        s[i].i = i;
    }
    qsort(s, n, sizeof *s, cmp_seg);
    size_t cnt = 0;
    for (size_t u = 0; u < n; u++) {
        const size_t i = s[u].i;
        const double *a = p + 2 * i, *b = p + 2 * ((i + 1) % n);
        const double ylo = fmin(a[1], b[1]), yhi = fmax(a[1], b[1]);
        for (size_t w = u + 1; w < n && s[w].xmin <= s[u].xmax; w++) {
            const size_t j = s[w].i;
            const size_t gap = i > j ? i - j : j - i;
            if (gap <= 1 || gap == n - 1) continue;  /* adjacent segments share a point */
            const double *c = p + 2 * j, *d = p + 2 * ((j + 1) % n);
            if (fmax(c[1], d[1]) < ylo || fmin(c[1], d[1]) > yhi) continue;
            cnt += (size_t)proper_cross(a, b, c, d);
        }
    }
    free(s);
    *count = cnt;
    return DFL_OK;
}

dfl_status dfl_offset_count(const dfl_offset *o, dfl_offset_counts *out, dfl_err *err)
{
    memset(out, 0, sizeof *out);
    const size_t n = o->n;
    size_t neg = 0, changes = 0, starts = 0;
    for (size_t i = 0; i < n; i++) {
        const int here = o->speed[i] < 0.0, next = o->speed[(i + 1) % n] < 0.0;
        neg += (size_t)here;
        changes += (size_t)(here != next);
        starts += (size_t)(!here && next);
    }
    out->cusps = changes;
    out->swallow_tails = starts;  /* all reversed (a circle past its centre): no tail */
    out->reversed_fraction = n ? (double)neg / (double)n : 0.0;
    return dfl_polyline_crossings(o->pts, n, &out->self_intersections, err);
}
