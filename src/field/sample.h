/* Regular grids and parallel sampling of fields on them.
 *
 * A grid has n[d] >= 2 nodes along each of its dim axes spanning [lo, hi]
 * inclusive (node i at lo + i*(hi-lo)/(n-1)); node index
 * idx = i + n0*(j + n1*k), x fastest, which is the VTK ImageData order.
 * For dim == 2, n[2] is 1 and the third coordinate is absent.
 */
#ifndef DFL_FIELD_SAMPLE_H
#define DFL_FIELD_SAMPLE_H

#include <stddef.h>

#include "core/status.h"
#include "field/field.h"

typedef struct dfl_grid {
    int dim;       /* 2 or 3 */
    int n[3];      /* nodes per axis; n[2] == 1 when dim == 2 */
    double lo[3];
    double hi[3];
} dfl_grid;

/* Checks dim, n >= 2 and lo < hi per axis; DFL_E_INPUT otherwise. */
dfl_status dfl_grid_check(const dfl_grid *g, dfl_err *err);
size_t dfl_grid_size(const dfl_grid *g);
double dfl_grid_spacing(const dfl_grid *g, int axis);
/* Coordinates of node idx (dim entries). */
void dfl_grid_node(const dfl_grid *g, size_t idx, double *x);

/* Samples f on g: val[idx] and, when grad != NULL, grad[idx*dim + j].
 * Parallel over chunks of nodes with `threads` OpenMP threads (<= 0: the
 * OpenMP default); f->ops->eval is called once per chunk. */
dfl_status dfl_field_sample(const dfl_field *f, const dfl_grid *g, int threads, double *val,
                            double *grad, dfl_err *err);

#endif
