/* Simple grid peers of the proxy fields (hvb25 "error per stored scalar"):
 * cell-centred N^3 grids of a shape's exact SDF, at the storage a proxy
 * grid of the same N spends.
 *
 * Function index
 *   dfl_gridpeer_kind       trilinear0 | taylor1 | taylor2 | tricubic (X-macro names)
 *   dfl_gridpeer_storage    float64 | float16
 *   dfl_gridpeer_new        build one as a dfl_field
 *   dfl_gridpeer_scalars    the number of stored scalars
 *   dfl_gridpeer_field_info kind, storage, n of a grid peer field
 *   dfl_gridpeer_stored     the stored scalars (their exact values)
 *   dfl_gridpeer_kind_name, _parse; dfl_gridpeer_storage_name, _parse
 *
 * Grid: N cells per axis over the box [lo, hi]; cell (i, j, k) has centre
 * c = lo + (i + 1/2, j + 1/2, k + 1/2) h with h = (hi - lo) / N per axis.
 * What each kind stores per cell and how it decodes at a query x:
 *   trilinear0  d(c)                      (1 scalar)  trilinear interpolation
 *               between the 8 centres around x; in the outer half cells
 *               (and outside the box) the trilinear form of the boundary
 *               cell pair is extrapolated, not clamped (clamp-to-edge gives
 *               L1 7.6e-3 on the protocol's sphere at N = 16, extrapolation
 *               its 2.92e-3)
 *   taylor1     d(c), grad d(c)           (4 scalars) u = d + g.(x - c) with c
 *               the nearest centre (the tangent-plane proxy as an algebraic
 *               expansion)
 *   taylor2     + Hessian (6 scalars)     (10 scalars) u = d + g.r + r.H r / 2,
 *               r = x - c
 *   tricubic    c(i, j, k)                (1 scalar)  the tensor cubic
 *               B-spline with knots at the centres whose coefficients c
 *               interpolate the samples d(centre) (the prefilter of SciPy's
 *               map_coordinates(order = 3)): C2 everywhere, the samples
 *               exactly (to rounding).  Boundary: not-a-knot (the third
 *               derivative is continuous at the second and the last-but-one
 *               centre of each axis, i.e. the first and last two centre
 *               intervals are one cubic piece); the n stored coefficients
 *               per axis determine the two ghost coefficients beyond them,
 *               c(-1) = 4 c(0) - 6 c(1) + 4 c(2) - c(3) (likewise at n), and
 *               the outer half cells and the outside of the box extrapolate
 *               the end pieces, as trilinear0 does.  Why not SciPy's mirror
 *               or reflect: they force d'(x) = 0 at a centre or at the box
 *               face, so a linear SDF (a plane, the far field of any shape)
 *               is decoded wrongly near every face; not-a-knot reproduces
 *               every cubic polynomial per axis (so the whole tensor space
 *               of degree <= 3 per variable) exactly everywhere, also in the
 *               outer cells and beyond the box.  It is the spline of SciPy's
 *               make_interp_spline(k = 3) (bc_type 'not-a-knot'), per axis.
 *               Needs n >= 4.  float16 storage rounds the coefficients (the
 *               samples are prefiltered in double first), so the samples
 *               are then reproduced to the coefficients' rounding only.
 * The nearest centre is the one of the cell holding x, x clamped into the
 * box (queries outside the box decode the boundary cell).  The value is
 * signed as the shape's SDF (negative inside).  Gradients are those of the
 * decoded polynomial (trilinear: of the trilinear interpolant, piecewise;
 * tricubic: of the spline).
 * Non-finite queries: a query with a NaN coordinate gets a NaN value (its
 * gradient is unspecified) and reads no cell outside the grid: it is
 * located in cell 0 (trilinear0, tricubic: the first piece) on that axis;
 * an infinite coordinate is located like a far one (the boundary cell or
 * piece), its value that cell's polynomial there (+-inf, or NaN where
 * inf - inf or 0 inf arises).  Either way the other queries of a batch are
 * unaffected, and every ISA gives the same.
 * Storage: float64 keeps the doubles; float16 rounds every stored scalar to
 * the nearest IEEE half (Imath's imath_float_to_half of the value rounded to
 * float first; |v| >= 65520 would become inf, and is rejected at build).
 * This is the protocol of results/reference/peers_measured.csv's simple3d
 * rows, so its numbers check ours.
 */
#ifndef DFL_FIELD_GRIDPEER_H
#define DFL_FIELD_GRIDPEER_H

#include <stddef.h>

#include "core/names.h"
#include "core/status.h"
#include "field/field.h"
#include "geom/shape.h"

#define DFL_GRIDPEER_KIND_LIST(X)                                 \
    X(DFL_GRIDPEER_TRILINEAR0, "trilinear0", 1)                   \
    X(DFL_GRIDPEER_TAYLOR1, "taylor1", 4)                         \
    X(DFL_GRIDPEER_TAYLOR2, "taylor2", 10)                        \
    X(DFL_GRIDPEER_TRICUBIC, "tricubic", 1)

typedef enum dfl_gridpeer_kind { DFL_GRIDPEER_KIND_LIST(DFL_NAMES_CODE) } dfl_gridpeer_kind;
enum { DFL_GRIDPEER_KIND_COUNT = 0 DFL_GRIDPEER_KIND_LIST(DFL_NAMES_ONE) };

#define DFL_GRIDPEER_STORAGE_LIST(X)              \
    X(DFL_GRIDPEER_FLOAT64, "float64", 8)         \
    X(DFL_GRIDPEER_FLOAT16, "float16", 2)

typedef enum dfl_gridpeer_storage {
    DFL_GRIDPEER_STORAGE_LIST(DFL_NAMES_CODE)
} dfl_gridpeer_storage;
enum { DFL_GRIDPEER_STORAGE_COUNT = 0 DFL_GRIDPEER_STORAGE_LIST(DFL_NAMES_ONE) };

extern const char *const dfl_gridpeer_kind_names[DFL_GRIDPEER_KIND_COUNT];
extern const char *const dfl_gridpeer_storage_names[DFL_GRIDPEER_STORAGE_COUNT];
const char *dfl_gridpeer_kind_name(dfl_gridpeer_kind k);
dfl_status dfl_gridpeer_kind_parse(const char *s, dfl_gridpeer_kind *out, dfl_err *err);
const char *dfl_gridpeer_storage_name(dfl_gridpeer_storage s);
dfl_status dfl_gridpeer_storage_parse(const char *s, dfl_gridpeer_storage *out, dfl_err *err);

typedef struct dfl_gridpeer_opts {
    dfl_gridpeer_kind kind;
    dfl_gridpeer_storage storage;
    int n;            /* cells per axis, 1 .. 1024 */
    double lo[3], hi[3];
    int threads;      /* OpenMP threads for the build (<= 0: the default) */
} dfl_gridpeer_opts;

/* Samples shape (3D; borrowed, only during the call) at the cell centres
 * and wraps the grid as a field (eval is batched and OpenMP-free; the
 * field has no jets).  taylor2 needs the shape's jets (dfl_shape_derivs_at).
 * Errors: DFL_E_INPUT for n outside 1..1024, lo >= hi, a 2D shape, taylor2
 * of a shape without jets, tricubic with n < 4, or a float16 scalar
 * (tricubic: a coefficient) that overflows a half;
 * DFL_E_NUMERIC when a sample is not finite; DFL_E_NOMEM.  *out is
 * untouched on failure. */
dfl_status dfl_gridpeer_new(const dfl_shape *shape, const dfl_gridpeer_opts *o, dfl_field *out,
                            dfl_err *err);

/* n^3 times the kind's scalars per cell. */
size_t dfl_gridpeer_scalars(dfl_gridpeer_kind kind, int n);

/* The options f was built with into *out; 0 (out untouched) when f is not
 * a grid peer field, else 1. */
int dfl_gridpeer_field_info(const dfl_field *f, dfl_gridpeer_opts *out);

/* The stored scalars of grid peer f as their exact values (float16: each
 * the half's value), dfl_gridpeer_scalars(kind, n) of them, cell index
 * i + n (j + n k) times the kind's scalars per cell (tricubic: the spline
 * coefficient of centre (i, j, k)); owned by f, valid while f lives.
 * NULL (*count untouched) when f is not a grid peer field. */
const double *dfl_gridpeer_stored(const dfl_field *f, size_t *count);

#endif
