/* Random Bezier patches (see geom/surface_random.h). */
#include "geom/surface_random.h"

#include <math.h>
#include <stdlib.h>

#include "core/rng.h"

dfl_status dfl_surface_random_bezier(uint64_t seed, int k, double half, double amp,
                                     dfl_surface_set *out, dfl_err *err)
{
    if (k < 2 || k > DFL_BSPLINE_MAX_ORDER || !(half > 0) || !(amp >= 0) || !isfinite(half) ||
        !isfinite(amp))
        return dfl_err_set(err, DFL_E_INPUT,
                           "random bezier: need order 2..%d, half > 0, amp >= 0 (got %d, %g, %g)",
                           DFL_BSPLINE_MAX_ORDER, k, half, amp);
    double *cp = malloc((size_t)k * k * 3 * sizeof *cp);
    if (!cp) return dfl_err_set(err, DFL_E_NOMEM, "random bezier: out of memory");
    uint64_t s = seed;
    for (int j = 0; j < k; j++)
        for (int i = 0; i < k; i++) {
            double *p = cp + 3 * (i + k * j);
            p[0] = -half + 2 * half * i / (k - 1);
            p[1] = -half + 2 * half * j / (k - 1);
            p[2] = dfl_rng_splitmix(&s, -amp, amp);
        }
    dfl_surface patch;
    dfl_status st = dfl_surface_init_bezier(k, k, cp, &patch, err);
    free(cp);
    if (st != DFL_OK) return st;
    return dfl_surface_set_init(1, &patch, out, err);
}
