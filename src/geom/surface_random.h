/* Random Bezier surfaces by seed (hvb25 Table 2's "random Bezier
 * surfaces"; the paper does not say how it drew them, so this is ours).
 *
 *   dfl_surface_random_bezier   one patch over a square, random heights
 *
 * The patch of orders (k, k) has control points
 *   P_ij = (-half + 2 half i/(k-1), -half + 2 half j/(k-1), z_ij),
 * z_ij uniform in [-amp, amp] from core/rng.h's SplitMix64 with state
 * seed, drawn in the order j-major, i fastest (the sequence is part of the
 * contract: a seed names one surface on every machine). */
#ifndef DFL_GEOM_SURFACE_RANDOM_H
#define DFL_GEOM_SURFACE_RANDOM_H

#include <stdint.h>

#include "core/status.h"
#include "geom/surface.h"

/* k in 2..DFL_BSPLINE_MAX_ORDER, half > 0, amp >= 0: DFL_E_INPUT otherwise;
 * DFL_E_NOMEM.  *out is a one-patch set (free with dfl_surface_set_free). */
dfl_status dfl_surface_random_bezier(uint64_t seed, int k, double half, double amp,
                                     dfl_surface_set *out, dfl_err *err);

#endif
