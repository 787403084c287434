/* Adaptive polygonization with certified bounds (see polygonize.h for the
 * proofs of the bounds).  Subdivision is depth-first, left piece first, so
 * curve points come out in parameter order without sorting. */
#include "geom/polygonize.h"
#include "geom/tridist.h"

#include <assert.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/segdist.h"

#define KMAX DFL_BSPLINE_MAX_ORDER
#define MAX_DEPTH 60
#define DEFAULT_CAP 10000000u

static double dist2(int dim, const double *a, const double *b)
{
    double s = 0.0;
    for (int j = 0; j < dim; j++) s += (a[j] - b[j]) * (a[j] - b[j]);
    return s;
}

double dfl_bezier_chord_bound(const double *bez, int np, int dim)
{
    const int p = np - 1;
    const double *a = bez, *b = bez + p * dim;
    double e[3], ee = 0.0;
    for (int j = 0; j < dim; j++) {
        e[j] = b[j] - a[j];
        ee += e[j] * e[j];
    }
    int monotone = ee > 0.0;
    for (int i = 0; i < p && monotone; i++) {
        double s = 0.0;
        for (int j = 0; j < dim; j++) s += e[j] * (bez[(i + 1) * dim + j] - bez[i * dim + j]);
        if (s < 0.0) monotone = 0;
    }
    double m = 0.0;
    if (monotone) {
        /* distance of each control point to the chord's line */
        for (int i = 1; i < p; i++) {
            double w[3], we = 0.0, ww = 0.0;
            for (int j = 0; j < dim; j++) {
                w[j] = bez[i * dim + j] - a[j];
                we += w[j] * e[j];
                ww += w[j] * w[j];
            }
            double d2 = ww - we * we / ee;
            if (d2 > m) m = d2;
        }
        return sqrt(m);
    }
    for (int i = 1; i < p; i++) {
        double d2 = 0.0;
        for (int j = 0; j < dim; j++) {
            double l = a[j] + (double)i / p * e[j];
            d2 += (bez[i * dim + j] - l) * (bez[i * dim + j] - l);
        }
        if (d2 > m) m = d2;
    }
    return sqrt(m);
}

/* ---- growable output arrays ---- */
typedef struct pl_buf {
    int dim;
    size_t n, cap;
    double *pts, *t, *sb;
} pl_buf;

static int pl_push(pl_buf *b, const double *x, double t, double seg_bound)
{
    if (b->n == b->cap) {
        size_t nc = b->cap ? 2 * b->cap : 256;
        double *p = realloc(b->pts, nc * (size_t)b->dim * sizeof(double));
        if (!p) return 0;
        b->pts = p;
        double *q = realloc(b->t, nc * sizeof(double));
        if (!q) return 0;
        b->t = q;
        double *r = realloc(b->sb, nc * sizeof(double));
        if (!r) return 0;
        b->sb = r;
        b->cap = nc;
    }
    memcpy(b->pts + b->n * (size_t)b->dim, x, (size_t)b->dim * sizeof(double));
    b->t[b->n] = t;
    b->sb[b->n] = seg_bound; /* bound of the segment ending here (unused for point 0) */
    b->n++;
    return 1;
}

dfl_status dfl_polygonize_curve(const dfl_bspline *c, double eps, size_t max_segments,
                                dfl_polyline *out, dfl_err *err)
{
    if (!isfinite(eps) || !(eps > 0.0))
        return dfl_err_set(err, DFL_E_INPUT, "eps = %g: expected a finite value > 0", eps);
    if (max_segments == 0) max_segments = DEFAULT_CAP;
    const int dim = c->dim, np = c->order;
    const size_t stride = (size_t)np * (size_t)dim;
    /* stack entries: Bezier net, parameter range, depth */
    double stack_bez[(MAX_DEPTH + 2) * KMAX * 3];
    double stack_a[MAX_DEPTH + 2], stack_b[MAX_DEPTH + 2];
    int stack_d[MAX_DEPTH + 2];
    pl_buf buf = {dim, 0, 0, NULL, NULL, NULL};
    dfl_status st = DFL_OK;
    double maxb = 0.0;
    const size_t nspan = dfl_bspline_span_count(c);
    for (size_t s = 0; s < nspan && st == DFL_OK; s++) {
        size_t j = dfl_bspline_span_index(c, s);
        double a = c->knots[j], b = c->knots[j + 1];
        int top = 0;
        dfl_bspline_span_bezier(c, j, a, b, stack_bez);
        stack_a[0] = a;
        stack_b[0] = b;
        stack_d[0] = 0;
        if (buf.n == 0 && !pl_push(&buf, stack_bez, a, 0.0)) {
            st = dfl_err_set(err, DFL_E_NOMEM, "out of memory in polygonization");
            break;
        }
        while (top >= 0) {
            double *bz = stack_bez + (size_t)top * stride;
            double bound = dfl_bezier_chord_bound(bz, np, dim);
            if (bound <= eps) {
                if (buf.n > max_segments) {
                    st = dfl_err_set(err, DFL_E_NUMERIC,
                                     "polygonization needs more than %zu segments at eps = %g",
                                     max_segments, eps);
                    break;
                }
                if (!pl_push(&buf, bz + (size_t)(np - 1) * (size_t)dim, stack_b[top], bound)) {
                    st = dfl_err_set(err, DFL_E_NOMEM, "out of memory in polygonization");
                    break;
                }
                if (bound > maxb) maxb = bound;
                top--;
                continue;
            }
            if (stack_d[top] >= MAX_DEPTH) {
                st = dfl_err_set(err, DFL_E_NUMERIC,
                                 "eps = %g too small for double precision: a piece near t = %g "
                                 "still deviates by %g after %d bisections",
                                 eps, stack_a[top], bound, MAX_DEPTH);
                break;
            }
            /* replace top by its right half, push the left half on top */
            double L[KMAX * 3], R[KMAX * 3];
            dfl_bezier_split(bz, np, dim, 0.5, L, R);
            double ta = stack_a[top], tb = stack_b[top], tm = 0.5 * (ta + tb);
            int d = stack_d[top] + 1;
            memcpy(bz, R, stride * sizeof(double));
            stack_a[top] = tm;
            stack_b[top] = tb;
            stack_d[top] = d;
            top++;
            assert(top < MAX_DEPTH + 2);
            memcpy(stack_bez + (size_t)top * stride, L, stride * sizeof(double));
            stack_a[top] = ta;
            stack_b[top] = tm;
            stack_d[top] = d;
        }
    }
    if (st != DFL_OK) {
        free(buf.pts);
        free(buf.t);
        free(buf.sb);
        return st;
    }
    assert(buf.n >= 2);
    if (c->closed) memcpy(buf.pts + (buf.n - 1) * (size_t)dim, buf.pts, (size_t)dim * sizeof(double));
    /* seg_bound[i] is the bound of segment i = (point i, point i+1) */
    memmove(buf.sb, buf.sb + 1, (buf.n - 1) * sizeof(double));
    out->dim = dim;
    out->n = buf.n;
    out->pts = buf.pts;
    out->t = buf.t;
    out->seg_bound = buf.sb;
    out->bound = maxb;
    return DFL_OK;
}

double dfl_polygonize_curve_segments_bound(const dfl_bspline *c, double eps)
{
    if (!(eps > 0.0)) return INFINITY;
    const int dim = c->dim, np = c->order, p = np - 1;
    double bez[KMAX * 3], total = 0.0;
    const size_t nspan = dfl_bspline_span_count(c);
    for (size_t s = 0; s < nspan; s++) {
        const size_t j = dfl_bspline_span_index(c, s);
        dfl_bspline_span_bezier(c, j, c->knots[j], c->knots[j + 1], bez);
        double D = 0.0, scale = 0.0;
        for (int i = 0; i + 2 < np; i++) {
            double d2 = 0.0;
            for (int a = 0; a < dim; a++) {
                const double v = bez[(i + 2) * dim + a] - 2 * bez[(i + 1) * dim + a] +
                                 bez[i * dim + a];
                d2 += v * v;
            }
            D = fmax(D, sqrt(d2));
        }
        for (int i = 0; i < np * dim; i++) scale = fmax(scale, fabs(bez[i]));
        /* the bound's own rounding: a few ulps of the coordinates */
        const double slack = 64 * DBL_EPSILON * scale;
        double b = D * p * p / 8.0, pieces = 1.0;
        for (int k = 0; b + slack > eps && k < MAX_DEPTH; k++) b /= 4.0, pieces *= 2.0;
        total += pieces;
        if (total > DEFAULT_CAP) return DEFAULT_CAP;
    }
    return total;
}

void dfl_polyline_free(dfl_polyline *p)
{
    if (!p) return;
    free(p->pts);
    free(p->t);
    free(p->seg_bound);
    memset(p, 0, sizeof *p);
}

/* ---- uniform grid over polyline segments for nearest-segment queries ---- */
typedef struct seg_grid {
    int dim;
    double lo[3], h;
    long nc[3];
    size_t *start, *idx; /* CSR: cell -> segment ids */
} seg_grid;

static long cell_coord(const seg_grid *g, int j, double x)
{
    /* clamped as a double: the cast of NaN or of one beyond long's range
     * is undefined (x86 gives LONG_MIN, so +inf went to cell 0) */
    const double c = floor((x - g->lo[j]) / g->h);
    return !(c >= 0.0) ? 0 : (c >= (double)g->nc[j] ? g->nc[j] - 1 : (long)c);
}

static size_t cell_id(const seg_grid *g, const long *c)
{
    size_t id = 0;
    for (int j = g->dim - 1; j >= 0; j--) id = id * (size_t)g->nc[j] + (size_t)c[j];
    return id;
}

/* calls visit for each cell in the box [lo, hi] (grid coordinates) */
#define FOR_CELLS(g, clo, chi, cc)                                                         \
    for (cc[2] = (g)->dim > 2 ? clo[2] : 0; cc[2] <= ((g)->dim > 2 ? chi[2] : 0); cc[2]++) \
        for (cc[1] = clo[1]; cc[1] <= chi[1]; cc[1]++)                                     \
            for (cc[0] = clo[0]; cc[0] <= chi[0]; cc[0]++)

static int grid_build(const dfl_polyline *p, seg_grid *g)
{
    const int dim = p->dim;
    const size_t ns = p->n - 1;
    memset(g, 0, sizeof *g);
    g->dim = dim;
    double hi[3] = {0, 0, 0}, len = 0.0;
    for (int j = 0; j < dim; j++) {
        g->lo[j] = INFINITY;
        hi[j] = -INFINITY;
    }
    for (size_t i = 0; i < p->n; i++)
        for (int j = 0; j < dim; j++) {
            g->lo[j] = fmin(g->lo[j], p->pts[i * (size_t)dim + (size_t)j]);
            hi[j] = fmax(hi[j], p->pts[i * (size_t)dim + (size_t)j]);
        }
    for (size_t i = 0; i < ns; i++)
        len += sqrt(dist2(dim, p->pts + i * (size_t)dim, p->pts + (i + 1) * (size_t)dim));
    double ext = 0.0;
    for (int j = 0; j < dim; j++) ext = fmax(ext, hi[j] - g->lo[j]);
    g->h = fmax(len / (double)ns, ext / 4096.0);
    if (!(g->h > 0.0)) g->h = 1.0;
    for (;;) {
        double cells = 1.0;
        for (int j = 0; j < dim; j++) cells *= floor((hi[j] - g->lo[j]) / g->h) + 1.0;
        if (cells <= 4.0 * (double)ns + 64.0) break;
        g->h *= 1.5;
    }
    size_t total = 1;
    for (int j = 0; j < 3; j++) {
        g->nc[j] = j < dim ? (long)floor((hi[j] - g->lo[j]) / g->h) + 1 : 1;
        total *= (size_t)g->nc[j];
    }
    g->start = calloc(total + 1, sizeof(size_t));
    if (!g->start) return 0;
    long clo[3] = {0, 0, 0}, chi[3] = {0, 0, 0}, cc[3];
    for (int pass = 0; pass < 2; pass++) {
        size_t *fill = NULL;
        if (pass == 1) {
            for (size_t c = 0; c < total; c++) g->start[c + 1] += g->start[c];
            g->idx = malloc((g->start[total] + 1) * sizeof(size_t));
            fill = calloc(total, sizeof(size_t));
            if (!g->idx || !fill) {
                free(fill);
                return 0;
            }
        }
        for (size_t i = 0; i < ns; i++) {
            const double *a = p->pts + i * (size_t)dim, *b = a + dim;
            for (int j = 0; j < dim; j++) {
                clo[j] = cell_coord(g, j, fmin(a[j], b[j]));
                chi[j] = cell_coord(g, j, fmax(a[j], b[j]));
            }
            FOR_CELLS(g, clo, chi, cc)
            {
                size_t id = cell_id(g, cc);
                if (pass == 0) g->start[id + 1]++;
                else g->idx[g->start[id] + fill[id]++] = i;
            }
        }
        free(fill);
    }
    return 1;
}

static void grid_free(seg_grid *g)
{
    free(g->start);
    free(g->idx);
}

/* distance from x to the polyline, given an upper bound d0 */
static double grid_dist(const seg_grid *g, const dfl_polyline *p, const double *x, double d0)
{
    const int dim = p->dim;
    double best = d0;
    long clo[3] = {0, 0, 0}, chi[3] = {0, 0, 0}, cc[3];
    for (int j = 0; j < dim; j++) {
        clo[j] = cell_coord(g, j, x[j] - best);
        chi[j] = cell_coord(g, j, x[j] + best);
    }
    FOR_CELLS(g, clo, chi, cc)
    {
        size_t id = cell_id(g, cc);
        for (size_t k = g->start[id]; k < g->start[id + 1]; k++) {
            size_t i = g->idx[k];
            double d = dfl_point_segment_dist(dim, x, p->pts + i * (size_t)dim,
                                              p->pts + (i + 1) * (size_t)dim);
            if (d < best) best = d;
        }
    }
    return best;
}

static double curve_poly_dist(const dfl_bspline *c, const dfl_polyline *p, const seg_grid *g,
                              size_t seg, double t)
{
    double x[3];
    dfl_bspline_eval(c, t, 0, x);
    const int dim = p->dim;
    double d0 = dfl_point_segment_dist(dim, x, p->pts + seg * (size_t)dim,
                                       p->pts + (seg + 1) * (size_t)dim);
    return grid_dist(g, p, x, d0);
}

dfl_status dfl_polyline_deviation(const dfl_bspline *c, const dfl_polyline *p, int samples,
                                  double *out, dfl_err *err)
{
    if (samples < 2) samples = 2;
    if (p->n < 2) return dfl_err_set(err, DFL_E_INPUT, "polyline has fewer than 2 points");
    seg_grid g;
    if (!grid_build(p, &g)) {
        grid_free(&g);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory measuring a polyline's deviation");
    }
    double dev = 0.0;
    const double gr = 0.5 * (sqrt(5.0) - 1.0);
    for (size_t i = 0; i + 1 < p->n; i++) {
        double ta = p->t[i], tb = p->t[i + 1];
        int kbest = 0;
        double dbest = -1.0;
        for (int k = 0; k < samples; k++) {
            double t = ta + (tb - ta) * (double)k / (samples - 1);
            double d = curve_poly_dist(c, p, &g, i, t);
            if (d > dbest) {
                dbest = d;
                kbest = k;
            }
        }
        /* golden-section maximization around the best sample */
        double lo = ta + (tb - ta) * (double)(kbest > 0 ? kbest - 1 : 0) / (samples - 1);
        double hi = ta + (tb - ta) * (double)(kbest < samples - 1 ? kbest + 1 : kbest) / (samples - 1);
        double x1 = hi - gr * (hi - lo), x2 = lo + gr * (hi - lo);
        double f1 = curve_poly_dist(c, p, &g, i, x1), f2 = curve_poly_dist(c, p, &g, i, x2);
        for (int it = 0; it < 60 && hi - lo > 1e-15 * (1.0 + fabs(hi)); it++) {
            if (f1 > f2) {
                hi = x2;
                x2 = x1;
                f2 = f1;
                x1 = hi - gr * (hi - lo);
                f1 = curve_poly_dist(c, p, &g, i, x1);
            } else {
                lo = x1;
                x1 = x2;
                f1 = f2;
                x2 = lo + gr * (hi - lo);
                f2 = curve_poly_dist(c, p, &g, i, x2);
            }
        }
        dbest = fmax(dbest, fmax(f1, f2));
        if (dbest > dev) dev = dbest;
    }
    grid_free(&g);
    *out = dev;
    return DFL_OK;
}

/* ---- surfaces ---- */

double dfl_point_triangle_dist(const double *p, const double *a, const double *b,
                               const double *c)
{
    return dfl_tridist_closest(p, a, b, c, NULL, NULL);
}

/* Bound and directional chord deviations (du along u, dv along v). */
static double cell_bound(const double *bez, int ku, int kv, double *du, double *dv)
{
    const int p = ku - 1, q = kv - 1;
    const double *P00 = bez, *P10 = bez + 3 * p, *P01 = bez + 3 * (ku * q),
                 *P11 = bez + 3 * (p + ku * q);
    double m = 0.0, mu = 0.0, mv = 0.0, w2 = 0.0;
    for (int c = 0; c < 3; c++) {
        double w = P00[c] - P10[c] - P01[c] + P11[c];
        w2 += w * w;
    }
    for (int j = 0; j <= q; j++)
        for (int i = 0; i <= p; i++) {
            double s = (double)i / p, t = (double)j / q;
            const double *B = bez + 3 * (i + ku * j);
            const double *R0 = bez + 3 * (ku * j), *R1 = bez + 3 * (p + ku * j);
            const double *C0 = bez + 3 * i, *C1 = bez + 3 * (i + ku * q);
            double e = 0.0, eu = 0.0, ev = 0.0;
            for (int c = 0; c < 3; c++) {
                double L = (1 - s) * (1 - t) * P00[c] + s * (1 - t) * P10[c] +
                           (1 - s) * t * P01[c] + s * t * P11[c];
                double Lu = (1 - s) * R0[c] + s * R1[c];
                double Lv = (1 - t) * C0[c] + t * C1[c];
                e += (B[c] - L) * (B[c] - L);
                eu += (B[c] - Lu) * (B[c] - Lu);
                ev += (B[c] - Lv) * (B[c] - Lv);
            }
            m = fmax(m, e);
            mu = fmax(mu, eu);
            mv = fmax(mv, ev);
        }
    if (du) *du = sqrt(mu);
    if (dv) *dv = sqrt(mv);
    return sqrt(m) + 0.25 * sqrt(w2);
}

double dfl_bezier_cell_bound(const double *bez, int ku, int kv)
{
    return cell_bound(bez, ku, kv, NULL, NULL);
}

static void cell_net(const dfl_surface *s, double ua, double ub, double va, double vb,
                     double *bez)
{
    size_t su = dfl_knot_span(s->knots_u, s->ku, s->nu, 0.5 * (ua + ub), 1);
    size_t sv = dfl_knot_span(s->knots_v, s->kv, s->nv, 0.5 * (va + vb), 1);
    dfl_surface_cell_bezier(s, su, sv, ua, ub, va, vb, bez);
}

/* interval breaks of one direction: growable */
typedef struct brk {
    size_t n;
    double *x;
} brk;

static int init_breaks(const dfl_surface *s, int dir, brk *b)
{
    size_t ns = dfl_surface_span_count(s, dir);
    const double *U = dir == 0 ? s->knots_u : s->knots_v;
    b->x = malloc((ns + 1) * sizeof(double));
    if (!b->x) return 0;
    b->n = ns + 1;
    for (size_t k = 0; k < ns; k++) b->x[k] = U[dfl_surface_span_index(s, dir, k)];
    b->x[ns] = dir == 0 ? s->u1 : s->v1;
    return 1;
}

static int split_breaks(brk *b, const unsigned char *mark)
{
    size_t add = 0;
    for (size_t i = 0; i + 1 < b->n; i++) add += mark[i] != 0;
    if (!add) return 1;
    double *nx = malloc((b->n + add) * sizeof(double));
    if (!nx) return 0;
    size_t k = 0;
    for (size_t i = 0; i + 1 < b->n; i++) {
        nx[k++] = b->x[i];
        if (mark[i]) nx[k++] = 0.5 * (b->x[i] + b->x[i + 1]);
    }
    nx[k++] = b->x[b->n - 1];
    free(b->x);
    b->x = nx;
    b->n = k;
    return 1;
}

typedef struct mesh_buf {
    size_t nv, cv, nt, ct;
    double *verts, *uv, *cb;
    size_t *tris, *tp;
} mesh_buf;

static int mesh_reserve(mesh_buf *m, size_t nv, size_t nt)
{
    if (m->nv + nv > m->cv) {
        size_t c = (m->nv + nv) * 2;
        double *a = realloc(m->verts, c * 3 * sizeof(double));
        if (!a) return 0;
        m->verts = a;
        double *b = realloc(m->uv, c * 2 * sizeof(double));
        if (!b) return 0;
        m->uv = b;
        m->cv = c;
    }
    if (m->nt + nt > m->ct) {
        size_t c = (m->nt + nt) * 2;
        size_t *a = realloc(m->tris, c * 3 * sizeof(size_t));
        if (!a) return 0;
        m->tris = a;
        size_t *b = realloc(m->tp, c * sizeof(size_t));
        if (!b) return 0;
        m->tp = b;
        double *d = realloc(m->cb, (c / 2 + 1) * sizeof(double));
        if (!d) return 0;
        m->cb = d;
        m->ct = c;
    }
    return 1;
}

static dfl_status mesh_patch(const dfl_surface *s, size_t pi, double eps, size_t max_tris,
                             mesh_buf *m, double *maxb, dfl_err *err)
{
    const int ku = s->ku, kv = s->kv;
    brk bu = {0, NULL}, bv = {0, NULL};
    unsigned char *mu = NULL, *mv = NULL;
    double *cbound = NULL;
    dfl_status st = DFL_OK;
    if (!init_breaks(s, 0, &bu) || !init_breaks(s, 1, &bv)) {
        st = dfl_err_set(err, DFL_E_NOMEM, "out of memory in triangulation");
        goto done;
    }
    for (int pass = 0;; pass++) {
        size_t nu = bu.n - 1, nv = bv.n - 1;
        if (2 * nu * nv + m->nt > max_tris) {
            st = dfl_err_set(err, DFL_E_NUMERIC,
                             "triangulation needs more than %zu triangles at eps = %g", max_tris,
                             eps);
            goto done;
        }
        free(mu);
        free(mv);
        free(cbound);
        mu = calloc(nu, 1);
        mv = calloc(nv, 1);
        cbound = malloc(nu * nv * sizeof(double));
        if (!mu || !mv || !cbound) {
            st = dfl_err_set(err, DFL_E_NOMEM, "out of memory in triangulation");
            goto done;
        }
        int any = 0;
        for (size_t j = 0; j < nv; j++)
            for (size_t i = 0; i < nu; i++) {
                double bez[KMAX * KMAX * 3], du, dv;
                cell_net(s, bu.x[i], bu.x[i + 1], bv.x[j], bv.x[j + 1], bez);
                double b = cell_bound(bez, ku, kv, &du, &dv);
                cbound[i + nu * j] = b;
                if (b > eps) {
                    any = 1;
                    if (du >= dv) mu[i] = 1;
                    else mv[j] = 1;
                }
            }
        if (!any) break;
        if (pass >= MAX_DEPTH) {
            st = dfl_err_set(err, DFL_E_NUMERIC,
                             "eps = %g too small for double precision: patch %zu still above "
                             "eps after %d refinement passes",
                             eps, pi, MAX_DEPTH);
            goto done;
        }
        if (!split_breaks(&bu, mu) || !split_breaks(&bv, mv)) {
            st = dfl_err_set(err, DFL_E_NOMEM, "out of memory in triangulation");
            goto done;
        }
    }
    {
        size_t nu = bu.n - 1, nv = bv.n - 1, v0 = m->nv;
        if (!mesh_reserve(m, bu.n * bv.n, 2 * nu * nv)) {
            st = dfl_err_set(err, DFL_E_NOMEM, "out of memory in triangulation");
            goto done;
        }
        for (size_t j = 0; j < bv.n; j++)
            for (size_t i = 0; i < bu.n; i++) {
                double d[3];
                dfl_surface_eval(s, bu.x[i], bv.x[j], 0, d);
                memcpy(m->verts + 3 * m->nv, d, sizeof d);
                m->uv[2 * m->nv] = bu.x[i];
                m->uv[2 * m->nv + 1] = bv.x[j];
                m->nv++;
            }
        for (size_t j = 0; j < nv; j++)
            for (size_t i = 0; i < nu; i++) {
                size_t a = v0 + i + bu.n * j, b = a + 1, c = a + bu.n, dd = c + 1;
                size_t *T = m->tris + 3 * m->nt;
                /* lower (P00, P10, P01) and upper (P11, P01, P10) */
                T[0] = a; T[1] = b; T[2] = c;
                T[3] = dd; T[4] = c; T[5] = b;
                m->tp[m->nt] = m->tp[m->nt + 1] = pi;
                m->cb[m->nt / 2] = cbound[i + nu * j];
                if (cbound[i + nu * j] > *maxb) *maxb = cbound[i + nu * j];
                m->nt += 2;
            }
    }
done:
    free(bu.x);
    free(bv.x);
    free(mu);
    free(mv);
    free(cbound);
    return st;
}

/* Hands the buffers of m over to *out. */
static void mesh_take(const mesh_buf *m, double maxb, dfl_trimesh *out)
{
    out->nverts = m->nv;
    out->verts = m->verts;
    out->uv = m->uv;
    out->ntris = m->nt;
    out->tris = m->tris;
    out->tri_patch = m->tp;
    out->cell_bound = m->cb;
    out->bound = maxb;
}

dfl_status dfl_polygonize_surface(const dfl_surface_set *s, double eps, size_t max_tris,
                                  dfl_trimesh *out, dfl_err *err)
{
    if (!isfinite(eps) || !(eps > 0.0))
        return dfl_err_set(err, DFL_E_INPUT, "eps = %g: expected a finite value > 0", eps);
    if (max_tris == 0) max_tris = DEFAULT_CAP;
    mesh_buf m;
    memset(&m, 0, sizeof m);
    double maxb = 0.0;
    dfl_trimesh t;
    for (size_t p = 0; p < s->npatch; p++) {
        dfl_status st = mesh_patch(&s->patch[p], p, eps, max_tris, &m, &maxb, err);
        if (st != DFL_OK) {
            mesh_take(&m, maxb, &t); /* no partial output: release what was built */
            dfl_trimesh_free(&t);
            return st;
        }
    }
    mesh_take(&m, maxb, out);
    return DFL_OK;
}

void dfl_trimesh_free(dfl_trimesh *m)
{
    if (!m) return;
    free(m->verts);
    free(m->uv);
    free(m->tris);
    free(m->tri_patch);
    free(m->cell_bound);
    memset(m, 0, sizeof *m);
}

static double cell_dev(const dfl_surface *s, const dfl_trimesh *m, size_t cell, double u,
                       double v)
{
    const size_t *T = m->tris + 6 * cell;
    double x[3];
    dfl_surface_eval(s, u, v, 0, x);
    double d1 = dfl_point_triangle_dist(x, m->verts + 3 * T[0], m->verts + 3 * T[1],
                                        m->verts + 3 * T[2]);
    double d2 = dfl_point_triangle_dist(x, m->verts + 3 * T[3], m->verts + 3 * T[4],
                                        m->verts + 3 * T[5]);
    return fmin(d1, d2);
}

dfl_status dfl_trimesh_deviation(const dfl_surface_set *s, const dfl_trimesh *m, int samples,
                                 double *out, dfl_err *err)
{
    (void)err;
    if (samples < 1) samples = 1;
    double dev = 0.0;
    for (size_t c = 0; c < m->ntris / 2; c++) {
        const dfl_surface *sp = &s->patch[m->tri_patch[2 * c]];
        const size_t *T = m->tris + 6 * c;
        double ua = m->uv[2 * T[0]], va = m->uv[2 * T[0] + 1];
        double ub = m->uv[2 * T[1]], vb = m->uv[2 * T[2] + 1];
        double bu = ua, bv = va, best = -1.0;
        for (int j = 0; j <= samples; j++)
            for (int i = 0; i <= samples; i++) {
                double u = ua + (ub - ua) * i / samples, v = va + (vb - va) * j / samples;
                double d = cell_dev(sp, m, c, u, v);
                if (d > best) {
                    best = d;
                    bu = u;
                    bv = v;
                }
            }
        /* compass search for the local maximum */
        double hu = (ub - ua) / samples, hv = (vb - va) / samples;
        for (int it = 0; it < 200 && (hu > 1e-9 * (ub - ua)); it++) {
            int moved = 0;
            static const int dirs[8][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1},
                                           {1, 1}, {-1, -1}, {1, -1}, {-1, 1}};
            for (int k = 0; k < 8; k++) {
                double u = fmin(ub, fmax(ua, bu + dirs[k][0] * hu));
                double v = fmin(vb, fmax(va, bv + dirs[k][1] * hv));
                double d = cell_dev(sp, m, c, u, v);
                if (d > best) {
                    best = d;
                    bu = u;
                    bv = v;
                    moved = 1;
                }
            }
            if (!moved) {
                hu *= 0.5;
                hv *= 0.5;
            }
        }
        if (best > dev) dev = best;
    }
    *out = dev;
    return DFL_OK;
}
