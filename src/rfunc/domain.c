#include "rfunc/domain.h"

#include <math.h>
#include <stdio.h>

/* "(x, y)" or "(x, y, z)" with %.17g into buf. */
static const char *fmt_point(int dim, const double *x, char *buf, size_t size)
{
    if (dim == 3) snprintf(buf, size, "(%.17g, %.17g, %.17g)", x[0], x[1], x[2]);
    else snprintf(buf, size, "(%.17g, %.17g)", x[0], dim > 1 ? x[1] : 0.0);
    return buf;
}

static dfl_status check(int dim, const double *x, double lim, const char *what, const char *why,
                        dfl_err *err)
{
    for (int j = 0; j < dim; j++)
        if (!(fabs(x[j]) <= lim)) {
            char b[160];
            return dfl_err_set(err, DFL_E_INPUT,
                               "%s %s: coordinate %.17g outside the rfunc fields' domain"
                               " |x| <= %g%s",
                               what, fmt_point(dim, x, b, sizeof b), x[j], lim, why);
        }
    return DFL_OK;
}

dfl_status dfl_rfunc_domain_coords(int dim, const double *x, const char *what, dfl_err *err)
{
    return check(dim, x, DFL_RFUNC_COORD_MAX, what, "", err);
}

dfl_status dfl_rfunc_domain_point(int dim, const double *x, bool jet, dfl_err *err)
{
    if (jet)
        return check(dim, x, DFL_RFUNC_JET_COORD_MAX, "point", " for exact derivatives (jets)",
                     err);
    return check(dim, x, DFL_RFUNC_COORD_MAX, "point", "", err);
}
