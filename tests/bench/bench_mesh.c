/* Mesh shapes (geom/mesh.h) on Wuson: exact signed and unsigned distance
 * queries per second on 2 OpenMP threads, in batches of 256 through the
 * shape's eval, beside brute force (field/meshdist.h for the distance plus
 * geom/winding.h's exact sum for the sign, the same values) on 2 threads.
 * Points: half uniform in [-1, 1]^3 (the mesh is fitted to a box of side
 * 1.6), half within 0.02 of a vertex (where the winding sum must open the
 * most clusters). */
#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench.h"
#include "core/rng.h"
#include "field/meshdist.h"
#include "geom/mesh.h"
#include "geom/trimesh.h"
#include "geom/winding.h"
#include "io/manifest.h"

#define WUSON "/usr/share/assimp/models/AC/Wuson.ac"
#define THREADS 2
#define BATCH 256

typedef struct mesh_job {
    const dfl_shape *s;
    const dfl_trimesh *m;
    size_t n;
    const double *pts;
    double *val;
} mesh_job;

static void run_shape(void *arg)
{
    mesh_job *j = arg;
    const long nb = (long)((j->n + BATCH - 1) / BATCH);
#pragma omp parallel for num_threads(THREADS) schedule(dynamic, 4)
    for (long b = 0; b < nb; b++) {
        size_t i0 = (size_t)b * BATCH, m = j->n - i0 < BATCH ? j->n - i0 : BATCH;
        dfl_shape_eval(j->s, m, j->pts + 3 * i0, j->val + i0, NULL);
    }
}

static void run_brute(void *arg)
{
    mesh_job *j = arg;
#pragma omp parallel for num_threads(THREADS) schedule(dynamic, 4)
    for (long i = 0; i < (long)j->n; i++) {
        const double *x = j->pts + 3 * i;
        double d = dfl_meshdist_eval(j->m, x);
        j->val[i] = dfl_winding_brute(j->m->verts, j->m->tris, j->m->ntris, x) > 0.5 ? -d : d;
    }
}

void bench_mesh(bench_ctx *ctx)
{
    (void)ctx;
    dfl_trimesh m;
    dfl_err err;
    double t0 = dfl_wall_seconds();
    if (dfl_trimesh_read(WUSON, &m, &err) != DFL_OK) {
        fprintf(stderr, "bench_mesh: %s\n", err.msg);
        return;
    }
    const double c[3] = {0, 0, 0};
    dfl_trimesh_fit(&m, c, 1.6);
    dfl_trimesh copy = m;
    copy.verts = malloc(3 * m.nverts * sizeof *copy.verts);
    copy.tris = malloc(3 * m.ntris * sizeof *copy.tris);
    for (size_t i = 0; i < 3 * m.nverts; i++) copy.verts[i] = m.verts[i];
    for (size_t i = 0; i < 3 * m.ntris; i++) copy.tris[i] = m.tris[i];
    dfl_shape sg, su;
    if (dfl_shape_mesh(&m, DFL_MESH_SIGNED, &sg, &err) != DFL_OK) {
        fprintf(stderr, "bench_mesh: %s\n", err.msg);
        return;
    }
    const double build = dfl_wall_seconds() - t0;
    dfl_trimesh m2 = copy;
    m2.verts = malloc(3 * copy.nverts * sizeof *m2.verts);
    m2.tris = malloc(3 * copy.ntris * sizeof *m2.tris);
    for (size_t i = 0; i < 3 * copy.nverts; i++) m2.verts[i] = copy.verts[i];
    for (size_t i = 0; i < 3 * copy.ntris; i++) m2.tris[i] = copy.tris[i];
    if (dfl_shape_mesh(&m2, DFL_MESH_UNSIGNED, &su, &err) != DFL_OK) return;
    bench_report("mesh.wuson.load_and_build", build, "s");

    const size_t N = 400000, NB = 4000;
    double *pts = malloc(3 * N * sizeof *pts), *val = malloc(N * sizeof *val);
    uint64_t r = 42;
    for (size_t i = 0; i < N; i++) {
        if (i % 2 == 0) {
            for (int j = 0; j < 3; j++) pts[3 * i + j] = dfl_rng_splitmix(&r, -1, 1);
        } else {
            size_t v = (size_t)dfl_rng_splitmix(&r, 0, (double)copy.nverts);
            for (int j = 0; j < 3; j++)
                pts[3 * i + j] = copy.verts[3 * v + j] + dfl_rng_splitmix(&r, -0.02, 0.02);
        }
    }
    mesh_job js = {&sg, &copy, N, pts, val}, ju = {&su, &copy, N, pts, val};
    mesh_job jb = {&sg, &copy, NB, pts, val};
    const double ts = bench_best(3, run_shape, &js);
    const double tu = bench_best(3, run_shape, &ju);
    const double tb = bench_best(1, run_brute, &jb);
    bench_pair("mesh.wuson.signed_2threads", N / ts, NB / tb, "queries/s");
    bench_report("mesh.wuson.unsigned_2threads", N / tu, "queries/s");
    free(pts);
    free(val);
    dfl_shape_free(&sg);
    dfl_shape_free(&su);
    dfl_trimesh_free(&copy);
}
