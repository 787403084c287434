/* Level sets of sampled fields: isolines by marching squares (a 2D grid or
 * a section plane of 3D space) and isosurfaces by marching cubes (a 3D grid:
 * the box it spans is the cutting region), as polylines and triangles that
 * io/vtk.h's dfl_vtp_write takes directly.
 *
 * Function index
 *   dfl_iso_lines      marching squares on node values of a 2D or plane grid
 *   dfl_iso_surface    marching cubes (6-tetrahedron split) on a 3D grid
 *   dfl_iso_refine     moves every vertex onto {f = level} along its grid edge
 *   dfl_iso_vtp        the result as dfl_vtp_data (borrowed pointers)
 *   dfl_iso_free
 *
 * Conventions.  Node values val[idx] are in the grid's node order
 * (field/sample.h: x fastest).  A node is "above" when val >= level, else
 * "below"; a vertex lies on every grid edge (or, in 3D, tetrahedron edge)
 * whose end nodes differ, at the linear interpolation of the two values,
 * and is shared by all cells using that edge, so the output is watertight
 * (closed isolines repeat their first point at the end; a level set cut by
 * the grid boundary ends there).  Points are always 3 coordinates (z = 0 on
 * a 2D grid).  Every vertex remembers its edge (end points a, b, a below,
 * b above) so that dfl_iso_refine can move it onto the true level set of a
 * field by a bracketed search.
 *   Marching squares resolves the saddle case (diagonal corners above) by
 *   the mean of the four corner values (the bilinear interpolant's value at
 *   the cell centre): mean >= level joins the above corners.
 *   Marching cubes splits every grid cube into 6 tetrahedra around the
 *   diagonal from its lowest to its highest corner (the split is the same
 *   on a shared face of neighbouring cubes, so the surface is watertight)
 *   and has no ambiguous cases.  Triangles are oriented with their normal
 *   (counter-clockwise order) pointing from below to above, i.e. along the
 *   field's gradient; for a signed distance (negative inside) that is
 *   outwards.
 *
 * Failure: DFL_E_INPUT for an invalid grid (dfl_grid_check), a grid of the
 * wrong kind (dfl_iso_lines: dim 2 or a plane; dfl_iso_surface: a 3D volume
 * grid) or a non-finite value; DFL_E_NOMEM.  *out is zeroed on failure.
 * Allocation only while building; refinement allocates one batch buffer.
 */
#ifndef DFL_FIELD_ISOLINE_H
#define DFL_FIELD_ISOLINE_H

#include <stddef.h>

#include "core/status.h"
#include "field/field.h"
#include "field/sample.h"
#include "io/vtk.h"

typedef struct dfl_iso {
    size_t npoints;
    double *points;        /* 3 * npoints */
    double *edge;          /* 6 * npoints: end points a (below), b (above) of the vertex's edge */
    size_t nlines;
    size_t *line_offsets;  /* nlines + 1 */
    size_t *line_conn;     /* line_offsets[nlines] point indices */
    size_t nclosed;        /* lines that are closed (first point repeated at the end) */
    size_t ntris;
    size_t *tris;          /* 3 * ntris */
} dfl_iso;

/* Isolines val = level of a 2D grid or a plane grid (dfl_grid_plane). */
dfl_status dfl_iso_lines(const dfl_grid *g, const double *val, double level, dfl_iso *out,
                         dfl_err *err);

/* Isosurface val = level of a 3D volume grid. */
dfl_status dfl_iso_surface(const dfl_grid *g, const double *val, double level, dfl_iso *out,
                           dfl_err *err);

/* Moves every vertex to a root of f - level on its edge [a, b] by the
 * Illinois variant of regula falsi, `iters` rounds (each one batched call
 * of f over all vertices, OpenMP-free), keeping the bracket; f must have
 * the grid's dimension (the first f->dim coordinates of a point are used,
 * so a 2D field takes 2D grids only) and f(a) < level <= f(b) should hold
 * (it does when val was sampled from f; where it does not, the vertex stays
 * at its linear estimate).  DFL_E_INPUT for a dimension mismatch,
 * DFL_E_NOMEM.  Deterministic. */
dfl_status dfl_iso_refine(dfl_iso *iso, const dfl_field *f, double level, int iters,
                          dfl_err *err);

/* iso as PolyData (lines and triangles; no point arrays): pointers into
 * iso, valid while iso lives. */
void dfl_iso_vtp(const dfl_iso *iso, dfl_vtp_data *out);

/* Releases everything and zeroes *iso (NULL or zeroed is fine). */
void dfl_iso_free(dfl_iso *iso);

#endif
