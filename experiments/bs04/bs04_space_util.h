/* Helpers shared by the bs04 studies in space (bs04_spacecurves,
 * bs04_triangle, bs04_triedge, bs04_surface; bs04_polygonization): their
 * output keys, .vtp output of polylines, triangle meshes and point
 * samples, and slices of 3D fields.  (Gradient statistics and error
 * metrics: field/metrics.h; log-log slopes: core/fit.h.)
 */
#ifndef DFL_EXPERIMENTS_BS04_SPACE_UTIL_H
#define DFL_EXPERIMENTS_BS04_SPACE_UTIL_H

#include <stdbool.h>
#include <stddef.h>

#include "core/budget.h"
#include "core/status.h"
#include "io/config.h"
#include "io/vtk.h"
#include "harness/field_out.h"

#define DFL_BS04_MAX_SLICES 4

/* What the studies in space write besides their table: section planes of
 * the field, zlib-compressed .vtp files or not, and the field files. */
typedef struct dfl_bs04_space_out {
    dfl_grid slices[DFL_BS04_MAX_SLICES];
    int nslices;
    bool compress;             /* [study] compress (default true): zlib .vtp */
    dfl_field_write_opts out;  /* [output] (harness/field_out.h) */
} dfl_bs04_space_out;

/* Reads the [study] section planes (cfg/slice_cfg.h: slices, slice_n,
 * slice_lo, slice_hi; at most DFL_BS04_MAX_SLICES), then, when
 * with_compress, [study] compress (a study that reads it earlier passes
 * false and sets o->compress itself), then [output], in that order.  Fails
 * as those readers do (DFL_E_INPUT naming file, line and key). */
dfl_status dfl_bs04_space_out_from_cfg(const dfl_cfg *cfg, bool with_compress,
                                       dfl_bs04_space_out *o, dfl_err *err);

/* .vtp writers (through dfl_vtp_write: atomic, optional zlib).
 *   polyline: n points of dimension dim (2D gets z = 0), one line, and
 *             the point array arr when not NULL (n tuples);
 *   trimesh: nv 3D points, nt triangles (3 indices each);
 *   points:  n 3D points with one scalar point array (name, values). */
dfl_status dfl_bs04_vtp_polyline(const char *path, int dim, size_t n, const double *pts,
                                 const dfl_vtk_array *arr, int compress, dfl_err *err);
dfl_status dfl_bs04_vtp_trimesh(const char *path, size_t nv, const double *verts, size_t nt,
                                const size_t *tris, int compress, dfl_err *err);
dfl_status dfl_bs04_vtp_points(const char *path, size_t n, const double *pts, const char *name,
                               const double *values, int compress, dfl_err *err);

/* Samples the 3D field f (value and gradient) on each of o's slices and
 * writes slice s as <prefix><s> as o->out asks (dfl_field_out_write; no
 * reference).  Stops at the first failure; temporary buffers are freed. */
dfl_status dfl_bs04_write_slices(const dfl_study_ctx *ctx, const dfl_field *f,
                                 const dfl_bs04_space_out *o, const char *prefix, dfl_err *err);

/* For a study's estimate: what dfl_bs04_write_slices holds and does for
 * o's slices, one slice at a time: the largest slice's value and gradient
 * (4 doubles a node) and the writer's buffers (dfl_field_out_bytes), named
 * [study] slice_n; every slice node evaluated once, `units` evaluations of
 * class cls each, plus `extra` of class xcls (the study's own per-node work
 * on a slice, e.g. a reference distance; 0 for none) and extra_bytes a node
 * held beside the value and gradient, and written (dfl_field_out_units). */
void dfl_bs04_slices_cost(const dfl_bs04_space_out *o, dfl_cost_class cls, double units,
                          dfl_cost_class xcls, double extra, double extra_bytes, dfl_cost *c);

#endif
