/* Private to proxy/input_implicit.c: the robust method's fast path, a
 * bucketed copy of the implicit's surface samples with their normals.
 *
 *   dfl_imp_index_new / _free   build / release the index
 *   dfl_imp_fast_foot           one Newton from the nearest sample, and the
 *                               cap test that says whether it is the answer
 *   dfl_imp_square_newton       Newton on the square footpoint system (also
 *                               the paper method's solver)
 *
 * The cap test: a surface point closer to x than the footpoint p found
 * (distance |d|) has a sample within the covering radius c = 2 h (h the
 * sample spacing: every surface point has a grid node within sqrt(3)/2 h,
 * moved by at most as much onto the surface), so all candidates lie among
 * the samples s with |x - s| <= |d| + c.  Each one farther than 2 h from p
 * must see the tangential part t of x - s (w.r.t. its normal n_s) point
 * towards p, t . (p - s) >= |t| |p - s| / 2: the descent of the distance
 * from s leads to p's basin, not to another footpoint.  A point that fails
 * (near-ties, the torus' axis, caps with a second basin) goes to the full
 * search.  Not an API: include proxy/input_implicit.h. */
#ifndef DFL_PROXY_INPUT_IMPLICIT_FAST_H
#define DFL_PROXY_INPUT_IMPLICIT_FAST_H

#include <stddef.h>

#include "core/status.h"
#include "geom/implicit.h"

typedef struct dfl_imp_index dfl_imp_index;

/* NULL on allocation failure. */
dfl_imp_index *dfl_imp_index_new(const dfl_implicit *s);
void dfl_imp_index_free(dfl_imp_index *ix);

/* 1 with p, d (signed, sign of g(x)) when the fast path answers x;
 * 0 when the full search must. */
int dfl_imp_fast_foot(const dfl_imp_index *ix, const double x[3], double p[3], double *d);

/* Newton on F(p, t) = (p - x + t grad g(p), g(p)) = 0 from p (in place;
 * t starts at the projection of x - p on grad g), 30 steps, converged when
 * |F_p| <= 1e-13 scale and |g| / |grad g| <= 1e-13 scale: 1, else 0 (p then
 * holds the last iterate). */
int dfl_imp_square_newton(const dfl_implicit *s, const double x[3], double p[3], double scale);

#endif
