/* The comparison study's one evaluation protocol: the same error points,
 * regions and measurements for every method on a shape.
 *
 * Function index
 *   cmp_points_build   the error points of a shape, their reference and regions
 *   cmp_points_free
 *   cmp_measure        one field on those points: errors, defects, jumps, rate
 *
 * Points (cmp_points_opts), in this order:
 *   grid     n^dim nodes of the box [lo, hi] (n = grid2d in 2D, grid3d in 3D)
 *   surface  `surface` points near the surface: a seeded random point x of
 *            the box is moved to its exact footpoint p = x - d(x) grad d(x)
 *            and then by t grad d(x), t uniform in [-band, band]; points
 *            that leave the box are drawn again (at most 64 tries each, then
 *            dropped: a shape far from its box has fewer)
 *   medial   seeded random points of the box that lie in the medial band of
 *            width `medial_band` (pht/validate.h's criterion, the exact SDF
 *            along the normal line), drawn from `medial_draws` candidates:
 *            where every method errs most (the SDF's kink)
 * Regions (masks over all points):
 *   whole    every point
 *   band     |d| <= band (the near-surface band)
 *   off      points off the medial band of width medial_band (pht criterion)
 * Reference: ref = d (signed methods) or |d| (unsigned ones, bs04's
 * R-function fields), gradient grad d or sign(d) grad d.
 *
 * Measurements (cmp_result), field/metrics.h's non-finite rule throughout (a
 * NaN or inf value or gradient is an error of +inf, counted in nonfinite,
 * never dropped):
 *   whole, band, off   dfl_metrics (L1, MSE, RMS, Linf, eikonal defect
 *                      mean/max | |grad u| - 1 |, nonfinite)
 *   grad_linf          max |grad u - grad ref| (Euclidean) over every point
 *   c0_jump, c1_jump   measured continuity: the largest |u(x+) - u(x-)| and
 *                      |grad u(x+) - grad u(x-)| over `pairs` pairs
 *                      x +- delta e_a straddling an axis plane
 *                      lo_a + i (hi_a - lo_a) / 2^10 (every cell face of a
 *                      uniform or dyadic cell grid of up to 1024 cells per
 *                      axis on this box: proxies, grid peers, PHT meshes),
 *                      delta = 1e-9 (hi_a - lo_a), pairs whose x+ lies in the
 *                      medial band left out (the SDF's own kink); a C0 field has
 *                      c0_jump <= 2 delta max |grad u| (tiny), a C1 field
 *                      c1_jump <= 2 delta max |Hess u|
 *   eval_seconds       best of `repeats` timed batched evaluations (value and
 *                      gradient) of all points; queries_per_s = count / it
 */
#ifndef DFL_EXPERIMENTS_COMPARE_EVAL_H
#define DFL_EXPERIMENTS_COMPARE_EVAL_H

#include <stdint.h>
#include <stddef.h>

#include "core/status.h"
#include "field/field.h"
#include "field/metrics.h"
#include "geom/shape.h"

typedef struct cmp_points_opts {
    double lo[3], hi[3];     /* the box (dim entries), lo < hi */
    int grid2d, grid3d;      /* nodes per axis, >= 2 */
    size_t surface;          /* near-surface points */
    size_t medial_draws;     /* candidates for the near-medial points */
    double band;             /* near-surface band half-width > 0 */
    double medial_band;      /* medial band width > 0 */
    size_t pairs;            /* continuity pairs */
    uint64_t seed;
} cmp_points_opts;

typedef struct cmp_points {
    int dim;
    size_t m;                        /* all points */
    size_t ngrid, nsurface, nmedial; /* of m, in this order */
    double *x;                       /* m * dim */
    double *d, *g;                   /* exact d, grad d (m, m * dim) */
    unsigned char *band, *off;       /* region masks (m) */
    size_t npairs;                   /* pairs kept (off the medial band) */
    double *xp, *xm;                 /* pair sides, npairs * dim each */
    unsigned char *pa;               /* the axis each pair straddles (npairs) */
    double lo[3], hi[3];
    double bandw;
} cmp_points;

/* The points of shape (borrowed, during the call) under o into *out.
 * DFL_E_INPUT for a bad box or counts, DFL_E_NUMERIC when the exact SDF is
 * not finite at a point (the reference is dflab's own), DFL_E_NOMEM.
 * *out holds no buffers on failure. */
dfl_status cmp_points_build(const dfl_shape *shape, const cmp_points_opts *o, cmp_points *out,
                            dfl_err *err);
void cmp_points_free(cmp_points *p);

typedef struct cmp_result {
    dfl_metrics whole, band, off;
    double grad_linf;
    double c0_jump, c1_jump;
    size_t nonfinite;        /* points (of m) with a non-finite value or gradient */
    double eval_seconds;     /* best of the repeats */
} cmp_result;

/* The planes of a method's own cells on every axis: origin + k step
 * (step > 0), e.g. faces and centres of N cells on [lo, hi]: origin lo,
 * step (hi - lo) / (2N); of voxels of size v from 0: origin 0, step v / 2. */
typedef struct cmp_planes {
    double origin[3], step[3];
} cmp_planes;

/* Measures f (dim of p, asserted) on p; `unsigned_ref` compares with |d|.
 * repeats >= 1.  planes (may be NULL): the continuity pairs are measured a
 * second time, each moved along its axis onto the nearest of these planes
 * (so cells that are not dyadic on the box are straddled too), and the
 * jumps are the larger of the two.  DFL_E_NOMEM. */
dfl_status cmp_measure(const dfl_field *f, const cmp_points *p, int unsigned_ref, int repeats,
                       const cmp_planes *planes, cmp_result *out, dfl_err *err);

#endif
