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

/* Peak bytes dfl_field_out_write itself allocates for a grid of `nodes`
 * nodes (the caller's u, gu, ref not counted), for a study's estimate: the
 * .vti writer's derived arrays (a 3-component gradient, grad_norm, error:
 * 5 doubles) and the zlib copies of all five point arrays, held together
 * until the file is written (7 doubles, compressBound's slack included),
 * 96 bytes a node; the .exr (three floats a pixel, written after the .vti
 * is freed) is less.  0 when opts writes neither. */
double dfl_field_out_bytes(const dfl_field_write_opts *opts, double nodes);
/* Its work, in CHEAP evaluations (core/budget.h): 100 a node, the derived
 * arrays, zlib and the float conversion (1.8 us a node measured on
 * bs04_corrected's 99^2 grids); 0 when opts writes neither file. */
double dfl_field_out_units(const dfl_field_write_opts *opts, double nodes);

/* ---- volumes of the 3D studies (hvb25_accuracy, sjp10_3d) ---------------
 * [output] vti   = true    write a volume per field the study measures
 *          vti_n = n       its nodes per axis (2..1024; default def_n, the
 *                          study's choice: its error grid, capped so that
 *                          make reproduce stays within disk and memory)
 *          compress = true zlib in the .vti
 * A volume holds point data value, gradient, grad_norm, reference and
 * error = value - reference (io/field_write.h) over the box of the study's
 * error grid, and the study's cell data (e.g. the T-mesh level). */
typedef struct dfl_volume_opts {
    bool vti, compress;
    long n;
} dfl_volume_opts;

dfl_status dfl_volume_opts_from_cfg(const dfl_cfg *cfg, long def_n, dfl_volume_opts *o,
                                    dfl_err *err);

/* Peak bytes of dfl_volume_write at n nodes per axis (its sample buffers,
 * the writer's derived arrays and zlib copies, and cell arrays of ncell_arrays
 * doubles per cell): for the study's estimate. */
double dfl_volume_bytes(long n, int ncell_arrays);

/* The n^3 node grid spanning [lo, hi] (3 doubles each). */
void dfl_volume_grid(const double lo[3], const double hi[3], long n, dfl_grid *g);

/* Samples field f (value and gradient) and the reference ref (value) on g
 * (3D) and writes <stem><tag>.vti with the cell arrays (dfl_vti_ncells
 * tuples each; NULL, 0 for none).  unsigned_ref: the reference is |ref|
 * (an unsigned decoding's error).  DFL_E_NOMEM, the sampling's and the
 * writer's errors. */
dfl_status dfl_volume_write(const dfl_study_ctx *ctx, const char *stem, const dfl_field *f,
                            const dfl_field *ref, bool unsigned_ref, const dfl_grid *g,
                            const dfl_vtk_array *cells, int ncells, bool compress, dfl_err *err);

#endif
