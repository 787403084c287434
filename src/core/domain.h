/* dflab's domain of validity: the coordinates and lengths its fields,
 * shapes and probes compute correctly.
 *
 *   DFL_COORD_MAX   largest magnitude of a coordinate, length or radius
 *   dfl_coord_ok(v) |v| <= DFL_COORD_MAX and v finite
 *
 * Every distance in dflab is built from differences, squares and products
 * of coordinates.  With |v| <= 1e150 a difference stays below 2e150 and a
 * squared length of three such components below 1.2e301, so no
 * intermediate overflows to inf and none of the formulas (sqrt of a square
 * sum, rfunc powers aside, which rfunc/ bounds itself) loses its meaning.
 * The config getters for vectors, point lists and number lists
 * (io/config.h), the shape keys (experiments/cfg/shape_cfg.c) and the probe
 * points (io/points.h readers' caller, `dflab probe`) refuse magnitudes
 * above it with exit status 2, naming the key or the point; inside it the
 * analytic shapes evaluate lengths in a scaled form where a square sum
 * could still leave the double range (geom/shape_analytic.c).
 *
 * Small scales: a length below DFL_LEN_MIN (1e-150) squares to below
 * 1e-300, next to the subnormal range; parameters that are lengths or
 * tolerances are refused below it where a key table states a lower bound.
 */
#ifndef DFL_CORE_DOMAIN_H
#define DFL_CORE_DOMAIN_H

#include <math.h>
#include <stdbool.h>

#define DFL_COORD_MAX 1e150
#define DFL_LEN_MIN 1e-150

static inline bool dfl_coord_ok(double v) { return isfinite(v) && fabs(v) <= DFL_COORD_MAX; }

#endif
