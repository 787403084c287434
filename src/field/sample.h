/* Regular grids and parallel sampling of fields on them.
 *
 * A grid has n[d] >= 2 nodes along each of its dim axes spanning [lo, hi]
 * inclusive (node i at (1 - t) lo + t hi, t = i/(n-1), so the last node is
 * hi exactly); node index idx = i + n0*(j + n1*k), x fastest, which is the
 * VTK ImageData order.  For dim == 2, n[2] is 1 and the third coordinate is
 * absent.
 *
 * A section plane of 3D space is a 3D grid with one flat axis: n = 1 and
 * lo == hi (the plane's coordinate) on that axis (dfl_grid_plane).  It is
 * sampled, indexed and written like any grid.
 *
 * Function index
 *   dfl_grid_check       validity (volume, 2D or plane grid)
 *   dfl_grid_plane       the plane x[axis] = at as a grid
 *   dfl_grid_flat_axis   the normal axis of a plane grid
 *   dfl_grid_size, dfl_grid_spacing, dfl_grid_node
 *   dfl_grid_frame       dims, origin, spacing as VTK ImageData wants them
 *   dfl_field_sample     values and gradients of a field at every node
 */
#ifndef DFL_FIELD_SAMPLE_H
#define DFL_FIELD_SAMPLE_H

#include <stddef.h>

#include "core/status.h"
#include "field/field.h"

typedef struct dfl_grid {
    int dim;       /* 2 or 3 */
    int n[3];      /* nodes per axis; n[2] == 1 when dim == 2; 1 on a plane's flat axis */
    double lo[3];
    double hi[3];
} dfl_grid;

/* Checks dim, n >= 2 and finite lo < hi per axis, except that a 3D grid
 * may have one flat axis (n == 1, finite lo == hi); DFL_E_INPUT otherwise,
 * naming the axis. */
dfl_status dfl_grid_check(const dfl_grid *g, dfl_err *err);

/* The plane x[axis] = at (axis 0, 1, 2) of 3D space as a grid of
 * n[0] x n[1] nodes spanning [lo, hi] of its two in-plane axes, the other
 * two in increasing order (axis z: (x, y); y: (x, z); x: (y, z)); grid
 * node i + n[0] j is in-plane node (i, j).  Copies the numbers unchecked
 * (dfl_grid_check checks them).  axis must be 0, 1 or 2. */
void dfl_grid_plane(int axis, double at, const int n[2], const double lo[2], const double hi[2],
                    dfl_grid *out);
/* The flat axis of a plane grid, -1 for a volume or a 2D grid. */
int dfl_grid_flat_axis(const dfl_grid *g);

size_t dfl_grid_size(const dfl_grid *g);
/* (hi - lo)/(n - 1) along axis (< dim); 0 on a flat axis. */
double dfl_grid_spacing(const dfl_grid *g, int axis);
/* Coordinates of node idx (dim entries). */
void dfl_grid_node(const dfl_grid *g, size_t idx, double *x);
/* g as VTK ImageData: nodes per axis, the position of node 0 and the node
 * spacing, 3 entries each.  Axes with one node (a 2D grid's z, a plane's
 * normal) get spacing 1; a 2D grid's z origin is 0. */
void dfl_grid_frame(const dfl_grid *g, int dims[3], double origin[3], double spacing[3]);

/* Samples f on g: val[idx] and, when grad != NULL, grad[idx*dim + j].
 * Parallel over chunks of nodes with `threads` OpenMP threads (<= 0: the
 * OpenMP default); f->ops->eval is called once per chunk.  DFL_E_INPUT for
 * an invalid grid (dfl_grid_check) or a field of another dimension. */
dfl_status dfl_field_sample(const dfl_field *f, const dfl_grid *g, int threads, double *val,
                            double *grad, dfl_err *err);

#endif
