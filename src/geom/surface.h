/* Tensor-product B-spline and Bezier surfaces in R^3, single and multi-patch.
 *
 * A patch of orders (ku, kv) has nu x nv control points P_ij (point (i, j)
 * at cp[(i + nu*j)*3]; i runs along u) and knot vectors U (nu + ku values)
 * and V (nv + kv values), as for curves (see geom/bspline.h): open knot
 * vectors, default clamped uniform.  S(u, v) = sum_ij N_i(u) N_j(v) P_ij on
 * [u0, u1] x [v0, v1] = [U_{ku-1}, U_{nu}] x [V_{kv-1}, V_{nv}].  A Bezier
 * patch of degree (ku-1, kv-1) is the patch with knots (0^ku 1^ku) and
 * (0^kv 1^kv), domain [0, 1]^2.
 *
 * A multi-patch surface (dfl_surface_set) is a list of patches; joins are
 * not stored but detected (dfl_surface_join): C0 when two patch edges
 * coincide, G1 when in addition the tangent planes agree along the edge and
 * the patches lie on opposite sides of it.
 *
 * Derivatives: S_{u^a v^b} for a + b <= nder (nder <= DFL_SURFACE_MAX_DER)
 * are written at out[DFL_SURF_IDX(a, b)*3 + c]; at knots right-sided (at the
 * upper domain end left-sided).
 *
 * Ownership: init allocates, dfl_surface_free releases.  Patches are
 * read-only after init and may be shared by threads; only init allocates.
 */
#ifndef DFL_GEOM_SURFACE_H
#define DFL_GEOM_SURFACE_H

#include <stddef.h>

#include "core/status.h"
#include "geom/bspline.h"

#define DFL_SURFACE_MAX_DER 3
/* Index of S_{u^a v^b} in the derivative array: 0:S 1:Su 2:Sv 3:Suu 4:Suv
 * 5:Svv 6:Suuu 7:Suuv 8:Suvv 9:Svvv. */
#define DFL_SURF_IDX(a, b) ((((a) + (b)) * ((a) + (b) + 1)) / 2 + (b))
/* Number of entries for derivatives up to total order nder. */
#define DFL_SURF_NDER(nder) ((((nder) + 1) * ((nder) + 2)) / 2)

typedef struct dfl_surface {
    int ku, kv;          /* orders, 2..DFL_BSPLINE_MAX_ORDER */
    size_t nu, nv;       /* control grid size (nu >= ku, nv >= kv) */
    double *cp;          /* nu*nv*3 */
    double *knots_u;     /* nu + ku */
    double *knots_v;     /* nv + kv */
    double u0, u1, v0, v1;
} dfl_surface;

/* B-spline patch.  knots_u / knots_v may be NULL (clamped uniform).
 * DFL_E_INPUT for a bad order, grid size, knot vector (as
 * dfl_bspline_check_knots) or a degenerate control net (all points equal),
 * DFL_E_NOMEM.  The message names "u" or "v" where it matters. */
dfl_status dfl_surface_init(int ku, int kv, size_t nu, size_t nv, const double *cp,
                            const double *knots_u, size_t nknots_u, const double *knots_v,
                            size_t nknots_v, dfl_surface *out, dfl_err *err);

/* Bezier patch of orders (ku, kv): ku*kv control points. */
dfl_status dfl_surface_init_bezier(int ku, int kv, const double *cp, dfl_surface *out,
                                   dfl_err *err);

void dfl_surface_free(dfl_surface *s);

/* (u, v) clamped into the domain. */
void dfl_surface_clamp(const dfl_surface *s, double *u, double *v);

/* Derivatives up to total order nder (0..DFL_SURFACE_MAX_DER); out holds
 * DFL_SURF_NDER(nder)*3 doubles.  (u, v) are clamped into the domain. */
void dfl_surface_eval(const dfl_surface *s, double u, double v, int nder, double *out);

/* Unit normal Su x Sv / |Su x Sv| at (u, v); returns |Su x Sv| (0 at a
 * singular point, normal then (0,0,0)). */
double dfl_surface_normal(const dfl_surface *s, double u, double v, double n[3]);

/* Non-empty knot spans in u and v (counts and knot indices, as for curves). */
size_t dfl_surface_span_count(const dfl_surface *s, int dir);
size_t dfl_surface_span_index(const dfl_surface *s, int dir, size_t k);

/* Bezier control net (ku*kv points, (i + ku*j)*3) of the polynomial piece of
 * spans (su, sv) restricted to [ua, ub] x [va, vb], by blossoming in u then v. */
void dfl_surface_cell_bezier(const dfl_surface *s, size_t su, size_t sv, double ua, double ub,
                             double va, double vb, double *bez);

/* ---- multi-patch ---- */
typedef struct dfl_surface_set {
    size_t npatch;
    dfl_surface *patch;  /* npatch patches, owned */
} dfl_surface_set;

/* Takes ownership of the npatch patches in `patches` (the array itself is
 * copied; the caller's structs are zeroed).  DFL_E_INPUT if npatch == 0. */
dfl_status dfl_surface_set_init(size_t npatch, dfl_surface *patches, dfl_surface_set *out,
                                dfl_err *err);
void dfl_surface_set_free(dfl_surface_set *s);

typedef enum dfl_join {
    DFL_JOIN_NONE = 0,   /* the edges do not coincide */
    DFL_JOIN_C0 = 1,     /* edges coincide (either direction) */
    DFL_JOIN_G1 = 2      /* C0, tangent planes agree, patches on opposite sides */
} dfl_join;

/* Edges: 0: v = v0, 1: u = u1, 2: v = v1, 3: u = u0.  Classifies the join
 * of edge ea of a with edge eb of b by sampling `samples` (>= 2) points:
 * positions must agree within tol * (1 + size of the control nets), normals
 * (unit) within tol_angle radians.  *reversed receives 1 if the edges run
 * in opposite directions (may be NULL). */
dfl_join dfl_surface_join(const dfl_surface *a, int ea, const dfl_surface *b, int eb, double tol,
                          double tol_angle, int samples, int *reversed);

/* Weakest join over all edge pairs that coincide (C0 or better) among
 * distinct patches, and the number of such shared edges.  A set of one
 * patch, or one without shared edges, reports DFL_JOIN_NONE and 0.  Also
 * writes in *isolated the index of a patch sharing no edge with any other
 * (or npatch if every patch has a neighbour). */
dfl_join dfl_surface_set_joins(const dfl_surface_set *s, double tol, double tol_angle,
                               size_t *nshared, size_t *isolated);

#endif
