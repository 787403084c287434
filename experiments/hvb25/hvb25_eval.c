#include "hvb25/hvb25_eval.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <omp.h>

#include "io/manifest.h"

dfl_status hvb25_filters_from_cfg(const dfl_cfg *cfg, const char *sec, const char *key,
                                  dfl_proxy_filter *f, int *n, dfl_err *err)
{
    const char *list;
    *n = 0;
    dfl_status st = dfl_cfg_string_opt(cfg, sec, key, "", &list, err);
    if (st) return st;
    char buf[256];
    snprintf(buf, sizeof buf, "%s", list);
    for (char *save = NULL, *tok = strtok_r(buf, " \t", &save); tok;
         tok = strtok_r(NULL, " \t", &save)) {
        if (*n == HVB25_MAX_DECODINGS)
            return dfl_cfg_reject(cfg, sec, key, err, "at most %d filters", HVB25_MAX_DECODINGS);
        dfl_err e2;
        if (dfl_proxy_filter_parse(tok, &f[*n], &e2))
            return dfl_cfg_reject(cfg, sec, key, err, "%s", e2.msg);
        (*n)++;
    }
    return DFL_OK;
}

static void view_eval(const void *ctx, size_t m, const double *pts, double *val, double *grad)
{
    const hvb25_view *v = ctx;
    dfl_proxy_filter_eval(v->g, &v->o, m, pts, val, grad);
}

static const dfl_field_ops view_ops = {"proxy", view_eval, NULL, NULL, NULL};

void hvb25_view_field(const hvb25_view *v, dfl_field *out)
{
    out->dim = 3;
    out->ops = &view_ops;
    out->ctx = (void *)v;
}

/* Running sums of one decoding: count-weighted means of the slab metrics. */
typedef struct acc {
    size_t n[3], nf[3];
    double s1[3], s2[3], mx[3];
    hvb25_acc_result r;
} acc;

typedef struct slab_bufs {
    double *pts, *d, *gd, *ref, *u, *jump;
    unsigned char *m_all, *m_band, *m_off;
    double *pc;  /* exact footpoints of the cell centres (3 per cell), or NULL */
} slab_bufs;

static void bufs_free(slab_bufs *b)
{
    free(b->pts), free(b->d), free(b->gd), free(b->ref), free(b->u), free(b->jump);
    free(b->m_all), free(b->m_band), free(b->m_off), free(b->pc);
}

static int bufs_alloc(slab_bufs *b, size_t m, size_t ncells)
{
    memset(b, 0, sizeof *b);
    b->pts = malloc(3 * m * sizeof *b->pts), b->d = malloc(m * sizeof *b->d);
    b->gd = malloc(3 * m * sizeof *b->gd), b->ref = malloc(m * sizeof *b->ref);
    b->u = malloc(m * sizeof *b->u), b->jump = malloc(m * sizeof *b->jump);
    b->m_all = malloc(m), b->m_band = malloc(m), b->m_off = malloc(m);
    if (ncells) b->pc = malloc(3 * ncells * sizeof *b->pc);
    return b->pts && b->d && b->gd && b->ref && b->u && b->jump && b->m_all && b->m_band &&
           b->m_off && (!ncells || b->pc);
}

static size_t cell_index(const hvb25_cells *c, const double *x)
{
    size_t idx = 0, stride = 1;
    for (int a = 0; a < 3; a++) {
        double t = floor((x[a] - c->lo[a]) / c->h[a]);
        if (!(t >= 0)) t = 0;
        if (t > c->n - 1) t = c->n - 1;
        idx += (size_t)t * stride;
        stride *= (size_t)c->n;
    }
    return idx;
}

/* p_c = x_c - d(x_c) grad d(x_c) for every cell centre. */
static void cell_footpoints(const hvb25_acc_spec *s, double *pc)
{
    const hvb25_cells *c = &s->cells;
    const long n = c->n, nc = n * n * n;
#pragma omp parallel for schedule(static) num_threads(s->threads)
    for (long i = 0; i < nc; i++) {
        const long ijk[3] = {i % n, (i / n) % n, i / (n * n)};
        double x[3], g[3], d;
        for (int a = 0; a < 3; a++) x[a] = c->lo[a] + (ijk[a] + 0.5) * c->h[a];
        s->ref->ops->eval(s->ref->ctx, 1, x, &d, g);
        for (int a = 0; a < 3; a++) pc[3 * i + a] = x[a] - d * g[a];
    }
}

static void decode(const hvb25_acc_spec *s, int k, size_t m, const double *pts, double *u)
{
    if (s->ndec == 0) {
        s->field->ops->eval(s->field->ctx, m, pts, u, NULL);
        return;
    }
    dfl_proxy_filter_eval(s->grid, &s->dec[k], m, pts, u, NULL);
}

/* u at every point of the slab in chunks of 256, in parallel. */
static void decode_slab(const hvb25_acc_spec *s, int k, size_t m, const double *pts, double *u)
{
    const long chunks = (long)((m + 255) / 256);
#pragma omp parallel for schedule(dynamic, 4) num_threads(s->threads)
    for (long c = 0; c < chunks; c++) {
        const size_t i0 = (size_t)c * 256, len = i0 + 256 <= m ? 256 : m - i0;
        decode(s, k, len, pts + 3 * i0, u + i0);
    }
}

/* mask NULL: every point, in the band |ref| <= band (band 0: all). */
static dfl_status add_masked(acc *a, int which, size_t m, const double *u, const double *ref,
                             const unsigned char *mask, double band, dfl_err *err)
{
    dfl_metrics mt;
    dfl_status st = mask ? dfl_metrics_compute_masked(m, 3, u, NULL, ref, mask, &mt, err)
                         : dfl_metrics_compute(m, 3, u, NULL, ref, band, &mt, err);
    if (st != DFL_OK || mt.count == 0) return st;
    a->n[which] += mt.count;
    a->nf[which] += mt.nonfinite;
    a->s1[which] += mt.l1 * (double)mt.count;
    a->s2[which] += mt.mse * (double)mt.count;
    if (mt.linf > a->mx[which]) a->mx[which] = mt.linf;
    return DFL_OK;
}

static dfl_status slab(const hvb25_acc_spec *s, int z, slab_bufs *b, acc *accs, int nres,
                       dfl_err *err)
{
    const dfl_grid *g = &s->eval;
    const size_t m = (size_t)g->n[0] * (size_t)g->n[1];
    /* the node coordinate of field/sample.h, so the slabs are the grid's nodes exactly */
    const double t = (double)z / (double)(g->n[2] - 1), zc = (1.0 - t) * g->lo[2] + t * g->hi[2];
    dfl_grid pg;
    dfl_grid_plane(2, zc, g->n, g->lo, g->hi, &pg);
    for (size_t i = 0; i < m; i++) {
        double x[3];
        dfl_grid_node(&pg, i, x);
        memcpy(b->pts + 3 * i, x, sizeof x);
    }
    const long chunks = (long)((m + 255) / 256);
#pragma omp parallel for schedule(static) num_threads(s->threads)
    for (long c = 0; c < chunks; c++) {
        const size_t i0 = (size_t)c * 256, len = i0 + 256 <= m ? 256 : m - i0;
        s->ref->ops->eval(s->ref->ctx, len, b->pts + 3 * i0, b->d + i0, b->gd + 3 * i0);
    }
    const double hmax = s->cells.n ? fmax(s->cells.h[0], fmax(s->cells.h[1], s->cells.h[2])) : 1;
    size_t nmedial = 0;
    for (size_t i = 0; i < m; i++) {
        if (!isfinite(b->d[i]))
            return dfl_err_set(err, DFL_E_NUMERIC, "reference not finite at %g %g %g",
                               b->pts[3 * i], b->pts[3 * i + 1], b->pts[3 * i + 2]);
        b->jump[i] = 0;
        if (b->pc) {
            const double *x = b->pts + 3 * i, *pc = b->pc + 3 * cell_index(&s->cells, x);
            double q = 0;
            for (int a = 0; a < 3; a++) {
                const double e = x[a] - b->d[i] * b->gd[3 * i + a] - pc[a];
                q += e * e;
            }
            b->jump[i] = sqrt(q) / hmax;
        }
        nmedial += b->jump[i] > s->medial;
    }
    for (int k = 0; k < nres; k++) {
        acc *a = accs + k;
        const int sgn = s->ndec ? s->dec[k].is_signed : s->field_signed;
        const double t0 = dfl_wall_seconds();
        decode_slab(s, k, m, b->pts, b->u);
        a->r.eval_seconds += dfl_wall_seconds() - t0;
        a->r.medial += nmedial;
        size_t nonfinite = 0;
        for (size_t i = 0; i < m; i++) {
            b->ref[i] = sgn ? b->d[i] : fabs(b->d[i]);
            const int fin = isfinite(b->u[i]);
            nonfinite += !fin;
            /* field/metrics' non-finite rule: such a point is an error of
             * +inf in every set it lies in (by its reference) */
            b->m_all[i] = 1;
            b->m_band[i] = (unsigned char)(fabs(b->d[i]) <= s->band);
            b->m_off[i] = (unsigned char)(b->jump[i] <= s->medial);
            const double e = fin ? fabs(b->u[i] - b->ref[i]) : INFINITY;
            if (e > a->r.worst_err) {
                a->r.worst_err = e;
                memcpy(a->r.worst, b->pts + 3 * i, sizeof a->r.worst);
                a->r.worst_d = b->d[i];
                a->r.worst_jump = b->jump[i];
            }
        }
        a->r.nonfinite += nonfinite;
        /* the band rule of field/metrics directly; the off-medial set by mask */
        dfl_status st = add_masked(a, 0, m, b->u, b->ref, NULL, 0, err);
        if (!st) st = add_masked(a, 1, m, b->u, b->ref, NULL, s->band, err);
        if (!st) st = add_masked(a, 2, m, b->u, b->ref, !nmedial ? NULL : b->m_off, 0, err);
        if (st) return st;
    }
    return DFL_OK;
}

static void finish(acc *a)
{
    dfl_metrics *ms[3] = {&a->r.all, &a->r.band, &a->r.off};
    for (int w = 0; w < 3; w++) {
        dfl_metrics *mt = ms[w];
        mt->count = a->n[w];
        mt->l1 = a->n[w] ? a->s1[w] / (double)a->n[w] : NAN;
        mt->mse = a->n[w] ? a->s2[w] / (double)a->n[w] : NAN;
        mt->rms = sqrt(mt->mse);
        mt->linf = a->n[w] ? a->mx[w] : NAN;
        mt->gdef_mean = mt->gdef_max = NAN;
        mt->nonfinite = a->nf[w];
    }
}

dfl_status hvb25_acc_run(const hvb25_acc_spec *s, hvb25_acc_result *res, dfl_err *err)
{
    const int nres = s->ndec ? s->ndec : 1;
    const size_t m = (size_t)s->eval.n[0] * (size_t)s->eval.n[1];
    const size_t ncells = s->cells.n ? (size_t)s->cells.n * s->cells.n * s->cells.n : 0;
    slab_bufs b;
    acc accs[HVB25_MAX_DECODINGS];
    memset(accs, 0, sizeof accs);
    for (int k = 0; k < nres; k++) accs[k].r.worst_err = -1;
    dfl_status st = DFL_OK;
    if (!bufs_alloc(&b, m, ncells)) st = dfl_err_set(err, DFL_E_NOMEM, "accuracy: out of memory");
    if (!st && b.pc) cell_footpoints(s, b.pc);
    for (int z = 0; !st && z < s->eval.n[2]; z++) st = slab(s, z, &b, accs, nres, err);
    bufs_free(&b);
    if (st) return st;
    for (int k = 0; k < nres; k++) {
        finish(accs + k);
        res[k] = accs[k].r;
    }
    return DFL_OK;
}

dfl_status hvb25_acc_put(dfl_table *t, const hvb25_acc_result *r, size_t npoints, dfl_err *err)
{
    dfl_status st = dfl_metrics_put(t, "", &r->all, err);
    if (!st) st = dfl_metrics_put(t, "_band", &r->band, err);
    if (!st) st = dfl_metrics_put(t, "_off", &r->off, err);
    if (!st) st = dfl_table_set_int(t, "medial", (long)r->medial, err);
    if (!st) st = dfl_table_set_double(t, "worst_x", r->worst[0], err);
    if (!st) st = dfl_table_set_double(t, "worst_y", r->worst[1], err);
    if (!st) st = dfl_table_set_double(t, "worst_z", r->worst[2], err);
    if (!st) st = dfl_table_set_double(t, "worst_d", r->worst_d, err);
    if (!st) st = dfl_table_set_double(t, "worst_err", r->worst_err, err);
    if (!st) st = dfl_table_set_double(t, "worst_jump", r->worst_jump, err);
    if (!st) st = dfl_table_set_double(t, "eval_seconds", r->eval_seconds, err);
    if (!st) st = dfl_table_set_double(t, "eval_ns_per_query",
                                       1e9 * r->eval_seconds / (double)npoints, err);
    return st;
}
