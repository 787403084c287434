/* What a [field] section's field costs to build and hold (core/budget.h's
 * dfl_cost), read from its keys without building it.
 *
 *   dfl_field_cost_from_cfg   the field of [sec] (kind and its size keys)
 *   dfl_shape_cost_class      the cost class of one distance to a [shape]
 *   dfl_shape_dim_guess       the dimension of a [shape] from its keys
 *
 * Bytes are upper bounds of what the field's own buffers take:
 *   proxy     res^3 cells x DFL_PROXY_NSCALAR(order) x the storage size,
 *             plus one sign byte per cell (2048^3 order 2 double: 550 GB)
 *   gridpeer  dfl_gridpeer_scalars(method, res) x 8 (float64) or 2 bytes
 *   pht       the uniform mesh at max_level, the worst an adaptive fit can
 *             reach (every cell misses eps): 2^(dim max_level) leaves
 *             (cross split; binary: 2^max_level) x 8/7 for the inner cells x
 *             DFL_PHT_CELL_BYTES(dim); a fit that converges early holds fewer
 *   openvdb   dfl_vdb_bytes_bound (field/vdb.h): every 8^3 leaf meeting the
 *             box's index range (widened by band + 1 voxels for a mesh's
 *             band) allocated, with the internal nodes above them, from
 *             OpenVDB's node sizes.  A band can meet every leaf (a fine
 *             lattice of surfaces), so no smaller bound holds for every
 *             shape; a surface of area A fills about A (2 band + 12) /
 *             voxel^2 voxels.  build = mesh adds 24 bytes per node of the
 *             box's voxel lattice: 8 for the sampled values and an allowance
 *             of 16 for the mesh (about 120 bytes per cube the surface cuts)
 *   exact, rfunc, normalized: nothing in proportion to a key
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

/* bytes one PHT mesh cell holds with its share of vertices, Hermite data,
 * cell polynomial (16 or 64 coefficients), error and bookkeeping */
#define DFL_PHT_CELL_BYTES(dim) ((dim) == 2 ? 512.0 : 2048.0)

dfl_status dfl_field_cost_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_cost *cost,
                                   dfl_err *err);

/* FOOTPOINT for implicit and parametric surfaces (bezier_surface,
 * bspline_surface) and CSG containing them, EXACT for curves and meshes,
 * CHEAP for the analytic kinds.  An absent or unreadable section: EXACT;
 * CSG nested deeper than 8 (or a cycle): FOOTPOINT. */
dfl_cost_class dfl_shape_cost_class(const dfl_cfg *cfg, const char *sec);

/* 2 or 3: circle, ellipse, bspline_curve 2; plane, box, segment their `dim`
 * key (defaults 3, 3, 2); csg its `a`; everything else 3. */
int dfl_shape_dim_guess(const dfl_cfg *cfg, const char *sec);

#endif
