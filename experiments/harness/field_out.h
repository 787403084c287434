/* Writing a sampled field as the DESIGN's output conventions ask:
 *
 *   <stem><tag>.vti  point data value, gradient (3 components, z = 0 in
 *                    2D), grad_norm, and error = value - reference and
 *                    reference when a reference is given
 *   <stem><tag>.exr  2D: the whole grid; 3D: the slice k = n[2]/2.
 *                    Channels value, grad_norm[, error]; row 0 is the top
 *                    (largest y), so viewers show y up.  FLOAT, or HALF
 *                    when half != 0.
 */
#ifndef DFL_EXPERIMENTS_FIELD_OUT_H
#define DFL_EXPERIMENTS_FIELD_OUT_H

#include "harness/experiment.h"
#include "field/sample.h"

typedef struct dfl_field_out_opts {
    int vti, exr, compress, half;
} dfl_field_out_opts;

/* Reads [output] vti, exr, compress (bools, default true) and half (default
 * false) into opts. */
dfl_status dfl_field_out_from_cfg(const dfl_cfg *cfg, dfl_field_out_opts *opts, dfl_err *err);

/* u: values (grid order), gu: dim-component gradients (may be NULL), ref:
 * reference values (may be NULL). */
dfl_status dfl_field_out_write(const dfl_study_ctx *ctx, const char *stem, const dfl_grid *g,
                               const double *u, const double *gu, const double *ref,
                               const dfl_field_out_opts *opts, dfl_err *err);

#endif
