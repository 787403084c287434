/* `[shape]` config section -> dfl_shape.
 *
 * Keys (contract):
 *   kind = one of geom/shape.h's DFL_SHAPE_KIND_LIST: circle | sphere | torus |
 *          cylinder | plane | cone | box | segment | ellipse | bspline_curve |
 *          bspline_surface | bezier_surface | implicit | csg | mesh
 *          (shape_cfg.c has one parser per kind)
 *   circle:   center = x y,      radius = r > 0
 *   sphere:   center = x y z,    radius = r > 0
 *   torus:    center = x y z, axis = ax ay az (non-zero), major = R > 0,
 *             minor = r in (0, R)
 *   cylinder: center = x y z (a point on the axis), axis, radius > 0
 *   plane:    dim = 2|3 (default 3), point = ..., normal = ... (non-zero;
 *             points to the outside)
 *   cone:     a = x y z, b = x y z (a != b), ra >= 0, rb >= 0, not both 0
 *   box:      dim = 2|3 (default 3), center, half = h... (all > 0)
 *   segment:  dim = 2|3 (default 2), a, b (a != b); unsigned distance
 *   ellipse:  center = x y, a = semi-axis along x > 0, b = semi-axis along
 *             y > 0 (axis-aligned; exact signed distance, no jets)
 *   bspline_curve | bspline_surface | bezier_surface: handed to
 *             dfl_param_shape_from_cfg (experiments/cfg/curve_cfg.h)
 *   implicit: see geom/implicit.h; surface = torus | goursat | genus2 |
 *             sphere | ellipsoid,
 *             solver = newton | ceres (default newton), plus the surface's
 *             parameters (dfl_implicit_from_cfg in this module documents them)
 *   csg:      op = union | intersection | difference | smooth_union |
 *             smooth_intersection | smooth_difference, a = <section>,
 *             b = <section> (each a shape section of its own), k = width > 0
 *             (smooth ops only)
 *   mesh:     a triangle mesh (geom/mesh.h: exact distance, sign of the
 *             generalized winding number), from exactly one of
 *               file = PATH: any format Assimp reads (OBJ, PLY, STL, OFF,
 *                 AC3D, ...; io/meshfile.h: vertices welded by position,
 *                 coordinates rounded to float by Assimp).  A relative PATH
 *                 is resolved against the folder of the file the key is
 *                 written in (the config, or the included shape file), a
 *                 --set value against the working directory.  Refused
 *                 (exit 2, naming the file and the reason): missing or not
 *                 a regular file, empty, not a mesh, no triangles, a
 *                 non-finite vertex, a degenerate (zero-area) triangle
 *                 (geom/trimesh.h says why such files are refused, not
 *                 repaired).
 *               polygonize = SECTION: marching cubes of that 3D shape
 *                 section (field/isomesh.h; implicit surfaces through their
 *                 polynomial) on a grid over lo = x y z .. hi = x y z
 *                 (defaults -1 -1 -1 and 1 1 1) with equal spacing,
 *                 resolution = nodes along the longest side (8..1024,
 *                 default 96), refine = regula falsi rounds (0..100,
 *                 default 8).
 *             fit = none | box (default none: the file's coordinates);
 *               box: the bounding box's centre moves to center = x y z
 *               (default 0 0 0) and its longest side is scaled to
 *               size > 0 (default 1.6), uniformly (center and size are
 *               refused with fit = none).
 *             distance = signed | unsigned (default signed).
 *             The triangles are available to methods through
 *             dfl_shape_mesh_trimesh (geom/mesh.h).
 *
 * Errors: DFL_E_INPUT naming file:line, [section] and key (missing key,
 * wrong type, radius <= 0, zero axis, unknown kind, CSG cycles).
 */
#ifndef DFL_EXPERIMENTS_SHAPE_CFG_H
#define DFL_EXPERIMENTS_SHAPE_CFG_H

#include "core/status.h"
#include "geom/implicit.h"
#include "geom/shape.h"
#include "io/config.h"

/* Builds the shape section sec describes into *out (caller frees with
 * dfl_shape_free).  *out is untouched on failure. */
dfl_status dfl_shape_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_shape *out, dfl_err *err);

/* The implicit surface of a kind = implicit section (the keys above) into
 * *out (caller frees with dfl_implicit_free); *out untouched on failure. */
dfl_status dfl_implicit_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_implicit **out,
                                 dfl_err *err);

#endif
