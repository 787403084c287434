/* Curvature of a surface from samples around a footpoint (hvb25 Sec. 5.2;
 * Goldfeather & Interrante 2004, the cubic fit with positions only).
 *
 * Function index
 *   dfl_curvfit             the precomputed fit: grid and pseudo-inverse
 *   dfl_curvfit_init        build it for a g x g grid of spacing h
 *   dfl_curvfit_coeffs      the 7 fitted coefficients from heights z
 *   dfl_curvfit_from_heights curvature from the heights over the grid
 *   dfl_curvfit_sdf         the whole method on an SDF at footpoint p
 *
 * Method: in the frame (b1, b2, n) at p (b1, b2 = dfl_vec3_tangent_basis(n),
 * so b1 x b2 = n) the grid nodes are (a_i, a_j, 0), a_i = (i - (g-1)/2) h;
 * each is projected orthogonally onto the surface (along n: the root t of
 * f(q + t n) = 0 by Newton from t = 0), which keeps its (x, y) and gives a
 * height z_ij = t.  The surface is fitted as the graph
 *     z = A x^2/2 + B x y + C y^2/2 + D x^3 + E x^2 y + F x y^2 + G y^3
 * (through p, tangent to the plane: no constant or linear terms) by least
 * squares; the design depends only on (g, h), so its Moore-Penrose
 * pseudo-inverse P = (M^T M)^{-1} M^T is computed once.  The Weingarten
 * matrix in geom/curvature.h's convention (eigenvalues of dn; a sphere
 * with outward n has z = -rho^2/(2r) + ..., hence kappa = +1/r) is
 *     W = -[[A, B], [B, C]],
 * its eigenpairs are the principal curvatures and directions.
 * Truncation: on the symmetric grid the odd cubic columns do not mix with
 * the even quadratic ones, so the quartic part of the surface's Taylor
 * series aliases into (A, B, C): |dA| <= sum_k |P_0k| |z_k - T3(x_k, y_k)|
 * (T3 the cubic Taylor polynomial), i.e. O(((g-1) h / 2)^2) times the
 * fourth derivatives (tests/proxy/test_curvfit.c derives its tolerance so).
 *
 * Thread safety: a dfl_curvfit is read-only after init; no allocation.
 */
#ifndef DFL_PROXY_CURVFIT_H
#define DFL_PROXY_CURVFIT_H

#include "core/status.h"
#include "geom/curvature.h"
#include "geom/shape.h"

#define DFL_CURVFIT_MAX_G 15
#define DFL_CURVFIT_NCOEF 7
#define DFL_CURVFIT_MIN_NODES 10 /* nodes a fit needs (dfl_curvfit_sdf) */

typedef struct dfl_curvfit {
    int g;                   /* grid nodes per side */
    double h;                /* spacing */
    int npts;                /* g * g, node (i, j) at index i + g j */
    double xy[2 * DFL_CURVFIT_MAX_G * DFL_CURVFIT_MAX_G];
    double pinv[DFL_CURVFIT_NCOEF][DFL_CURVFIT_MAX_G * DFL_CURVFIT_MAX_G];
} dfl_curvfit;

/* g in 3..DFL_CURVFIT_MAX_G, h > 0 finite: DFL_E_INPUT otherwise. */
dfl_status dfl_curvfit_init(int g, double h, dfl_curvfit *out, dfl_err *err);

/* coef[0..6] = (A, B, C, D, E, F, G) = P z for heights z[npts]. */
void dfl_curvfit_coeffs(const dfl_curvfit *F, const double *z, double coef[DFL_CURVFIT_NCOEF]);

/* Curvatures from heights z over the grid in the frame (b1, b2, n). */
void dfl_curvfit_from_heights(const dfl_curvfit *F, const double *z, const double b1[3],
                              const double b2[3], const double n[3], dfl_curvature *out);

/* The method on the 3D shape s at the footpoint p with unit normal n.
 * Each node's height is the root of t -> f(q + t n) with |t| <= 3 grid
 * widths: Newton from t = 0 (all nodes in one batch, 30 steps); a node
 * where Newton fails (slope along n below 0.1, a non-finite value, a step
 * beyond the reach, no convergence) takes the sign change of f nearest to
 * t = 0 on the ladder +-h/2, +-h, +-2h, ... and Illinois steps (a triangle
 * mesh's kinks: the normal line meets a face at a grazing angle).  Where
 * Newton succeeds for every node the result is Newton's alone.  A node
 * with no sign change within the reach (its normal line misses the
 * surface: past a boundary, through a mesh's hole), a non-finite f, or a
 * sign change where f jumps instead of passing 0 (|f| at the converged
 * bracket above its width plus 1e-12 (1 + |t|): an open mesh's
 * winding-number sign flips across a sheet off the surface) is left out,
 * and the least squares is solved on the nodes that remain;
 * DFL_E_NUMERIC when fewer than DFL_CURVFIT_MIN_NODES remain or their
 * design is singular; out is then untouched. */
dfl_status dfl_curvfit_sdf(const dfl_curvfit *F, const dfl_shape *s, const double p[3],
                           const double n[3], dfl_curvature *out);

#endif
