/* A closed triangle mesh of a field's zero set, as geom/polygonize.h's
 * dfl_trimesh: what a mesh-based peer (OpenVDB's meshToLevelSet, field/
 * vdb.h) takes when the shape is implicit in a field.
 *
 *   dfl_iso_trimesh(f, g, refine, threads, out)
 *
 * Steps: f sampled at the nodes of the 3D grid g (dfl_field_sample), marching
 * cubes at level 0 (dfl_iso_surface: watertight, triangles oriented along
 * grad f, i.e. outwards for a signed distance), every vertex moved onto
 * {f = 0} along its edge by `refine` Illinois rounds (dfl_iso_refine), then
 * copied into a dfl_trimesh (verts, tris; uv, tri_patch and cell_bound are
 * NULL, bound is NAN: marching cubes certifies no Hausdorff bound).
 * Deviation: a triangle's vertices lie on the surface and within one grid
 * cube, so its edges are at most the cube's diagonal e; for a sphere of
 * radius R every point of such a triangle is within R - sqrt(R^2 - e^2/3)
 * of the sphere (|sum l_i v_i - c|^2 = R^2 - sum_{i<j} l_i l_j |v_i - v_j|^2
 * >= R^2 - e^2/3).  The mesh is closed where the zero set stays inside
 * the grid's box; where the box cuts it the mesh ends at the box.
 * Errors: those of the three steps (a 2D field or grid: DFL_E_INPUT),
 * DFL_E_NOMEM; *out zeroed on failure.  Free with dfl_trimesh_free.
 */
#ifndef DFL_FIELD_ISO_MESH_H
#define DFL_FIELD_ISO_MESH_H

#include "core/status.h"
#include "field/field.h"
#include "field/sample.h"
#include "geom/polygonize.h"

dfl_status dfl_iso_trimesh(const dfl_field *f, const dfl_grid *g, int refine, int threads,
                           dfl_trimesh *out, dfl_err *err);

#endif
