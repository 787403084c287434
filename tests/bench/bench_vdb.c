/* OpenVDB as a peer (field/vdb.h), issue 19's setting: the torus R = 0.6,
 * r = 0.25 in [-1, 1]^3 at 8.65 MB (the proxy grid of order 2, float
 * storage, 64^3 cells: 64^3 (8 x 4 + 1) bytes), queries in the
 * near-surface band |d| <= 0.05.
 *
 *   vdb.fill.direct        active voxels / s of the direct fill (exact SDF)
 *   vdb.fill.direct.per_cpu_second  the same per CPU-second of the process
 *                          (OpenVDB's threads): the peer the summary's
 *                          proxy_build_param / _implicit rows get
 *   vdb.fill.mesh          active voxels / s of meshToLevelSet (the torus'
 *                          marching-cubes mesh on the voxel lattice, its
 *                          polygonization not timed)
 *   vdb.query.box / .quadratic (and .grad)   queries / s, with the error
 *                          (max and RMS |u - d|) beside
 *   proxy.torus.query.hermite / .nearest     dflab's proxy decode on the
 *                          same points, same run, same chunks and threads
 *   *.one_thread_per_cpu_second   the value queries on one thread per
 *                          CPU-second, best of 5: the summary's
 *                          proxy_decode_* rows (both sides so measured)
 *
 * The grid's band must hold |d| <= 0.05 plus the samplers' reach (2.5
 * voxels per axis with the gradient's half steps, 2.5 sqrt(3) voxels in
 * the worst direction), so band = ceil(0.05 / voxel + 4.5); the voxel is
 * the one (bisection) whose grid takes 8.65 MB (dfl_vdb_bytes). */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "bench.h"
#include "field/exact.h"
#include "field/isomesh.h"
#include "field/vdb.h"
#include "geom/shape.h"
#include "proxy/filter.h"
#include "proxy/input_sdf.h"
#include "proxy/proxy.h"

#define NQ (1 << 20)
#define QCHUNK 256
static const double kR = 0.6, kr = 0.25, kBandD = 0.05;
static const double kBytes = 64.0 * 64 * 64 * 33; /* 8,650,752 */

static dfl_shape torus(void)
{
    const double c[3] = {0, 0, 0}, ax[3] = {0, 0, 1};
    dfl_shape s;
    if (dfl_shape_torus(c, ax, kR, kr, &s, NULL) != DFL_OK) abort();
    return s;
}

static int band_for(double h) { return (int)ceil(kBandD / h + 4.5); }

static dfl_vdb *build_direct(const dfl_shape *s, double h)
{
    dfl_vdb_opts o;
    dfl_vdb_opts_default(&o);
    o.voxel = h;
    o.band = band_for(h);
    dfl_vdb *g = NULL;
    if (dfl_vdb_from_shape(s, &o, &g, NULL) != DFL_OK) abort();
    return g;
}

/* The voxel whose grid takes kBytes (bytes fall as the voxel grows). */
static double voxel_at_bytes(const dfl_shape *s)
{
    double lo = 0.002, hi = 0.05;
    for (int it = 0; it < 14; it++) {
        const double mid = sqrt(lo * hi);
        dfl_vdb *g = build_direct(s, mid);
        const double b = (double)dfl_vdb_bytes(g);
        dfl_vdb_free(g);
        if (b > kBytes) lo = mid;
        else hi = mid;
    }
    return sqrt(lo * hi);
}

typedef struct fill_job {
    const dfl_shape *s;
    const dfl_trimesh *m;
    double h;
    size_t active;
} fill_job;

static void run_direct(void *a)
{
    fill_job *j = a;
    dfl_vdb *g = build_direct(j->s, j->h);
    j->active = dfl_vdb_active_count(g);
    dfl_vdb_free(g);
}

static void run_mesh(void *a)
{
    fill_job *j = a;
    dfl_vdb_opts o;
    dfl_vdb_opts_default(&o);
    o.voxel = j->h;
    o.band = band_for(j->h);
    dfl_vdb *g = NULL;
    if (dfl_vdb_from_mesh(j->m, &o, &g, NULL) != DFL_OK) abort();
    j->active = dfl_vdb_active_count(g);
    dfl_vdb_free(g);
}

/* The torus mesh on the voxel lattice of [-1, 1]^3 (vdb_cfg.c's mesh build). */
static dfl_trimesh torus_mesh(double h)
{
    dfl_shape s = torus();
    dfl_field f;
    if (dfl_field_exact_new(&s, &f, NULL) != DFL_OK) abort();
    dfl_grid g = {3, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    for (int a = 0; a < 3; a++) {
        const double l = floor(-1 / h), u = ceil(1 / h);
        g.n[a] = (int)(u - l) + 1;
        g.lo[a] = l * h;
        g.hi[a] = u * h;
    }
    dfl_trimesh m;
    if (dfl_field_isomesh(&f, &g, 30, 0, &m, NULL, NULL) != DFL_OK) abort();
    dfl_field_destroy(&f);
    return m;
}

typedef struct query_job {
    const dfl_vdb *g;
    dfl_vdb_sampler smp;
    const dfl_proxy_grid *pg;
    dfl_proxy_filter_opts po;
    const double *x;
    double *v, *gr;
    int grad;
} query_job;

static void run_vdb(void *a)
{
    query_job *j = a;
#pragma omp parallel for schedule(static)
    for (size_t k = 0; k < NQ / QCHUNK; k++)
        dfl_vdb_sample(j->g, j->smp, QCHUNK, j->x + 3 * k * QCHUNK, j->v + k * QCHUNK,
                       j->grad ? j->gr + 3 * k * QCHUNK : NULL);
}

static void run_proxy(void *a)
{
    query_job *j = a;
#pragma omp parallel for schedule(static)
    for (size_t k = 0; k < NQ / QCHUNK; k++)
        dfl_proxy_filter_eval(j->pg, &j->po, QCHUNK, j->x + 3 * k * QCHUNK, j->v + k * QCHUNK,
                              j->grad ? j->gr + 3 * k * QCHUNK : NULL);
}

/* Points of the band |d| <= 0.05 with their exact d: on the torus at
 * angles (u, v) pushed by s along the normal, all three from a
 * deterministic sequence (a shuffled order: queries follow no lattice). */
static void band_points(double *x, double *d)
{
    uint64_t st = 0x9e3779b97f4a7c15ull;
    for (size_t i = 0; i < NQ; i++) {
        double r3[3];
        for (int k = 0; k < 3; k++) {
            st = st * 6364136223846793005ull + 1442695040888963407ull;
            r3[k] = (double)(st >> 11) * 0x1.0p-53;
        }
        const double u = 2 * M_PI * r3[0], v = 2 * M_PI * r3[1], s = kBandD * (2 * r3[2] - 1);
        const double rho = kR + (kr + s) * cos(v);
        x[3 * i] = rho * cos(u);
        x[3 * i + 1] = rho * sin(u);
        x[3 * i + 2] = (kr + s) * sin(v);
        d[i] = s;
    }
}

static void errors(const double *v, const double *d, double *linf, double *rms)
{
    double m = 0, q = 0;
    for (size_t i = 0; i < NQ; i++) {
        const double e = isfinite(v[i]) ? fabs(v[i] - d[i]) : INFINITY;
        m = fmax(m, e);
        q += e * e;
    }
    *linf = m;
    *rms = sqrt(q / NQ);
}

/* Prints the rate and errors; returns the rate (queries/s). */
/* Queries per CPU-second of fn on one thread, best of 5 (the summary's
 * unit: on a shared machine a 2-thread team's wall time waits for its
 * slower thread, so wall-clock ratios swung 2.6-3.4x between runs). */
static double one_thread_rate(const char *name, query_job *j, void (*fn)(void *))
{
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    double t = INFINITY;
    for (int rep = 0; rep < 5; rep++) {
        struct timespec a0, a1;
        clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &a0);
        fn(j);
        clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &a1);
        t = fmin(t, (double)(a1.tv_sec - a0.tv_sec) + 1e-9 * (double)(a1.tv_nsec - a0.tv_nsec));
    }
    omp_set_num_threads(threads);
    char buf[160];
    snprintf(buf, sizeof buf, "%s.one_thread_per_cpu_second", name);
    bench_report(buf, NQ / t, "queries/s");
    return NQ / t;
}

static double report_query(const char *name, query_job *j, void (*fn)(void *), const double *d)
{
    char buf[160];
    const double t = bench_best(5, fn, j);
    bench_report(name, NQ / t, "queries/s");
    double linf, rms;
    errors(j->v, d, &linf, &rms);
    snprintf(buf, sizeof buf, "%s.err_max", name);
    bench_report(buf, linf, "");
    snprintf(buf, sizeof buf, "%s.err_rms", name);
    bench_report(buf, rms, "");
    return NQ / t;
}

void bench_vdb(bench_ctx *c)
{
    dfl_shape s = torus();
    const double h = voxel_at_bytes(&s);
    dfl_vdb *g = build_direct(&s, h);
    bench_report("vdb.torus.voxel", h, "");
    bench_report("vdb.torus.band", band_for(h), "voxels");
    bench_report("vdb.torus.bytes", (double)dfl_vdb_bytes(g), "B");
    bench_report("vdb.torus.active", (double)dfl_vdb_active_count(g), "voxels");
    bench_report("vdb.torus.evals_per_active",
                 (double)dfl_vdb_evals(g) / (double)dfl_vdb_active_count(g), "");

    /* builds: best of 3 */
    fill_job fj = {&s, NULL, h, 0};
    double t = bench_best(3, run_direct, &fj);
    bench_report("vdb.fill.direct", (double)fj.active / t, "voxels/s");
    /* per CPU-second (process CPU time over OpenVDB's threads, best of 3):
     * the unit of the proxy_build_* rows, whose peer this fill is */
    double fcpu = INFINITY;
    for (int rep = 0; rep < 3; rep++) {
        struct timespec a0, a1;
        clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &a0);
        run_direct(&fj);
        clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &a1);
        fcpu = fmin(fcpu, (double)(a1.tv_sec - a0.tv_sec) + 1e-9 * (double)(a1.tv_nsec - a0.tv_nsec));
    }
    const double fill_cpu = (double)fj.active / fcpu;
    bench_report("vdb.fill.direct.per_cpu_second", fill_cpu, "voxels/s");
    bench_summary_peer(c, "proxy_build_param", "OpenVDB direct fill voxels per CPU-s", fill_cpu);
    bench_summary_peer(c, "proxy_build_implicit", "OpenVDB direct fill voxels per CPU-s", fill_cpu);
    dfl_trimesh m = torus_mesh(h);
    fj.m = &m;
    bench_report("vdb.fill.mesh.triangles", (double)m.ntris, "");
    t = bench_best(3, run_mesh, &fj);
    bench_report("vdb.fill.mesh", (double)fj.active / t, "voxels/s");
    dfl_trimesh_free(&m);

    /* queries: OpenVDB's samplers and dflab's proxy decode at equal bytes,
     * interleaved on the same points */
    double *x = malloc(3 * NQ * sizeof *x), *d = malloc(NQ * sizeof *d),
           *v = malloc(NQ * sizeof *v), *gr = malloc(3 * NQ * sizeof *gr);
    if (!x || !d || !v || !gr) abort();
    band_points(x, d);
    dfl_shape s2 = torus();
    dfl_proxy_input in;
    if (dfl_proxy_input_sdf(&s2, DFL_PROXY_CURV_ANALYTIC, NULL, &in, NULL) != DFL_OK) abort();
    dfl_proxy_build_opts po;
    dfl_proxy_build_opts_default(&po);
    po.order = 2;
    po.res = 64;
    po.storage = DFL_PROXY_FLOAT;
    dfl_proxy_grid pg;
    if (dfl_proxy_grid_build(&in, &po, &pg, NULL) != DFL_OK) abort();
    bench_report("proxy.torus.bytes", (double)pg.ncells * (8 * 4 + 1), "B");
    for (int grad = 0; grad < 2; grad++) {
        static const dfl_vdb_sampler smp[2] = {DFL_VDB_BOX, DFL_VDB_QUADRATIC};
        static const dfl_proxy_filter pf[2] = {DFL_PROXY_NEAREST, DFL_PROXY_HERMITE};
        for (int k = 0; k < 2; k++) {
            char name[128];
            query_job j = {g, smp[k], &pg, {0}, x, v, gr, grad};
            snprintf(name, sizeof name, "vdb.query.%s%s", dfl_vdb_sampler_name(smp[k]),
                     grad ? ".grad" : "");
            report_query(name, &j, run_vdb, d);
            const double rv1 = grad ? NAN : one_thread_rate(name, &j, run_vdb);
            dfl_proxy_filter_opts_default(pf[k], &pg, &j.po);
            j.po.is_signed = 1;
            snprintf(name, sizeof name, "proxy.torus.query.%s%s", dfl_proxy_filter_name(pf[k]),
                     grad ? ".grad" : "");
            report_query(name, &j, run_proxy, d);
            /* issue 19's peer rows: dflab's decode against OpenVDB's sampler at
             * (about) equal bytes on the same band points, value only, one
             * thread per CPU-second on both sides */
            if (!grad) {
                const double rp1 = one_thread_rate(name, &j, run_proxy);
                bench_summary_add(c, k ? "proxy_decode_hermite_vs_vdb" : "proxy_decode_nearest_vs_vdb",
                                  rp1, k ? "OpenVDB QuadraticSampler 1 thread"
                                         : "OpenVDB BoxSampler 1 thread",
                                  rv1, rp1 / rv1, NAN);
            }
        }
    }
    dfl_proxy_grid_free(&pg);
    dfl_proxy_input_free(&in);
    free(x), free(d), free(v), free(gr);
    dfl_vdb_free(g);
    dfl_shape_free(&s);
}
