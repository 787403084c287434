/* Helpers shared by the bs04 studies (bs04_spacecurves, bs04_triangle,
 * bs04_triedge, bs04_surface, bs04_hetero, bs04_polygonization): table
 * cells for gradient statistics (error metrics: field/metrics.h),
 * log-log slopes,
 * .vtp output of polylines, triangle meshes and point samples, and slices
 * of 3D fields.
 */
#ifndef DFL_EXPERIMENTS_BS04_SPACE_UTIL_H
#define DFL_EXPERIMENTS_BS04_SPACE_UTIL_H

#include <stddef.h>

#include "core/status.h"
#include "field/metrics.h"
#include "io/config.h"
#include "io/table.h"
#include "io/vtk.h"
#include "rfunc/join.h"
#include "rfunc/segment.h"
#include "harness/field_out.h"

/* Statistics of |grad u| over the m samples whose mask entry is non-zero
 * (mask may be NULL: all): min, mean, max; NAN when none. */
typedef struct dfl_gradstat {
    size_t count;
    double min, mean, max;
} dfl_gradstat;
void dfl_bs04_gradstat(size_t m, int dim, const double *grad, const unsigned char *mask,
                       dfl_gradstat *out);
/* Sets grad_min<sfx>, grad_mean<sfx>, grad_max<sfx>. */
dfl_status dfl_bs04_put_gradstat(dfl_table *t, const char *sfx, const dfl_gradstat *g,
                                 dfl_err *err);

/* Least-squares slope of log(y) against log(x) over n >= 2 pairs (x, y >
 * 0, not all x equal): the growth exponent of y in x. */
double dfl_bs04_loglog_slope(size_t n, const double *x, const double *y);

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

/* Samples the 3D field f (value and gradient) on each of the n slices
 * (plane grids, cfg/slice_cfg.h) and writes slice s as <prefix><s> (see
 * dfl_field_out_write; no reference).  Stops at the first failure;
 * temporary buffers are freed. */
dfl_status dfl_bs04_write_slices(const dfl_study_ctx *ctx, const dfl_field *f,
                                 const dfl_grid *slices, int n, const char *prefix,
                                 const dfl_field_write_opts *o, dfl_err *err);

#endif
