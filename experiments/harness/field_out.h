/* Study glue for the field files: the [output] keys, and the study's file
 * names for io/field_write.h.
 *
 *   <stem><tag>.vti, <stem><tag>.exr   (dfl_study_path names; see
 *   io/field_write.h for what they hold: for a 3D volume the .exr is the
 *   section k = n[2]/2, for a section plane (a grid with a flat axis,
 *   field/sample.h) the plane itself)
 */
#ifndef DFL_EXPERIMENTS_FIELD_OUT_H
#define DFL_EXPERIMENTS_FIELD_OUT_H

#include "field/sample.h"
#include "harness/experiment.h"
#include "io/field_write.h"

/* Reads [output] vti, exr, compress (bools, default true) and half (default
 * false) into opts. */
dfl_status dfl_field_out_from_cfg(const dfl_cfg *cfg, dfl_field_write_opts *opts, dfl_err *err);

/* Writes the samples of a field on grid g (a 2D grid, a volume or a plane)
 * as the files opts asks for.  u: values (grid order), gu: g->dim-component
 * gradients (may be NULL), ref: reference values (may be NULL). */
dfl_status dfl_field_out_write(const dfl_study_ctx *ctx, const char *stem, const dfl_grid *g,
                               const double *u, const double *gu, const double *ref,
                               const dfl_field_write_opts *opts, dfl_err *err);

#endif
