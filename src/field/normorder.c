#include "field/normorder.h"

#include <assert.h>
#include <math.h>

dfl_status dfl_normorder_measure(const dfl_jet *j, double sigma, double L, double tol,
                                 dfl_normorder *out, dfl_err *err)
{
    if (sigma != 1.0 && sigma != -1.0)
        return dfl_err_set(err, DFL_E_INPUT, "normorder: sigma must be +1 or -1, got %g", sigma);
    if (!(L > 0.0) || !isfinite(L) || !(tol > 0.0))
        return dfl_err_set(err, DFL_E_INPUT, "normorder: need L > 0 and tol > 0 (got %g, %g)", L,
                           tol);
    const int kmax = dfl_jet_order(j);
    if (kmax < 1)
        return dfl_err_set(err, DFL_E_INPUT, "normorder: jet known to order %d < 1", kmax);
    if (!j->zero && j->v < 0)
        return dfl_err_set(err, DFL_E_NUMERIC, "normorder: the jet has a pole (valuation %d)",
                           j->v);
    dfl_normorder r = {0};
    r.d1 = dfl_jet_coeff(j, 1);
    /* factorial grows with k; kept as a double (exact up to 22!) */
    double fact = 1.0, Lk = 1.0 / L; /* L^(k-1) at k = 0 */
    for (int k = 0; k <= kmax; k++) {
        if (k > 0) fact *= k;
        const double a = dfl_jet_coeff(j, k);
        if (isnan(a))
            return dfl_err_set(err, DFL_E_NUMERIC, "normorder: coefficient %d is NAN", k);
        const double target = k == 1 ? sigma : 0.0;
        if (fabs(a - target) * (k == 1 ? 1.0 : Lk) > tol) {
            r.order = k - 1;
            r.k = k;
            r.coef = a;
            r.deriv = fact * a;
            *out = r;
            return DFL_OK;
        }
        Lk *= L;
    }
    r.order = kmax;
    r.capped = 1;
    r.k = kmax + 1;
    r.coef = NAN;
    r.deriv = NAN;
    assert(r.order >= 1);
    *out = r;
    return DFL_OK;
}

double dfl_normorder_scale(const dfl_jet *j)
{
    double R = INFINITY;
    const int kmax = dfl_jet_order(j);
    for (int k = 2; k <= kmax; k++) {
        const double a = fabs(dfl_jet_coeff(j, k));
        if (a > 0.0 && isfinite(a)) {
            const double r = pow(a, -1.0 / (k - 1));
            if (r < R) R = r;
        }
    }
    return R;
}
