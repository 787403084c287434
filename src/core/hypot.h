/* Euclidean lengths the way dflab's distance code measures them.
 *
 *   dfl_hypot2(a, b)       sqrt(a^2 + b^2); hypot() only outside the safe range
 *   dfl_hypot_vec(dim, w)  |w| for dim 2 or 3, as nested dfl_hypot2
 *
 * dfl_hypot2 is sqrt(a*a + b*b) rounded twice (square sum, root) when the
 * square sum lies in (1e-290, 1e290), which is where it cannot overflow or
 * lose precision to underflow; outside that range it is libm's hypot().  It
 * is cheaper than hypot() and, unlike it, rounds the same way as the plain
 * formula, which callers that compare lengths from different modules rely
 * on: the rfunc primitives (trim, segment carrier, point, vertex guards) and
 * rfunc/exact_polyline measure every length through it, so they agree bit
 * for bit.
 *
 * dfl_hypot_vec(3, w) is dfl_hypot2(dfl_hypot2(w0, w1), w2) -- not the
 * square root of the three-term sum: the inner length is rounded first.
 * Inline, pure, no checks beyond an assert on dim. */
#ifndef DFL_CORE_HYPOT_H
#define DFL_CORE_HYPOT_H

#include <assert.h>
#include <math.h>

static inline double dfl_hypot2(double a, double b)
{
    const double s = a * a + b * b;
    if (s > 1e-290 && s < 1e290) return sqrt(s);
    return hypot(a, b);
}

/* dim == 2 or 3 (asserted); w holds dim doubles. */
static inline double dfl_hypot_vec(int dim, const double *w)
{
    assert(dim == 2 || dim == 3);
    return dim == 2 ? dfl_hypot2(w[0], w[1]) : dfl_hypot2(dfl_hypot2(w[0], w[1]), w[2]);
}

#endif
