#include "field/metrics.h"

#include <math.h>

dfl_status dfl_metrics_compute(size_t m, int dim, const double *u, const double *gu,
                               const double *ref, double band, dfl_metrics *out, dfl_err *err)
{
    const int use_band = band > 0.0 && isfinite(band);
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
            double n2 = 0;
            for (int d = 0; d < dim; d++) n2 += gu[i * (size_t)dim + d] * gu[i * (size_t)dim + d];
            double gd = fabs(sqrt(n2) - 1.0);
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
