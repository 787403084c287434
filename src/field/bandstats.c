/* Band statistics (see bandstats.h).  One pass; sums in long double would
 * not change the reported digits at the grid sizes used (<= 4096^2). */
#include "field/bandstats.h"

#include <math.h>

dfl_status dfl_bandstats_compute(size_t m, int dim, const double *u, const double *gu,
                                 const double *ref, double band, dfl_bandstats *out,
                                 dfl_err *err)
{
    if (!(band > 0.0)) return dfl_err_set(err, DFL_E_INPUT, "band must be > 0, got %g", band);
    double s = 0, sr = 0, sa = 0, s2 = 0, mx = 0, gs = 0, gmn = INFINITY, gmx = 0;
    size_t cnt = 0, rcnt = 0, gcnt = 0;
    for (size_t i = 0; i < m; i++) {
        if (!(fabs(ref[i]) <= band)) {
            if (isnan(ref[i]))
                return dfl_err_set(err, DFL_E_NUMERIC, "reference is NaN at node %zu", i);
            continue;
        }
        if (!isfinite(u[i]) || !isfinite(ref[i]))
            return dfl_err_set(err, DFL_E_NUMERIC, "non-finite value %g (reference %g) at node %zu",
                               u[i], ref[i], i);
        const double e = u[i] - ref[i];
        cnt++;
        s += e, sa += fabs(e), s2 += e * e;
        if (fabs(e) > mx) mx = fabs(e);
        if (ref[i] != 0.0) sr += e / fabs(ref[i]), rcnt++;
        if (gu && u[i] != 0.0) {
            double g2 = 0;
            for (int d = 0; d < dim; d++) g2 += gu[i * (size_t)dim + (size_t)d] * gu[i * (size_t)dim + (size_t)d];
            const double g = sqrt(g2);
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

dfl_status dfl_bandstats_put(dfl_table *t, const dfl_bandstats *b, dfl_err *err)
{
    dfl_status st = dfl_table_set_int(t, "band_count", (long)b->count, err);
    if (!st) st = dfl_table_set_double(t, "band_bias", b->bias, err);
    if (!st) st = dfl_table_set_double(t, "band_rel_bias", b->rel_bias, err);
    if (!st) st = dfl_table_set_double(t, "band_l1", b->l1, err);
    if (!st) st = dfl_table_set_double(t, "band_rms", b->rms, err);
    if (!st) st = dfl_table_set_double(t, "band_linf", b->linf, err);
    if (!st) st = dfl_table_set_double(t, "grad_min", b->gmin, err);
    if (!st) st = dfl_table_set_double(t, "grad_mean", b->gmean, err);
    if (!st) st = dfl_table_set_double(t, "grad_max", b->gmax, err);
    return st;
}
