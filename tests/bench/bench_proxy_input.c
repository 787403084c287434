/* Proxy inputs (issue 9's aims on 2 cores): proxies-input answers per
 * second for the SDF input at order 1 (no curvature) and order 2 (analytic
 * and fit curvature), the parametric torus and a random Bezier patch, and
 * the implicit torus (robust and paper footpoints), over the cell centres
 * of an N^3 grid in [-1, 1]^3, OpenMP over chunks of 256 cells (the proxy
 * builder's pattern).  Baseline in the same process: the shape's bare
 * batched SDF evaluation over the same points.  Also the failure counts of
 * the paper and the robust footpoints on the implicit torus at 16^3 and
 * 32^3 against the exact torus distance: uncertified answers and answers
 * whose distance is off by more than 1e-9. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench.h"
#include "geom/implicit.h"
#include "geom/surface_random.h"
#include "proxy/input_implicit.h"
#include "proxy/input_param.h"
#include "proxy/input_sdf.h"

#define CH 256

typedef struct job {
    const dfl_proxy_input *in;
    const dfl_shape *shape;  /* baseline: bare eval */
    size_t m;
    const double *x;
    dfl_surfpoint *o;
    double *val, *grad;
    int need_curv;
} job;

static void run_input(void *a)
{
    job *j = a;
    long nc = (long)((j->m + CH - 1) / CH);
#pragma omp parallel for schedule(dynamic, 4)
    for (long c = 0; c < nc; c++) {
        size_t i0 = (size_t)c * CH, n = j->m - i0 < CH ? j->m - i0 : CH;
        dfl_proxy_input_query(j->in, n, j->x + 3 * i0, j->need_curv, j->o + i0, NULL);
    }
}

static void run_eval(void *a)
{
    job *j = a;
    long nc = (long)((j->m + CH - 1) / CH);
#pragma omp parallel for schedule(dynamic, 4)
    for (long c = 0; c < nc; c++) {
        size_t i0 = (size_t)c * CH, n = j->m - i0 < CH ? j->m - i0 : CH;
        dfl_shape_eval(j->shape, n, j->x + 3 * i0, j->val + i0, j->grad + 3 * i0);
    }
}

static double *cell_centres(int N, size_t *m)
{
    *m = (size_t)N * N * N;
    double *x = malloc(3 * *m * sizeof *x);
    for (int k = 0; k < N; k++)
        for (int j = 0; j < N; j++)
            for (int i = 0; i < N; i++) {
                double *p = x + 3 * ((size_t)(k * N + j) * N + i);
                p[0] = -1 + (i + 0.5) * 2.0 / N;
                p[1] = -1 + (j + 0.5) * 2.0 / N;
                p[2] = -1 + (k + 0.5) * 2.0 / N;
            }
    return x;
}

static double rate(job *j, int reps) { return (double)j->m / bench_best(reps, run_input, j); }

static void failures(const dfl_proxy_input *in, const char *name, int N)
{
    size_t m;
    double *x = cell_centres(N, &m);
    dfl_surfpoint *o = malloc(m * sizeof *o);
    job j = {in, NULL, m, x, o, NULL, NULL, 1};
    run_input(&j);
    long unc = 0, wrong = 0;
    for (size_t i = 0; i < m; i++) {
        const double *p = x + 3 * i;
        double want = hypot(hypot(p[0], p[1]) - 0.6, p[2]) - 0.25;
        unc += !o[i].certified;
        wrong += !(fabs(o[i].d - want) <= 1e-9);
    }
    char col[128];
    snprintf(col, sizeof col, "proxy_input.implicit_torus.%s.%d3.uncertified", name, N);
    bench_report(col, (double)unc, "points");
    snprintf(col, sizeof col, "proxy_input.implicit_torus.%s.%d3.wrong_distance", name, N);
    bench_report(col, (double)wrong, "points");
    free(x);
    free(o);
}

void bench_proxy_input(bench_ctx *ctx)
{
    (void)ctx;
    const double c[3] = {0, 0, 0}, ax[3] = {0, 0, 1}, R = 0.6, r = 0.25;
    size_t m;
    double *x = cell_centres(64, &m);
    dfl_surfpoint *o = malloc(m * sizeof *o);
    double *val = malloc(m * sizeof *val), *grad = malloc(3 * m * sizeof *grad);
    dfl_shape base, s1, s2;
    if (dfl_shape_torus(c, ax, R, r, &base, NULL) != DFL_OK ||
        dfl_shape_torus(c, ax, R, r, &s1, NULL) != DFL_OK ||
        dfl_shape_torus(c, ax, R, r, &s2, NULL) != DFL_OK)
        return;
    dfl_proxy_input sdf_a, sdf_f;
    dfl_curvfit_opts fit = {5, 0.01, 0, 0};
    dfl_proxy_input_sdf(&s1, DFL_PROXY_CURV_ANALYTIC, NULL, &sdf_a, NULL);
    dfl_proxy_input_sdf(&s2, DFL_PROXY_CURV_FIT, &fit, &sdf_f, NULL);
    job j = {&sdf_a, &base, m, x, o, val, grad, 0};
    double base_rate = (double)m / bench_best(5, run_eval, &j);
    bench_pair("proxy_input.sdf.torus.order1", rate(&j, 5), base_rate, "proxies/s");
    j.need_curv = 1;
    bench_pair("proxy_input.sdf.torus.order2_analytic", rate(&j, 3), base_rate, "proxies/s");
    j.in = &sdf_f;
    j.m = m / 8;
    bench_pair("proxy_input.sdf.torus.order2_fit", rate(&j, 3), base_rate, "proxies/s");

    dfl_proxy_input par, bez, imp_r, imp_p;
    dfl_surface_set set;
    dfl_implicit *i1, *i2;
    dfl_proxy_input_param_torus(c, ax, R, r, NULL, &par, NULL);
    dfl_surface_random_bezier(1, 4, 0.8, 0.4, &set, NULL);
    dfl_proxy_input_param_surfaces(&set, NULL, &bez, NULL);
    dfl_implicit_torus(c, ax, R, r, NULL, &i1, NULL);
    dfl_implicit_torus(c, ax, R, r, NULL, &i2, NULL);
    dfl_proxy_input_implicit(&i1, DFL_IMPLICIT_FOOT_ROBUST, &imp_r, NULL);
    dfl_proxy_input_implicit(&i2, DFL_IMPLICIT_FOOT_PAPER, &imp_p, NULL);
    j.in = &par;
    j.m = m / 8;
    bench_pair("proxy_input.parametric.torus.order2", rate(&j, 3), base_rate, "proxies/s");
    j.in = &bez;
    bench_pair("proxy_input.parametric.random_bezier.order2", rate(&j, 3), base_rate,
               "proxies/s");
    j.in = &imp_r;
    j.m = m / 32;
    bench_pair("proxy_input.implicit.torus.robust.order2", rate(&j, 2), base_rate, "proxies/s");
    j.in = &imp_p;
    bench_pair("proxy_input.implicit.torus.paper.order2", rate(&j, 2), base_rate, "proxies/s");
    for (int N = 16; N <= 32; N *= 2) {
        failures(&imp_p, "paper", N);
        failures(&imp_r, "robust", N);
    }
    dfl_proxy_input_free(&sdf_a);
    dfl_proxy_input_free(&sdf_f);
    dfl_proxy_input_free(&par);
    dfl_proxy_input_free(&bez);
    dfl_proxy_input_free(&imp_r);
    dfl_proxy_input_free(&imp_p);
    dfl_shape_free(&base);
    free(x);
    free(o);
    free(val);
    free(grad);
}
