/* sjp10 study glue: cached validation references, table columns, mesh and
 * graph files.  Parallel loops run over fixed chunks and combine per-chunk
 * partial results in chunk order, so tables are bit-identical at any
 * thread count. */
#include "sjp10/sjp10_common.h"

#include "cfg/field_cost.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/path.h"
#include "io/table.h"
#include "io/vtk.h"
#include "cfg/curve_cfg.h"
#include "cfg/list_cfg.h"
#include "cfg/pht_cfg.h"
#include "cfg/shape_cfg.h"
#include "pht/spline.h"

#define CHUNK 4096

static dfl_status nomem(dfl_err *err, const char *what)
{
    return dfl_err_set(err, DFL_E_NOMEM, "sjp10: out of memory (%s)", what);
}

static size_t nchunks(size_t m)
{
    return (m + CHUNK - 1) / CHUNK;
}

void sjp10_eval(const dfl_field *f, size_t m, const double *pts, double *val, double *grad,
                int threads)
{
    const long nc = (long)nchunks(m);
    const int dim = f->dim;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads > 0 ? threads : 1)
    for (long c = 0; c < nc; c++) {
        const size_t a = (size_t)c * CHUNK, k = m - a < CHUNK ? m - a : CHUNK;
        f->ops->eval(f->ctx, k, pts + a * (size_t)dim, val + a, grad ? grad + a * (size_t)dim : NULL);
    }
}

void sjp10_shape_eval(const dfl_shape *s, size_t m, const double *pts, double *val,
                           double *grad, int threads)
{
    const long nc = (long)nchunks(m);
    const int dim = s->dim;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads > 0 ? threads : 1)
    for (long c = 0; c < nc; c++) {
        const size_t a = (size_t)c * CHUNK, k = m - a < CHUNK ? m - a : CHUNK;
        dfl_shape_eval(s, k, pts + a * (size_t)dim, val + a, grad + a * (size_t)dim);
    }
}

void sjp10_ref_free(sjp10_ref *r)
{
    if (!r) return;
    free(r->pts);
    free(r->d);
    free(r->g);
    free(r->near);
    memset(r, 0, sizeof *r);
}

/* Nodes n^dim and midpoints (n-1)^dim (0 without midpoints) of the grid protocol. */
static void grid_counts(int dim, int n, int midpoints, size_t *nn, size_t *nm)
{
    *nn = *nm = 1;
    for (int j = 0; j < dim; j++) {
        *nn *= (size_t)n;
        *nm *= (size_t)(n - 1);
    }
    if (!midpoints) *nm = 0;
}

/* Node (or midpoint) i of the grid with n (or n - 1) points per axis. */
static void grid_point(int dim, const double *lo, const double *hi, int n, int mid, size_t i,
                       double *x)
{
    const size_t k = (size_t)(mid ? n - 1 : n);
    for (int j = 0; j < dim; j++) {
        const size_t ij = i % k;
        i /= k;
        const double t = mid ? ((double)ij + 0.5) / (double)(n - 1) : (double)ij / (double)(n - 1);
        x[j] = (1.0 - t) * lo[j] + t * hi[j];
    }
}

dfl_status sjp10_ref_grid(const dfl_shape *shape, const double *lo, const double *hi, int n,
                          int midpoints, double band, int threads, sjp10_ref *out, dfl_err *err)
{
    memset(out, 0, sizeof *out);
    if (n < 2) return dfl_err_set(err, DFL_E_INPUT, "validation grid: n must be >= 2, got %d", n);
    const int dim = shape->dim;
    size_t nn, nm;
    grid_counts(dim, n, midpoints, &nn, &nm);
    const size_t m = nn + nm;
    out->dim = dim;
    out->m = m;
    out->band = band;
    out->pts = malloc(m * (size_t)dim * sizeof *out->pts);
    out->d = malloc(m * sizeof *out->d);
    out->g = malloc(m * (size_t)dim * sizeof *out->g);
    out->near = calloc(m ? m : 1, 1);
    if (!out->pts || !out->d || !out->g || !out->near) {
        sjp10_ref_free(out);
        return nomem(err, "validation points");
    }
    for (size_t i = 0; i < nn; i++) grid_point(dim, lo, hi, n, 0, i, out->pts + i * (size_t)dim);
    for (size_t i = 0; i < nm; i++)
        grid_point(dim, lo, hi, n, 1, i, out->pts + (nn + i) * (size_t)dim);
    sjp10_shape_eval(shape, m, out->pts, out->d, out->g, threads);
    dfl_status st = DFL_OK;
    if (band > 0.0) st = dfl_pht_medial_band(shape, m, out->pts, band, out->near, err);
    if (st) sjp10_ref_free(out);
    return st;
}

typedef struct acc {
    size_t n;
    double max, sum, sq, gmax, gsum;
} acc;

/* field/metrics' non-finite rule: a NaN error (a non-finite value of the
 * fit) is +inf, so max, mean and rms become inf instead of a NaN that the
 * max would drop. */
static void acc_add(acc *a, double e, double ge)
{
    if (isnan(e)) e = INFINITY;
    if (isnan(ge)) ge = INFINITY;
    a->n++;
    if (e > a->max) a->max = e;
    a->sum += e;
    a->sq += e * e;
    if (ge > a->gmax) a->gmax = ge;
    a->gsum += ge;
}

static void acc_merge(acc *a, const acc *b)
{
    a->n += b->n;
    a->max = fmax(a->max, b->max);
    a->sum += b->sum;
    a->sq += b->sq;
    a->gmax = fmax(a->gmax, b->gmax);
    a->gsum += b->gsum;
}

static void acc_stats(const acc *a, dfl_pht_val_stats *s)
{
    s->n = a->n;
    s->max = a->n ? a->max : NAN;
    s->mean = a->n ? a->sum / (double)a->n : NAN;
    s->rms = a->n ? sqrt(a->sq / (double)a->n) : NAN;
    s->gmax = a->n ? a->gmax : NAN;
    s->gmean = a->n ? a->gsum / (double)a->n : NAN;
}

dfl_status sjp10_ref_errors(const dfl_field *f, const sjp10_ref *r, int threads, dfl_pht_val *out,
                            dfl_err *err)
{
    memset(out, 0, sizeof *out);
    const size_t m = r->m, nc = nchunks(m);
    const int dim = r->dim;
    double *v = malloc((m ? m : 1) * sizeof *v), *g = malloc((m ? m : 1) * (size_t)dim * sizeof *g);
    acc *pa = calloc(2 * (nc ? nc : 1), sizeof *pa);
    size_t *pband = calloc(nc ? nc : 1, sizeof *pband), *pskip = calloc(nc ? nc : 1, sizeof *pskip);
    if (!v || !g || !pa || !pband || !pskip) {
        free(v), free(g), free(pa), free(pband), free(pskip);
        return nomem(err, "validation values");
    }
    sjp10_eval(f, m, r->pts, v, g, threads);
#pragma omp parallel for schedule(static) num_threads(threads > 0 ? threads : 1)
    for (long c = 0; c < (long)nc; c++) {
        const size_t a = (size_t)c * CHUNK, b = a + CHUNK < m ? a + CHUNK : m;
        for (size_t i = a; i < b; i++) {
            if (!isfinite(r->d[i])) {
                pskip[c]++;
                continue;
            }
            const double e = fabs(v[i] - r->d[i]);
            double gg = 0;
            for (int j = 0; j < dim; j++) {
                const double dg = g[i * dim + j] - r->g[i * dim + j];
                gg += dg * dg;
            }
            acc_add(&pa[2 * c], e, sqrt(gg));
            if (r->near[i]) pband[c]++;
            else acc_add(&pa[2 * c + 1], e, sqrt(gg));
        }
    }
    acc all = {0}, off = {0};
    for (size_t c = 0; c < nc; c++) {
        acc_merge(&all, &pa[2 * c]);
        acc_merge(&off, &pa[2 * c + 1]);
        out->band += pband[c];
        out->skipped += pskip[c];
    }
    acc_stats(&all, &out->all);
    acc_stats(&off, &out->off);
    free(v), free(g), free(pa), free(pband), free(pskip);
    return DFL_OK;
}

dfl_status sjp10_put_fit(dfl_table *t, const dfl_pht_fit *f, const dfl_pht_cellval *cv, double eps,
                         dfl_err *err)
{
    int conv = f->converged;
    const char *reason = "none";
    if (!(eps > 0)) reason = "no_target";
    else if (!f->converged) reason = "level_cap";
    else if (cv && !(cv->max <= eps)) reason = "estimator", conv = 0;
    const dfl_pht_level *last = &f->levels[f->nlevels - 1];
    double tf = 0, ts = 0, tm = 0;
    for (int k = 0; k < f->nlevels; k++) {
        tf += f->levels[k].t_foot;
        ts += f->levels[k].t_spline;
        tm += f->levels[k].t_mesh;
    }
    dfl_status st = dfl_table_set_int(t, "cells", (long)last->cells, err);
    if (!st) st = dfl_table_set_int(t, "base_vertices", (long)last->base_vertices, err);
    if (!st) st = dfl_table_set_int(t, "dofs", (long)last->dofs, err);
    if (!st) st = dfl_table_set_int(t, "levels", (long)f->nlevels, err);
    if (!st) st = dfl_table_set_int(t, "max_cell_level", (long)dfl_tmesh_max_level(f->mesh), err);
    if (!st) st = dfl_table_set_int(t, "converged", (long)conv, err);
    if (!st) st = dfl_table_set_string(t, "reason", reason, err);
    if (!st) st = dfl_table_set_int(t, "capped_cells", (long)f->capped, err);
    if (!st) st = dfl_table_set_int(t, "medial_vertices", (long)f->medial_vertices, err);
    if (!st) st = dfl_table_set_double(t, "est_max", last->max_err, err);
    if (!st) st = dfl_table_set_double(t, "est_mean", last->mean_err, err);
    if (!st) st = dfl_table_set_double(t, "t_total", f->t_total, err);
    if (!st) st = dfl_table_set_double(t, "t_foot", tf, err);
    if (!st) st = dfl_table_set_double(t, "t_spline", ts, err);
    if (!st) st = dfl_table_set_double(t, "t_mesh", tm, err);
    return st;
}

dfl_status sjp10_put_val(dfl_table *t, const char *prefix, const dfl_pht_val *v, dfl_err *err)
{
    static const char *const names[] = {"max", "mean", "rms", "gmax", "off_max", "off_mean",
                                        "off_rms", "off_gmax"};
    const double vals[] = {v->all.max, v->all.mean, v->all.rms, v->all.gmax,
                           v->off.max, v->off.mean, v->off.rms, v->off.gmax};
    char col[96];
    dfl_status st = DFL_OK;
    for (int i = 0; i < 8 && !st; i++) {
        snprintf(col, sizeof col, "%s%s", prefix, names[i]);
        st = dfl_table_set_double(t, col, vals[i], err);
    }
    snprintf(col, sizeof col, "%spoints", prefix);
    if (!st) st = dfl_table_set_int(t, col, (long)v->all.n, err);
    snprintf(col, sizeof col, "%sband_points", prefix);
    if (!st) st = dfl_table_set_int(t, col, (long)v->band, err);
    /* read by the runner's non-finite rule (harness/nonfinite.h) */
    snprintf(col, sizeof col, "%snonfinite", prefix);
    if (!st) st = dfl_table_set_int(t, col, (long)v->nonfinite, err);
    return st;
}

dfl_status sjp10_cellval(const dfl_pht_spline *s, const dfl_shape *shape, double band, double eps,
                         dfl_pht_cellval *out, dfl_err *err)
{
    dfl_pht_cellval_opts o;
    dfl_pht_cellval_opts_default(shape->dim, &o);
    o.band = band;
    o.eps = eps;
    return dfl_pht_validate_cells(s, shape, &o, out, err);
}

dfl_status sjp10_put_cellval(dfl_table *t, const dfl_pht_cellval *cv, double eps, dfl_err *err)
{
    dfl_pht_cellval none;
    if (!cv) {
        memset(&none, 0, sizeof none);
        none.max = none.band_max = none.off_max = none.medial_max = none.gmax = NAN;
        cv = &none;
        eps = NAN;
    }
    dfl_status st = dfl_table_set_int(t, "cv_points", (long)cv->n, err);
    if (!st) st = dfl_table_set_double(t, "cv_max", cv->max, err);
    if (!st) st = dfl_table_set_double(t, "cv_band_max", cv->band_max, err);
    if (!st) st = dfl_table_set_double(t, "cv_off_max", cv->off_max, err);
    if (!st) st = dfl_table_set_double(t, "cv_medial_max", cv->medial_max, err);
    if (!st) st = dfl_table_set_int(t, "cv_medial_points", (long)cv->medial, err);
    if (!st) st = dfl_table_set_int(t, "cv_medial_cells", (long)cv->medial_cells, err);
    const double share = eps > 0 && cv->n ? (double)cv->above / (double)cv->n : NAN;
    if (!st) st = dfl_table_set_double(t, "cv_above_eps", share, err);
    if (!st) st = dfl_table_set_double(t, "cv_gmax", cv->gmax, err);
    if (!st) st = dfl_table_set_int(t, "cv_nonfinite", (long)cv->nonfinite, err);
    return st;
}

static const char *const rule_names[SJP10_RULES] = {"dflab", "paper"};

const char *sjp10_rule_name(int rule)
{
    return rule >= 0 && rule < SJP10_RULES ? rule_names[rule] : "?";
}

void sjp10_rule_apply(int rule, dfl_pht_fit_opts *o)
{
    if (rule == 1) o->grade = o->peaks = 0;
}

dfl_status sjp10_run(const sjp10_study *s, void *keys, const dfl_cfg *cfg, const dfl_study_ctx *ctx,
                     dfl_table *t, dfl_err *err)
{
    memset(keys, 0, s->size);
    dfl_status st = s->read(cfg, keys, err);
    if (!st) st = dfl_cfg_check_used(cfg, err);
    if (!st) st = s->cases(keys, ctx, t, err);
    s->free(keys);
    return st;
}

dfl_status sjp10_fit_at(const dfl_pht_source *src, const char *name, dfl_pht_fit_opts *o,
                        double eps, long level, long uniform_samples, dfl_pht_fit *fit,
                        dfl_err *err)
{
    dfl_status st;
    if (level < 0) {
        o->eps = eps;
        st = dfl_pht_fit_run(src, o, fit, err);
    } else {
        o->samples = (int)uniform_samples;
        st = dfl_pht_fit_uniform(src, o, (int)level, fit, err);
    }
    return st ? dfl_err_prefix(err, "[%s]", name) : DFL_OK;
}

dfl_status sjp10_each_fit(const int *rules, int nrules, const double *eps, size_t neps,
                          const double *lev, size_t nlev, sjp10_fit_fn fn, void *arg,
                          dfl_err *err)
{
    dfl_status st = DFL_OK;
    for (int r = 0; r < nrules && !st; r++)
        for (size_t i = 0; i < neps && !st; i++) st = fn(arg, rules[r], eps[i], -1, i, err);
    for (size_t i = 0; i < nlev && !st; i++) st = fn(arg, 0, NAN, (long)lev[i], i, err);
    return st;
}

dfl_status sjp10_rules_from_cfg(const dfl_cfg *cfg, int *rules, int *n, dfl_err *err)
{
    char names[SJP10_RULES + 1][DFL_SECTION_NAME_LEN];
    *n = 0;
    if (!dfl_cfg_has(cfg, "study", "rules")) {
        rules[(*n)++] = 0;
        return DFL_OK;
    }
    int k = 0;
    dfl_status st = dfl_section_names_from_cfg(cfg, "study", "rules", SJP10_RULES, names, &k,
                                               "fit rule", err);
    if (st) return st;
    for (int i = 0; i < k; i++) {
        int r = -1;
        for (int j = 0; j < SJP10_RULES; j++)
            if (strcmp(names[i], rule_names[j]) == 0) r = j;
        for (int j = 0; j < *n; j++)
            if (rules[j] == r) r = -2;
        if (r < 0)
            return dfl_cfg_reject(cfg, "study", "rules", err,
                                  "expected dflab and/or paper, each once, got '%s'", names[i]);
        rules[(*n)++] = r;
    }
    return DFL_OK;
}

/* ---- files ---- */

static dfl_status write_cells_csv(const dfl_study_ctx *ctx, const char *stem,
                                  const dfl_pht_spline *s, dfl_err *err)
{
    const int dim = dfl_pht_spline_dim(s);
    const size_t nc = dfl_pht_spline_ncells(s);
    static const char *const lo_n[] = {"lo_x", "lo_y", "lo_z"}, *const hi_n[] = {"hi_x", "hi_y", "hi_z"};
    dfl_table *t = dfl_table_new();
    if (!t) return nomem(err, "cell table");
    dfl_status st = DFL_OK;
    for (size_t i = 0; i < nc && !st; i++) {
        double lo[3], hi[3];
        int level;
        dfl_pht_spline_cell(s, i, lo, hi, &level);
        st = dfl_table_row(t, err);
        for (int j = 0; j < dim && !st; j++) {
            st = dfl_table_set_double(t, lo_n[j], lo[j], err);
            if (!st) st = dfl_table_set_double(t, hi_n[j], hi[j], err);
        }
        if (!st) st = dfl_table_set_int(t, "level", level, err);
    }
    char path[4400];
    dfl_study_path(ctx, stem, "csv", path, sizeof path);
    if (!st) st = dfl_table_write_csv(t, path, err);
    dfl_table_free(t);
    return st;
}

/* Corner c (bit j = high side along axis j) of a box into x[3]. */
static void box_corner(int dim, const double *lo, const double *hi, int c, double *x)
{
    for (int j = 0; j < 3; j++) x[j] = j < dim ? ((c >> j) & 1 ? hi[j] : lo[j]) : 0.0;
}

dfl_status sjp10_write_mesh(const dfl_study_ctx *ctx, const char *stem, const dfl_pht_spline *s,
                            dfl_err *err)
{
    const int dim = dfl_pht_spline_dim(s);
    const size_t nc = dfl_pht_spline_ncells(s);
    const size_t per = dim == 2 ? 4 : 8;            /* points per cell */
    const size_t quads = dim == 2 ? 1 : 6;          /* faces per cell */
    /* quad corner order (counter-clockwise in the face) */
    static const int Q2[1][4] = {{0, 1, 3, 2}};
    static const int Q3[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                                 {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
    double *pts = malloc(nc * per * 3 * sizeof *pts), *lev = malloc(nc * per * sizeof *lev);
    size_t *tris = malloc(nc * quads * 6 * sizeof *tris);
    size_t *off = malloc((nc + 1) * sizeof *off), *conn = malloc(nc * 5 * sizeof *conn);
    dfl_status st = DFL_OK;
    if (!pts || !lev || !tris || !off || !conn) st = nomem(err, "mesh file");
    for (size_t i = 0; i < nc && !st; i++) {
        double lo[3], hi[3];
        int level;
        dfl_pht_spline_cell(s, i, lo, hi, &level);
        for (size_t c = 0; c < per; c++) {
            box_corner(dim, lo, hi, (int)c, pts + 3 * (i * per + c));
            lev[i * per + c] = level;
        }
        for (size_t q = 0; q < quads; q++) {
            const int *Q = dim == 2 ? Q2[q] : Q3[q];
            size_t *tr = tris + 6 * (i * quads + q);
            tr[0] = i * per + (size_t)Q[0], tr[1] = i * per + (size_t)Q[1], tr[2] = i * per + (size_t)Q[2];
            tr[3] = i * per + (size_t)Q[0], tr[4] = i * per + (size_t)Q[2], tr[5] = i * per + (size_t)Q[3];
        }
        /* outline of the (bottom) face */
        off[i] = 5 * i;
        for (int k = 0; k < 5; k++) conn[5 * i + (size_t)k] = i * per + (size_t)Q2[0][k % 4];
    }
    off[nc] = 5 * nc;
    if (!st) {
        dfl_vtk_array arr = {"level", 1, lev};
        dfl_vtp_data d = {.npoints = nc * per, .points = pts, .nlines = nc, .line_offsets = off,
                          .line_conn = conn, .ntris = nc * quads * 2, .tris = tris,
                          .point_arrays = &arr, .narrays = 1};
        char path[4400];
        dfl_study_path(ctx, stem, "vtp", path, sizeof path);
        st = dfl_vtp_write(path, &d, 1, err);
    }
    free(pts), free(lev), free(tris), free(off), free(conn);
    if (!st) st = write_cells_csv(ctx, stem, s, err);
    return st;
}

dfl_status sjp10_write_graph(const dfl_study_ctx *ctx, const char *stem, const dfl_field *f,
                             const dfl_shape *ref, const double lo[2], const double hi[2], int n,
                             int threads, dfl_err *err)
{
    const size_t m = (size_t)n * (size_t)n;
    double *xy = malloc(2 * m * sizeof *xy), *v = malloc(m * sizeof *v);
    double *dv = malloc(m * sizeof *dv), *dg = malloc(2 * m * sizeof *dg);
    double *pts = malloc(3 * m * sizeof *pts);
    size_t *tris = malloc(6 * (size_t)(n - 1) * (size_t)(n - 1) * sizeof *tris);
    dfl_status st = DFL_OK;
    if (!xy || !v || !dv || !dg || !pts || !tris) st = nomem(err, "graph file");
    if (!st) {
        for (size_t i = 0; i < m; i++) {
            const double tx = (double)(i % (size_t)n) / (n - 1), ty = (double)(i / (size_t)n) / (n - 1);
            xy[2 * i] = (1 - tx) * lo[0] + tx * hi[0];
            xy[2 * i + 1] = (1 - ty) * lo[1] + ty * hi[1];
        }
        sjp10_eval(f, m, xy, v, NULL, threads);
        if (ref) sjp10_shape_eval(ref, m, xy, dv, dg, threads);
        for (size_t i = 0; i < m; i++) {
            pts[3 * i] = xy[2 * i], pts[3 * i + 1] = xy[2 * i + 1], pts[3 * i + 2] = v[i];
            dv[i] = ref ? v[i] - dv[i] : 0.0;
        }
        size_t k = 0;
        for (size_t j = 0; j + 1 < (size_t)n; j++)
            for (size_t i = 0; i + 1 < (size_t)n; i++) {
                const size_t a = i + (size_t)n * j, b = a + 1, c = a + (size_t)n, d = c + 1;
                tris[k++] = a, tris[k++] = b, tris[k++] = d;
                tris[k++] = a, tris[k++] = d, tris[k++] = c;
            }
        dfl_vtk_array arr[2] = {{"value", 1, v}, {"error", 1, dv}};
        dfl_vtp_data d = {.npoints = m, .points = pts, .ntris = k / 3, .tris = tris,
                          .point_arrays = arr, .narrays = ref ? 2 : 1};
        char path[4400];
        dfl_study_path(ctx, stem, "vtp", path, sizeof path);
        st = dfl_vtp_write(path, &d, 1, err);
    }
    free(xy), free(v), free(dv), free(dg), free(pts), free(tris);
    return st;
}

dfl_status sjp10_fit_from_cfg(const dfl_cfg *cfg, const char *key, int dim, dfl_pht_fit_opts *o,
                              dfl_err *err)
{
    const char *fsec;
    dfl_status st = dfl_cfg_string(cfg, "study", key, &fsec, err);
    if (st) return st;
    if (!dfl_cfg_has_section(cfg, fsec))
        return dfl_cfg_reject(cfg, "study", key, err, "no section [%s]", fsec);
    return dfl_pht_opts_from_cfg(cfg, fsec, dim, o, err);
}

dfl_status sjp10_source_new(const dfl_cfg *cfg, const char *sec, const dfl_shape *shape,
                            dfl_pht_source **src, dfl_err *err)
{
    dfl_status st = dfl_pht_source_new(shape, src, err);
    if (st) return dfl_cfg_err_at(cfg, sec, "kind", st, err);
    /* the library's sign test (pht/hermite.h; the fits repeat it on their
     * own box): an open curve's distance is unsigned.  Seen from the unit
     * box, wherever the shape lies: the probe decides the sign, not a box. */
    static const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    if ((st = dfl_pht_source_check_signed(*src, lo, hi, err))) {
        dfl_pht_source_free(*src);
        *src = NULL;
        const int curve = strcmp(shape->ops->kind, "bspline_curve") == 0;
        return dfl_cfg_err_at(cfg, sec, curve ? "closed" : "kind", st, err);
    }
    return DFL_OK;
}

void sjp10_cases_free(sjp10_case *c, int n)
{
    for (int i = 0; i < n; i++) {
        dfl_pht_source_free(c[i].src);
        c[i].src = NULL;
        if (c[i].have_shape) dfl_shape_free(&c[i].shape);
        c[i].have_shape = 0;
    }
}

dfl_status sjp10_cases_from_cfg(const dfl_cfg *cfg, const char *sec, const char *key, int want_src,
                                sjp10_case *c, int *n, dfl_err *err)
{
    char names[SJP10_MAX_CASES][DFL_SECTION_NAME_LEN];
    memset(c, 0, SJP10_MAX_CASES * sizeof *c);
    *n = 0;
    dfl_status st = dfl_section_names_from_cfg(cfg, sec, key, SJP10_MAX_CASES, names, n,
                                               "shape section", err);
    for (int i = 0; i < *n && !st; i++) {
        memcpy(c[i].name, names[i], DFL_SECTION_NAME_LEN);
        if (!dfl_cfg_has_section(cfg, names[i]))
            return dfl_cfg_reject(cfg, sec, key, err, "no section [%s]", names[i]);
        if ((st = dfl_shape_from_cfg(cfg, names[i], &c[i].shape, err))) break;
        c[i].have_shape = 1;
        if (want_src) st = sjp10_source_new(cfg, names[i], &c[i].shape, &c[i].src, err);
    }
    if (st) sjp10_cases_free(c, *n);
    return st;
}

dfl_status sjp10_stream_errors(const dfl_field *f, const dfl_shape *shape, const double *lo,
                               const double *hi, int n, int midpoints, double band, int threads,
                               dfl_pht_val *out, dfl_err *err)
{
    memset(out, 0, sizeof *out);
    if (n < 2) return dfl_err_set(err, DFL_E_INPUT, "validation grid: n must be >= 2, got %d", n);
    const int dim = shape->dim;
    size_t nn, nm;
    grid_counts(dim, n, midpoints, &nn, &nm);
    const size_t m = nn + nm, nc = nchunks(m);
    acc *pa = calloc(2 * (nc ? nc : 1), sizeof *pa);
    size_t *pband = calloc(nc ? nc : 1, sizeof *pband), *pskip = calloc(nc ? nc : 1, sizeof *pskip);
    int *fail = calloc(nc ? nc : 1, sizeof *fail);
    if (!pa || !pband || !pskip || !fail) {
        free(pa), free(pband), free(pskip), free(fail);
        return nomem(err, "validation chunks");
    }
#pragma omp parallel num_threads(threads > 0 ? threads : 1)
    {
        double *x = malloc(CHUNK * (size_t)dim * sizeof *x), *d = malloc(CHUNK * sizeof *d);
        double *dg = malloc(CHUNK * (size_t)dim * sizeof *dg), *v = malloc(CHUNK * sizeof *v);
        double *g = malloc(CHUNK * (size_t)dim * sizeof *g);
        unsigned char *near = calloc(CHUNK, 1);
#pragma omp for schedule(dynamic, 1)
        for (long c = 0; c < (long)nc; c++) {
            if (!x || !d || !dg || !v || !g || !near) {
                fail[c] = 1;
                continue;
            }
            const size_t a = (size_t)c * CHUNK, b = a + CHUNK < m ? a + CHUNK : m, k = b - a;
            for (size_t i = a; i < b; i++) {
                const int mid = i >= nn;
                grid_point(dim, lo, hi, n, mid, mid ? i - nn : i, x + (i - a) * (size_t)dim);
            }
            dfl_shape_eval(shape, k, x, d, dg);
            f->ops->eval(f->ctx, k, x, v, g);
            if (band > 0.0 && dfl_pht_medial_band(shape, k, x, band, near, NULL)) fail[c] = 1;
            for (size_t i = 0; i < k; i++) {
                if (!isfinite(d[i])) {
                    pskip[c]++;
                    continue;
                }
                const double e = fabs(v[i] - d[i]);
                double gg = 0;
                for (int j = 0; j < dim; j++) {
                    const double q = g[i * dim + j] - dg[i * dim + j];
                    gg += q * q;
                }
                acc_add(&pa[2 * c], e, sqrt(gg));
                if (band > 0.0 && near[i]) pband[c]++;
                else acc_add(&pa[2 * c + 1], e, sqrt(gg));
            }
        }
        free(x), free(d), free(dg), free(v), free(g), free(near);
    }
    acc all = {0}, off = {0};
    int failed = 0;
    for (size_t c = 0; c < nc; c++) {
        acc_merge(&all, &pa[2 * c]);
        acc_merge(&off, &pa[2 * c + 1]);
        out->band += pband[c];
        out->skipped += pskip[c];
        failed |= fail[c];
    }
    acc_stats(&all, &out->all);
    acc_stats(&off, &out->off);
    free(pa), free(pband), free(pskip), free(fail);
    return failed ? nomem(err, "validation chunk") : DFL_OK;
}

void sjp10_ref_cost(int dim, long n, int midpoints, dfl_cost_class cls, const char *sec,
                    const char *key, dfl_cost *c)
{
    const double m = pow((double)n, dim) + (midpoints ? pow((double)n - 1, dim) : 0);
    dfl_cost_add_bytes(c, sec, key, m * (8.0 * (3 * dim + 2) + 1),
                       "%.3g validation points (%ld^%d nodes%s)", m, n, dim,
                       midpoints ? " and midpoints" : "");
    dfl_cost_add_work(c, sec, key, cls, 2 * m, "%.3g validation points", m);
}

void sjp10_fit_cost(const dfl_pht_fit_opts *o, int dim, int uniform, dfl_cost_class cls,
                    int cellval, const char *sec, const char *key, dfl_cost *c)
{
    double leaves, bytes;
    if (uniform >= 0) {
        leaves = ldexp(1.0, dim * uniform);
        const double fan = ldexp(1.0, dim);
        bytes = leaves * fan / (fan - 1) * DFL_PHT_CELL_BYTES(dim);
    } else {
        bytes = dfl_pht_fit_bytes_bound(o, dim, &leaves);
    }
    if (cellval) bytes += 96 * leaves;
    dfl_cost_add_bytes(c, sec, key, bytes, "a PHT fit of up to %.3g cells (%s %d in %dD)", leaves,
                       uniform >= 0 ? "level" : "max_level", uniform >= 0 ? uniform : o->max_level,
                       dim);
    const double per = (double)o->samples + 2 * dim + 2 + (cellval ? 31 : 0);
    dfl_cost_add_work(c, sec, key, cls, leaves * per, "a fit of up to %.3g cells", leaves);
}
