/* The two computations keep separate loops on purpose: dfl_metrics_compute
 * reduces in parallel, dfl_metrics_bandstats sums serially, and each
 * order of summation is what the reproduced tables hold.  They share the
 * band rule and the gradient norm. */
#include "field/metrics.h"

#include <math.h>
#include <stdio.h>

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

dfl_status dfl_metrics_compute(size_t m, int dim, const double *u, const double *gu,
                               const double *ref, double band, dfl_metrics *out, dfl_err *err)
{
    int use_band = 0;
    dfl_status st = band_rule(band, &use_band, err);
    if (st != DFL_OK) return st;
    size_t bad = (size_t)-1;
    double s1 = 0, s2 = 0, mx = 0, g1 = 0, gmx = 0;
    size_t cnt = 0;
#pragma omp parallel for reduction(+ : s1, s2, g1, cnt) reduction(max : mx, gmx) reduction(min : bad)
    for (size_t i = 0; i < m; i++) {
        if (!isfinite(u[i]) || !isfinite(ref[i])) {
            if (i < bad) bad = i;
            continue;
        }
        if (use_band && fabs(ref[i]) > band) continue;
        double e = fabs(u[i] - ref[i]);
        s1 += e;
        s2 += e * e;
        if (e > mx) mx = e;
        if (gu) {
            double gd = fabs(grad_norm(gu + i * (size_t)dim, dim) - 1.0);
            g1 += gd;
            if (gd > gmx) gmx = gd;
        }
        cnt++;
    }
    if (bad != (size_t)-1)
        return dfl_err_set(err, DFL_E_NUMERIC, "non-finite field value at sample %zu", bad);
    out->count = cnt;
    if (cnt == 0) {
        out->l1 = out->mse = out->rms = out->linf = out->gdef_mean = out->gdef_max = NAN;
        return DFL_OK;
    }
    out->l1 = s1 / (double)cnt;
    out->mse = s2 / (double)cnt;
    out->rms = sqrt(out->mse);
    out->linf = mx;
    out->gdef_mean = gu ? g1 / (double)cnt : NAN;
    out->gdef_max = gu ? gmx : NAN;
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
    size_t cnt = 0, rcnt = 0, gcnt = 0;
    for (size_t i = 0; i < m; i++) {
        if (isnan(ref[i]))
            return dfl_err_set(err, DFL_E_NUMERIC, "reference is NaN at node %zu", i);
        if (use_band && !(fabs(ref[i]) <= band)) continue;
        if (!isfinite(u[i]) || !isfinite(ref[i]))
            return dfl_err_set(err, DFL_E_NUMERIC, "non-finite value %g (reference %g) at node %zu",
                               u[i], ref[i], i);
        const double e = u[i] - ref[i];
        cnt++;
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
    return st;
}

dfl_status dfl_metrics_put_bandstats(dfl_table *t, const dfl_bandstats *b, dfl_err *err)
{
    const char *const names[8] = {"band_bias", "band_rel_bias", "band_l1", "band_rms",
                                  "band_linf", "grad_min",      "grad_mean", "grad_max"};
    const double v[8] = {b->bias, b->rel_bias, b->l1, b->rms, b->linf, b->gmin, b->gmean, b->gmax};
    dfl_status st = dfl_table_set_int(t, "band_count", (long)b->count, err);
    for (int i = 0; i < 8 && st == DFL_OK; i++) st = dfl_table_set_double(t, names[i], v[i], err);
    return st;
}
