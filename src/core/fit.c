#include "core/fit.h"

#include <math.h>

/* The normal-equations form, not a centred one: the tables dflab
 * reproduces were computed with it, and for the few well-spread points it
 * is given (decades of eps) the two agree to a few ulps. */
double dfl_fit_loglog_slope(size_t n, const double *x, const double *y)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (size_t i = 0; i < n; i++) {
        const double lx = log(x[i]), ly = log(y[i]);
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
    }
    const double dn = (double)n;
    return (dn * sxy - sx * sy) / (dn * sxx - sx * sx);
}
