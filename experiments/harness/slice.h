/* Axis-aligned section planes of 3D fields (the "section planes" of bs04
 * Figs. 8, 9c, 11b and 12): sampling in parallel and writing the result.
 *
 * A slice is the plane x[axis] = at, sampled on an n[0] x n[1] grid of its
 * two in-plane coordinates (the other two axes in increasing order: axis z
 * -> (x, y), y -> (x, z), x -> (y, z)) from lo to hi inclusive; sample
 * (i, j) is at index i + n[0] j.
 *
 * Output: <stem><tag>.vti, ImageData with one node along the normal axis so
 * that ParaView shows the slice where it is in space (point data value,
 * gradient (3D), grad_norm, and error = value - reference, reference when
 * a reference is given), and <stem><tag>.exr (channels value, grad_norm[,
 * error]; row 0 = largest second in-plane coordinate, so viewers show it
 * up).  Both respect [output] vti/exr/compress/half (field_out.h).
 */
#ifndef DFL_EXPERIMENTS_SLICE_H
#define DFL_EXPERIMENTS_SLICE_H

#include <stddef.h>

#include "core/status.h"
#include "harness/experiment.h"
#include "field/field.h"
#include "harness/field_out.h"
#include "io/config.h"

typedef struct dfl_slice {
    int axis;        /* 0, 1, 2: normal axis */
    double at;       /* plane coordinate */
    int n[2];        /* samples per in-plane axis, >= 2 */
    double lo[2], hi[2];
} dfl_slice;

/* The two in-plane axes of a normal axis, in increasing order. */
void dfl_slice_axes(int axis, int *a0, int *a1);

/* Parses "<axis> <at> [lo0 lo1 hi0 hi1]" (axis x, y or z) as used in lists
 * of slices; without the extent, out->lo/hi are left as the caller set
 * them.  DFL_E_INPUT naming where (a caller-made "file:line: [sec] key"
 * string) on a bad axis, number or extent. */
dfl_status dfl_slice_parse(const char *text, const char *where, dfl_slice *out, dfl_err *err);

/* Reads "[sec] slices = z 0.5; y 0.25 -1 -1 1 1 ..." (at least one, at
 * most max), "[sec] slice_n" (2..2048, default 200) and the default extent
 * "slice_lo = a b", "slice_hi = a b" (in-plane coordinates, lo < hi;
 * defaults 0 0 and 1 1) for slices without their own.  Returns the count
 * in *count. */
dfl_status dfl_slices_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_slice *out, int max,
                               int *count, dfl_err *err);

size_t dfl_slice_size(const dfl_slice *s);
/* Coordinates (3 doubles) of sample idx. */
void dfl_slice_point(const dfl_slice *s, size_t idx, double *x);

/* Samples the 3D field f on s: val[idx], grad[3 idx + j] (grad may be
 * NULL).  Parallel over chunks with `threads` OpenMP threads (<= 0:
 * default); f->ops->eval is called once per chunk.  DFL_E_INPUT if f is
 * not 3D. */
dfl_status dfl_slice_sample(const dfl_field *f, const dfl_slice *s, int threads, double *val,
                            double *grad, dfl_err *err);

/* Writes the slice files (see above).  grad (3 per sample) and ref may be
 * NULL. */
dfl_status dfl_slice_write(const dfl_study_ctx *ctx, const char *stem, const dfl_slice *s,
                           const double *val, const double *grad, const double *ref,
                           const dfl_field_out_opts *o, dfl_err *err);

#endif
