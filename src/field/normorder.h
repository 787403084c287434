/* The normalization order of a field at a boundary point, read off a jet.
 *
 * bs04 eq. 1: u is normalized to order m at a boundary point p along the
 * unit direction nu when, at s = 0+,
 *     u(p) = 0,  d/ds u(p + s nu) = sigma,  d^k/ds^k u(p + s nu) = 0 (k = 2..m)
 * with sigma = +1 (sigma = -1 along the inward normal of a signed field).
 *
 * Floating point cannot see exact zeros.  The Taylor coefficient
 * a_k = d_k / k! has units length^(1-k), so it is made dimensionless with a
 * length scale L of the geometry (the caller's choice: a segment length, a
 * radius of curvature) and counts as zero when
 *     |a_k| L^(k-1) <= tol;
 * d1 counts as sigma when |d1 - sigma| <= tol, and u(p) as zero when
 * |a_0| <= tol L.  With tol = 1e-9 this is "zero to 1e-9 relative to the
 * first derivative" on the scale L.
 */
#ifndef DFL_EXPERIMENTS_NORMORDER_H
#define DFL_EXPERIMENTS_NORMORDER_H

#include "core/jet.h"
#include "core/status.h"

typedef struct dfl_normorder {
    /* -1: u(p) != 0 (p is not on the zero set); 0: d1 != sigma; m >= 1:
     * d1 = sigma and a_2..a_m vanish. */
    int order;
    /* 1 when every known coefficient vanished: the order is at least the
     * jet's order (order is then set to it, and k to one more). */
    int capped;
    /* Derivative order of the first violation of eq. 1: order + 1 (0 when
     * order == -1, kmax + 1 when capped). */
    int k;
    double coef;   /* a_k (k = 1: d1; k = 0: u(p)); NAN when capped */
    double deriv;  /* d_k = k! a_k; NAN when capped */
    double d1;     /* first derivative at 0+ */
} dfl_normorder;

/* The length on which the jet's coefficients are at most 1 in size:
 *     R = min over k = 2..kmax with a_k != 0 of |a_k|^(-1/(k-1)),
 * a Cauchy-Hadamard estimate of the radius of convergence of the series
 * along the ray.  INFINITY when a_2..a_kmax are all 0 (or unknown).  With
 * L = min(geometric scale, R) the zero test reads "small relative to the
 * expansion's own size": rounding residue in a jet scales with its largest
 * terms (a field normalized by recursion, normalize.h, has coefficients far
 * larger than any radius of curvature suggests). */
double dfl_normorder_scale(const dfl_jet *j);

/* Measures the order of the jet j (of s -> u(p + s nu), nu unit) up to its
 * known order dfl_jet_order(j) (>= 1).  DFL_E_INPUT for sigma not +-1,
 * L <= 0, tol <= 0 or a jet known to order < 1; DFL_E_NUMERIC for a pole
 * (negative valuation) or a NAN coefficient. */
dfl_status dfl_normorder_measure(const dfl_jet *j, double sigma, double L, double tol,
                                 dfl_normorder *out, dfl_err *err);

#endif
