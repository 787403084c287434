/* Implicit surfaces g(p) = 0 in 3D and their signed distance.
 *
 * g is a polynomial (stored as a sparse list of monomials in a local frame
 * p_loc = Q (p - o)), negative inside a bounded solid.  g is NOT a distance:
 * the distance of x to the surface comes from a footpoint p solving
 *
 *     g(p) = 0,   x - p = t grad g(p)   (equivalently grad g(p) x (p - x) = 0)
 *
 * with several starts and the smallest |x - p| kept.  Starts are surface
 * samples made once at construction (grid nodes within 1.5 h of the
 * surface projected onto it, h = sample spacing): every sample within
 * D0 + 1.5 h of x (D0 = distance of the nearest sample, an upper bound of
 * the true distance; the true footpoint has a sample within h) is a start
 * candidate, thinned to representatives at least 3 h apart (at most
 * DFL_IMPLICIT_MAX_STARTS, the nearest kept).
 *
 * Backends (one interface, chosen by dfl_implicit_options.backend):
 *   NEWTON  in-house Riemannian Newton on the surface: minimizes |p - x|^2/2
 *           over g = 0 with tangent-plane Newton steps (Hessian I + d W, W
 *           the shape operator) and projection onto g = 0 as retraction;
 *           no allocation.  Robust where a circle of footpoints nearly ties.
 *   CERES   Levenberg-Marquardt (src/solve/lsq.h) on the residuals
 *           (g(p), grad g(p) x (p - x)) with p boxed in x +- (D0 + 2 h)
 *           (the footpoint lies in the ball of radius D0 around x, and
 *           every start inside the box).
 * Both end with the same acceptance test, so they agree to rounding where
 * the closest footpoint is unique.
 *
 * Signed distance: d(x) = sign(g(x)) |x - p|, negative inside; its gradient
 * is the unit normal n(p) = grad g(p) / |grad g(p)| (outward).
 * Medial axis: when two footpoints at least 1e-6 * scale apart have
 * distances equal to 1e-9 * scale, the point is flagged medial and the
 * footpoint with the lexicographically smallest (x, y, z) is chosen, so the
 * choice does not depend on the order of the starts.
 *
 * Curvatures: geom/curvature.h's convention with the outward normal n(p)
 * (a sphere has kappa = +1/r, and the SDF Hessian at x = p + d n is
 * sum_i kappa_i / (1 + kappa_i d) e_i e_i^T).
 *
 * Thread safety: a dfl_implicit is read-only after construction; all
 * queries may run concurrently (the Ceres context is shared, see lsq.h).
 *
 * Files: implicit.c (construction, g, samples), implicit_foot.c
 * (footpoints), implicit_sdf.c (jets, Hermite data, the shape wrapper),
 * implicit_surfaces.c (torus, Goursat, genus 2, sphere, scrambled ellipsoid); the polynomial type is
 * geom/poly3.h.
 */
#ifndef DFL_GEOM_IMPLICIT_H
#define DFL_GEOM_IMPLICIT_H

#include "core/jet.h"
#include "core/status.h"
#include "geom/foot_backend.h"
#include "geom/poly3.h"
#include "geom/shape.h"

#define DFL_IMPLICIT_MAX_TERMS DFL_POLY3_MAX_TERMS
#define DFL_IMPLICIT_MAX_DEGREE DFL_POLY3_MAX_DEGREE
#define DFL_IMPLICIT_MAX_STARTS 16


typedef struct dfl_implicit_options {
    dfl_foot_backend backend;   /* default NEWTON */
    int resolution;             /* sample grid nodes along the longest bbox side; default 64, >= 8 */
    int max_iterations;         /* Newton steps per start; default 100 */
    int ceres_max_iterations;   /* LM iterations per start; default 1000 (LM crawls
                                   along the curved valley near the medial axis) */
} dfl_implicit_options;

void dfl_implicit_options_default(dfl_implicit_options *opt);

typedef struct dfl_implicit dfl_implicit;

/* One monomial c * u^e[0] v^e[1] w^e[2] in local coordinates. */
typedef struct dfl_monomial {
    double c;
    int e[3];
} dfl_monomial;

/* General polynomial surface: g(p) = sum_k terms[k] at (u, v, w) = Q (p - o),
 * Q orthonormal (rows are the local axes; NULL = identity), o NULL = 0.
 * [lo, hi] (local coordinates) must contain the whole zero set, which must
 * be non-empty and regular (grad g != 0 on it).  DFL_E_INPUT otherwise
 * (checked on the samples).  opt may be NULL (defaults).  Total degree
 * <= DFL_IMPLICIT_MAX_DEGREE, nterms <= DFL_IMPLICIT_MAX_TERMS. */
dfl_status dfl_implicit_new(int nterms, const dfl_monomial *terms, const double *o,
                            const double Q[9], const double lo[3], const double hi[3],
                            const dfl_implicit_options *opt, dfl_implicit **out, dfl_err *err);

/* Torus quartic (|q|^2 + R^2 - r^2)^2 - 4 R^2 (q_u^2 + q_v^2), q = local
 * coordinates around centre c with w along axis; 0 < r < R. */
dfl_status dfl_implicit_torus(const double c[3], const double axis[3], double R, double r,
                              const dfl_implicit_options *opt, dfl_implicit **out, dfl_err *err);
/* Goursat's family x^4 + y^4 + z^4 + a (|q|^2)^2 + b |q|^2 + c, q = p - centre;
 * needs a > -1/3 (bounded) and a non-empty zero set.  The tangle cube is
 * a = 0, b = -5, c = 11.8. */
dfl_status dfl_implicit_goursat(const double centre[3], double a, double b, double c,
                                const dfl_implicit_options *opt, dfl_implicit **out,
                                dfl_err *err);
/* Genus-2 surface: a tube around Bernoulli's lemniscate,
 * g = L^2 + z^2 - eps^2 with L = (x^2 + y^2)^2 - x^2 + y^2, q = p - centre,
 * 0 < eps < 1/4 (L's minimum is -1/4 at the lobe centres: a larger eps
 * closes the two holes). */
dfl_status dfl_implicit_genus2(const double centre[3], double eps, const dfl_implicit_options *opt,
                               dfl_implicit **out, dfl_err *err);

/* Sphere as the polynomial |q|^2 - r^2 (q = p - c; not a distance: its
 * gradient has length 2 |q|), r > 0. */
dfl_status dfl_implicit_sphere(const double c[3], double r, const dfl_implicit_options *opt,
                               dfl_implicit **out, dfl_err *err);
/* Ellipsoid sum_j q_j^2 / semi_j^2 - 1 (axis-aligned, q = p - c) scrambled
 * by the positive factor 1 + k (q_x^2 + q_y^4 + q_x^2 q_z^2), k >= 0: same
 * zero set and inside, g far from a distance (degree 6). */
dfl_status dfl_implicit_ellipsoid(const double c[3], const double semi[3], double k,
                                  const dfl_implicit_options *opt, dfl_implicit **out,
                                  dfl_err *err);

void dfl_implicit_free(dfl_implicit *s);

/* g, grad g (3, may be NULL) and Hessian (9 row-major, may be NULL) at the
 * world point x. */
double dfl_implicit_g(const dfl_implicit *s, const double x[3], double grad[3], double hess[9]);
/* Third derivatives d3[i*9 + j*3 + k] = d^3 g / dx_i dx_j dx_k (world). */
void dfl_implicit_g3(const dfl_implicit *s, const double x[3], double d3[27]);
/* Sample spacing h and scale (bbox diagonal), world units. */
double dfl_implicit_spacing(const dfl_implicit *s);
double dfl_implicit_scale(const dfl_implicit *s);
/* The surface samples used as starts (borrowed, n*3 doubles, world). */
const double *dfl_implicit_samples(const dfl_implicit *s, size_t *n);

typedef struct dfl_footpoint {
    double p[3];       /* footpoint on g = 0 */
    double n[3];       /* outward unit normal at p */
    double d;          /* signed distance, negative inside */
    double t;          /* x - p = t grad g(p) */
    int medial;        /* 1 if another footpoint is as close (see top) */
    int converged;     /* number of starts that converged */
} dfl_footpoint;

/* Closest footpoint of x with the configured backend.  DFL_E_NUMERIC if no
 * start converged, or x has a NaN or infinite coordinate (then nothing is
 * read: the shape's value and gradient are NaN). */
dfl_status dfl_implicit_footpoint(const dfl_implicit *s, const double x[3], dfl_footpoint *out,
                                  dfl_err *err);
/* The same with an explicit backend (for comparisons). */
dfl_status dfl_implicit_footpoint_with(const dfl_implicit *s, dfl_foot_backend backend,
                                       const double x[3], dfl_footpoint *out, dfl_err *err);

/* Exact jet of s -> d(x + s dir) at 0+ to order K, from the footpoint of x
 * continued along the ray by Newton steps in truncated power series (one
 * exact order per step, with the Jacobian frozen at s = 0).  DFL_E_NUMERIC
 * at a focal point (singular Jacobian); meaningless on the medial axis
 * (foot->medial tells).  foot may be NULL (then computed). */
dfl_status dfl_implicit_jet(const dfl_implicit *s, const dfl_footpoint *foot, const double x[3],
                            const double dir[3], int K, dfl_jet *out, dfl_err *err);

/* SDF derivatives for Hermite data: value, gradient, full Hessian and the
 * mixed third derivative d_xyz (polarization of third directional
 * derivatives: d_xyz = 1/24 sum over e in {(1,1,1),(1,1,-1),(1,-1,1),
 * (-1,1,1)} of eps1 eps2 eps3 D^3_e d). */
typedef struct dfl_sdf_derivs {
    double d;
    double g[3];
    double H[9];       /* row-major, symmetric */
    double dxyz;
    dfl_footpoint foot;
} dfl_sdf_derivs;
dfl_status dfl_implicit_sdf_derivs(const dfl_implicit *s, const double x[3], dfl_sdf_derivs *out,
                                   dfl_err *err);

/* The implicit surface as a dfl_shape (eval: d and n(p) per point, NaN where
 * no start converged or the point is not finite; jet: dfl_implicit_jet).
 * Takes ownership of *s (set to NULL), also on failure. */
dfl_status dfl_implicit_shape(dfl_implicit **s, dfl_shape *out, dfl_err *err);
/* The implicit inside a shape made by dfl_implicit_shape (NULL otherwise). */
const dfl_implicit *dfl_implicit_of_shape(const dfl_shape *shape);

#endif
