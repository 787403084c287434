/* Study glue for the field files: the [output] keys, buffers for a
 * sampled field, and the study's file names for io/field_write.h.
 *
 *   <stem><tag>.vti, <stem><tag>.exr   (dfl_study_path names; see
 *   io/field_write.h for what they hold: for a 3D volume the .exr is the
 *   section k = n[2]/2, for a section plane (a grid with a flat axis,
 *   field/sample.h) the plane itself)
 */
#ifndef DFL_EXPERIMENTS_FIELD_OUT_H
#define DFL_EXPERIMENTS_FIELD_OUT_H

#include <stdbool.h>
#include <stddef.h>

#include "field/sample.h"
#include "harness/experiment.h"
#include "io/field_write.h"

/* Reads [output] vti, exr, compress (bools, default true) and half (default
 * false) into opts. */
dfl_status dfl_field_out_from_cfg(const dfl_cfg *cfg, dfl_field_write_opts *opts, dfl_err *err);

/* A field sampled at m points of a dim-D grid: values u (m), gradients gu
 * (dim m, grid order) and, when asked for, reference values ref (m; else
 * NULL) -- what dfl_field_sample fills and dfl_field_out_write takes. */
typedef struct dfl_field_bufs {
    double *u, *gu, *ref;
} dfl_field_bufs;

/* Allocates b's buffers for m samples (m may be 0).  Returns false when
 * out of memory; the caller reports it in its own words, and
 * dfl_field_bufs_free releases what was allocated. */
bool dfl_field_bufs_alloc(dfl_field_bufs *b, size_t m, int dim, bool with_ref);

/* Frees the buffers and sets them to NULL (safe on a zeroed struct and
 * twice). */
void dfl_field_bufs_free(dfl_field_bufs *b);

/* Writes the samples of a field on grid g (a 2D grid, a volume or a plane)
 * as the files opts asks for.  u: values (grid order), gu: g->dim-component
 * gradients (may be NULL), ref: reference values (may be NULL). */
dfl_status dfl_field_out_write(const dfl_study_ctx *ctx, const char *stem, const dfl_grid *g,
                               const double *u, const double *gu, const double *ref,
                               const dfl_field_write_opts *opts, dfl_err *err);

#endif
