/* Mesh shapes (geom/mesh.h) on Wuson: exact signed and unsigned distance
 * queries per second on 1 and 2 OpenMP threads, in batches of 256 through
 * the shape's eval, beside
 *   - brute force (field/meshdist.h for the distance plus geom/winding.h's
 *     exact sum for the sign, the same values) on 2 threads;
 *   - the previous sign test, a ladder of clustered sums at beta = 3, 6, 12
 *     (dfl_mesh_bvh_winding) then the exact sum, with the same Embree
 *     distance (the same values), on 1 and 2 threads;
 *   - OpenVDB's meshToLevelSet (field/vdb.h dfl_vdb_from_mesh) on the same
 *     mesh at voxel 1/256 of the box, band 3: active voxels (each an exact
 *     narrow-band distance) per second of the build, on OpenVDB's own
 *     threads (all cores).
 * Also the sign test alone (points per second, one thread, new and
 * ladder), which is what the signed query adds to the unsigned one.
 * Points: half uniform in [-1, 1]^3 (the mesh is fitted to a box of side
 * 1.6), half within 0.02 of a vertex (where the winding sum must open the
 * most clusters). */
#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench.h"
#include "core/rng.h"
#include "field/meshdist.h"
#include "field/vdb.h"
#include "geom/mesh_anchor.h"
#include "geom/mesh_bvh.h"
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
    int threads;
    const dfl_mesh_bvh *bvh; /* the ladder peer and the sign-only runs */
} mesh_job;

static void run_shape(void *arg)
{
    mesh_job *j = arg;
    const long nb = (long)((j->n + BATCH - 1) / BATCH);
#pragma omp parallel for num_threads(j->threads) schedule(dynamic, 4)
    for (long b = 0; b < nb; b++) {
        size_t i0 = (size_t)b * BATCH, m = j->n - i0 < BATCH ? j->n - i0 : BATCH;
        dfl_shape_eval(j->s, m, j->pts + 3 * i0, j->val + i0, NULL);
    }
}

/* The sign test before the adaptive traversal (geom/mesh_bvh.h's history):
 * beta = 3, 6, 12, the first with |w - 1/2| > bound + 1e-9, else the exact
 * sum. */
static int ladder_inside(const dfl_mesh_bvh *b, const dfl_trimesh *m, const double *x)
{
    static const double betas[] = {DFL_MESH_WINDING_BETA, 2 * DFL_MESH_WINDING_BETA,
                                   4 * DFL_MESH_WINDING_BETA};
    for (size_t k = 0; k < 3; k++) {
        double B;
        const double w = dfl_mesh_bvh_winding(b, x, betas[k], &B);
        if (fabs(w - 0.5) > B + 1e-9) return w > 0.5;
    }
    return dfl_winding_brute(m->verts, m->tris, m->ntris, x) > 0.5;
}

/* The shape's eval with the ladder for the sign (same values). */
static void run_ladder(void *arg)
{
    mesh_job *j = arg;
#pragma omp parallel for num_threads(j->threads) schedule(dynamic, 1024)
    for (long i = 0; i < (long)j->n; i++) {
        const double *x = j->pts + 3 * i;
        dfl_mesh_hit h;
        dfl_mesh_bvh_closest(j->bvh, x, &h);
        j->val[i] = h.d > 0.0 && ladder_inside(j->bvh, j->m, x) ? -h.d : h.d;
    }
}

static void run_sign_ladder(void *arg)
{
    mesh_job *j = arg;
    for (size_t i = 0; i < j->n; i++) j->val[i] = ladder_inside(j->bvh, j->m, j->pts + 3 * i);
}

static void run_sign(void *arg)
{
    mesh_job *j = arg;
    for (size_t i = 0; i < j->n; i++) j->val[i] = dfl_mesh_bvh_inside(j->bvh, j->pts + 3 * i);
}

static void run_sign_traversal(void *arg)
{
    mesh_job *j = arg;
    for (size_t i = 0; i < j->n; i++) j->val[i] = dfl_mesh_bvh_inside_traversal(j->bvh, j->pts + 3 * i);
}

/* CPU seconds of the calling thread for fn(arg) (one-thread jobs run on
 * it): on a machine shared beyond its cores, wall time counts the waits. */
static double thread_cpu(void (*fn)(void *), void *arg)
{
    struct timespec a, b;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &a);
    fn(arg);
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &b);
    return (double)(b.tv_sec - a.tv_sec) + 1e-9 * (double)(b.tv_nsec - a.tv_nsec);
}

typedef struct vdb_job {
    const dfl_trimesh *m;
    size_t active;
} vdb_job;

static void run_vdb(void *arg)
{
    vdb_job *j = arg;
    dfl_vdb_opts o;
    dfl_vdb_opts_default(&o);
    o.voxel = 1.6 / 256;
    o.band = 3;
    for (int a = 0; a < 3; a++) {
        o.lo[a] = -0.8;
        o.hi[a] = 0.8;
    }
    dfl_vdb *g = NULL;
    if (dfl_vdb_from_mesh(j->m, &o, &g, NULL) != DFL_OK) abort();
    j->active = dfl_vdb_active_count(g);
    dfl_vdb_free(g);
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
    dfl_mesh_bvh *bv;
    const double tb0 = dfl_wall_seconds();
    if (dfl_mesh_bvh_new(copy.verts, copy.nverts, copy.tris, copy.ntris, &bv, &err) != DFL_OK) {
        fprintf(stderr, "bench_mesh: %s\n", err.msg);
        return;
    }
    dfl_mesh_bvh_anchors(bv); /* built on first use: here, inside the timing */
    bench_report("mesh.wuson.bvh_and_anchors_build", dfl_wall_seconds() - tb0, "s");
    {   /* the anchors (geom/mesh_anchor.h): size, and the share of the
         * bench's points whose sign they decide (the rest: the traversal) */
        size_t leaves, bytes, dec[2] = {0, 0};
        dfl_mesh_anchor_stats(dfl_mesh_bvh_anchors(bv), &leaves, &bytes);
        bench_report("mesh.wuson.anchors.leaves", (double)leaves, "cells");
        bench_report("mesh.wuson.anchors.bytes", (double)bytes, "bytes");
        for (size_t i = 0; i < N; i++) {
            int in;
            dec[i % 2] += dfl_mesh_anchor_decide(dfl_mesh_bvh_anchors(bv), pts + 3 * i, &in);
        }
        bench_report("mesh.wuson.anchors.decided_uniform", dec[0] / (0.5 * N), "fraction");
        bench_report("mesh.wuson.anchors.decided_near_vertex", dec[1] / (0.5 * N), "fraction");
    }
    for (int th = 1; th <= THREADS; th++) {
        char name[64];
        mesh_job js = {&sg, &copy, N, pts, val, th, bv}, ju = {&su, &copy, N, pts, val, th, bv};
        mesh_job jl = {&sg, &copy, N / 4, pts, val, th, bv};
        const double ts = bench_best(3, run_shape, &js);
        const double tl = bench_best(2, run_ladder, &jl);
        const double tu = bench_best(3, run_shape, &ju);
        snprintf(name, sizeof name, "mesh.wuson.signed_vs_ladder_%dthread%s", th, th > 1 ? "s" : "");
        bench_pair(name, N / ts, (N / 4) / tl, "queries/s");
        snprintf(name, sizeof name, "mesh.wuson.unsigned_%dthread%s", th, th > 1 ? "s" : "");
        bench_report(name, N / tu, "queries/s");
        snprintf(name, sizeof name, "mesh.wuson.signed_over_unsigned_%dthread%s", th, th > 1 ? "s" : "");
        bench_report(name, tu / ts, "x");
    }
    {   /* one thread, CPU time, the three runs interleaved (best of 3 each) */
        const size_t n = N / 4;
        mesh_job js1 = {&sg, &copy, n, pts, val, 1, bv}, jl1 = {&sg, &copy, n, pts, val, 1, bv},
                 ju1 = {&su, &copy, n, pts, val, 1, bv};
        double cs = INFINITY, cl = INFINITY, cu = INFINITY;
        for (int rep = 0; rep < 3; rep++) {
            cs = fmin(cs, thread_cpu(run_shape, &js1));
            cl = fmin(cl, thread_cpu(run_ladder, &jl1));
            cu = fmin(cu, thread_cpu(run_shape, &ju1));
        }
        bench_pair("mesh.wuson.signed_vs_ladder_1thread_cpu", n / cs, n / cl, "queries/s per core");
        bench_report("mesh.wuson.unsigned_1thread_cpu", n / cu, "queries/s per core");
        bench_report("mesh.wuson.signed_1thread_cpu_times_2", 2 * n / cs,
                     "queries/s (aim: >= 1e6 on 2 cores)");
    }
    {   /* the peer's values are the shape's, bit for bit */
        double *v2 = malloc((N / 4) * sizeof *v2);
        mesh_job a = {&sg, &copy, N / 4, pts, val, THREADS, bv}, l = {&sg, &copy, N / 4, pts, v2, THREADS, bv};
        run_shape(&a);
        run_ladder(&l);
        size_t diff = 0;
        for (size_t i = 0; i < N / 4; i++) diff += memcmp(val + i, v2 + i, sizeof *v2) != 0;
        bench_report("mesh.wuson.signed_vs_ladder.values_differing", (double)diff, "points");
        free(v2);
    }
    mesh_job js = {&sg, &copy, N, pts, val, THREADS, bv};
    mesh_job jb = {&sg, &copy, NB, pts, val, THREADS, bv};
    const double ts = bench_best(3, run_shape, &js);
    const double tb = bench_best(1, run_brute, &jb);
    bench_pair("mesh.wuson.signed_2threads", N / ts, NB / tb, "queries/s");
    mesh_job jg = {&sg, &copy, N / 4, pts, val, 1, bv};
    const double tg = bench_best(3, run_sign, &jg);
    const double tgl = bench_best(2, run_sign_ladder, &jg);
    bench_pair("mesh.wuson.sign_only_1thread_vs_ladder", (N / 4) / tg, (N / 4) / tgl, "points/s");
    {   /* CPU time, interleaved: with the anchors and the traversal alone */
        double ca = INFINITY, ct = INFINITY;
        for (int rep = 0; rep < 3; rep++) {
            ca = fmin(ca, thread_cpu(run_sign, &jg));
            ct = fmin(ct, thread_cpu(run_sign_traversal, &jg));
        }
        bench_pair("mesh.wuson.sign_only_1thread_cpu_vs_traversal", (N / 4) / ca, (N / 4) / ct,
                   "points/s per core");
    }
    vdb_job jv = {&copy, 0};
    const double tv = bench_best(3, run_vdb, &jv);
    bench_report("mesh.wuson.vdb_mesh_to_level_set", jv.active / tv, "voxels/s");
    bench_report("mesh.wuson.vdb_mesh_to_level_set.active_voxels", (double)jv.active, "voxels");
    bench_report("mesh.wuson.signed_2threads_over_vdb_mesh_to_level_set", (N / ts) / (jv.active / tv), "x");
    dfl_mesh_bvh_free(bv);
    free(pts);
    free(val);
    dfl_shape_free(&sg);
    dfl_shape_free(&su);
    dfl_trimesh_free(&copy);
}
