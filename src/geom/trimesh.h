/* Triangle meshes as data (geom/polygonize.h's dfl_trimesh, the one mesh
 * type of dflab): reading them from files, checking, counting boundary
 * edges and fitting them into a box.  Meshes that do not come from
 * polygonization leave uv, tri_patch and cell_bound NULL and bound 0.
 *
 *   dfl_trimesh_read(path, out, err)          any file io/meshfile.h reads, checked
 *   dfl_trimesh_check(m, err)                 the rules below
 *   dfl_trimesh_edges(m, boundary, nonmanifold)  edge counts
 *   dfl_trimesh_fit(m, center, size)          uniform scale + shift into a box
 *   dfl_trimesh_bbox(m, lo, hi)
 *
 * A valid mesh (dfl_trimesh_check) has at least one triangle, every index
 * < nverts, every vertex coordinate finite and within core/domain.h's
 * |x| <= DFL_COORD_MAX, and no degenerate triangle: |(b - a) x (c - a)| > 0
 * in double precision (a zero-area triangle is a segment or a point, which
 * would add the distance to a segment, not to a surface, and has no normal;
 * such files are refused, not repaired, so what is measured is the file).
 * Orientation, watertightness and self-intersections are not required: the
 * mesh shape's sign comes from the generalized winding number
 * (geom/winding.h), which is meaningful for any soup. */
#ifndef DFL_GEOM_TRIMESH_H
#define DFL_GEOM_TRIMESH_H

#include <stddef.h>

#include "core/status.h"
#include "geom/polygonize.h"

/* Reads path (io/meshfile.h: welded vertices, the file's orientation) into
 * *out and checks it; caller frees with dfl_trimesh_free.  DFL_E_INPUT with
 * "PATH: <what is wrong>" (the reader's errors and dfl_trimesh_check's),
 * DFL_E_NOMEM; *out is zeroed on failure. */
dfl_status dfl_trimesh_read(const char *path, dfl_trimesh *out, dfl_err *err);

/* DFL_OK or DFL_E_INPUT naming the first offending triangle or vertex
 * ("triangle 12 is degenerate (zero area)", ...). */
dfl_status dfl_trimesh_check(const dfl_trimesh *m, dfl_err *err);

/* Undirected edges (vertex index pairs) used by exactly one triangle into
 * *boundary and by three or more into *nonmanifold (either may be NULL).
 * Allocates scratch; DFL_E_NOMEM. */
dfl_status dfl_trimesh_edges(const dfl_trimesh *m, size_t *boundary, size_t *nonmanifold,
                             dfl_err *err);

/* Axis-aligned bounding box of the vertices (lo, hi: 3 doubles each). */
void dfl_trimesh_bbox(const dfl_trimesh *m, double *lo, double *hi);

/* x <- center + s (x - mid) for every vertex, mid the bounding box's
 * centre and s = size / (its longest side): the mesh's box then has its
 * centre at center and longest side size (> 0, finite; asserted), the
 * shape is unchanged up to similarity (distances scale by s).  A mesh
 * whose box has zero extent cannot pass dfl_trimesh_check. */
void dfl_trimesh_fit(dfl_trimesh *m, const double *center, double size);

#endif
