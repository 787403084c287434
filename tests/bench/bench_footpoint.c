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
#include "core/rng.h"
#include "core/vec.h"
#include "geom/curve_sdf.h"
#include "geom/footpoint.h"
#include "geom/implicit.h"
#include "geom/surface.h"

#define NPTS 400

/* One footpoint of x: its distance into *d; DFL_OK or the solver's failure. */
typedef dfl_status (*foot_fn)(const void *ctx, const double *x, double *d);

typedef struct foot_job {
    foot_fn foot;
    const void *ctx;
    const double *pts;
    double sum; /* of the distances, to compare the backends */
} foot_job;

static void run_job(void *a)
{
    foot_job *j = a;
    j->sum = 0;
    for (int i = 0; i < NPTS; i++) {
        double d;
        if (j->foot(j->ctx, j->pts + 3 * i, &d) == DFL_OK) j->sum += d;
    }
}

static dfl_status surface_foot(const void *ctx, const double *x, double *d)
{
    dfl_surface_foot f;
    dfl_status st = dfl_surface_footpoint(ctx, x, &f, NULL);
    if (st == DFL_OK) *d = f.dist;
    return st;
}

typedef struct imp_ctx {
    const dfl_implicit *s;
    dfl_foot_backend b;
} imp_ctx;

static dfl_status implicit_foot(const void *ctx, const double *x, double *d)
{
    const imp_ctx *c = ctx;
    dfl_footpoint f;
    dfl_status st = dfl_implicit_footpoint_with(c->s, c->b, x, &f, NULL);
    if (st == DFL_OK) *d = fabs(f.d);
    return st;
}

/* Times job[0] (Newton, best of 3) and job[1] (Ceres, once) and reports
 * footpoint.<name>.{newton, ceres, newton_over_ceres,
 * mean_distance_difference}. */
static void compare_backends(const char *name, foot_job job[2])
{
    double rate[2];
    char col[128];
    for (int b = 0; b < 2; b++) rate[b] = NPTS / bench_best(b ? 1 : 3, run_job, &job[b]);
    snprintf(col, sizeof col, "footpoint.%s.newton", name);
    bench_report(col, rate[0], "footpoints/s");
    snprintf(col, sizeof col, "footpoint.%s.ceres", name);
    bench_report(col, rate[1], "footpoints/s");
    snprintf(col, sizeof col, "footpoint.%s.newton_over_ceres", name);
    bench_report(col, rate[0] / rate[1], "x");
    snprintf(col, sizeof col, "footpoint.%s.mean_distance_difference", name);
    bench_report(col, fabs(job[0].sum - job[1].sum) / NPTS, "units");
}

/* bspline_sdf: exact signed distances (value and gradient, what a PHT fit
 * samples) of sjp10's convex curve (configs/shapes/sjp10_convex.ini: a
 * periodic cubic, 8 control points) against plain curve evaluations
 * (position at a parameter) on the same thread.  ratio = SDF queries/s ÷
 * curve evaluations/s; its inverse is the cost of one exact query in curve
 * evaluations (issue 19's aim: <= 20). */
#define NCURVE 20000
typedef struct curve_job {
    const dfl_curve_sdf *S;
    const dfl_bspline *c;
    const double *pts; /* NCURVE points (SDF) or NCURVE parameters in pts[2i] */
    double sum;
} curve_job;

static void run_sdf(void *a)
{
    curve_job *j = a;
    j->sum = 0;
    for (int i = 0; i < NCURVE; i++) {
        dfl_curve_sdf_val v;
        if (dfl_curve_sdf_eval(j->S, j->pts + 2 * i, 1, &v, NULL) == DFL_OK) j->sum += v.d;
    }
}

static void run_curve_eval(void *a)
{
    curve_job *j = a;
    j->sum = 0;
    for (int i = 0; i < NCURVE; i++) {
        double p[2];
        dfl_bspline_eval(j->c, j->pts[2 * i], 0, p);
        j->sum += p[0];
    }
}

static void bench_curve_sdf(bench_ctx *ctx)
{
    static const double cp[] = {0.5, 0.12, 0.78, 0.18, 0.9,  0.45, 0.82, 0.75,
                                0.55, 0.9, 0.3,  0.84, 0.14, 0.58, 0.2,  0.26};
    dfl_bspline c;
    dfl_curve_sdf *S = NULL;
    dfl_err err;
    if (dfl_bspline_init_periodic(2, 4, 8, cp, NULL, 0, &c, &err) != DFL_OK ||
        dfl_curve_sdf_new(&c, NULL, &S, &err) != DFL_OK) {
        fprintf(stderr, "bench_footpoint: %s\n", err.msg);
        return;
    }
    double *pts = malloc(2 * NCURVE * sizeof *pts), *ts = malloc(2 * NCURVE * sizeof *ts);
    if (!pts || !ts) {
        fprintf(stderr, "bench_footpoint: out of memory\n");
        free(pts), free(ts), dfl_curve_sdf_free(S), dfl_bspline_free(&c);
        return;
    }
    uint64_t seed = 11;
    for (int i = 0; i < NCURVE; i++) {
        pts[2 * i] = dfl_rng_splitmix(&seed, 0.0, 1.0); /* the unit square, as sjp10 */
        pts[2 * i + 1] = dfl_rng_splitmix(&seed, 0.0, 1.0);
        ts[2 * i] = dfl_rng_splitmix(&seed, c.t0, c.t1);
    }
    curve_job js = {S, &c, pts, 0}, jc = {S, &c, ts, 0};
    const double sdf = NCURVE / bench_best(3, run_sdf, &js);
    const double ev = NCURVE / bench_best(3, run_curve_eval, &jc);
    bench_report("footpoint.bspline_sdf.queries", sdf, "queries/s");
    bench_report("footpoint.bspline_sdf.curve_evals", ev, "evaluations/s");
    bench_report("footpoint.bspline_sdf.evals_per_query", ev / sdf, "evaluations");
    bench_summary_add(ctx, "bspline_sdf", sdf, "curve evaluations/s (same thread)", ev, sdf / ev,
                      NAN);
    free(pts), free(ts);
    dfl_curve_sdf_free(S);
    dfl_bspline_free(&c);
}

void bench_footpoint(bench_ctx *ctx)
{
    bench_curve_sdf(ctx);
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
            p[2] = 0.25 + 0.3 * sin(DFL_PI * x) * sin(DFL_PI * y) + 0.6 * (x - 0.5) * (y - 0.5);
        }
    dfl_surface patch;
    dfl_surface_set set;
    if (dfl_surface_init(4, 4, 6, 6, cp, NULL, 0, NULL, 0, &patch, &err) != DFL_OK ||
        dfl_surface_set_init(1, &patch, &set, &err) != DFL_OK) {
        fprintf(stderr, "bench_footpoint: %s\n", err.msg);
        return;
    }
    for (int i = 0; i < NPTS; i++) {
        pts[3 * i] = -0.2 + 1.4 * dfl_rng_lcg(&seed);
        pts[3 * i + 1] = -0.2 + 1.4 * dfl_rng_lcg(&seed);
        pts[3 * i + 2] = -0.4 + 1.4 * dfl_rng_lcg(&seed);
    }
    dfl_surface_locator *L[2] = {NULL, NULL};
    for (int b = 0; b < 2; b++) {
        dfl_foot_opts o;
        dfl_foot_opts_default(&o);
        o.backend = b ? DFL_FOOT_CERES : DFL_FOOT_NEWTON;
        if (dfl_surface_locator_new(&set, &o, &L[b], &err) != DFL_OK) {
            fprintf(stderr, "bench_footpoint: %s\n", err.msg);
            dfl_surface_locator_free(L[0]);
            dfl_surface_set_free(&set);
            return;
        }
    }
    foot_job sj[2] = {{surface_foot, L[0], pts, 0}, {surface_foot, L[1], pts, 0}};
    compare_backends("bspline_surface", sj);
    for (int b = 0; b < 2; b++) dfl_surface_locator_free(L[b]);
    dfl_surface_set_free(&set);

    /* implicit torus R = 0.5, r = 0.2 */
    const double c[3] = {0, 0, 0}, ax[3] = {0, 0, 1};
    dfl_implicit *tor = NULL;
    if (dfl_implicit_torus(c, ax, 0.5, 0.2, NULL, &tor, &err) != DFL_OK) {
        fprintf(stderr, "bench_footpoint: %s\n", err.msg);
        return;
    }
    for (int i = 0; i < NPTS; i++)
        for (int k = 0; k < 3; k++) pts[3 * i + k] = -1.0 + 2.0 * dfl_rng_lcg(&seed);
    const imp_ctx ic[2] = {{tor, DFL_FOOT_NEWTON}, {tor, DFL_FOOT_CERES}};
    foot_job ij[2] = {{implicit_foot, &ic[0], pts, 0}, {implicit_foot, &ic[1], pts, 0}};
    compare_backends("implicit_torus", ij);
    dfl_implicit_free(tor);
}
