/* Adaptive PHT-spline fit of a signed distance function (sjp10 Sec. 4).
 *
 * Algorithm (level k = 0, 1, ...):
 *   1. T^0 is the one-cell mesh of the box; Hermite data (pht/hermite.h) at
 *      every new base vertex, data at hanging vertices by dfl_pht_resolve,
 *      spline f^k (pht/spline.h);
 *   2. every leaf cell gets an error estimate (the estimator below); split
 *      every leaf whose error is > eps and whose level is < max_level (cross
 *      or binary rule) into T^{k+1} and continue with 1 (only new base
 *      vertices get new footpoints; vertices keep their data across
 *      levels); stop when there is none (all cells meet eps, or the ones
 *      that do not are at max_level: the paper's "k reached kmax", counted
 *      per cell, since with grading a cell may reach max_level after more
 *      than max_level iterations).
 * Grading (opts.grade, on by default; not in the paper): the data at a
 * hanging corner of a cell are the coarse neighbour's polynomial there, so a
 * cell's error includes the coarse neighbour's error on their common edge,
 * which the neighbour's own interior sample points may miss.  With the
 * paper's rule alone the fine cells then split level after level without
 * getting better (seen on the circle at eps = 1e-5: the max error stalls at
 * 1.8e-5 while the cell count doubles per level).  So when a cell is split,
 * the owner of each of its hanging corners (dfl_tmesh_vertex.owner) is split
 * too if it is two or more levels coarser.
 * Estimators (the cell error is the max over the cell's sample points of):
 *   random    |f - d| at `samples` seeded uniform random points (the paper's)
 *             and, with opts.peaks (default on), also at the cell centre and
 *             the 2 dim face centres: the error of cubic Hermite
 *             interpolation, f''''(xi) u^2 (1-u)^2 h^4 / 24 per axis, peaks at
 *             u = 1/2, so these points catch the maximum of a smooth cell that
 *             random points only approach (circle, eps = 1e-5: 16 random points
 *             alone left 1.02e-5 at validation points);
 *   grid      |f - d| on a fixed sub-grid of n^dim points at the centres of
 *             an n^dim subdivision of the cell, n = max(1, round(samples^(1/dim)));
 *   gradient  max(|f - d|, |grad f - grad d|) at the random points (and
 *             peaks; the gradient term is unitless and compared with the same
 *             eps; it does not shrink with the cell at a kink of d, so cells
 *             on the medial axis go to max_level).
 * The random points of a cell are drawn from a SplitMix64 stream seeded by
 * (seed, the cell's level and the bits of its world low corner lo[]; lo is
 * a function of the lattice corner and the box), so they do not depend on the
 * order in which cells are visited or on the thread count; per-cell work runs
 * in parallel over cells and every reduction combines per-cell results in
 * leaf order: results are bit-identical at any OMP_NUM_THREADS.  A cell whose
 * polynomial did not change since the previous level keeps its error (same
 * points, same values) without new distance evaluations.  Exact distances
 * are reused, never recomputed: a cell re-estimated because its polynomial
 * changed takes the exact values kept from its first estimate (its points
 * are a function of the cell), and within one pass a face centre shared
 * by two cells of equal size (the same point, bit for bit) is evaluated
 * once; the values used are the same, so are the results.  Memory: the
 * exact values of every tree node's points are kept for the fit.
 *
 * Uniform mode (dfl_pht_fit_uniform): every cell refined to level k by the
 * cross rule, i.e. the uniform bicubic / tricubic Hermite grid with 2^k
 * cells per axis; the studies' uniform-grid baseline.  It records one level
 * with the same estimator.
 *
 * Function index:
 *   dfl_pht_estimator_name / _parse       names of the estimators
 *   dfl_pht_fit_opts_default              defaults (below)
 *   dfl_pht_fit_opts_check                DFL_E_INPUT naming the bad option
 *   dfl_pht_fit_run                       adaptive fit
 *   dfl_pht_fit_uniform                   uniform-level fit
 *   dfl_pht_fit_free                      releases a result
 */
#ifndef DFL_PHT_FIT_H
#define DFL_PHT_FIT_H

#include <stddef.h>
#include <stdint.h>

#include "core/names.h"
#include "core/status.h"
#include "pht/hermite.h"
#include "pht/spline.h"
#include "pht/tmesh.h"

/* The estimators (above), one list (core/names.h): X(code, config name, note). */
#define DFL_PHT_ESTIMATOR_LIST(X)                                                  \
    X(DFL_PHT_EST_RANDOM, "random", "|f - d| at seeded random points (+ peaks)")  \
    X(DFL_PHT_EST_GRID, "grid", "|f - d| on a fixed sub-grid")                    \
    X(DFL_PHT_EST_GRADIENT, "gradient", "max(|f - d|, |grad f - grad d|) at the random points")

typedef enum dfl_pht_estimator { DFL_PHT_ESTIMATOR_LIST(DFL_NAMES_CODE) } dfl_pht_estimator;
enum { DFL_PHT_EST_COUNT = 0 DFL_PHT_ESTIMATOR_LIST(DFL_NAMES_ONE) };

/* Config names indexed by code. */
extern const char *const dfl_pht_estimator_names[DFL_PHT_EST_COUNT];
/* Config name of an estimator; "?" outside the list. */
const char *dfl_pht_estimator_name(dfl_pht_estimator e);
/* The estimator called name (exact match) into *out; DFL_E_INPUT "unknown
 * estimator '<name>' (expected one of random|grid|gradient)" otherwise
 * (*out untouched). */
dfl_status dfl_pht_estimator_parse(const char *name, dfl_pht_estimator *out, dfl_err *err);

typedef struct dfl_pht_fit_opts {
    double lo[3], hi[3];          /* the box (dim entries); lo < hi */
    double eps;                   /* > 0, default 1e-3 (units of the shape) */
    int max_level;                /* 0..DFL_TMESH_MAX_LEVEL (cross) or
                                     0..dim*DFL_TMESH_MAX_LEVEL (binary); default 10 */
    int samples;                  /* estimator points per cell, 1..4096; default 16 */
    dfl_pht_split split;          /* default cross */
    dfl_pht_estimator estimator;  /* default random */
    uint64_t seed;                /* default 1 */
    int peaks;                    /* 1 (default): random/gradient estimators add the
                                     centre and face centres of the cell (above) */
    int grade;                    /* 1 (default): also split the coarse cell that owns a
                                     hanging corner of a split cell when it is >= 2 levels
                                     coarser; 0: the paper's rule alone (see above) */
} dfl_pht_fit_opts;

/* One record per iteration k = 0..nlevels-1 (the mesh T^k before its
 * refinement; without grading k is also the deepest cell level). */
typedef struct dfl_pht_level {
    int level;
    size_t cells;            /* leaf cells of T^k */
    size_t base_vertices;
    size_t dofs;             /* base_vertices * DFL_PHT_NDATA(dim) */
    size_t refined;          /* cells split to make T^{k+1} (0 at the last level) */
    size_t new_base;         /* base vertices whose data were computed at this level */
    double max_err;          /* max over all cells of the estimator error (NaN if
                                any cell's estimate is: a NaN exact distance) */
    double mean_err;         /* mean of the value error |f - d| over all estimator points */
    double t_foot;           /* s: Hermite data and exact distances (footpoints) */
    double t_spline;         /* s: resolve, cell polynomials, spline evaluation */
    double t_mesh;           /* s: refinement and vertex classification */
} dfl_pht_level;

typedef struct dfl_pht_fit {
    int dim;
    dfl_tmesh *mesh;         /* the final T-mesh (owned) */
    dfl_pht_spline *spline;  /* the final spline (owned; dfl_pht_field_new may take it) */
    double *data;            /* vertex data, nverts * DFL_PHT_NDATA(dim) (owned) */
    double *cell_err;        /* estimator error per leaf cell of the final mesh (owned) */
    int nlevels;
    dfl_pht_level *levels;   /* nlevels records (owned) */
    int converged;           /* 1 if every cell's estimate met eps, 0 if max_level stopped it */
    size_t capped;           /* leaf cells whose estimate is > eps at max_level (0 iff converged;
                                uniform fits: cells above eps) */
    size_t medial_vertices;  /* base vertices whose data came from a medial tie */
    double t_total;          /* s, wall time of the whole fit */
} dfl_pht_fit;

/* Defaults for dimension dim; the box is set to [0,1]^dim. */
void dfl_pht_fit_opts_default(int dim, dfl_pht_fit_opts *o);
/* DFL_E_INPUT with a message naming the option (eps, max_level, samples,
 * split, estimator, box) and the accepted range. */
dfl_status dfl_pht_fit_opts_check(int dim, const dfl_pht_fit_opts *o, dfl_err *err);

/* Adaptive fit of src's SDF over o's box.  *out is filled on success (free
 * with dfl_pht_fit_free); on failure it is zeroed.  DFL_E_INPUT for bad
 * options or an unsigned distance such as an open curve's
 * (dfl_pht_source_check_signed's message), DFL_E_NUMERIC if Hermite data cannot be computed at a base vertex,
 * DFL_E_NOMEM. */
dfl_status dfl_pht_fit_run(const dfl_pht_source *src, const dfl_pht_fit_opts *o,
                           dfl_pht_fit *out, dfl_err *err);

/* Uniform bicubic / tricubic Hermite grid: all cells at level `level`
 * (0..DFL_TMESH_MAX_LEVEL) by the cross rule; o gives the box, samples,
 * estimator, peaks and seed; max_level, split and grade are ignored, and eps
 * refines nothing: it only sets capped (cells whose estimate is not <= eps)
 * and converged (capped == 0); eps <= 0 or NaN counts as 1, +inf is
 * DFL_E_INPUT.  One level record; errors as dfl_pht_fit_run. */
dfl_status dfl_pht_fit_uniform(const dfl_pht_source *src, const dfl_pht_fit_opts *o, int level,
                               dfl_pht_fit *out, dfl_err *err);

/* Releases everything *f owns and zeroes it (NULL members are fine). */
void dfl_pht_fit_free(dfl_pht_fit *f);

#endif
