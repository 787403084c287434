/* Tests for field/trace: depth and normal of an exact sphere against the
 * closed-form ray-sphere intersection, misses and box clipping, thread
 * invariance, the EXR round trip, bad input. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/vec.h"
#include "field/exact.h"
#include "field/trace.h"
#include "io/exr.h"
#include "util/tmpdir.h"

static dfl_field sphere_field(double r)
{
    const double c[3] = {0, 0, 0};
    dfl_shape s;
    dfl_field f;
    cr_assert_eq(dfl_shape_sphere(c, r, &s, NULL), DFL_OK);
    cr_assert_eq(dfl_field_exact_new(&s, &f, NULL), DFL_OK);
    return f;
}

static dfl_camera cam0(int w, int h)
{
    dfl_camera c = {{0.3, -2.5, 0.8}, {0, 0, 0}, {0, 0, 1}, 40.0, w, h};
    return c;
}

static dfl_trace_opts opts0(void)
{
    dfl_trace_opts o = {10.0, 1e-6, 1.0, 200, 0, {0}, {0}, 1};
    return o;
}

/* t of the first intersection of eye + t dir with |x| = r, NAN on a miss. */
static double ray_sphere(const double *e, const double *d, double r)
{
    const double b = dfl_vec3_dot(e, d), c = dfl_vec3_dot(e, e) - r * r, disc = b * b - c;
    return disc < 0 ? NAN : -b - sqrt(disc);
}

Test(trace, sphere_depth_and_normal_match_the_closed_form)
{
    const double r = 0.5;
    dfl_field f = sphere_field(r);
    dfl_camera cam = cam0(48, 32);
    dfl_trace_opts o = opts0();
    dfl_frame fr;
    dfl_err err;
    cr_assert_eq(dfl_trace_frame(&f, &cam, &o, &fr, &err), DFL_OK, "%s", err.msg);
    size_t hits = 0, misses = 0;
    for (int py = 0; py < cam.height; py++)
        for (int px = 0; px < cam.width; px++) {
            const size_t i = (size_t)py * cam.width + px;
            double d[3];
            dfl_camera_ray(&cam, px, py, d);
            const double t = ray_sphere(cam.eye, d, r);
            if (isnan(t)) {
                cr_assert(isinf(fr.depth[i]), "pixel %d %d must miss", px, py);
                misses++;
                continue;
            }
            /* |u| <= eps at the stop: the true hit is within eps / cos(theta) */
            double x[3], n[3];
            for (int j = 0; j < 3; j++) x[j] = cam.eye[j] + t * d[j], n[j] = x[j] / r;
            const double cs = fabs(dfl_vec3_dot(d, n));
            if (cs < 0.05) continue;  /* grazing: may legitimately run out of steps */
            cr_assert(isfinite(fr.depth[i]), "pixel %d %d must hit", px, py);
            hits++;
            cr_assert(fabs(fr.depth[i] - t) <= o.eps / cs + 1e-6 * t, "depth %g vs %g",
                      fr.depth[i], t);
            for (int j = 0; j < 3; j++) cr_assert(fabs(fr.normal[3 * i + j] - n[j]) < 1e-5);
            cr_assert(fr.steps[i] >= 1);
        }
    cr_assert(hits > 100 && misses > 100);
    cr_assert_eq(fr.hits + fr.misses + fr.exhausted, (size_t)cam.width * cam.height);
    dfl_frame_free(&fr);
    dfl_field_destroy(&f);
}

Test(trace, frames_are_thread_invariant)
{
    dfl_field f = sphere_field(0.5);
    dfl_camera cam = cam0(37, 23);
    dfl_trace_opts o = opts0();
    dfl_frame a, b;
    cr_assert_eq(dfl_trace_frame(&f, &cam, &o, &a, NULL), DFL_OK);
    o.threads = 2;
    cr_assert_eq(dfl_trace_frame(&f, &cam, &o, &b, NULL), DFL_OK);
    const size_t np = 37 * 23;
    cr_assert(memcmp(a.depth, b.depth, np * sizeof *a.depth) == 0);
    cr_assert(memcmp(a.normal, b.normal, 3 * np * sizeof *a.normal) == 0);
    cr_assert(memcmp(a.steps, b.steps, np * sizeof *a.steps) == 0);
    cr_assert_eq(a.evals, b.evals);
    dfl_frame_free(&a);
    dfl_frame_free(&b);
    dfl_field_destroy(&f);
}

/* A box that holds only the far half of the sphere (y > 0.1): rays start
 * at the box's face, so they see the sphere behind the cut from inside,
 * and rays missing the box take no step. */
Test(trace, box_clips_the_rays)
{
    dfl_field f = sphere_field(0.5);
    dfl_camera cam = {{0, -3, 0}, {0, 0, 0}, {0, 0, 1}, 30.0, 31, 31};
    dfl_trace_opts o = opts0();
    o.use_box = 1;
    const double lo[3] = {-0.3, 0.1, -0.3}, hi[3] = {0.3, 1, 0.3};
    memcpy(o.box_lo, lo, sizeof lo);
    memcpy(o.box_hi, hi, sizeof hi);
    dfl_frame fr;
    cr_assert_eq(dfl_trace_frame(&f, &cam, &o, &fr, NULL), DFL_OK);
    const size_t mid = 15 * 31 + 15;
    /* the centre ray enters at y = 0.1, inside the sphere: |u| = 0.4 steps
     * on to the far wall y = 0.5 */
    cr_assert(fabs(fr.depth[mid] - 3.5) < 1e-5, "depth %g", fr.depth[mid]);
    /* seen from inside: the outward gradient +y, turned to face the eye */
    cr_assert(fr.normal[3 * mid + 1] < -0.999f, "the far wall's normal, facing the eye");
    cr_assert(isinf(fr.depth[0]) && fr.steps[0] == 0.0f, "a corner ray misses the box");
    dfl_frame_free(&fr);
    dfl_field_destroy(&f);
}

Test(trace, exr_round_trip)
{
    dfl_field f = sphere_field(0.5);
    dfl_camera cam = cam0(16, 12);
    dfl_trace_opts o = opts0();
    dfl_frame fr;
    cr_assert_eq(dfl_trace_frame(&f, &cam, &o, &fr, NULL), DFL_OK);
    char dir[256], path[320];
    tmpdir_file(dir, sizeof dir, "frame.exr", path, sizeof path);
    dfl_err err;
    cr_assert_eq(dfl_frame_write_exr(path, &fr, &err), DFL_OK, "%s", err.msg);
    const char *names[5] = {"depth", "normal.x", "normal.y", "normal.z", "steps"};
    for (int c = 0; c < 5; c++) {
        int w, h;
        float *data;
        cr_assert_eq(dfl_exr_read_channel(path, names[c], &w, &h, &data, &err), DFL_OK, "%s",
                     err.msg);
        cr_assert(w == 16 && h == 12);
        for (int i = 0; i < w * h; i++) {
            const float want = c == 0 ? fr.depth[i] : c == 4 ? fr.steps[i]
                                                             : fr.normal[3 * i + c - 1];
            cr_assert(memcmp(&want, data + i, sizeof want) == 0, "%s pixel %d", names[c], i);
        }
        free(data);
    }
    tmpdir_remove(dir);
    dfl_frame_free(&fr);
    dfl_field_destroy(&f);
}

Test(trace, bad_input)
{
    dfl_field f = sphere_field(0.5);
    dfl_frame fr;
    dfl_err err;
    dfl_trace_opts o = opts0();
    dfl_camera cam = cam0(0, 10);
    cr_assert_eq(dfl_trace_frame(&f, &cam, &o, &fr, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "width"));
    cam = cam0(8, 8);
    cam.fov_deg = 180;
    cr_assert_eq(dfl_trace_frame(&f, &cam, &o, &fr, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "fov"));
    cam = cam0(8, 8);
    memcpy(cam.up, (double[3]){0.3, -2.5, 0.8}, 3 * sizeof(double));
    cr_assert_eq(dfl_trace_frame(&f, &cam, &o, &fr, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "parallel"));
    cam = cam0(8, 8);
    o.step_scale = 0;
    cr_assert_eq(dfl_trace_frame(&f, &cam, &o, &fr, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "step_scale"));
    cr_assert_null(fr.depth);
    dfl_field_destroy(&f);
}
