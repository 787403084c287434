/* Parts of dimension 0 and 2 for heterogeneous sets (bs04 sec. 4.2, Fig.
 * 13a: a square region, a segment and a point joined into one field).
 *
 * Point (any dim): h = |x - c|, the exact distance (normalized to every
 * order everywhere except at c).
 *
 * Convex polygon region (2D): the region is the intersection of the inner
 * half-planes p_i = (x - V_i) . m_i >= 0 of its edges.  Its field is 0 on
 * the whole region and, outside,
 *     h = sqrt( sum_i max(-p_i, 0)^2 ),
 * the 2-norm of the distances to the violated half-planes (an R-disjunction
 * of the outer half-planes that is exact wherever one half-plane is
 * violated: h = distance to the edge's line, normalized to every order at
 * regular boundary points; near a vertex where two are violated it is the
 * exact distance to the vertex when the edges are orthogonal, e.g. for a
 * rectangle, and a close bound otherwise).  h is C1 off the region.
 */
#ifndef DFL_RFUNC_REGION_H
#define DFL_RFUNC_REGION_H

#include <stddef.h>

#include "core/jet.h"
#include "core/status.h"

typedef struct dfl_rfunc_point {
    int dim;
    double c[3];
} dfl_rfunc_point;

/* DFL_E_INPUT for dim not 2/3 or non-finite coordinates. */
dfl_status dfl_rfunc_point_init(int dim, const double *c, dfl_rfunc_point *out, dfl_err *err);
/* h = |x - c| and gradient (may be NULL; 0 at c). */
double dfl_rfunc_point_eval(const dfl_rfunc_point *p, const double *x, double *grad);
dfl_status dfl_rfunc_point_jet(const dfl_rfunc_point *p, const double *x, const double *dir,
                               int K, dfl_jet *out, dfl_err *err);

typedef struct dfl_rfunc_region {
    size_t n;             /* number of vertices (= edges), >= 3 */
    double *v;            /* 2n vertex coordinates (owned) */
    double *m;            /* 2n inward unit edge normals; edge i: v_i -> v_(i+1) */
    double scale;         /* for jet snapping */
} dfl_rfunc_region;

/* Copies n >= 3 vertices (either orientation).  DFL_E_INPUT if the polygon
 * is not strictly convex (or has repeated vertices), DFL_E_NOMEM.  Release
 * with dfl_rfunc_region_free. */
dfl_status dfl_rfunc_region_init(const double *v, size_t n, dfl_rfunc_region *out, dfl_err *err);
void dfl_rfunc_region_free(dfl_rfunc_region *r);

double dfl_rfunc_region_eval(const dfl_rfunc_region *r, const double *x, double *grad);
dfl_status dfl_rfunc_region_jet(const dfl_rfunc_region *r, const double *x, const double *dir,
                                int K, dfl_jet *out, dfl_err *err);

#endif
