/* The computations keep separate loops on purpose: dfl_metrics_compute
 * reduces in parallel over fixed chunks, dfl_metrics_bandstats and the saturating variant sum
 * serially, and each order of summation (and the saturating variant's
 * hypot) is what the reproduced tables hold.  They share the band rule and,
 * but for the saturating variant, the gradient norm. */
#include "field/metrics.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* The band rule of metrics.h: *use = 0 means every sample. */
static dfl_status band_rule(double band, int *use, dfl_err *err)
{
    if (isnan(band)) return dfl_err_set(err, DFL_E_INPUT, "metrics: the band is NaN");
    *use = band > 0.0 && isfinite(band);
    return DFL_OK;
}

static inline double grad_norm(const double *g, int dim)
{
    double n2 = 0;
    for (int d = 0; d < dim; d++) n2 += g[d] * g[d];
    return sqrt(n2);
}

/* The dfl_metrics of cnt samples from the sums of |e|, e^2 and the
 * gradient defect and the maxima; NAN metrics for cnt == 0. */
static void metrics_finish(size_t cnt, double s1, double s2, double mx, int has_grad, double g1,
                           double gmx, dfl_metrics *out)
{
    out->count = cnt;
    if (cnt == 0) {
        out->l1 = out->mse = out->rms = out->linf = out->gdef_mean = out->gdef_max = NAN;
        return;
    }
    out->l1 = s1 / (double)cnt;
    out->mse = s2 / (double)cnt;
    out->rms = sqrt(out->mse);
    out->linf = mx;
    out->gdef_mean = has_grad ? g1 / (double)cnt : NAN;
    out->gdef_max = has_grad ? gmx : NAN;
}

/* Sums of one fixed chunk of samples (see dfl_metrics_compute). */
typedef struct chunk_sums {
    double s1, s2, g1, mx, gmx;
    size_t cnt, nonfinite, bad;
} chunk_sums;

/* The non-finite rule of metrics.h: the error of a sample whose value (or,
 * with a gradient, whose gradient) is not finite is +inf. */
static inline int sample_finite(const double *u, const double *gu, int dim, size_t i)
{
    if (!isfinite(u[i])) return 0;
    for (int d = 0; gu && d < dim; d++)
        if (!isfinite(gu[i * (size_t)dim + (size_t)d])) return 0;
    return 1;
}

static void chunk_sum(size_t i0, size_t i1, int dim, const double *u, const double *gu,
                      const double *ref, int use_band, double band, chunk_sums *o)
{
    chunk_sums c = {0, 0, 0, 0, 0, 0, 0, (size_t)-1};
    for (size_t i = i0; i < i1; i++) {
        if (!isfinite(ref[i])) {
            if (i < c.bad) c.bad = i;
            continue;
        }
        if (use_band && fabs(ref[i]) > band) continue;
        const int fin = sample_finite(u, gu, dim, i);
        double e = fin ? fabs(u[i] - ref[i]) : INFINITY;
        c.nonfinite += !fin;
        c.s1 += e;
        c.s2 += e * e;
        if (e > c.mx) c.mx = e;
        if (gu) {
            double gd = fin ? fabs(grad_norm(gu + i * (size_t)dim, dim) - 1.0) : INFINITY;
            c.g1 += gd;
            if (gd > c.gmx) c.gmx = gd;
        }
        c.cnt++;
    }
    *o = c;
}

/* Bitwise the same at any thread count: the samples are cut into chunks of
 * DFL_METRICS_CHUNK fixed by m alone, each chunk is summed in index order
 * (in parallel over chunks), and the chunk sums are added in chunk order.
 * Maxima and counts are exact in any order. */
dfl_status dfl_metrics_compute(size_t m, int dim, const double *u, const double *gu,
                               const double *ref, double band, dfl_metrics *out, dfl_err *err)
{
    int use_band = 0;
    dfl_status st = band_rule(band, &use_band, err);
    if (st != DFL_OK) return st;
    const size_t C = DFL_METRICS_CHUNK, nch = (m + C - 1) / C;
    chunk_sums one, *cs = nch <= 1 ? &one : malloc(nch * sizeof *cs);
    if (!cs) return dfl_err_set(err, DFL_E_NOMEM, "metrics: out of memory");
#pragma omp parallel for schedule(static) if (nch > 1)
    for (size_t k = 0; k < nch; k++)
        chunk_sum(k * C, k + 1 == nch ? m : (k + 1) * C, dim, u, gu, ref, use_band, band, &cs[k]);
    size_t bad = (size_t)-1, cnt = 0, nonfinite = 0;
    double s1 = 0, s2 = 0, mx = 0, g1 = 0, gmx = 0;
    for (size_t k = 0; k < nch; k++) {
        s1 += cs[k].s1, s2 += cs[k].s2, g1 += cs[k].g1, cnt += cs[k].cnt;
        nonfinite += cs[k].nonfinite;
        if (cs[k].mx > mx) mx = cs[k].mx;
        if (cs[k].gmx > gmx) gmx = cs[k].gmx;
        if (cs[k].bad < bad) bad = cs[k].bad;
    }
    if (cs != &one) free(cs);
    if (bad != (size_t)-1)
        return dfl_err_set(err, DFL_E_NUMERIC, "non-finite reference value at sample %zu", bad);
    metrics_finish(cnt, s1, s2, mx, gu != NULL, g1, gmx, out);
    out->nonfinite = nonfinite;
    return DFL_OK;
}

dfl_status dfl_metrics_compute_masked(size_t m, int dim, const double *u, const double *gu,
                                      const double *ref, const unsigned char *mask,
                                      dfl_metrics *out, dfl_err *err)
{
    const size_t n = m ? m : 1, nd = (size_t)dim;
    double *cu = malloc(n * sizeof *cu), *cr = malloc(n * sizeof *cr);
    double *cg = gu ? malloc(n * nd * sizeof *cg) : NULL;
    dfl_status st = DFL_OK;
    if (!cu || !cr || (gu && !cg)) st = dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    size_t k = 0;
    for (size_t i = 0; i < m && st == DFL_OK; i++) {
        if (!mask[i]) continue;
        cu[k] = u[i];
        cr[k] = ref[i];
        for (size_t j = 0; gu && j < nd; j++) cg[k * nd + j] = gu[i * nd + j];
        k++;
    }
    if (st == DFL_OK) st = dfl_metrics_compute(k, dim, cu, cg, cr, 0.0, out, err);
    free(cu), free(cr), free(cg);
    return st;
}

static double hypot_norm(const double *g, int dim)
{
    assert(dim >= 1 && dim <= 3);
    if (dim == 1) return fabs(g[0]);
    const double h = hypot(g[0], g[1]);
    return dim == 2 ? h : hypot(h, g[2]);
}

dfl_status dfl_metrics_compute_saturating(size_t m, int dim, const double *u, const double *gu,
                                          const double *ref, double band, dfl_metrics *out,
                                          dfl_err *err)
{
    int use_band = 0;
    dfl_status st = band_rule(band, &use_band, err);
    if (st != DFL_OK) return st;
    double s1 = 0, s2 = 0, mx = 0, g1 = 0, gmx = 0;
    size_t cnt = 0, nonfinite = 0;
    for (size_t i = 0; i < m; i++) {
        if (use_band && !(fabs(ref[i]) <= band)) continue;
        double e = fabs(u[i] - ref[i]);
        if (!isfinite(e)) e = INFINITY;
        nonfinite += !sample_finite(u, gu, dim, i);
        cnt++;
        s1 += e;
        s2 += e * e;
        if (e > mx) mx = e;
        if (gu) {
            double gd = fabs(hypot_norm(gu + i * (size_t)dim, dim) - 1.0);
            if (!isfinite(gd)) gd = INFINITY;
            g1 += gd;
            if (gd > gmx) gmx = gd;
        }
    }
    metrics_finish(cnt, s1, s2, mx, gu != NULL, g1, gmx, out);
    out->nonfinite = nonfinite;
    return DFL_OK;
}

/* One pass; sums in long double would not change the reported digits at
 * the grid sizes used (<= 4096^2). */
dfl_status dfl_metrics_bandstats(size_t m, int dim, const double *u, const double *gu,
                                 const double *ref, double band, dfl_bandstats *out,
                                 dfl_err *err)
{
    int use_band = 0;
    dfl_status st = band_rule(band, &use_band, err);
    if (st != DFL_OK) return st;
    double s = 0, sr = 0, sa = 0, s2 = 0, mx = 0, gs = 0, gmn = INFINITY, gmx = 0;
    size_t cnt = 0, rcnt = 0, gcnt = 0, nonfinite = 0;
    for (size_t i = 0; i < m; i++) {
        if (isnan(ref[i]))
            return dfl_err_set(err, DFL_E_NUMERIC, "reference is NaN at node %zu", i);
        if (use_band && !(fabs(ref[i]) <= band)) continue;
        if (!isfinite(ref[i]))
            return dfl_err_set(err, DFL_E_NUMERIC, "reference is %g at node %zu", ref[i], i);
        cnt++;
        if (!isfinite(u[i])) { /* the non-finite rule: an error of +inf */
            nonfinite++;
            s = sa = s2 = mx = INFINITY;
            if (ref[i] != 0.0) sr = INFINITY, rcnt++;
            continue;
        }
        const double e = u[i] - ref[i];
        s += e, sa += fabs(e), s2 += e * e;
        if (fabs(e) > mx) mx = fabs(e);
        if (ref[i] != 0.0) sr += e / fabs(ref[i]), rcnt++;
        if (gu && u[i] != 0.0) {
            const double g = grad_norm(gu + i * (size_t)dim, dim);
            gcnt++;
            gs += g;
            if (g < gmn) gmn = g;
            if (g > gmx) gmx = g;
        }
    }
    out->count = cnt;
    out->nonfinite = nonfinite;
    out->gcount = gcnt;
    out->bias = cnt ? s / (double)cnt : NAN;
    out->l1 = cnt ? sa / (double)cnt : NAN;
    out->rms = cnt ? sqrt(s2 / (double)cnt) : NAN;
    out->linf = cnt ? mx : NAN;
    out->rel_bias = rcnt ? sr / (double)rcnt : NAN;
    out->gmin = gcnt ? gmn : NAN;
    out->gmean = gcnt ? gs / (double)gcnt : NAN;
    out->gmax = gcnt ? gmx : NAN;
    return DFL_OK;
}

void dfl_metrics_gradstat(size_t m, int dim, const double *grad, const unsigned char *mask,
                          dfl_gradstat *out)
{
    size_t c = 0;
    double mn = INFINITY, mx = -INFINITY, s = 0;
    for (size_t i = 0; i < m; i++) {
        if (mask && !mask[i]) continue;
        const double q = grad_norm(grad + i * (size_t)dim, dim);
        mn = fmin(mn, q);
        mx = fmax(mx, q);
        s += q;
        c++;
    }
    out->count = c;
    out->min = c ? mn : NAN;
    out->max = c ? mx : NAN;
    out->mean = c ? s / (double)c : NAN;
}

dfl_status dfl_metrics_put(dfl_table *t, const char *sfx, const dfl_metrics *m, dfl_err *err)
{
    const char *const names[7] = {"count", "l1", "mse", "rms", "linf", "graddefect_mean",
                                  "graddefect_max"};
    const double v[6] = {m->l1, m->mse, m->rms, m->linf, m->gdef_mean, m->gdef_max};
    char col[96];
    snprintf(col, sizeof col, "%s%s", names[0], sfx);
    dfl_status st = dfl_table_set_int(t, col, (long)m->count, err);
    for (int i = 0; i < 6 && st == DFL_OK; i++) {
        snprintf(col, sizeof col, "%s%s", names[i + 1], sfx);
        st = dfl_table_set_double(t, col, v[i], err);
    }
    snprintf(col, sizeof col, "nonfinite%s", sfx);
    if (st == DFL_OK) st = dfl_table_set_int(t, col, (long)m->nonfinite, err);
    return st;
}

dfl_status dfl_metrics_put_bandstats(dfl_table *t, const dfl_bandstats *b, dfl_err *err)
{
    const char *const names[8] = {"band_bias", "band_rel_bias", "band_l1", "band_rms",
                                  "band_linf", "grad_min",      "grad_mean", "grad_max"};
    const double v[8] = {b->bias, b->rel_bias, b->l1, b->rms, b->linf, b->gmin, b->gmean, b->gmax};
    dfl_status st = dfl_table_set_int(t, "band_count", (long)b->count, err);
    for (int i = 0; i < 8 && st == DFL_OK; i++) st = dfl_table_set_double(t, names[i], v[i], err);
    if (st == DFL_OK) st = dfl_table_set_int(t, "band_nonfinite", (long)b->nonfinite, err);
    return st;
}

dfl_status dfl_metrics_put_gradstat(dfl_table *t, const char *sfx, const dfl_gradstat *g,
                                    dfl_err *err)
{
    const char *const names[3] = {"grad_min", "grad_mean", "grad_max"};
    const double v[3] = {g->min, g->mean, g->max};
    char col[96];
    dfl_status st = DFL_OK;
    for (int i = 0; i < 3 && st == DFL_OK; i++) {
        snprintf(col, sizeof col, "%s%s", names[i], sfx);
        st = dfl_table_set_double(t, col, v[i], err);
    }
    return st;
}
