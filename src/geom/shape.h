/* Shapes with signed distance functions: the interface, the analytic
 * kinds with exact SDFs, CSG of SDFs, and the table of shape kinds.
 *
 * A dfl_shape is a region of R^2 or R^3 (dim) with a signed distance
 * function d: negative inside, zero on the boundary, positive outside, in the
 * units of its parameters.  Every shape gives d and its gradient in batches
 * and, where supported, the exact jet of s -> d(x + s dir) at s = 0+ (see
 * core/jet.h): the jet is taken on the branch of d that is valid for small
 * s > 0 (at a kink the one-sided derivatives of that side), so jets are exact
 * also on the boundary and on ties of min/max.
 *
 * Gradients: where d is not differentiable (the medial axis, the centre of a
 * circle, the axis of a cylinder, a box's diagonal planes) eval returns one
 * of the one-sided gradients, chosen deterministically (at a circle's or a
 * sphere's centre, on a cylinder's or torus' axis: the first coordinate
 * direction of the local frame), so |grad d| = 1 holds everywhere for the
 * exact SDFs.
 *
 * Analytic kinds (shape_analytic.c; all exact Euclidean SDFs with jets):
 *   circle (2D), sphere (3D): |x - c| - r
 *   torus (3D): centre, axis, major R > 0, minor r > 0 (r < R not required
 *               for the formula but required here so the torus is a ring)
 *   cylinder (3D): infinite, around the line through p with direction axis
 *   plane (2D line / 3D plane): through p with normal n; the side n points to
 *               is outside (d = (x - p) . n / |n|)
 *   cone (3D): capped cone (frustum) from a (radius ra) to b (radius rb),
 *               ra, rb >= 0, not both 0; ra == rb is a capped cylinder
 *   box (2D/3D): axis-aligned, centre and half sizes > 0
 *   segment (2D/3D): UNSIGNED distance to the segment ab (>= 0 everywhere)
 * CSG (shape_csg.c): union / intersection / difference of two shapes, exact
 *   min/max or polynomial smooth min/max with smoothing width k > 0 (a bound
 *   of the true distance, not a distance).
 * Kinds built elsewhere on the same interface: ellipse (geom/ellipse.h),
 *   parametric curves and surfaces (geom/param_shape.h), implicit surfaces
 *   (geom/implicit.h), triangle meshes (geom/mesh.h: exact distance, sign of
 *   the generalized winding number).
 *
 * Domain of validity (core/domain.h): parameters and points with
 * |x_j| <= 1e150.  The analytic kinds square differences of coordinates, so
 * within it no intermediate overflows; circle and sphere measure |x - c|
 * in a scaled form where the square sum leaves (1e-290, 1e290), so their
 * values stay finite and within a few ulps across the whole domain (the
 * same bits as the plain formula inside that range).  The config glue
 * (experiments/cfg/shape_cfg.c) refuses larger parameters with exit 2.
 *
 * Ownership: constructors allocate impl; dfl_shape_free releases it.  The
 * CSG constructor takes ownership of its children (their structs are zeroed).
 */
#ifndef DFL_GEOM_SHAPE_H
#define DFL_GEOM_SHAPE_H

#include <stddef.h>

#include "core/jet.h"
#include "core/names.h"
#include "core/status.h"

/* The shape kinds, one list (core/names.h): X(code, name, note) gives the
 * code and the name used in configs ([shape] kind = name).  A new kind adds
 * one row here and one parser row in experiments/cfg/shape_cfg.c. */
#define DFL_SHAPE_KIND_LIST(X)                                                   \
    X(DFL_SHAPE_CIRCLE, "circle", "2D, analytic")                                \
    X(DFL_SHAPE_SPHERE, "sphere", "3D, analytic")                                \
    X(DFL_SHAPE_TORUS, "torus", "3D, analytic")                                  \
    X(DFL_SHAPE_CYLINDER, "cylinder", "3D, analytic, infinite")                  \
    X(DFL_SHAPE_PLANE, "plane", "2D line or 3D plane, analytic half-space")       \
    X(DFL_SHAPE_CONE, "cone", "3D, analytic capped cone")                        \
    X(DFL_SHAPE_BOX, "box", "2D or 3D, analytic")                                \
    X(DFL_SHAPE_SEGMENT, "segment", "unsigned distance to a segment")            \
    X(DFL_SHAPE_ELLIPSE, "ellipse", "2D, no jets")                               \
    X(DFL_SHAPE_BSPLINE_CURVE, "bspline_curve", "signed if closed and planar")   \
    X(DFL_SHAPE_BSPLINE_SURFACE, "bspline_surface", "unsigned, no jets")         \
    X(DFL_SHAPE_BEZIER_SURFACE, "bezier_surface", "unsigned, no jets")           \
    X(DFL_SHAPE_IMPLICIT, "implicit", "implicit surface (geom/implicit.h)")      \
    X(DFL_SHAPE_CSG, "csg", "union, intersection, difference of two shapes")     \
    X(DFL_SHAPE_MESH, "mesh", "triangle mesh (geom/mesh.h)")

typedef enum dfl_shape_kind { DFL_SHAPE_KIND_LIST(DFL_NAMES_CODE) } dfl_shape_kind;
enum { DFL_SHAPE_KIND_COUNT = 0 DFL_SHAPE_KIND_LIST(DFL_NAMES_ONE) };

/* Names indexed by kind (the list above, in its order). */
extern const char *const dfl_shape_kind_names[DFL_SHAPE_KIND_COUNT];
/* The name of kind, "?" outside 0..DFL_SHAPE_KIND_COUNT-1. */
const char *dfl_shape_kind_name(dfl_shape_kind kind);
/* The kind called name (exact match) into *out; DFL_E_INPUT "unknown shape
 * kind '<name>' (expected one of circle|...)" otherwise (*out untouched). */
dfl_status dfl_shape_kind_parse(const char *name, dfl_shape_kind *out, dfl_err *err);

typedef struct dfl_shape_ops {
    const char *kind;
    /* Signed distance (negative inside) at m points pts[i*dim+j]; grad
     * (m*dim) may be NULL.  Thread-safe, no allocation. */
    void (*eval)(const void *impl, size_t m, const double *pts, double *val, double *grad);
    /* Exact jet of s -> d(x + s dir) (core/jet.h's dfl_dir_jet_fn), or NULL
     * if unsupported. */
    dfl_dir_jet_fn jet;
    void (*free)(void *impl);
    /* Optional (NULL: dfl_shape_eval_unsigned folds eval's output): what
     * dfl_shape_eval_unsigned promises, computed without deciding the side
     * (a signed mesh skips its winding-number test). */
    void (*eval_unsigned)(const void *impl, size_t m, const double *pts, double *val,
                          double *grad);
} dfl_shape_ops;

typedef struct dfl_shape {
    int dim;                  /* 2 or 3 */
    const dfl_shape_ops *ops;
    void *impl;               /* owned; freed by dfl_shape_free */
} dfl_shape;

/* ---- constructors: DFL_E_INPUT for degenerate parameters (radius <= 0,
 * zero axis, ...), DFL_E_NOMEM on allocation failure; *out is untouched on
 * failure. ---- */
dfl_status dfl_shape_circle(const double c[2], double r, dfl_shape *out, dfl_err *err);
dfl_status dfl_shape_sphere(const double c[3], double r, dfl_shape *out, dfl_err *err);
/* Torus around the line through c with direction axis (any length > 0). */
dfl_status dfl_shape_torus(const double c[3], const double axis[3], double major, double minor,
                           dfl_shape *out, dfl_err *err);
/* Infinite circular cylinder of radius r around the line p + t axis. */
dfl_status dfl_shape_cylinder(const double p[3], const double axis[3], double r, dfl_shape *out,
                              dfl_err *err);
/* Half-space {(x - p) . n <= 0} in dim 2 or 3; n any length > 0. */
dfl_status dfl_shape_plane(int dim, const double *p, const double *n, dfl_shape *out,
                           dfl_err *err);
/* Capped cone (frustum) with base disc (a, ra) and top disc (b, rb). */
dfl_status dfl_shape_cone(const double a[3], const double b[3], double ra, double rb,
                          dfl_shape *out, dfl_err *err);
/* Axis-aligned box centre c, half sizes h[j] > 0, dim 2 or 3. */
dfl_status dfl_shape_box(int dim, const double *c, const double *h, dfl_shape *out,
                         dfl_err *err);
/* Unsigned distance to the segment ab (a != b), dim 2 or 3. */
dfl_status dfl_shape_segment(int dim, const double *a, const double *b, dfl_shape *out,
                             dfl_err *err);

typedef enum dfl_csg_op {
    DFL_CSG_UNION = 0,              /* min(a, b) */
    DFL_CSG_INTERSECTION,           /* max(a, b) */
    DFL_CSG_DIFFERENCE,             /* max(a, -b): a minus b */
    DFL_CSG_SMOOTH_UNION,           /* polynomial smooth min, width k */
    DFL_CSG_SMOOTH_INTERSECTION,    /* -smin(-a, -b) */
    DFL_CSG_SMOOTH_DIFFERENCE       /* -smin(-a, b) */
} dfl_csg_op;

/* Smooth min used by the smooth variants (Quilez' quadratic polynomial
 * smin): h = clamp(1/2 + (b - a)/(2k), 0, 1),
 * smin = b (1 - h) + a h - k h (1 - h).  Equals min(a, b) when |a - b| >= k,
 * is C1 everywhere and lies in [min(a,b) - k/4, min(a,b)]. */
double dfl_csg_smin(double a, double b, double k);

/* CSG node; takes ownership of *a and *b (both zeroed on success AND on
 * failure, children freed on failure).  Children must have the same dim.
 * k is ignored for the exact ops and must be > 0 for the smooth ones.
 * Jets exist if both children have jets. */
dfl_status dfl_shape_csg(dfl_csg_op op, double k, dfl_shape *a, dfl_shape *b, dfl_shape *out,
                         dfl_err *err);

/* ---- use ---- */
/* d at one point (grad, dim doubles, may be NULL).  Convenience, not for
 * hot loops. */
double dfl_shape_eval1(const dfl_shape *s, const double *x, double *grad);
/* Batch evaluation (see dfl_shape_ops.eval). */
void dfl_shape_eval(const dfl_shape *s, size_t m, const double *pts, double *val, double *grad);
/* |d| and, when grad is not NULL, sgn(d) grad d, bit for bit what
 * dfl_shape_eval gives with every value < 0 and its gradient negated (0,
 * -0 and NaN values and their gradients as eval gives them).  For callers
 * that need d grad d, d / (grad d . n) or the nearest surface point, all
 * unchanged by the fold, and not the side: the shape's eval_unsigned when
 * it has one (a signed mesh then skips its winding-number test), else eval
 * and the fold.  Same threading and allocation rules as eval. */
void dfl_shape_eval_unsigned(const dfl_shape *s, size_t m, const double *pts, double *val,
                             double *grad);
/* Jet along dir; DFL_E_INPUT if the shape has none or K is out of range. */
dfl_status dfl_shape_jet(const dfl_shape *s, const double *x, const double *dir, int K,
                         dfl_jet *out, dfl_err *err);
/* Footpoint of an SDF input (hvb25): p = x - d(x) grad d(x), then refined by
 * projections p <- p - d(p) grad d(p) until |d(p)| <= 1e-14 * (1 + |x|) or
 * 20 steps.  Exact for exact SDFs up to rounding; for CSG and smooth
 * variants it is an approximation (the shape's d is not a true distance).
 * Writes p (dim doubles); DFL_E_NUMERIC if the refinement did not reach the
 * tolerance (p then holds the last iterate). */
dfl_status dfl_shape_footpoint(const dfl_shape *s, const double *x, double *p, dfl_err *err);

/* Hermite data of the SDF at x (sjp10, hvb25): value, gradient, Hessian and,
 * in 3D, the mixed third derivative d_xyz, all exact (from jets by
 * polarization: H_ij = (D2_{e_i+e_j} - D2_{e_i} - D2_{e_j}) / 2 and
 * d_xyz = 1/24 sum_{e in (1,1,1),(1,1,-1),(1,-1,1),(-1,1,1)} e1 e2 e3 D3_e).
 * Meaningful where d is C3 around x (off the medial axis and off the
 * boundaries between closest-feature regions); at a kink the one-sided
 * values of the jets' directions are mixed.  DFL_E_INPUT if the shape has
 * no jets. */
typedef struct dfl_shape_derivs {
    double d;
    double g[3];       /* dim entries used */
    double H[9];       /* dim x dim, row-major, symmetric */
    double dxyz;       /* 3D only (0 in 2D) */
} dfl_shape_derivs;
dfl_status dfl_shape_derivs_at(const dfl_shape *s, const double *x, dfl_shape_derivs *out,
                               dfl_err *err);

/* Hessian H (n x n, row-major) and, for n == 3, the mixed third derivative
 * *dxyz of a function at x from its jets along coordinate directions and
 * their sums (the polarization of dfl_shape_derivs_at, dfl_shape_hessian and
 * dfl_implicit_sdf_derivs); dxyz is not written for n == 2, and for n == 3
 * it may be NULL (then no order-3 jets are taken).  n is 2 or 3 (asserted).  Fails with the first failing jet's
 * status; H is then partly written. */
dfl_status dfl_jets_polarize(int n, dfl_dir_jet_fn jet, const void *ctx, const double *x,
                             double *H, double *dxyz, dfl_err *err);

/* Hessian H (9 doubles, row-major) of a 3D shape's d at x: in closed form
 * for sphere, torus, cylinder, plane and exact (not smooth) CSG over them
 * (the branch eval takes at x, ties to a), else the polarization of six
 * order-2 jets (along e_i and e_i + e_k; the branch of d valid on the
 * positive side of each direction, as the jets).  DFL_E_INPUT for a 2D
 * shape or one with neither; a failing jet's status otherwise. */
dfl_status dfl_shape_hessian(const dfl_shape *s, const double *x, double *H, dfl_err *err);

/* Frees impl and zeroes *s.  s may be NULL or already freed. */
void dfl_shape_free(dfl_shape *s);

#endif
