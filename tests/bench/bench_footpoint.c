/* Footpoints per second for the two backends on the same points: the
 * in-house Newton iteration and Ceres Levenberg–Marquardt, on a bicubic
 * B-spline surface (the bump of configs/shapes/surface.ini, control points
 * generated from the same formula) and on the implicit torus quartic.
 * Points: deterministic pseudo-random in a box around each surface.  The
 * ratio newton/ceres is the speed-up; both backends agree to 1e-10 on hard
 * points (tests/geom/test_footpoint.c, test_implicit.c).  Serial, one
 * point at a time, as the solvers are called inside the samplers. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench.h"
#include "geom/footpoint.h"
#include "geom/implicit.h"
#include "geom/surface.h"

#define NPTS 400
static const double PI = 3.14159265358979323846;

static double lcg(unsigned *s)
{
    *s = *s * 1103515245u + 12345u;
    return (double)(*s >> 8) / (double)(1u << 24);
}

typedef struct surf_job {
    dfl_surface_locator *L;
    const double *pts;
    double sum;
} surf_job;

static void run_surface(void *a)
{
    surf_job *j = a;
    dfl_surface_foot f;
    j->sum = 0;
    for (int i = 0; i < NPTS; i++)
        if (dfl_surface_footpoint(j->L, j->pts + 3 * i, &f, NULL) == DFL_OK) j->sum += f.dist;
}

typedef struct imp_job {
    dfl_implicit *s;
    dfl_foot_backend b;
    const double *pts;
    double sum;
} imp_job;

static void run_implicit(void *a)
{
    imp_job *j = a;
    dfl_footpoint f;
    j->sum = 0;
    for (int i = 0; i < NPTS; i++)
        if (dfl_implicit_footpoint_with(j->s, j->b, j->pts + 3 * i, &f, NULL) == DFL_OK)
            j->sum += fabs(f.d);
}

void bench_footpoint(void)
{
    double pts[3 * NPTS];
    unsigned seed = 7;
    dfl_err err;

    /* bicubic surface: z = 0.25 + 0.3 sin(pi x) sin(pi y) + 0.6 (x-.5)(y-.5) at x, y = i/5 */
    double cp[6 * 6 * 3];
    for (int j = 0; j < 6; j++)
        for (int i = 0; i < 6; i++) {
            double x = i / 5.0, y = j / 5.0;
            double *p = cp + 3 * (i + 6 * j);
            p[0] = x, p[1] = y;
            p[2] = 0.25 + 0.3 * sin(PI * x) * sin(PI * y) + 0.6 * (x - 0.5) * (y - 0.5);
        }
    dfl_surface patch;
    dfl_surface_set set;
    if (dfl_surface_init(4, 4, 6, 6, cp, NULL, 0, NULL, 0, &patch, &err) != DFL_OK ||
        dfl_surface_set_init(1, &patch, &set, &err) != DFL_OK) {
        fprintf(stderr, "bench_footpoint: %s\n", err.msg);
        return;
    }
    for (int i = 0; i < NPTS; i++) {
        pts[3 * i] = -0.2 + 1.4 * lcg(&seed);
        pts[3 * i + 1] = -0.2 + 1.4 * lcg(&seed);
        pts[3 * i + 2] = -0.4 + 1.4 * lcg(&seed);
    }
    double rate[2], sum[2];
    for (int b = 0; b < 2; b++) {
        dfl_foot_opts o;
        dfl_foot_opts_default(&o);
        o.backend = b ? DFL_FOOT_CERES : DFL_FOOT_NEWTON;
        surf_job j = {NULL, pts, 0};
        if (dfl_surface_locator_new(&set, &o, &j.L, &err) != DFL_OK) {
            fprintf(stderr, "bench_footpoint: %s\n", err.msg);
            dfl_surface_set_free(&set);
            return;
        }
        double t = bench_best(b ? 1 : 3, run_surface, &j);
        rate[b] = NPTS / t;
        sum[b] = j.sum;
        dfl_surface_locator_free(j.L);
    }
    bench_report("footpoint.bspline_surface.newton", rate[0], "footpoints/s");
    bench_report("footpoint.bspline_surface.ceres", rate[1], "footpoints/s");
    bench_report("footpoint.bspline_surface.newton_over_ceres", rate[0] / rate[1], "x");
    bench_report("footpoint.bspline_surface.mean_distance_difference",
                 fabs(sum[0] - sum[1]) / NPTS, "units");
    dfl_surface_set_free(&set);

    /* implicit torus R = 0.5, r = 0.2 */
    const double c[3] = {0, 0, 0}, ax[3] = {0, 0, 1};
    dfl_implicit *tor = NULL;
    if (dfl_implicit_torus(c, ax, 0.5, 0.2, NULL, &tor, &err) != DFL_OK) {
        fprintf(stderr, "bench_footpoint: %s\n", err.msg);
        return;
    }
    for (int i = 0; i < NPTS; i++)
        for (int k = 0; k < 3; k++) pts[3 * i + k] = -1.0 + 2.0 * lcg(&seed);
    for (int b = 0; b < 2; b++) {
        imp_job j = {tor, b ? DFL_FOOT_CERES : DFL_FOOT_NEWTON, pts, 0};
        double t = bench_best(b ? 1 : 3, run_implicit, &j);
        rate[b] = NPTS / t;
        sum[b] = j.sum;
    }
    bench_report("footpoint.implicit_torus.newton", rate[0], "footpoints/s");
    bench_report("footpoint.implicit_torus.ceres", rate[1], "footpoints/s");
    bench_report("footpoint.implicit_torus.newton_over_ceres", rate[0] / rate[1], "x");
    bench_report("footpoint.implicit_torus.mean_distance_difference", fabs(sum[0] - sum[1]) / NPTS,
                 "units");
    dfl_implicit_free(tor);
}
