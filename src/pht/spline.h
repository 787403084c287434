/* C1 bicubic / tricubic PHT splines over hierarchical T-meshes (sjp10 Sec. 2).
 *
 * A PHT spline is given by Hermite data at the base vertices of a T-mesh
 * (pht/tmesh.h): 4 values per vertex in 2D, 8 in 3D, in mask order
 * (pht/hermite.h: data[b] = the derivative w.r.t. the coordinates whose bits
 * are set in b).  Hanging vertices get their data by cubic Hermite
 * interpolation along the edge they lie on (EDGE), or tensor-product cubic
 * Hermite on the face (FACE, 3D), from the corners the mesh records, coarse
 * levels first (dfl_pht_resolve).  Each leaf cell then carries the
 * bicubic / tricubic polynomial that interpolates the data at its 2^dim
 * corners.  The restriction of a cell's polynomial to one of its edges
 * (faces) depends only on the data at that edge's (face's) corners, and the
 * data of a hanging vertex are the coarse element's polynomial there, so
 * neighbouring cells agree in value and gradient: the spline is C1.  Any
 * bicubic (tricubic) polynomial is reproduced exactly.
 *
 * Evaluation: a point is located in the spline's own copy of the cell tree
 * (a uniform grid of start nodes, then O(levels) steps, no allocation;
 * dfl_pht_eval locates its points in blocks, so that their cache misses
 * overlap, and leaves out the Hessian's terms unless asked for them), then
 * the cell's polynomial, stored as
 * 4^dim power-basis coefficients in the cell's local coordinates
 * u = (x - lo) / (hi - lo), is evaluated by Horner's rule.  Points outside
 * the box are evaluated with the polynomial of the nearest boundary cell
 * (smooth extrapolation, no clamping of the value).  A point with a NaN
 * coordinate is located below every split on that axis (the cell at the
 * box's low face there; no read outside the tree or its cells, on every
 * ISA) and gets NaN value, gradient and Hessian; an infinite coordinate is
 * located like a far point (the boundary cell; the values are its
 * polynomial's there, +-inf or NaN).
 *
 * Function index:
 *   dfl_pht_resolve             data of hanging vertices from the base data
 *   dfl_pht_cell_poly           power-basis coefficients of one cell from its corner data
 *   dfl_pht_spline_new / _free  spline from a mesh and resolved vertex data (copies)
 *   dfl_pht_spline_dim, _ncells, _nbase, _dofs, _bytes, _box   sizes
 *   dfl_pht_spline_locate       index of the cell holding a point (tmesh leaf order)
 *   dfl_pht_spline_cell         box and coefficients of cell i
 *   dfl_pht_eval                batched value, gradient, Hessian
 *   dfl_pht_eval_cell           the same with the cell given (no location)
 *   dfl_pht_jet                 exact jet along a ray (a dfl_dir_jet_fn)
 */
#ifndef DFL_PHT_SPLINE_H
#define DFL_PHT_SPLINE_H

#include <stddef.h>

#include "core/jet.h"
#include "core/status.h"
#include "pht/tmesh.h"

#define DFL_PHT_NCOEF(dim) ((dim) == 2 ? 16 : 64)

/* Fills data[v*nd + b] (nd = DFL_PHT_NDATA(dim)) of every hanging vertex v
 * from the entries of the vertices it depends on, in dfl_tmesh_order; the
 * entries of base vertices are read, never written. */
void dfl_pht_resolve(const dfl_tmesh *m, double *data);

/* Coefficients c[i + 4 j (+ 16 k)] of the cell polynomial
 * p(u) = sum c[..] u^i v^j (w^k) in local coordinates u in [0,1]^dim of the
 * box [lo, hi], from corner data corner[c*nd + b] (corner index c: bit j =
 * high side along axis j; b in mask order, derivatives in world units). */
void dfl_pht_cell_poly(int dim, const double *lo, const double *hi, const double *corner,
                       double *coef);

typedef struct dfl_pht_spline dfl_pht_spline;

/* The spline of mesh m with vertex data data[v*nd + b] for all vertices
 * (resolved: call dfl_pht_resolve first).  Copies the cell tree, the leaf
 * boxes and the cell polynomials, so m and data may be freed afterwards;
 * memory is O(cells).  DFL_E_NOMEM. */
dfl_status dfl_pht_spline_new(const dfl_tmesh *m, const double *data, dfl_pht_spline **out,
                              dfl_err *err);
/* s may be NULL. */
void dfl_pht_spline_free(dfl_pht_spline *s);

int dfl_pht_spline_dim(const dfl_pht_spline *s);
/* Leaf cells (in the mesh's leaf order). */
size_t dfl_pht_spline_ncells(const dfl_pht_spline *s);
/* Base vertices of the mesh it was built from, and the degrees of freedom
 * nbase * DFL_PHT_NDATA(dim) (the stored scalars that define the spline). */
size_t dfl_pht_spline_nbase(const dfl_pht_spline *s);
size_t dfl_pht_spline_dofs(const dfl_pht_spline *s);
/* Bytes held (tree, boxes, coefficients). */
size_t dfl_pht_spline_bytes(const dfl_pht_spline *s);
/* The box (dim doubles each). */
void dfl_pht_spline_box(const dfl_pht_spline *s, double *lo, double *hi);

/* Cell index (0..ncells-1) holding x, with dfl_tmesh_locate's tie rules
 * (dir may be NULL); a NaN coordinate goes below every split on its axis
 * (as the box's low face does), an infinite one as a far point does.
 * Thread-safe, no allocation. */
size_t dfl_pht_spline_locate(const dfl_pht_spline *s, const double *x, const double *dir);
/* Box of cell i into lo/hi (may be NULL), its level into *level (may be
 * NULL); returns its DFL_PHT_NCOEF(dim) coefficients (borrowed). */
const double *dfl_pht_spline_cell(const dfl_pht_spline *s, size_t i, double *lo, double *hi,
                                  int *level);

/* At m points pts[i*dim + j]: val[i] (may be NULL), grad[i*dim + j] (may be
 * NULL), hess[i*dim*dim + j*dim + k] (may be NULL).  Serial, no allocation,
 * thread-safe: callers parallelize over chunks (the field adapter does). */
void dfl_pht_eval(const dfl_pht_spline *s, size_t m, const double *pts, double *val,
                  double *grad, double *hess);

/* As dfl_pht_eval, but every point is evaluated with the polynomial of cell
 * i (also outside that cell: polynomial extrapolation). */
void dfl_pht_eval_cell(const dfl_pht_spline *s, size_t i, size_t m, const double *pts,
                       double *val, double *grad, double *hess);

/* Exact jet of t -> f(x + t dir) at t = 0+ to order K: the cell that
 * x + t dir enters for small t > 0 is a polynomial of degree <= 3 dim along
 * the ray, so the jet is exact (terms above the degree are exact zeros).
 * ctx is the spline (the dfl_dir_jet_fn signature).  DFL_E_INPUT for K
 * outside [0, DFL_JET_MAX]. */
dfl_status dfl_pht_jet(const void *spline, const double *x, const double *dir, int K,
                       dfl_jet *out, dfl_err *err);

#endif
