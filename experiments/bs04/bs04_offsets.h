/* The offset measurement of bs04_bulging and bs04_scurve: where the level
 * set {u = delta} of a field lies against the true offset {d = delta} of a
 * planar curve, along rays from the curve (field/curveprobe.h), and the
 * band statistics of u against d on a grid (field/metrics.h).
 *
 *   dfl_bs04_offset_opts_from_cfg   the search keys smax, steps, rounds, valid_tol
 *   dfl_bs04_offsets_alloc    buffers for m grid nodes and the rays
 *   dfl_bs04_offsets_sample   u and d on the grid
 *   dfl_bs04_offsets_level    one delta: ray statistics and band statistics
 *   dfl_bs04_offsets_free
 *
 * The caller fills u, exact, pl and rays (it owns how they are built); the
 * struct then owns them and the buffers, and dfl_bs04_offsets_free releases
 * everything (safe on a zeroed struct).
 */
#ifndef DFL_EXPERIMENTS_BS04_OFFSETS_H
#define DFL_EXPERIMENTS_BS04_OFFSETS_H

#include <stddef.h>

#include "core/budget.h"
#include "core/status.h"
#include "field/metrics.h"
#include "field/curveprobe.h"
#include "field/field.h"
#include "field/sample.h"
#include "geom/polygonize.h"
#include "io/config.h"

typedef struct dfl_bs04_offsets {
    dfl_field u, exact;        /* the field and the exact distance d */
    dfl_polyline pl;           /* the curve's polygonization u is built on */
    dfl_rayset rays;           /* rays from the curve */
    double *uv, *ug, *dv, *dg; /* u and d on the grid: values, 2D gradients */
    double *s;                 /* per ray: the first crossing of u = delta */
    int *valid, *branch;       /* per ray: curveprobe's offset and branch tests */
} dfl_bs04_offsets;

/* How crossings are searched and rays validated at an offset delta. */
typedef struct dfl_bs04_offset_opts {
    double smax;      /* crossings are searched in [0, smax delta] */
    int steps;        /* bracketing samples per ray */
    int rounds;       /* 16-fold refinements of the bracket */
    double valid_tol; /* relative tolerance of the offset test */
} dfl_bs04_offset_opts;

/* [sec] smax (default 8, in [1, 1e6]), steps (128, 1..DFL_CROSS_MAX_STEPS),
 * rounds (6, 0..40), valid_tol (1e-6, [0, 0.5]), read in that order. */
dfl_status dfl_bs04_offset_opts_from_cfg(const dfl_cfg *cfg, const char *sec,
                                         dfl_bs04_offset_opts *out, dfl_err *err);

/* Buffers for m grid nodes and rays.n rays (set rays first).  DFL_E_NOMEM
 * "<what>: out of memory". */
dfl_status dfl_bs04_offsets_alloc(dfl_bs04_offsets *o, size_t m, const char *what, dfl_err *err);

/* u into uv, ug and d into dv, dg at the nodes of the 2D grid g. */
dfl_status dfl_bs04_offsets_sample(dfl_bs04_offsets *o, const dfl_grid *g, int threads,
                                   dfl_err *err);

/* Ray and band statistics at offset delta: rays valid for delta, their
 * first crossings (searched as opts says), the on-branch test and the ray
 * statistics (into *rs); band statistics of the m grid samples against d
 * (into *bs). */
dfl_status dfl_bs04_offsets_level(dfl_bs04_offsets *o, size_t m, double delta,
                                  const dfl_bs04_offset_opts *opts, int threads,
                                  dfl_ray_stats *rs, dfl_bandstats *bs, dfl_err *err);

void dfl_bs04_offsets_free(dfl_bs04_offsets *o);

/* For a study's estimate (core/budget.h): what the measurement holds and
 * does for a grid of `nodes` nodes (its section gsec, key n), `rays` rays
 * (key rays of section rsec), a field whose evaluation costs `units` CHEAP
 * (its parts + DFL_RFUNC_EVAL_UNITS, cfg/field_cost.h) and nlevels offsets:
 *   bytes  48 a node (u, d and their gradients) and 128 a ray (origin,
 *          direction, parameter, curvature, side, kind, crossing, flags:
 *          72, with the allocator's slack);
 *   work   per node u and d once (d: FOOTPOINT, on the curve);
 *          per offset and ray the validity and branch tests (3 FOOTPOINT) and
 *          the crossing search, steps + 16 rounds evaluations of u.
 * Section names must outlive c (the config's own: dfl_cfg_section_name). */
void dfl_bs04_offsets_cost(const char *gsec, double nodes, const char *rsec, double rays,
                           double units, size_t nlevels, const dfl_bs04_offset_opts *o,
                           dfl_cost *c);

#endif
