/* Writing a sampled field: values on a regular lattice of nodes, their
 * gradients and a reference, as the files dflab's output conventions ask
 * for.  Each function takes the path it writes; naming files is the
 * caller's business.
 *
 *   .vti  VTK ImageData (io/vtk.h) over the whole lattice, point data
 *         value, gradient (3 components; 2D gradients get z = 0) and
 *         grad_norm when a gradient is given, error = value - reference
 *         and reference when a reference is given; the caller's cell data
 *         (e.g. a T-mesh level per cell) as <CellData>.
 *   .exr  one section of the lattice as an OpenEXR image (io/exr.h):
 *         channels value, grad_norm (with a gradient) and error (with a
 *         reference), FLOAT or HALF.  The section is normal to the last
 *         axis with one node (a 2D lattice's z, a section plane's normal)
 *         or, in a volume, to z at node dims[2]/2; image x runs along the
 *         first remaining axis, image y along the second, row 0 at its
 *         largest coordinate (so viewers show it up).
 *
 * Both go through a temporary file renamed on success (nothing is left
 * behind on failure).  Errors: DFL_E_NOMEM naming the path, and those of
 * dfl_vti_write / dfl_exr_write (DFL_E_IO naming the path, DFL_E_INPUT for
 * a bad lattice).
 *
 * Function index
 *   dfl_field_write_vti   the .vti file
 *   dfl_field_write_exr   the .exr file
 *   dfl_field_write       those of the two that the options ask for
 */
#ifndef DFL_IO_FIELD_WRITE_H
#define DFL_IO_FIELD_WRITE_H

#include "core/status.h"
#include "io/vtk.h"

/* Which files and how: vti, exr (write the file when != 0), compress (zlib
 * in the .vti), half (HALF channels in the .exr). */
typedef struct dfl_field_write_opts {
    int vti, exr, compress, half;
} dfl_field_write_opts;

/* A sampled field.  Node (i, j, k) is index i + dims[0] (j + dims[1] k)
 * at origin + (i, j, k) * spacing. */
typedef struct dfl_field_samples {
    int dims[3];         /* nodes per axis, >= 1 */
    double origin[3];
    double spacing[3];   /* > 0; any positive value on an axis of one node */
    int gdim;            /* gradient components per node: 2 or 3 */
    const double *u;     /* value per node */
    const double *gu;    /* gdim components per node, or NULL */
    const double *ref;   /* reference value per node, or NULL */
    const dfl_vtk_array *cells; /* .vti cell data (io/vtk.h dfl_vti_write_cells: one tuple
                                   per cell of the lattice), or NULL; not in the .exr */
    int ncells;                 /* number of cell arrays */
} dfl_field_samples;

dfl_status dfl_field_write_vti(const char *path, const dfl_field_samples *s, int compress,
                               dfl_err *err);
dfl_status dfl_field_write_exr(const char *path, const dfl_field_samples *s, int half,
                               dfl_err *err);
/* The .vti at vti_path when o->vti, then the .exr at exr_path when o->exr
 * (a path not asked for may be NULL).  Stops at the first failure. */
dfl_status dfl_field_write(const char *vti_path, const char *exr_path, const dfl_field_samples *s,
                           const dfl_field_write_opts *o, dfl_err *err);

#endif
