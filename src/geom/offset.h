/* Untrimmed offset curves of closed planar curves and their
 * self-intersections: what a trimmed offset (a level set of the signed
 * distance) removes.
 *
 * Function index
 *   dfl_offset_curve        samples o(t) = C(t) + delta N(t) and the speed factor 1 + kappa delta
 *   dfl_offset_count        cusps, swallow-tails and self-intersections of a sampled offset
 *   dfl_polyline_crossings  proper crossings of a closed polyline with itself
 *   dfl_offset_free
 *
 * Conventions (geom/curvature.h, geom/curve_sdf.h): N is the OUTWARD unit
 * normal, kappa the curvature for it (a circle of radius R: +1/R), so
 * delta > 0 offsets outwards and delta < 0 inwards (dflab's signed distance
 * is negative inside).  Along the offset do/dt = (1 + kappa delta) C'(t):
 * the offset runs backwards where 1 + kappa delta < 0, and every maximal
 * arc of the parameter circle where it does (between two cusps, where the
 * factor changes sign) is one swallow-tail.  Self-intersections are counted
 * on the sampled polyline: proper crossings of non-adjacent segments (exact
 * orientation tests, no tolerance; touching or collinear overlaps do not
 * count), so each swallow-tail contributes one crossing where the two arcs
 * beside it cross, and global crossings (two distant arcs of the offset
 * meeting across the medial axis) add to the count.
 *
 * The curve must be planar and closed (dfl_bspline_is_closed); the
 * orientation (+1 counter-clockwise, -1 clockwise) picks the outward side:
 * N = orient * (T_y, -T_x).  Samples are taken at n parameters uniformly in
 * [t0, t1) (n >= 8).  Failure: DFL_E_INPUT (open or non-planar curve, n out
 * of range, orient not +-1, delta not finite), DFL_E_NOMEM; *out zeroed.
 * Pure and thread-safe apart from the allocation of the result.
 */
#ifndef DFL_GEOM_OFFSET_H
#define DFL_GEOM_OFFSET_H

#include <stddef.h>

#include "core/status.h"
#include "geom/bspline.h"

typedef struct dfl_offset {
    size_t n;          /* samples (the polyline is closed: point n-1 joins point 0) */
    double delta;
    double *t;         /* n parameters */
    double *pts;       /* 2n: C(t) + delta N(t) */
    double *foot;      /* 2n: C(t) */
    double *speed;     /* n: 1 + kappa(t) delta (< 0: the offset runs backwards) */
} dfl_offset;

typedef struct dfl_offset_counts {
    size_t cusps;               /* sign changes of the speed factor around the curve */
    size_t swallow_tails;       /* maximal arcs with speed < 0 */
    size_t self_intersections;  /* proper crossings of the sampled offset */
    double reversed_fraction;   /* share of samples with speed < 0 */
} dfl_offset_counts;

dfl_status dfl_offset_curve(const dfl_bspline *c, int orient, double delta, size_t n,
                            dfl_offset *out, dfl_err *err);

/* Counts of a sampled offset (no allocation beyond a sort buffer; DFL_E_NOMEM). */
dfl_status dfl_offset_count(const dfl_offset *o, dfl_offset_counts *out, dfl_err *err);

/* Proper crossings of the closed polyline p (n points, 2 doubles each,
 * segment i from p_i to p_(i+1 mod n)) with itself: pairs of non-adjacent
 * segments whose interiors cross (strict orientation tests).  Segments are
 * swept in x order (sorted by their left end), so the cost is
 * O(n log n + candidate pairs).  DFL_E_NOMEM. */
dfl_status dfl_polyline_crossings(const double *p, size_t n, size_t *count, dfl_err *err);

void dfl_offset_free(dfl_offset *o);

#endif
