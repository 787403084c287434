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
 *   dfl_shape_cost            what a [shape] itself holds and costs to build
 *   dfl_mesh_file_tris_bound  the triangles a mesh file can hold, by its size
 *   dfl_mesh_bytes_bound      the bytes of a mesh shape of n triangles
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
 *             eps), the triangles (a surface's: max_tris; a mesh
 *             section's: dfl_mesh_tris_bound, and its shape's cost), the
 *             points and the region (dfl_rfunc_parts_bound)
 *   exact, normalized: nothing in proportion to a key
 * Every kind built on a shape (exact, proxy, gridpeer, pht, openvdb) adds
 * its shape's own cost (dfl_shape_cost): nothing for the analytic kinds,
 * a mesh's triangles, BVH and anchors (below), both operands of a CSG.
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

/* A mesh shape's own bytes (geom/mesh.h), n triangles:
 *   n DFL_MESH_TRI_BYTES + DFL_MESH_FIXED_BYTES   (reading, trimesh, BVH)
 *   + n DFL_MESH_ANCHOR_TRI_BYTES + DFL_MESH_ANCHOR_FIXED_BYTES   (signed)
 * plus, for file = PATH, the file's size (io/meshfile.h holds its bytes
 * while Assimp parses them).  Reading, trimesh and Embree BVH: measured
 * as peak RSS growth of `dflab run` (smoke, a 2^3 grid of the exact field,
 * unsigned, 2 threads, GNU time's maximum resident set size) over the same
 * run on a sphere: Wuson (3,732 triangles, AC3D) 7.5 MB, a 20,000-triangle
 * OBJ sheet 32.6 MB, a 125,000-triangle sheet 100 MB, a 119,400-triangle
 * closed OBJ sphere 100.5 MB: at most 844 bytes a triangle on the large
 * meshes (about 650 bytes a triangle and 20 MB besides between the
 * sheets), counted as 2 KB a triangle and 32 MB (2^25).  The anchors
 * (geom/mesh_anchor.h) are bounded by their caps, not measured: at most
 * 64 n + 2^18 octree nodes, each with its 4-byte entry, a 112-byte leaf
 * and a 32-byte build record (leaffar), and 256 n + 2^20 list entries of
 * at most 24 bytes, plus per triangle 72 + 72 bytes of edges, 160 of the
 * per-depth buffers and 16 of index arrays: 15,936 bytes a triangle
 * (counted as 16 KB) and 63,963,136 besides (counted as 2^26); a mesh
 * beyond the caps gets no anchors.  Measured signed runs stay well below
 * (Wuson 20 MB in all, one triangle 42 MB, a 20,000-triangle sheet 59 MB). */
#define DFL_MESH_TRI_BYTES 2048.0
#define DFL_MESH_FIXED_BYTES 33554432.0
#define DFL_MESH_ANCHOR_TRI_BYTES 16384.0
#define DFL_MESH_ANCHOR_FIXED_BYTES 67108864.0

/* The bytes above for tris triangles (>= 0), anchors when is_signed. */
double dfl_mesh_bytes_bound(double tris, int is_signed);

/* The most triangles the mesh file path can give dfl_trimesh_read, from
 * its size in bytes (*file_bytes) and its extension (case-insensitive),
 * without parsing it: a binary STL (84 + 50 t bytes, its header's count t
 * agreeing) exactly t; other files size / (the fewest bytes a triangle
 * takes in the format):
 *   stl  36  (ASCII: a facet's three "vertex x y z" of at least 12 bytes)
 *   ac   6   (AC3D: a surface of k refs gives k - 2 triangles, each ref
 *             "i u v" at least 6 bytes with its separators)
 *   obj, off  2  (a polygon of k indices gives k - 2 triangles; each index
 *             at least one digit and a separator)
 *   other  1 (PLY's binary uchar index lists; any uncompressed format)
 * and, when smaller, for OBJ and AC3D a count from one pass over the
 * text (no allocation): OBJ, every line whose first word starts with 'f'
 * (with its backslash continuations) its words but two; AC3D, k - 2 for
 * every "refs k", or with a "subdiv s" anywhere (Assimp then subdivides:
 * a k-gon becomes k quads, each further level 4 of each) 2 k 4^(s - 1)
 * summed, for the largest s, in place of the size's bound, which then
 * does not hold.
 * Formats that compress their arrays (FBX, 3MF, ZAE, a compressed .x or
 * .blend) can hold more triangles than bytes: the bound does not hold
 * for them.  DFL_E_INPUT "PATH: <why>" when the file cannot be
 * examined (the reader then refuses it too). */
dfl_status dfl_mesh_file_tris_bound(const char *path, double *tris, double *file_bytes,
                                    dfl_err *err);

/* The most triangles of the kind = mesh section [sec]: its file's
 * (dfl_mesh_file_tris_bound) or its polygonize allowance (below); -1 when
 * it cannot tell (no such file, no source: the reader names it).  Errors:
 * a polygonize key out of the reader's range, named as the reader does. */
dfl_status dfl_mesh_tris_bound(const dfl_cfg *cfg, const char *sec, double *tris, dfl_err *err);

/* Adds to *c the bytes and build work of the shape [sec] itself:
 *   mesh, file = PATH       dfl_mesh_bytes_bound(dfl_mesh_file_tris_bound)
 *                           + the file's size; work: a triangle one EXACT
 *                           (reading and the BVH) and, signed, the
 *                           anchors' 512 EXACT a triangle and 2^20 besides
 *                           (geom/mesh_anchor.c's 0.88 s CPU for Wuson's
 *                           3,732 triangles, 236 us a triangle; a closed
 *                           119,400-triangle OBJ sphere signed took 33 s
 *                           of wall time more than unsigned on 2 threads
 *                           of a loaded machine, 277 us a triangle, 9.6 s
 *                           in all unloaded; one triangle 0.4 s)
 *   mesh, polygonize = S    the lattice of its grid (g nodes, as the
 *                           reader sizes it: `resolution` along the
 *                           longest side of lo..hi) at 24 bytes a node (as
 *                           openvdb's mesh build), the shape S's own cost,
 *                           and dfl_mesh_bytes_bound of an allowance of 12
 *                           triangles (the 6-tetrahedron split's most) in
 *                           each cube of a surface half as large as the
 *                           lattice's boundary (three sheets across the
 *                           box), 12 (cx cy + cy cz + cz cx) for cx cy cz
 *                           cubes a side: an allowance, not a bound (a
 *                           surface folded more densely, a lattice of
 *                           sheets, can exceed it; genus2_mc's 96^2 x 25
 *                           lattice is allowed 163,020 triangles); work: a
 *                           node one sample and `refine`
 *                           rounds over 7 vertices of S's class (CHEAP for
 *                           an implicit S: its defining function), and
 *                           the mesh's as above
 *   csg                     both operands (a, b)
 *   other kinds             nothing
 * Keys the cost needs and cannot read (a missing file, a bad number) add
 * nothing: the factory names them.  Recursion ends at depth 8. */
dfl_status dfl_shape_cost(const dfl_cfg *cfg, const char *sec, dfl_cost *c, dfl_err *err);

/* The parts of the kind = rfunc field of [sec], at most (*parts), and the
 * key that sets their number (*key: "eps" for a curve, "max_tris" for a
 * surface, else "vertices", "triangles", "points" or "region", the largest
 * contribution): segments of vertices (n - 1, n when closed), of a curve
 * dfl_polygonize_curve_segments_bound at eps, triangles (a surface's:
 * max_tris; a mesh section's: dfl_mesh_tris_bound, key "surface"), points,
 * and 1 for a region.  Reads the curve's keys as
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
