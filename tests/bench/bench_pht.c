/* PHT splines (src/pht): fit time and degrees of freedom, evaluation
 * throughput, memory per cell.
 *
 *   pht.fit.circle.eps1e-5          full adaptive fit of the circle (r 0.3 in the
 *                                   unit square): time, cells, dofs, max error
 *   pht.fit.blob.eps1e-5.L10        the non-convex closed cubic of
 *                                   configs/shapes/blob.ini, eps 1e-5 capped at
 *                                   max_level 10 (a full 1e-5 fit refines the medial
 *                                   axis, a curve, to ~1e5 cells: minutes, all in
 *                                   geom's footpoints); the footpoint rate beside it
 *                                   extrapolates
 *   pht.fit.oval.eps1e-5.L10        a convex closed cubic (8 points on an ellipse
 *                                   0.4 x 0.25), same protocol
 *   pht.fit.torus.eps1e-3           the analytic torus R 0.3, r 0.1 in the unit cube
 *   pht.eval.*.value_grad           batched evaluation (value + gradient) over 2^20
 *                                   random points, OpenMP over chunks, against the
 *                                   naive one-point loop (dfl_field_eval1) and, for
 *                                   the blob, against the exact SDF it replaces
 *   pht.bytes_per_cell.*            spline memory / cells (memory ~ cells)
 * Aims (issue 8): 2D fits <= 1 s, >= 3e7 evaluations/s on 2 cores. */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench.h"
#include "core/rng.h"
#include "field/exact.h"
#include "geom/param_shape.h"
#include "geom/shape.h"
#include "io/manifest.h"
#include "pht/fit.h"
#include "pht/pht_field.h"

#define NEVAL (1 << 20)
#define CHUNK 1024

static const double BLOB[] = {0.9, 0.5,  0.85, 0.85, 0.5, 0.9,  0.15, 0.85,
                              0.1, 0.5,  0.2,  0.15, 0.5, 0.45, 0.8,  0.15};

static void oval_points(double *cp)
{
    for (int i = 0; i < 8; i++) {
        double a = 2 * 3.14159265358979323846 * i / 8;
        cp[2 * i] = 0.5 + 0.4 * cos(a);
        cp[2 * i + 1] = 0.5 + 0.25 * sin(a);
    }
}

static dfl_shape closed_curve(const double *cp)
{
    dfl_bspline c;
    dfl_shape s;
    if (dfl_bspline_init_periodic(2, 4, 8, cp, NULL, 0, &c, NULL) != DFL_OK ||
        dfl_shape_param_curve(&c, NULL, 1, &s, NULL) != DFL_OK)
        abort();
    return s;
}

typedef struct eval_job {
    const dfl_field *f;
    const double *pts;
    double *val, *grad;
    size_t n;
} eval_job;

static void run_batched(void *a)
{
    eval_job *j = a;
    const int dim = j->f->dim;
    size_t nch = (j->n + CHUNK - 1) / CHUNK;
#pragma omp parallel for schedule(static)
    for (size_t c = 0; c < nch; c++) {
        size_t i0 = c * CHUNK, m = j->n - i0 < CHUNK ? j->n - i0 : CHUNK;
        j->f->ops->eval(j->f->ctx, m, j->pts + i0 * dim, j->val + i0, j->grad + i0 * dim);
    }
}

static void run_naive(void *a)
{
    eval_job *j = a;
    const int dim = j->f->dim;
    for (size_t i = 0; i < j->n; i++)
        j->val[i] = dfl_field_eval1(j->f, j->pts + i * dim, j->grad + i * dim);
}

static double cpu_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double *random_points(int dim, size_t n, uint64_t seed)
{
    double *p = malloc(n * (size_t)dim * sizeof *p);
    for (size_t i = 0; i < n * (size_t)dim; i++) p[i] = dfl_rng_splitmix(&seed, 0, 1);
    return p;
}

/* Fits s, reports, and returns the spline as a field. */
static dfl_field fit_report(const char *name, const dfl_shape *s, double eps, int max_level)
{
    dfl_pht_source *src;
    dfl_pht_fit_opts o;
    dfl_pht_fit f;
    dfl_field fld;
    if (dfl_pht_source_new(s, &src, NULL) != DFL_OK) abort();
    dfl_pht_fit_opts_default(s->dim, &o);
    o.eps = eps;
    o.max_level = max_level;
    double t0 = dfl_wall_seconds();
    if (dfl_pht_fit_run(src, &o, &f, NULL) != DFL_OK) abort();
    double t = dfl_wall_seconds() - t0, tf = 0;
    for (int k = 0; k < f.nlevels; k++) tf += f.levels[k].t_foot;
    const dfl_pht_level *last = &f.levels[f.nlevels - 1];
    char buf[160];
    snprintf(buf, sizeof buf, "pht.fit.%s.time", name);
    bench_report(buf, t, "s");
    snprintf(buf, sizeof buf, "pht.fit.%s.footpoint_share", name);
    bench_report(buf, tf / t, "of the time");
    snprintf(buf, sizeof buf, "pht.fit.%s.cells", name);
    bench_report(buf, (double)last->cells, "cells");
    snprintf(buf, sizeof buf, "pht.fit.%s.dofs", name);
    bench_report(buf, (double)last->dofs, "scalars");
    snprintf(buf, sizeof buf, "pht.fit.%s.max_err", name);
    bench_report(buf, last->max_err, "(estimator)");
    snprintf(buf, sizeof buf, "pht.fit.%s.converged", name);
    bench_report(buf, f.converged, "(1 = eps met)");
    snprintf(buf, sizeof buf, "pht.bytes_per_cell.%s", name);
    bench_report(buf, (double)dfl_pht_spline_bytes(f.spline) / (double)last->cells, "bytes");
    if (dfl_pht_field_new(&f.spline, &fld, NULL) != DFL_OK) abort();
    dfl_pht_fit_free(&f);
    dfl_pht_source_free(src);
    return fld;
}

/* Operations of one value + gradient evaluation (pht/spline.c eval2_vg,
 * eval3_vg; the cell location is not counted): per Horner cubic H3 3 mul + 3 add, its
 * derivative D3 4 mul + 2 add.  2D: the local coordinates (2 sub, 2 mul),
 * H3 and D3 of 4 rows in u, H3 of both in v and D3 of the values in v, 2
 * scalings.  3D: the local coordinates (3, 3), H3 and D3 of 16 rows in u,
 * H3 (of both) and D3 (of the values) of 4 rows in v, then H3 x 3 and D3
 * in w, 3 scalings. */
static bench_ops eval_ops(int dim)
{
    if (dim == 2) return (bench_ops){2 + 4 * 7 + 3 + 3 + 4 + 2, 2 + 4 * 5 + 3 + 3 + 2, 0, 0};
    return (bench_ops){3 + 16 * 7 + 4 * 10 + 3 * 3 + 4 + 3, 3 + 16 * 5 + 4 * 8 + 3 * 3 + 2, 0, 0};
}

static void eval_report(bench_ctx *c, const char *name, const dfl_field *f,
                        const dfl_field *exact)
{
    eval_job j = {f, random_points(f->dim, NEVAL, 11), NULL, NULL, NEVAL};
    j.val = malloc(NEVAL * sizeof *j.val);
    j.grad = malloc(NEVAL * (size_t)f->dim * sizeof *j.grad);
    double t = bench_best(5, run_batched, &j);
    /* CPU time of one batched run: the machine is shared, so wall-clock rates
     * undercount; points per CPU-second times the threads is what the
     * cores deliver when they are ours */
    double c0 = cpu_seconds();
    run_batched(&j);
    double cpu = cpu_seconds() - c0;
    char buf[160];
    snprintf(buf, sizeof buf, "pht.eval.%s.value_grad.per_cpu_second", name);
    bench_report(buf, NEVAL / cpu, "points/s");
    snprintf(buf, sizeof buf, "pht.eval.%s.value_grad.per_cpu_second", name);
    const bench_ops op = eval_ops(f->dim);
    const double fp = bench_kernel_floor(c, buf, NEVAL / cpu, &op);
    if (strcmp(name, "circle") == 0 || strcmp(name, "torus") == 0)
        bench_summary_add(c, f->dim == 2 ? "pht2d_eval" : "pht3d_eval", NEVAL / cpu, NULL, NAN,
                          NAN, fp);
    snprintf(buf, sizeof buf, "pht.eval.%s.value_grad.cpu_bound_all_threads", name);
    bench_report(buf, NEVAL / cpu * omp_get_max_threads(), "points/s (aim: >= 3e7 on 2 cores)");
    snprintf(buf, sizeof buf, "pht.eval.%s.value_grad", name);
    eval_job jn = j;
    jn.n = NEVAL / 4;
    double tn = bench_best(3, run_naive, &jn) * 4;
    bench_pair(buf, NEVAL / t, NEVAL / tn, "points/s");
    if (exact) {
        eval_job je = j;
        je.f = exact;
        je.n = 4096;
        double te = bench_best(1, run_batched, &je);
        snprintf(buf, sizeof buf, "pht.eval.%s.vs_exact_sdf", name);
        bench_pair(buf, NEVAL / t, 4096 / te, "points/s");
    }
    free((void *)j.pts);
    free(j.val);
    free(j.grad);
}

void bench_pht(bench_ctx *c)
{
    bench_report("pht.threads", omp_get_max_threads(), "threads");
    dfl_shape s;
    const double c2[2] = {0.5, 0.5}, c3[3] = {0.5, 0.5, 0.5}, ax[3] = {0, 0, 1};
    if (dfl_shape_circle(c2, 0.3, &s, NULL) != DFL_OK) abort();
    dfl_field circle = fit_report("circle.eps1e-5", &s, 1e-5, 22);
    eval_report(c, "circle", &circle, NULL);
    dfl_field_destroy(&circle);
    dfl_shape_free(&s);

    s = closed_curve(BLOB);
    dfl_field blob = fit_report("blob.eps1e-5.L10", &s, 1e-5, 10);
    dfl_field exact;
    dfl_shape s2 = closed_curve(BLOB);
    if (dfl_field_exact_new(&s2, &exact, NULL) != DFL_OK) abort();
    eval_report(c, "blob", &blob, &exact);
    dfl_field_destroy(&exact);
    dfl_field_destroy(&blob);
    dfl_shape_free(&s);

    double oval[16];
    oval_points(oval);
    s = closed_curve(oval);
    dfl_field ov = fit_report("oval.eps1e-5.L10", &s, 1e-5, 10);
    dfl_field_destroy(&ov);
    dfl_shape_free(&s);

    if (dfl_shape_torus(c3, ax, 0.3, 0.1, &s, NULL) != DFL_OK) abort();
    dfl_field torus = fit_report("torus.eps1e-3", &s, 1e-3, 14);
    eval_report(c, "torus", &torus, NULL);
    dfl_field_destroy(&torus);
    dfl_shape_free(&s);
}
