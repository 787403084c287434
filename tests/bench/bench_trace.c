/* A 512^2 sphere-traced frame (field/trace.h) of the order-2 proxy grid of
 * the hvb25 torus (SDF input, 32^3, half storage) per decoding filter,
 * beside the same frame of the exact torus SDF (the baseline: what the
 * proxy decoding costs over an analytic distance).  Aim: nearest <= 0.5 s. */
#include <stdio.h>
#include <stdlib.h>

#include "bench.h"
#include "field/exact.h"
#include "field/trace.h"
#include "hvb25/hvb25_eval.h"
#include "proxy/input_sdf.h"

typedef struct job {
    const dfl_field *f;
    dfl_camera cam;
    dfl_trace_opts o;
    size_t evals;
} job;

static void run_frame(void *a)
{
    job *j = a;
    dfl_frame fr;
    if (dfl_trace_frame(j->f, &j->cam, &j->o, &fr, NULL) != DFL_OK) abort();
    j->evals = fr.evals;
    dfl_frame_free(&fr);
}

static void torus(dfl_shape *s)
{
    const double c[3] = {0, 0, 0}, ax[3] = {0, 0, 1};
    if (dfl_shape_torus(c, ax, 0.6, 0.25, s, NULL) != DFL_OK) abort();
}

void bench_trace(bench_ctx *ctx)
{
    (void)ctx;
    dfl_shape s;
    dfl_field exact;
    torus(&s);
    if (dfl_field_exact_new(&s, &exact, NULL) != DFL_OK) abort();
    job j = {&exact,
             {{1.6, -2.2, 1.4}, {0, 0, 0}, {0, 0, 1}, 40.0, 512, 512},
             {8.0, 1e-4, 1.0, 256, 1, {-1, -1, -1}, {1, 1, 1}, 0},
             0};
    const double tx = bench_best(3, run_frame, &j);
    bench_report("trace.frame512.exact_torus", tx, "s");

    torus(&s);
    dfl_proxy_input in;
    if (dfl_proxy_input_sdf(&s, DFL_PROXY_CURV_ANALYTIC, NULL, &in, NULL) != DFL_OK) abort();
    dfl_proxy_build_opts bo;
    dfl_proxy_build_opts_default(&bo);
    bo.order = 2, bo.res = 32, bo.storage = DFL_PROXY_HALF;
    dfl_proxy_grid g;
    if (dfl_proxy_grid_build(&in, &bo, &g, NULL) != DFL_OK) abort();
    dfl_proxy_input_free(&in);
    for (int k = 0; k < DFL_PROXY_FILTER_COUNT; k++) {
        hvb25_view v = {&g, {0}};
        dfl_proxy_filter_opts_default((dfl_proxy_filter)k, &g, &v.o);
        dfl_field f;
        hvb25_view_field(&v, &f);
        j.f = &f;
        const double t = bench_best(3, run_frame, &j);
        char name[96];
        snprintf(name, sizeof name, "trace.frame512.proxy2_torus32.%s",
                 dfl_proxy_filter_name((dfl_proxy_filter)k));
        bench_report(name, t, "s");
        snprintf(name, sizeof name, "trace.frame512.proxy2_torus32.%s.vs_exact",
                 dfl_proxy_filter_name((dfl_proxy_filter)k));
        bench_report(name, t / tx, "x");
        snprintf(name, sizeof name, "trace.frame512.proxy2_torus32.%s.queries",
                 dfl_proxy_filter_name((dfl_proxy_filter)k));
        bench_report(name, (double)j.evals / t, "queries/s");
    }
    dfl_proxy_grid_free(&g);
    dfl_field_destroy(&exact);
}
