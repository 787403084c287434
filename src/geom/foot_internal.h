/* Private to the footpoint files (footpoint.c, foot_curve.c,
 * foot_surface.c, curve_sdf.c, curve_jet.c, param_shape.c): the objects'
 * layouts and the helpers the curve and surface searches share.  Not an
 * API: include geom/footpoint.h, geom/curve_sdf.h or geom/param_shape.h. */
#ifndef DFL_GEOM_FOOT_INTERNAL_H
#define DFL_GEOM_FOOT_INTERNAL_H

#include <stddef.h>

#include "geom/curve_sdf.h"
#include "geom/footpoint.h"
#include "geom/polygonize.h"
#include "solve/lsq.h"

struct dfl_curve_locator {
    const dfl_bspline *c;
    dfl_foot_opts o;
    size_t ns;
    double *ts, *ps;     /* sample parameters and points */
    double *ds;          /* C, C', C'' at each wrapped ts (3 * dim each): Newton's start */
    double size;         /* extent of the control polygon */
    dfl_lsq_ctx *lsq;    /* ceres backend only */
};

struct dfl_curve_sdf {
    const dfl_bspline *c;
    dfl_curve_locator *L;
    dfl_polyline poly;   /* certified polygon for the winding number */
    double *chunk_y;     /* per DFL_WINDING_CHUNK edges of poly: min y, max y of their ends */
    int orient;          /* +1 counter-clockwise */
};
/* Edges of the winding polygon per y-range chunk (curve_sdf.c). */
#define DFL_WINDING_CHUNK 16

/* |a - b|^2 over n coordinates, summed from 0.0 in order. */
static inline double dfl_foot_d2(int n, const double *a, const double *b)
{
    double s = 0.0;
    for (int j = 0; j < n; j++) s += (a[j] - b[j]) * (a[j] - b[j]);
    return s;
}

/* Rounding of g = |P - x|^2 / 2 at the point P (n coordinates): |r| times
 * the rounding of P and x, plus g's own.  The Newton step controls of
 * curves and surfaces accept a step that stays within it. */
double dfl_foot_g_noise(int n, const double *P, const double *x, double g);

/* Largest coordinate extent of n control points of dimension dim. */
double dfl_foot_extent(int dim, size_t n, const double *cp);

/* The k best sampled local minima (value g, patch p, indices i, j), kept
 * sorted ascending; ties keep the earlier insertion first. */
typedef struct dfl_foot_topk {
    int n, k;
    double g[DFL_FOOT_MAX_CAND];
    size_t i[DFL_FOOT_MAX_CAND];
    size_t j[DFL_FOOT_MAX_CAND];
    size_t p[DFL_FOOT_MAX_CAND];
} dfl_foot_topk;

void dfl_foot_topk_insert(dfl_foot_topk *t, double g, size_t p, size_t i, size_t j);

/* Ranks n (1..DFL_FOOT_MAX_CAND) refined footpoints: candidate q has its
 * distance at dist and its point (dim used coordinates) at p, both
 * advanced by q * stride bytes (an array of foot structs: &res[0].dist,
 * res[0].p, sizeof *res).  Sorts them by distance (stable), drops each one
 * within 1e-7 size of a kept closer one or in the same basin as one
 * (same_basin(ctx, kept, cand, tol) != 0: no barrier of the distance
 * between them, as at a degenerate minimum where a centre of curvature
 * meets the medial axis), writes the kept indices closest first to keep[]
 * and returns their count.  *ntied receives how many of them are within
 * tol = tie_rel * (closest distance) + 1e-14 size of the closest. */
int dfl_foot_rank(int n, int dim, const double *dist, const double *p, size_t stride,
                  double size, double tie_rel,
                  int (*same_basin)(const void *ctx, int kept, int cand, double tol),
                  const void *ctx, int *keep, int *ntied);

/* The signed-distance value (and derivatives to order) of S at x from the
 * footpoint f (curve_sdf.c). */
void dfl_curve_sdf_from_foot(const dfl_curve_sdf *S, const double *x, const dfl_curve_foot *f,
                             int order, dfl_curve_sdf_val *o);

/* Jet of the distance to L's curve along dir (curve_jet.c): signed with S's
 * sign and orientation when S != NULL (L is then S's locator), else the
 * unsigned |x - C|. */
dfl_status dfl_curve_dist_jet(const dfl_curve_locator *L, const dfl_curve_sdf *S, const double *x,
                              const double *dir, int K, dfl_jet *out, dfl_err *err);

#endif
