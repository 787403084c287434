/* Checks of dfl_shape kinds against references that never come from a
 * previous run:
 *  - distances: brute-force closest point over a dense sampling of the
 *    shape's boundary patches (>= 1e5 samples per shape and query, then a
 *    local pattern search in the patch parameters), signed by an
 *    independent closed-form inside test;
 *  - gradients: central finite differences of the SDF;
 *  - jets: 7-point finite-difference stencils along the ray (orders 1-3),
 *    used only where two step sizes agree (the stencil does not straddle a
 *    curvature jump such as a box's face/edge region boundary).
 * Shared by the shape test files; sc_urand is one xorshift sequence per
 * test process. */
#ifndef DFL_TESTS_GEOM_SHAPE_CHECK_H
#define DFL_TESTS_GEOM_SHAPE_CHECK_H

#include "geom/shape.h"

/* Uniform in [lo, hi): the test process' sequence. */
double sc_urand(double lo, double hi);
void sc_normalize3(double *a);
/* Orthonormal u, v perpendicular to unit w (Gram-Schmidt from e_x or e_y). */
void sc_perp_basis(const double w[3], double u[3], double v[3]);

/* A boundary patch: point(ctx, params) over the box [lo, hi] (np params). */
typedef struct sc_patch {
    int np;
    double lo[2], hi[2];
    void (*point)(const void *ctx, const double *prm, double *p);
    const void *ctx;
} sc_patch;

/* Unsigned distance from x to the union of patches: dense grid (total
 * >= nsamp samples) then refinement of every patch's best sample. */
double sc_brute_dist(const sc_patch *P, int npatch, int dim, const double *x, long nsamp);

typedef int (*sc_inside_fn)(const double *x);

/* At npts random points in [lo, hi]^dim: the value against brute force
 * (check_values; negated where inside() for is_signed), the gradient
 * against central FD (and |grad| = 1 for unit_grad), and, with jets, the
 * jets of orders 0-3 against the value, grad . dir and FD stencils (at
 * least half of the stencils must be consistent); without jets, that the
 * shape has none. */
void sc_check_shape(const dfl_shape *s, const sc_patch *P, int npatch, sc_inside_fn inside,
                    int is_signed, double lo, double hi, int npts, int check_values,
                    int unit_grad, int jets);

#endif
