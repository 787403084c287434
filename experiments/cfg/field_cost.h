/* What a [field] section's field costs to build and hold (core/budget.h's
 * dfl_cost), read from its keys without building it.
 *
 *   dfl_field_cost_from_cfg   the field of [sec] (kind and its size keys)
 *   dfl_shape_cost_class      the cost class of one distance to a [shape]
 *   dfl_shape_dim_guess       the dimension of a [shape] from its keys
 *   dfl_field_dim_guess       the dimension of a [field] from its keys
 *   dfl_field_eval_cost       the cost of one evaluation of a [field]
 *   dfl_rfunc_parts_bound     the parts of a kind = rfunc field, at most
 *   dfl_pht_fit_bytes_bound   the PHT bound below, for given fit options
 *
 * Bytes are upper bounds of what the field's own buffers take:
 *   proxy     res^3 cells x DFL_PROXY_NSCALAR(order) x the storage size,
 *             plus one sign byte per cell (2048^3 order 2 double: 550 GB)
 *   gridpeer  dfl_gridpeer_scalars(method, res) x 8 (float64) or 2 bytes
 *   pht       the uniform mesh at max_level, the worst an adaptive fit can
 *             reach (every cell misses eps): 2^(dim max_level) leaves
 *             (cross split; binary: 2^max_level), and the inner cells above
 *             them (cross: 1/(2^dim - 1) of the leaves, a tree of fan 2^dim;
 *             binary: as many as the leaves, fan 2), each
 *             DFL_PHT_CELL_BYTES(dim) (dfl_pht_fit_bytes_bound); a fit that
 *             converges early holds fewer
 *   openvdb   dfl_vdb_bytes_bound (field/vdb.h): every 8^3 leaf meeting the
 *             box's index range (widened by band + 1 voxels for a mesh's
 *             band) allocated, with the internal nodes above them, from
 *             OpenVDB's node sizes.  A band can meet every leaf (a fine
 *             lattice of surfaces), so no smaller bound holds for every
 *             shape; a surface of area A fills about A (2 band + 12) /
 *             voxel^2 voxels.  build = mesh adds 24 bytes per node of the
 *             box's voxel lattice: 8 for the sampled values and an allowance
 *             of 16 for the mesh (about 120 bytes per cube the surface cuts)
 *   rfunc     DFL_RFUNC_PART_BYTES per part: the polyline's segments (a
 *             curve's bounded by dfl_polygonize_curve_segments_bound at
 *             eps), the triangles (a surface's: max_tris), the points and
 *             the region (dfl_rfunc_parts_bound)
 *   exact, normalized: nothing in proportion to a key
 * Work: one distance per proxy or grid-peer cell, and per PHT leaf
 * `samples` distances (the estimator) plus one Hermite footpoint, each of
 * the shape's cost class; openvdb direct: 513 per leaf meeting the range
 * (the band search's worst case), mesh: per lattice node one sample and
 * 30 refinement rounds over at most 7 vertices.  Keys are read with the factories' getters and
 * ranges, so a bad value fails here as it would in the factory.
 */
#ifndef DFL_EXPERIMENTS_FIELD_COST_H
#define DFL_EXPERIMENTS_FIELD_COST_H

#include "core/budget.h"
#include "core/status.h"
#include "io/config.h"
#include "pht/fit.h"

/* bytes one PHT mesh cell holds with its share of vertices, Hermite data,
 * cell polynomial (16 or 64 coefficients), error and bookkeeping, and the
 * fit's own arrays at its peak: measured (peak RSS over the process's own,
 * every cell split to max_level, eps = 1e-14) 1.0 KB a leaf in 2D (circle,
 * max_level 9) and 1.9 KB in 3D (torus, max_level 6), inner cells included;
 * with the inner cells counted as cells (x 4/3, x 8/7) these bound them */
#define DFL_PHT_CELL_BYTES(dim) ((dim) == 2 ? 1024.0 : 2048.0)

/* bytes one R-function part holds: its segment, triangle or point data, its
 * share of the join's vertex data and of the batch evaluator's copy, and of
 * the parsed spec's vertices and polyline (about 300 bytes measured by
 * sizeof; counted as 1 KB) */
#define DFL_RFUNC_PART_BYTES 1024.0

/* CHEAP evaluations one R-function evaluation costs besides one per part:
 * the per-point path's setup, scaled accumulator and gradient (fields the
 * batch kernels do not take, e.g. exact parts or the corrected join,
 * measured up to 0.3 us a point) */
#define DFL_RFUNC_EVAL_UNITS 50.0

/* The parts of the kind = rfunc field of [sec], at most (*parts), and the
 * key that sets their number (*key: "eps" for a curve, "max_tris" for a
 * surface, else "vertices", "triangles", "points" or "region", the largest
 * contribution): segments of vertices (n - 1, n when closed), of a curve
 * dfl_polygonize_curve_segments_bound at eps, triangles (a surface's:
 * max_tris), points, and 1 for a region.  Reads the curve's keys as
 * the factory does (errors alike); builds nothing else. */
dfl_status dfl_rfunc_parts_bound(const dfl_cfg *cfg, const char *sec, double *parts,
                                 const char **key, dfl_err *err);

/* The bytes bound of a PHT fit with options o in dimension dim (pht above);
 * *leaves (may be NULL) receives the leaves of the uniform mesh at
 * max_level. */
double dfl_pht_fit_bytes_bound(const dfl_pht_fit_opts *o, int dim, double *leaves);

/* 2 or 3, the dimension of the field [sec] describes: a kind = rfunc
 * field's first part's point dimension, normalized 2, the others their
 * shape's (dfl_shape_dim_guess of their shape key, default [shape]). */
int dfl_field_dim_guess(const dfl_cfg *cfg, const char *sec);

/* One evaluation of the field [sec] describes, as *units evaluations of
 * class *cls (core/budget.h):
 *   exact       1 of its shape's class (dfl_shape_cost_class)
 *   rfunc       one CHEAP per part (dfl_rfunc_parts_bound): the join
 *               evaluates every part's trim and carrier at every point;
 *               and DFL_RFUNC_EVAL_UNITS more
 *   normalized  (m (m + 1) / 2 + 2)^(2 dim) CHEAP: the Taylor degree of
 *               the recursion to the power 2 dim (rfunc/normalize.h); a unit
 *               measured about 1.3 ns (bs04_recursive's grid, m = 1..6)
 *   proxy, gridpeer, pht, openvdb   1 DECODE (a lookup and a polynomial) */
dfl_status dfl_field_eval_cost(const dfl_cfg *cfg, const char *sec, dfl_cost_class *cls,
                               double *units, dfl_err *err);

dfl_status dfl_field_cost_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_cost *cost,
                                   dfl_err *err);

/* FOOTPOINT for implicit and parametric surfaces (bezier_surface,
 * bspline_surface), B-spline curves (a footpoint by sampling and Newton
 * steps: 3.3e-5 s measured on bs04's cubic space curves) and CSG
 * containing them, EXACT for meshes,
 * CHEAP for the analytic kinds.  An absent or unreadable section: EXACT;
 * CSG nested deeper than 8 (or a cycle): FOOTPOINT. */
dfl_cost_class dfl_shape_cost_class(const dfl_cfg *cfg, const char *sec);

/* 2 or 3: circle, ellipse 2; bspline_curve its control points' dimension
 * (2 when unreadable); plane, box, segment their `dim`
 * key (defaults 3, 3, 2); csg its `a`; everything else 3. */
int dfl_shape_dim_guess(const dfl_cfg *cfg, const char *sec);

#endif
