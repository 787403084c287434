#include "field/trace.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <omp.h>

#include "core/vec.h"
#include "io/exr.h"

static int finite3(const double *v) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

static void unit3(double *v)
{
    const double l = dfl_vec3_norm(v);
    for (int j = 0; j < 3; j++) v[j] /= l;
}

/* The camera frame f, r, v (see trace.h). */
static void camera_frame(const dfl_camera *cam, double f[3], double r[3], double v[3])
{
    for (int j = 0; j < 3; j++) f[j] = cam->target[j] - cam->eye[j];
    unit3(f);
    dfl_vec3_cross(f, cam->up, r);
    unit3(r);
    dfl_vec3_cross(r, f, v);
}

dfl_status dfl_camera_check(const dfl_camera *cam, dfl_err *err)
{
    if (cam->width < 1 || cam->width > 16384 || cam->height < 1 || cam->height > 16384)
        return dfl_err_set(err, DFL_E_INPUT, "camera: expected 1 <= width, height <= 16384, got %d x %d",
                           cam->width, cam->height);
    if (!(cam->fov_deg > 0 && cam->fov_deg < 180))
        return dfl_err_set(err, DFL_E_INPUT, "camera: expected 0 < fov < 180 degrees, got %g",
                           cam->fov_deg);
    if (!finite3(cam->eye) || !finite3(cam->target) || !finite3(cam->up))
        return dfl_err_set(err, DFL_E_INPUT, "camera: eye, target and up must be finite");
    double f[3], c[3];
    for (int j = 0; j < 3; j++) f[j] = cam->target[j] - cam->eye[j];
    const double lf = dfl_vec3_norm(f), lu = dfl_vec3_norm(cam->up);
    if (!(lf > 0)) return dfl_err_set(err, DFL_E_INPUT, "camera: eye equals target");
    dfl_vec3_cross(f, cam->up, c);
    if (!(dfl_vec3_norm(c) > 1e-9 * lf * lu))
        return dfl_err_set(err, DFL_E_INPUT, "camera: up is parallel to the view direction");
    return DFL_OK;
}

void dfl_camera_ray(const dfl_camera *cam, int px, int py, double dir[3])
{
    double f[3], r[3], v[3];
    camera_frame(cam, f, r, v);
    const double s = tan(cam->fov_deg * DFL_PI / 360.0),
                 a = (double)cam->width / cam->height;
    const double sx = (2.0 * (px + 0.5) / cam->width - 1.0) * s * a,
                 sy = (1.0 - 2.0 * (py + 0.5) / cam->height) * s;
    for (int j = 0; j < 3; j++) dir[j] = f[j] + sx * r[j] + sy * v[j];
    unit3(dir);
}

dfl_status dfl_trace_check(const dfl_trace_opts *o, dfl_err *err)
{
    if (!(o->tmax > 0 && isfinite(o->tmax)))
        return dfl_err_set(err, DFL_E_INPUT, "trace: expected finite tmax > 0, got %g", o->tmax);
    if (!(o->eps > 0 && isfinite(o->eps)))
        return dfl_err_set(err, DFL_E_INPUT, "trace: expected finite eps > 0, got %g", o->eps);
    if (!(o->step_scale > 0 && o->step_scale <= 1))
        return dfl_err_set(err, DFL_E_INPUT, "trace: expected 0 < step_scale <= 1, got %g",
                           o->step_scale);
    if (o->max_steps < 1)
        return dfl_err_set(err, DFL_E_INPUT, "trace: expected max_steps >= 1, got %d",
                           o->max_steps);
    if (o->use_box)
        for (int j = 0; j < 3; j++)
            if (!(isfinite(o->box_lo[j]) && isfinite(o->box_hi[j]) && o->box_lo[j] < o->box_hi[j]))
                return dfl_err_set(err, DFL_E_INPUT, "trace: expected box lo < hi on axis %d", j);
    return DFL_OK;
}

/* The ray's parameter interval inside [0, tmax] and the box (slab test);
 * empty when *t0 > *t1. */
static void ray_span(const dfl_trace_opts *o, const double *e, const double *d, double *t0,
                     double *t1)
{
    *t0 = 0.0, *t1 = o->tmax;
    if (!o->use_box) return;
    for (int j = 0; j < 3; j++) {
        if (d[j] == 0.0) {
            if (e[j] < o->box_lo[j] || e[j] > o->box_hi[j]) *t0 = INFINITY;
            continue;
        }
        double a = (o->box_lo[j] - e[j]) / d[j], b = (o->box_hi[j] - e[j]) / d[j];
        if (a > b) {
            const double c = a;
            a = b, b = c;
        }
        if (a > *t0) *t0 = a;
        if (b < *t1) *t1 = b;
    }
}

/* Per-thread scratch for one row of w rays. */
typedef struct row_buf {
    double *dir, *t, *t1, *pts, *val, *grad;
    int *live, *nsteps, *state;  /* state: 0 marching, 1 hit, 2 miss, 3 exhausted */
} row_buf;

static void row_buf_free(row_buf *b)
{
    free(b->dir), free(b->t), free(b->t1), free(b->pts), free(b->val), free(b->grad);
    free(b->live), free(b->nsteps), free(b->state);
    memset(b, 0, sizeof *b);
}

static int row_buf_alloc(row_buf *b, int w)
{
    const size_t n = (size_t)w;
    b->dir = malloc(3 * n * sizeof *b->dir), b->t = malloc(n * sizeof *b->t);
    b->t1 = malloc(n * sizeof *b->t1), b->pts = malloc(3 * n * sizeof *b->pts);
    b->val = malloc(n * sizeof *b->val), b->grad = malloc(3 * n * sizeof *b->grad);
    b->live = malloc(n * sizeof *b->live), b->nsteps = malloc(n * sizeof *b->nsteps);
    b->state = malloc(n * sizeof *b->state);
    return b->dir && b->t && b->t1 && b->pts && b->val && b->grad && b->live && b->nsteps &&
           b->state;
}

static void trace_row(const dfl_field *f, const dfl_camera *cam, const dfl_trace_opts *o,
                      int py, row_buf *b, dfl_frame *out, unsigned char *state)
{
    const int w = cam->width;
    const double *e = cam->eye;
    int nlive = 0;
    for (int px = 0; px < w; px++) {
        double *d = b->dir + 3 * px;
        dfl_camera_ray(cam, px, py, d);
        ray_span(o, e, d, b->t + px, b->t1 + px);
        b->nsteps[px] = 0;
        b->state[px] = b->t[px] > b->t1[px] ? 2 : 0;
        if (!b->state[px]) b->live[nlive++] = px;
    }
    while (nlive > 0) {
        for (int k = 0; k < nlive; k++) {
            const int px = b->live[k];
            for (int j = 0; j < 3; j++) b->pts[3 * k + j] = e[j] + b->t[px] * b->dir[3 * px + j];
        }
        f->ops->eval(f->ctx, (size_t)nlive, b->pts, b->val, NULL);
        int keep = 0;
        for (int k = 0; k < nlive; k++) {
            const int px = b->live[k];
            const double u = fabs(b->val[k]);
            b->nsteps[px]++;
            if (u <= o->eps) b->state[px] = 1;
            else if (!(u < INFINITY)) b->state[px] = 2;  /* NaN or inf: nothing to follow */
            else {
                b->t[px] += o->step_scale * u;
                if (b->t[px] > b->t1[px]) b->state[px] = 2;
                else if (b->nsteps[px] >= o->max_steps) b->state[px] = 3;
                else b->live[keep++] = px;
            }
        }
        nlive = keep;
    }
    /* The hits' normals in one batch. */
    int nh = 0;
    for (int px = 0; px < w; px++)
        if (b->state[px] == 1) {
            for (int j = 0; j < 3; j++) b->pts[3 * nh + j] = e[j] + b->t[px] * b->dir[3 * px + j];
            b->live[nh++] = px;
        }
    if (nh) f->ops->eval(f->ctx, (size_t)nh, b->pts, b->val, b->grad);
    const size_t row = (size_t)py * (size_t)w;
    for (int px = 0; px < w; px++) {
        out->depth[row + px] = INFINITY;
        out->steps[row + px] = (float)b->nsteps[px];
        state[row + px] = (unsigned char)b->state[px];
        for (int j = 0; j < 3; j++) out->normal[3 * (row + px) + j] = 0.0f;
    }
    for (int k = 0; k < nh; k++) {
        const int px = b->live[k];
        const double *g = b->grad + 3 * k, l = dfl_vec3_norm(g);
        /* facing the eye: an unsigned field's gradient flips across its zero set */
        const double s = dfl_vec3_dot(g, b->dir + 3 * px) > 0 ? -l : l;
        out->depth[row + px] = (float)b->t[px];
        if (l > 0 && isfinite(l))
            for (int j = 0; j < 3; j++) out->normal[3 * (row + px) + j] = (float)(g[j] / s);
    }
}

void dfl_frame_free(dfl_frame *fr)
{
    if (!fr) return;
    free(fr->depth), free(fr->normal), free(fr->steps);
    memset(fr, 0, sizeof *fr);
}

dfl_status dfl_trace_frame(const dfl_field *f, const dfl_camera *cam, const dfl_trace_opts *o,
                           dfl_frame *out, dfl_err *err)
{
    memset(out, 0, sizeof *out);
    if (!f || !f->ops || f->dim != 3)
        return dfl_err_set(err, DFL_E_INPUT, "trace: a 3D field is required");
    dfl_status st = dfl_camera_check(cam, err);
    if (st == DFL_OK) st = dfl_trace_check(o, err);
    if (st != DFL_OK) return st;
    const size_t np = (size_t)cam->width * (size_t)cam->height;
    out->width = cam->width, out->height = cam->height;
    out->depth = malloc(np * sizeof *out->depth);
    out->normal = malloc(3 * np * sizeof *out->normal);
    out->steps = malloc(np * sizeof *out->steps);
    unsigned char *state = malloc(np);
    if (!out->depth || !out->normal || !out->steps || !state) {
        free(state);
        dfl_frame_free(out);
        return dfl_err_set(err, DFL_E_NOMEM, "trace: out of memory for %zu pixels", np);
    }
    int nomem = 0;
    const int threads = o->threads > 0 ? o->threads : omp_get_max_threads();
#pragma omp parallel num_threads(threads) reduction(| : nomem)
    {
        row_buf b;
        memset(&b, 0, sizeof b);
        if (!row_buf_alloc(&b, cam->width)) nomem = 1;
#pragma omp for schedule(dynamic, 1)
        for (int py = 0; py < cam->height; py++)
            if (!nomem) trace_row(f, cam, o, py, &b, out, state);
        row_buf_free(&b);
    }
    if (nomem) {
        free(state);
        dfl_frame_free(out);
        return dfl_err_set(err, DFL_E_NOMEM, "trace: out of memory for a row of %d rays",
                           cam->width);
    }
    for (size_t i = 0; i < np; i++) {
        out->evals += (size_t)out->steps[i];
        if (state[i] == 1) out->hits++;
        else if (state[i] == 3) out->exhausted++;
        else out->misses++;
    }
    free(state);
    return DFL_OK;
}

dfl_status dfl_frame_write_exr(const char *path, const dfl_frame *fr, dfl_err *err)
{
    const size_t np = (size_t)fr->width * (size_t)fr->height;
    float *nx = malloc(3 * np * sizeof *nx);
    if (!nx) return dfl_err_set(err, DFL_E_NOMEM, "trace: out of memory writing %s", path);
    for (size_t i = 0; i < np; i++)
        for (int j = 0; j < 3; j++) nx[j * np + i] = fr->normal[3 * i + j];
    const dfl_exr_channel ch[5] = {{"depth", fr->depth},
                                   {"normal.x", nx},
                                   {"normal.y", nx + np},
                                   {"normal.z", nx + 2 * np},
                                   {"steps", fr->steps}};
    dfl_status st = dfl_exr_write(path, fr->width, fr->height, ch, 5, 0, err);
    free(nx);
    return st;
}
