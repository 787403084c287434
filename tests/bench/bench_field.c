/* Grid sampling of the exact circle field through the batched, OpenMP
 * sampler, against a naive serial loop calling the field once per point. */
#include <math.h>
#include <stdlib.h>

#include "bench.h"
#include "field/exact.h"
#include "field/sample.h"
#include "geom/shape.h"

typedef struct job {
    dfl_field *f;
    dfl_grid g;
    double *v, *gr;
} job;

static void run_sampler(void *a)
{
    job *j = a;
    dfl_field_sample(j->f, &j->g, 0, j->v, j->gr, NULL);
}

static void run_naive(void *a)
{
    job *j = a;
    size_t m = dfl_grid_size(&j->g);
    for (size_t i = 0; i < m; i++) {
        double x[3];
        dfl_grid_node(&j->g, i, x);
        j->v[i] = dfl_field_eval1(j->f, x, j->gr + 2 * i);
    }
}

void bench_field(bench_ctx *ctx)
{
    (void)ctx;
    dfl_shape s;
    dfl_field f;
    const double c[2] = {0.5, 0.5};
    if (dfl_shape_circle(c, 0.3, &s, NULL) != DFL_OK || dfl_field_exact_new(&s, &f, NULL) != DFL_OK)
        abort();
    job j = {&f, {2, {1024, 1024, 1}, {0, 0, 0}, {1, 1, 0}}, NULL, NULL};
    size_t m = dfl_grid_size(&j.g);
    j.v = malloc(m * sizeof *j.v);
    j.gr = malloc(2 * m * sizeof *j.gr);
    double t = bench_best(5, run_sampler, &j);
    double tn = bench_best(3, run_naive, &j);
    bench_pair("field.sample.circle.value_grad", (double)m / t, (double)m / tn, "points/s");
    free(j.v);
    free(j.gr);
    dfl_field_destroy(&f);
}
