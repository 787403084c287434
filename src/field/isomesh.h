/* The zero level set of a 3D field as a triangle mesh (geom/polygonize.h's
 * dfl_trimesh): marching cubes (field/isoline.h's dfl_iso_surface, the
 * 6-tetrahedron split) on a grid, every vertex then moved onto {f = 0}
 * along its grid edge (dfl_iso_refine), so that the mesh of an implicit
 * surface or any shape's SDF has its vertices on the true surface and
 * dflab can use it as `[shape] kind = mesh` (geom/mesh.h) or write it
 * (io/meshfile.h).
 *
 *   dfl_field_isomesh(f, g, refine, threads, out, dropped, err)
 *   dfl_shape_isomesh(s, g, refine, threads, out, dropped, err)   of a shape's zero set
 *
 * Properties.  The surface is watertight (every edge in two triangles)
 * when the level set does not reach the grid's boundary; triangles are
 * oriented counter-clockwise seen from where f > 0 (outside for a signed
 * distance), so the mesh's winding number is 1 inside.  Triangles whose
 * area is exactly zero after refinement (two vertices moved onto the same
 * grid node) are dropped and counted (*dropped): their three edges are
 * shared with the neighbouring triangles, so neither the surface nor its
 * distance changes.  Unused vertices are dropped.  uv, tri_patch and
 * cell_bound are NULL, bound 0.
 *
 * Errors: DFL_E_INPUT for a field that is not 3D, a grid that is not a 3D
 * volume, a non-finite sample or an empty level set (no triangle);
 * DFL_E_NOMEM.  *out zeroed on failure. */
#ifndef DFL_FIELD_ISOMESH_H
#define DFL_FIELD_ISOMESH_H

#include <stddef.h>

#include "core/status.h"
#include "field/field.h"
#include "field/sample.h"
#include "geom/polygonize.h"
#include "geom/shape.h"

/* refine: regula falsi rounds of dfl_iso_refine (0: linear vertices);
 * threads: for sampling (field/sample.h). dropped may be NULL. */
dfl_status dfl_field_isomesh(const dfl_field *f, const dfl_grid *g, int refine, int threads,
                             dfl_trimesh *out, size_t *dropped, dfl_err *err);

/* dfl_field_isomesh of the shape s (borrowed, 3D): an implicit surface
 * (geom/implicit.h) through its defining function g, which has the same
 * zero set and sign as its distance but costs no footpoint per sample;
 * any other shape through its signed distance.  Errors as above. */
dfl_status dfl_shape_isomesh(const dfl_shape *s, const dfl_grid *g, int refine, int threads,
                             dfl_trimesh *out, size_t *dropped, dfl_err *err);

#endif
