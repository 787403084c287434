/* Sphere tracing of any 3D dfl_field: a pinhole camera, per-pixel depth,
 * normal and step count, written as an EXR frame (hvb25 Table 4: the time
 * of one sphere-traced frame per decoding filter).
 *
 * Function index
 *   dfl_camera_check     validity of a camera
 *   dfl_camera_ray       the unit ray through a pixel centre
 *   dfl_trace_check      validity of the tracing options
 *   dfl_trace_frame      trace every pixel into a dfl_frame
 *   dfl_frame_write_exr  the frame as an EXR image (io/exr)
 *   dfl_frame_free       release a frame
 *
 * Camera: eye, a target it looks at, an up hint (not parallel to
 * target - eye), a vertical field of view fov_deg in (0, 180) and the image
 * size.  Pixel (px, py), row 0 at the top (as EXR stores it), has its ray
 * through the pixel centre: with f = unit(target - eye), r = unit(f x up),
 * v = r x f, s = tan(fov/2),
 *   dir = unit(f + (2 (px + 1/2) / W - 1) s (W/H) r + (1 - 2 (py + 1/2) / H) s v).
 *
 * Tracing: t starts at 0 (or where the ray enters the box when a box is
 * given, rays missing the box are misses with 0 steps) and advances by
 * step_scale |u(eye + t dir)|; a ray hits when |u| <= eps, misses when t
 * passes tmax (or leaves the box) and is exhausted after max_steps field
 * evaluations without either.  The step count of a pixel is the number of
 * field values it took (the hit's gradient evaluation not counted).  This
 * is safe for signed and unsigned fields alike as long as |u| does not
 * overestimate the distance to the zero set by more than 1/step_scale.
 * Per pixel: depth = t at the hit (+inf otherwise), normal = +-grad u/|grad u|
 * at the hit with the sign that faces the eye (n.dir <= 0: an unsigned
 * field's gradient flips across its zero set, a signed field seen from
 * outside keeps its outward gradient; 0 0 0 on a miss or where the
 * gradient vanishes), steps.
 *
 * Cost: rays of one image row advance in lockstep, so each step is one
 * batched eval of the row's live rays (no dispatch per point); rows are
 * spread over OpenMP threads.  A pixel's result depends only on its own
 * ray (the field's eval is per point), so frames are bit-identical at any
 * thread count.
 */
#ifndef DFL_FIELD_TRACE_H
#define DFL_FIELD_TRACE_H

#include <stddef.h>

#include "core/status.h"
#include "field/field.h"

typedef struct dfl_camera {
    double eye[3], target[3], up[3];
    double fov_deg;     /* vertical field of view, (0, 180) */
    int width, height;  /* pixels, 1 .. 16384 */
} dfl_camera;

typedef struct dfl_trace_opts {
    double tmax;        /* > 0 */
    double eps;         /* > 0: hit threshold on |u| */
    double step_scale;  /* (0, 1] */
    int max_steps;      /* >= 1 */
    int use_box;        /* clip every ray to [box_lo, box_hi] (box_lo < box_hi) */
    double box_lo[3], box_hi[3];
    int threads;        /* OpenMP threads (<= 0: the default) */
} dfl_trace_opts;

typedef struct dfl_frame {
    int width, height;
    float *depth;       /* width*height, row 0 at the top */
    float *normal;      /* 3*width*height, interleaved x y z */
    float *steps;       /* width*height */
    size_t hits, misses, exhausted;  /* pixel counts (sum: width*height) */
    size_t evals;       /* sum of the step counts */
} dfl_frame;

/* DFL_E_INPUT naming the bad member: image size, fov, eye == target, up
 * parallel to the view direction, non-finite numbers. */
dfl_status dfl_camera_check(const dfl_camera *cam, dfl_err *err);

/* The unit ray direction through the centre of pixel (px, py) (any
 * integers; the formula above).  The camera must pass dfl_camera_check. */
void dfl_camera_ray(const dfl_camera *cam, int px, int py, double dir[3]);

/* DFL_E_INPUT naming the bad member (tmax, eps, step_scale, max_steps, box). */
dfl_status dfl_trace_check(const dfl_trace_opts *o, dfl_err *err);

/* Traces f (dim 3) through every pixel into *out (allocated here; free
 * with dfl_frame_free).  Errors: DFL_E_INPUT (a 2D field, a bad camera or
 * options, as the checks above), DFL_E_NOMEM; *out is zeroed on failure. */
dfl_status dfl_trace_frame(const dfl_field *f, const dfl_camera *cam, const dfl_trace_opts *o,
                           dfl_frame *out, dfl_err *err);

/* Writes channels depth, normal.x, normal.y, normal.z and steps as FLOAT
 * (bit-exact; io/exr's dfl_exr_write, staged and renamed).  Fails as
 * dfl_exr_write does. */
dfl_status dfl_frame_write_exr(const char *path, const dfl_frame *fr, dfl_err *err);

/* Frees the buffers and zeroes *fr (safe on a zeroed frame and twice). */
void dfl_frame_free(dfl_frame *fr);

#endif
