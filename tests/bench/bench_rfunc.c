/* bs04 field throughput: segment evaluations per second (value + gradient)
 * of a 2D polyline of 1500 segments (disk trim, eq. 4; R-equivalence,
 * eq. 6) sampled on a 2D grid, for p = 2 and p = 7:
 *
 *   fast      rfunc/batch.h through the OpenMP grid sampler
 *             (dfl_field_sample, all threads), and on one thread
 *   library   rfunc/rfield.h (the generic field) through the same sampler
 *   naive     a scalar loop calling a function per segment, pow() for
 *             every power, one thread
 *   numpy     scripts/bench_rfunc_numpy.py, the same formulas with numpy
 *             broadcasting, run through $DFL_PYTHON (default
 *             /usr/bin/python3); its values at a few nodes are checked
 *             against the fast path (1e-12 relative), so the rates compare
 *             the same function
 *
 * and the gap to the floor: operations per segment evaluation (kernel_ops
 * below, counted from the lines of rfunc/batch_seg.c's seg_term) times the
 * one-thread rate, against the floor measured at the start of the run
 * (bench_floor.c; nothing about the CPU is assumed). */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "bench/rfunc_naive.h"
#include "core/vec.h"
#include "field/sample.h"
#include "rfunc/batch.h"
#include "rfunc/rfield.h"
#include "rfunc/tri3d.h"

#define NSEG 1500

typedef struct job {
    const dfl_field *f;
    const rfunc_naive *naive;
    dfl_grid g;
    int threads;
    double *pts, *v, *gr;
} job;

static void run_sampler(void *a)
{
    job *j = a;
    dfl_field_sample(j->f, &j->g, j->threads, j->v, j->gr, NULL);
}

static void run_naive(void *a)
{
    job *j = a;
    rfunc_naive_eval(j->naive, dfl_grid_size(&j->g), j->pts, j->v, j->gr);
}

/* Multiplications by x^k's repeated squaring (rfunc/batch.c ipow_sq). */
static int ipow_muls(int k)
{
    int n = -1;
    for (; k; k >>= 1) n += 1 + (k & 1);
    return n - 1;
}

/* Operations per segment evaluation of the fast path (value + gradient):
 * multiplications, additions/subtractions and divisions (|.| is a logic
 * operation and not counted), from the per-line counts in rfunc/batch.c's
 * seg_term; rsqrt_newton: 0.5 x, then 3 mul and 1 sub per step. */
static void kernel_ops(int p, int *mul, int *add, int *div)
{
    /*        x-a  x-b   f  -td  max  mt  mi  h^2  gx  gy   q   S   V */
    *mul = 0 + 0 + 2 + 2 + 0 + 1 + 1 + 2 + 2 + 2 + 1 + 0 + 2;
    *add = 2 + 2 + 1 + 1 + 1 + 0 + 0 + 1 + 2 + 2 + 0 + 1 + 2;
    *div = 0;
    if (p & 1) {
        *mul += 13 + 1 + (p == 1 ? 0 : ipow_muls(p / 2) + 1);
        *add += 4;
    } else {
        *div = 1;
        *mul += ipow_muls(p / 2);
    }
}

/* The numpy script's polyline (same formula). */
static void polyline(double *v)
{
    for (int i = 0; i < NSEG; i++) {
        const double th = 2.0 * DFL_PI * i / NSEG, r = 0.3 + 0.05 * sin(5.0 * th);
        v[2 * i] = 0.5 + r * cos(th);
        v[2 * i + 1] = 0.5 + r * sin(th);
    }
}

static double *grid_points(const dfl_grid *g)
{
    const size_t m = dfl_grid_size(g);
    double *pts = malloc(2 * m * sizeof *pts);
    if (!pts) abort();
    for (size_t i = 0; i < m; i++) dfl_grid_node(g, i, pts + 2 * i);
    return pts;
}

/* Runs the numpy script for kind (disk2, strip2, disk3, strip3); returns
 * its rate (NAN if it failed) and checks its values at a few nodes of its
 * n x n grid (z = 0 in 3D) against the field f. */
static double numpy_rate_kind(const dfl_field *f, const char *kind, int p, int n)
{
    const char *py = getenv("DFL_PYTHON");
    if (!py || !*py) py = "/usr/bin/python3";
    const size_t chk[4] = {0, 37, (size_t)n * (size_t)n / 2 + 5, (size_t)n * (size_t)n - 1};
    char cmd[1024], tmp[] = "/tmp/dflab_bench_numpy_XXXXXX";
    if (strchr(py, '\'')) return NAN; /* it is single-quoted below */
    int fd = mkstemp(tmp);
    if (fd < 0) return NAN;
    snprintf(cmd, sizeof cmd,
             "'%s' scripts/bench_rfunc_numpy.py --kind %s --p %d --segments %d --grid %d --reps 3 "
             "--check %zu %zu %zu %zu > '%s' 2>&1",
             py, kind, p, NSEG, n, chk[0], chk[1], chk[2], chk[3], tmp);
    const int rc = system(cmd);
    FILE *fp = fopen(tmp, "r");
    double rate = NAN;
    int checked = 0, bad = 0;
    char line[512];
    dfl_grid g = {2, {n, n, 1}, {0, 0, 0}, {1, 1, 0}};
    while (fp && fgets(line, sizeof line, fp)) {
        size_t i;
        double u, gx, gy;
        if (sscanf(line, "rate: %lf", &rate) == 1) continue;
        if (sscanf(line, "check %zu %lf %lf %lf", &i, &u, &gx, &gy) == 4) {
            double x[3] = {0, 0, 0}, gf[3];
            dfl_grid_node(&g, i, x);
            const double uf = dfl_field_eval1(f, x, gf);
            const double gn = hypot(gf[0], gf[1]);
            if (!(fabs(u - uf) <= 1e-12 * uf && fabs(gx - gf[0]) <= 1e-10 * gn &&
                  fabs(gy - gf[1]) <= 1e-10 * gn)) {
                fprintf(stderr, "bench_rfunc: numpy disagrees at node %zu: %.17g vs %.17g\n", i,
                        u, uf);
                bad = 1;
            }
            checked++;
        } else {
            fprintf(stderr, "bench_rfunc: numpy: %s", line);
        }
    }
    if (fp) fclose(fp);
    remove(tmp);
    if (rc != 0 || checked != 4 || bad) return NAN;
    return rate;
}

static void bench_order(int p, bench_ctx *c)
{
    double v[2 * NSEG];
    polyline(v);
    dfl_field fast, lib;
    dfl_err err;
    if (dfl_rfunc_batch_field(v, NSEG, 1, p, &fast, &err) != DFL_OK) {
        fprintf(stderr, "bench_rfunc: %s\n", err.msg);
        abort();
    }
    const dfl_rfunc_batch *b = fast.ctx;
    rfunc_naive nv;
    if (rfunc_naive_init(&nv, v, NSEG, 1, p)) abort();
    char name[128];
    const int threads = omp_get_max_threads();

    /* fast path: 512^2 points (3.9e8 segment evaluations) */
    job j = {&fast, &nv, {2, {512, 512, 1}, {0, 0, 0}, {1, 1, 0}}, threads, NULL, NULL, NULL};
    size_t m = dfl_grid_size(&j.g);
    j.v = malloc(m * sizeof *j.v);
    j.gr = malloc(2 * m * sizeof *j.gr);
    j.pts = grid_points(&j.g);
    const size_t fb = dfl_rfunc_batch_fallbacks(b, m, j.pts);
    const double rate = (double)m * NSEG / bench_best(5, run_sampler, &j);
    j.threads = 1;
    const double rate1 = (double)m * NSEG / bench_best(3, run_sampler, &j);
    free(j.pts);

    /* library field and naive loop: 64^2 points (6e6 segment evaluations) */
    job jn = {&fast, &nv, {2, {64, 64, 1}, {0, 0, 0}, {1, 1, 0}}, threads, NULL, j.v, j.gr};
    jn.pts = grid_points(&jn.g);
    const size_t mn = dfl_grid_size(&jn.g);
    const double naive = (double)mn * NSEG / bench_best(3, run_naive, &jn);
    /* the library's own field (dfl_rfield_polyline: the batch evaluator
     * since it is eligible) and its per-point accumulator (the batch's
     * reference, built with the fast path off) */
    if (dfl_rfield_polyline(2, v, NSEG, 1, DFL_RFUNC_REQUIV, p, DFL_RFUNC_TRIM_DISK, &lib,
                            &err) != DFL_OK || !dfl_rfield_is_fast(&lib)) {
        fprintf(stderr, "bench_rfunc: library field: %s\n", err.msg);
        abort();
    }
    jn.f = &lib;
    const double librate = (double)mn * NSEG / bench_best(3, run_sampler, &jn);
    dfl_field_destroy(&lib);
    jn.f = dfl_rfunc_batch_reference(b);
    const double slowrate = (double)mn * NSEG / bench_best(3, run_sampler, &jn);
    free(jn.pts);

    snprintf(name, sizeof name, "bs04.rfunc.p%d.segment_evals", p);
    bench_pair(name, rate, naive, "segment-evals/s");
    snprintf(name, sizeof name, "bs04.rfunc.p%d.segment_evals.fallback_points", p);
    bench_report(name, (double)fb, "of 262144");
    snprintf(name, sizeof name, "bs04.rfunc.p%d.segment_evals.one_thread", p);
    bench_report(name, rate1, "segment-evals/s");
    snprintf(name, sizeof name, "bs04.rfunc.p%d.segment_evals.threads", p);
    bench_report(name, threads, "");
    snprintf(name, sizeof name, "bs04.rfunc.p%d.segment_evals.library_rfield", p);
    bench_report(name, librate, "segment-evals/s");
    snprintf(name, sizeof name, "bs04.rfunc.p%d.segment_evals.library_rfield_per_point", p);
    bench_report(name, slowrate, "segment-evals/s");

    const double np = numpy_rate_kind(&fast, "disk2", p, 96);
    snprintf(name, sizeof name, "bs04.rfunc.p%d.segment_evals.numpy", p);
    bench_report(name, np, "segment-evals/s");
    snprintf(name, sizeof name, "bs04.rfunc.p%d.segment_evals.vs_numpy", p);
    bench_report(name, rate / np, "x (aim: >= 20)");

    /* The gap to the floor: the kernel's operations at the one-thread
     * rate against the floor measured on this CPU (bench_floor.c) at the
     * kernels' ISA, and against the machine's FMA peak. */
    int mul, add, dv;
    kernel_ops(p, &mul, &add, &dv);
    const bench_ops op = {mul, add, dv, 0};
    printf("# p = %d: %d multiplications, %d additions, %d divisions per segment evaluation\n", p,
           mul, add, dv);
    snprintf(name, sizeof name, "bs04.rfunc.p%d.segment_evals.one_thread", p);
    const double fp = bench_kernel_floor(c, name, rate1, &op);
    snprintf(name, sizeof name, "bs04.rfunc.p%d.achieved_one_thread", p);
    bench_report(name, rate1 * (mul + add + dv) / 1e9, "GFLOP/s");
    if (p == 2)
        bench_summary_add(c, "bs04_disk2", rate1, "numpy (one thread)", np, rate1 / np, fp);
    free(j.v);
    free(j.gr);
    rfunc_naive_free(&nv);
    dfl_field_destroy(&fast);
}

/* ---- every field kind ---------------------------------------------------
 * Part-evaluations per second (value + gradient, p = 2) of each kind's
 * field through the grid sampler (all threads): the batched kernel where
 * the kind has one, beside the per-point path (the same field built with
 * the fast path off) and, for the segment kinds, the numpy peer. */

typedef struct kind_job {
    const dfl_field *f;
    const double *pts;
    size_t m;
    double *v, *g;
    int threads;
} kind_job;

static void run_points(void *a)
{
    kind_job *j = a;
    /* chunks of 256 points, in parallel: what the samplers do */
#pragma omp parallel for schedule(static) num_threads(j->threads)
    for (size_t i = 0; i < j->m; i += 256) {
        const size_t c = j->m - i < 256 ? j->m - i : 256;
        const int d = j->f->dim;
        j->f->ops->eval(j->f->ctx, c, j->pts + (size_t)d * i, j->v + i, j->g + (size_t)d * i);
    }
}

/* Points on [0, 1]^2 (z = 0 in 3D): an n x n grid. */
static double *kind_points(int dim, int n)
{
    double *pts = calloc((size_t)n * (size_t)n * (size_t)dim, sizeof *pts);
    if (!pts) abort();
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            const size_t k = (size_t)j * (size_t)n + (size_t)i;
            pts[(size_t)dim * k] = i / (n - 1.0);
            pts[(size_t)dim * k + 1] = j / (n - 1.0);
        }
    return pts;
}

/* Rate of f at n x n points on `threads` threads: parts x points / best
 * time. */
static double kind_rate(const dfl_field *f, size_t parts, int n, int reps, int threads)
{
    kind_job j = {f, kind_points(f->dim, n), (size_t)n * (size_t)n, NULL, NULL, threads};
    j.v = malloc(j.m * sizeof *j.v);
    j.g = malloc(j.m * (size_t)f->dim * sizeof *j.g);
    const double r = (double)j.m * (double)parts / bench_best(reps, run_points, &j);
    free((void *)j.pts), free(j.v), free(j.g);
    return r;
}

typedef dfl_status (*kind_build)(bool fast, dfl_field *out, dfl_err *err);

static double *kind_curve(int dim)
{
    static double v[3 * NSEG];
    double v2[2 * NSEG];
    polyline(v2);
    for (int i = 0; i < NSEG; i++) {
        v[dim * i] = v2[2 * i];
        v[dim * i + 1] = v2[2 * i + 1];
        if (dim == 3) v[3 * i + 2] = 0.05 * sin(3.0 * 2.0 * DFL_PI * i / NSEG);
    }
    return v;
}

static dfl_status polyline_kind(int dim, dfl_rfunc_join join, dfl_rfunc_trim trim, bool fast,
                                dfl_field *out, dfl_err *err)
{
    return dfl_rfield_polyline_opts(dim, kind_curve(dim), NSEG, true, join, 2, trim, fast, out,
                                    err);
}

static dfl_status k_strip2(bool fast, dfl_field *o, dfl_err *e)
{
    return polyline_kind(2, DFL_RFUNC_REQUIV, DFL_RFUNC_TRIM_STRIP, fast, o, e);
}
static dfl_status k_disk3(bool fast, dfl_field *o, dfl_err *e)
{
    return polyline_kind(3, DFL_RFUNC_REQUIV, DFL_RFUNC_TRIM_DISK, fast, o, e);
}
static dfl_status k_strip3(bool fast, dfl_field *o, dfl_err *e)
{
    return polyline_kind(3, DFL_RFUNC_REQUIV, DFL_RFUNC_TRIM_STRIP, fast, o, e);
}
static dfl_status k_smooth2(bool fast, dfl_field *o, dfl_err *e)
{
    return polyline_kind(2, DFL_RFUNC_REQUIV, DFL_RFUNC_TRIM_DISK_SMOOTH, fast, o, e);
}
static dfl_status k_rconj2(bool fast, dfl_field *o, dfl_err *e)
{
    return polyline_kind(2, DFL_RFUNC_RCONJ, DFL_RFUNC_TRIM_DISK, fast, o, e);
}
static dfl_status k_corrected2(bool fast, dfl_field *o, dfl_err *e)
{
    return polyline_kind(2, DFL_RFUNC_REQUIV_CORRECTED, DFL_RFUNC_TRIM_DISK, fast, o, e);
}

/* Finishes the builder r into out when st is DFL_OK, else frees it. */
static dfl_status finish_kind(dfl_rfield *r, dfl_status st, dfl_field *out, dfl_err *err)
{
    if (st) {
        dfl_rfield_free(r);
        return st;
    }
    return dfl_rfield_finish(&r, out, err);
}

#define NTRI 500
/* NTRI triangles: a strip of a wavy surface over [0, 1]^2 (z = 0.3 + ...). */
static dfl_status tris_kind(dfl_rfunc_tri_trim trim, bool fast, dfl_field *out, dfl_err *err)
{
    dfl_rfield *r;
    dfl_status st = dfl_rfield_new(3, DFL_RFUNC_REQUIV, 2, &r, err);
    if (st) return st;
    dfl_rfield_set_fast(r, fast);
    dfl_rfunc_tri_opts o = dfl_rfunc_tri_defaults();
    o.trim = trim;
    for (int t = 0; t < NTRI && !st; t++) {
        const int i = (t / 2) % 25, j = (t / 2) / 25;
        const double x0 = i / 25.0, y0 = j / 10.0, hx = 1 / 25.0, hy = 0.1;
#define ZW(x, y) (0.3 + 0.05 * sin(6 * (x)) * cos(4 * (y)))
        const double A[3] = {x0, y0, ZW(x0, y0)}, B[3] = {x0 + hx, y0, ZW(x0 + hx, y0)},
                     C[3] = {x0, y0 + hy, ZW(x0, y0 + hy)},
                     D[3] = {x0 + hx, y0 + hy, ZW(x0 + hx, y0 + hy)};
#undef ZW
        st = t % 2 ? dfl_rfield_add_triangle(r, B, D, C, &o, err)
                   : dfl_rfield_add_triangle(r, A, B, C, &o, err);
    }
    return finish_kind(r, st, out, err);
}
static dfl_status k_tri_prism(bool fast, dfl_field *o, dfl_err *e)
{
    return tris_kind(DFL_RFUNC_TRI_PRISM, fast, o, e);
}
static dfl_status k_tri_cond(bool fast, dfl_field *o, dfl_err *e)
{
    return tris_kind(DFL_RFUNC_TRI_CONDITIONAL, fast, o, e);
}
static dfl_status k_points(bool fast, dfl_field *out, dfl_err *err)
{
    dfl_rfield *r;
    dfl_status st = dfl_rfield_new(2, DFL_RFUNC_REQUIV, 2, &r, err);
    if (st) return st;
    dfl_rfield_set_fast(r, fast);
    const double *v = kind_curve(2);
    for (int i = 0; i < NSEG && !st; i++) st = dfl_rfield_add_point(r, v + 2 * i, err);
    return finish_kind(r, st, out, err);
}
#define NREG 100
static dfl_status k_regions(bool fast, dfl_field *out, dfl_err *err)
{
    dfl_rfield *r;
    dfl_status st = dfl_rfield_new(2, DFL_RFUNC_REQUIV, 2, &r, err);
    if (st) return st;
    dfl_rfield_set_fast(r, fast);
    for (int i = 0; i < NREG && !st; i++) {
        const double cx = (i % 10 + 0.5) / 10, cy = (i / 10 + 0.5) / 10, h = 0.03;
        const double q[8] = {cx - h, cy - h, cx + h, cy - h, cx + h, cy + h, cx - h, cy + h};
        st = dfl_rfield_add_region(r, q, 4, err);
    }
    return finish_kind(r, st, out, err);
}

/* 2D mixed kinds (bs04 Fig. 13a style): the polyline's segments, every
 * tenth vertex as a point part and NREG / 4 small squares, R-equivalence. */
static dfl_status k_mixed2(bool fast, dfl_field *out, dfl_err *err)
{
    dfl_rfield *r;
    dfl_status st = dfl_rfield_new(2, DFL_RFUNC_REQUIV, 2, &r, err);
    if (st) return st;
    dfl_rfield_set_fast(r, fast);
    const double *v = kind_curve(2);
    st = dfl_rfield_add_polyline(r, v, NSEG, true, DFL_RFUNC_TRIM_DISK, err);
    for (int i = 0; i < NSEG && !st; i += 10) st = dfl_rfield_add_point(r, v + 2 * i, err);
    for (int i = 0; i < NREG / 4 && !st; i++) {
        const double cx = (i % 5 + 0.5) / 5, cy = (i / 5 + 0.5) / 5, h = 0.02;
        const double q[8] = {cx - h, cy - h, cx + h, cy - h, cx + h, cy + h, cx - h, cy + h};
        st = dfl_rfield_add_region(r, q, 4, err);
    }
    return finish_kind(r, st, out, err);
}
static dfl_status k_strip_smooth2(bool fast, dfl_field *o, dfl_err *e)
{
    return polyline_kind(2, DFL_RFUNC_REQUIV, DFL_RFUNC_TRIM_STRIP_SMOOTH, fast, o, e);
}
static dfl_status k_smooth3(bool fast, dfl_field *o, dfl_err *e)
{
    return polyline_kind(3, DFL_RFUNC_REQUIV, DFL_RFUNC_TRIM_DISK_SMOOTH, fast, o, e);
}
static dfl_status k_rconj3(bool fast, dfl_field *o, dfl_err *e)
{
    return polyline_kind(3, DFL_RFUNC_RCONJ, DFL_RFUNC_TRIM_DISK, fast, o, e);
}
static dfl_status k_corrected2_eq20(bool fast, dfl_field *out, dfl_err *err)
{
    dfl_rfield *r;
    dfl_status st = dfl_rfield_new(2, DFL_RFUNC_REQUIV_CORRECTED, 2, &r, err);
    if (st) return st;
    dfl_rfield_set_fast(r, fast);
    dfl_rfield_set_correction(r, DFL_RFUNC_CORR_EQ20);
    st = dfl_rfield_add_polyline(r, kind_curve(2), NSEG, true, DFL_RFUNC_TRIM_DISK, err);
    return finish_kind(r, st, out, err);
}

typedef struct kind_row {
    const char *name, *numpy;
    kind_build build;
    size_t parts;
    double aim; /* part-evals/s the batched kernel aims at (issue: all threads) */
    const char *why; /* why it stays on the per-point path, or below its aim when batched */
    /* Operations per part evaluation at p = 2 (value + gradient; mul, add
     * (add, sub), div, sqrt; compares, min/max, |.| and blends are not
     * counted), read off the AVX-512 kernel's p = 2 loop (objdump -d of
     * build/src/rfunc/batch_*.o: its vmulpd, vaddpd + vsubpd, vdivpd,
     * vsqrtpd per vector of parts); all zero: not counted (per-point
     * path, or a kernel whose loops depend on the input: regions' edge
     * counts, mixed kinds, the corrected join's vertex layouts).  The
     * R-conjunction's loop runs two vectors of points (batch_rconj.c
     * RC_LANES): its counts are half the loop's. */
    bench_ops op;
    /* What bounds it beyond the operation counts: the dependency chain
     * through the divider (a division or root waiting on another), where
     * that is why the kernel sits below its floor. */
    const char *chain;
} kind_row;

static void bench_kinds(bench_ctx *c)
{
    static const kind_row rows[] = {
        {"strip2", "strip2", k_strip2, NSEG, 1e9,
         "per part 24 mul, 20 add, 2 divisions and a root, the three on one divider", {24, 20, 2, 1}, "sqrt -> division (t) -> division (1/(r h^2)) in series per part"},
        {"disk3", "disk3", k_disk3, NSEG, 1e9,
         "per part 27 muls (3D dot products with two normals) and a division; ~6 cycles/part/core measured", {27, 28, 1, 0}, NULL},
        {"strip3", "strip3", k_strip3, NSEG, 1e9,
         "per part 38 mul, 33 add, 2 divisions and a root, the three on one divider", {38, 33, 2, 1}, "sqrt -> division (t) -> division (1/(r h^2)) in series per part"},
        {"disk_smooth2", NULL, k_smooth2, NSEG, 1e9, "eq. 5 (batch_smooth.c): ~36 mul (13 in 1/sqrt), 2 div per part vs ~17 mul, 1 div for disk2", {36, 25, 2, 0}, "two divisions in series per part"},
        {"strip_smooth2", NULL, k_strip_smooth2, NSEG, 1e9, "eq. 5 (batch_smooth.c): ~55 mul (26 in two 1/sqrt), 3 div per part", {55, 34, 3, 0}, "three divisions in series per part"},
        {"disk_smooth3", NULL, k_smooth3, NSEG, 1e9, "eq. 5 (batch_smooth.c): ~48 mul (13 in 1/sqrt), 2 div per part", {49, 37, 2, 0}, "two divisions in series per part"},
        {"rconj2", NULL, k_rconj2, NSEG, 1e9,
         "two roots per part (h and (1 + r^2)^(1/2), Newton steps): 49 multiplications and 2"
         " divisions per part against R-equivalence's 15", {49, 28, 2, 0}, "the fold across parts is one chain per point (each part waits on the last): 16 points side by side"},
        {"rconj3", NULL, k_rconj3, NSEG, 1e9,
         "as rconj2 with the 3D carrier (two normals): 62 multiplications and 2 divisions per"
         " part", {62, 39, 2, 0}, "the fold across parts is one chain per point (each part waits on the last): 16 points side by side"},
        {"corrected2", NULL, k_corrected2, NSEG, 1e9,
         "per part a segment and a guarded vertex term: ~26 mul, 2 div, ~45 add/cmp/blend"
         " (batch_corrected.c): ~2.5x the disk2 kernel's work", {0, 0, 0, 0}, NULL},
        {"corrected2_eq20", NULL, k_corrected2_eq20, NSEG, 1e9,
         "per part a segment and a vertex term: ~25 mul, 2 div, ~25 add", {0, 0, 0, 0}, NULL},
        {"triangles_prism", NULL, k_tri_prism, NTRI, 4e8,
         "57 mul, 47 add, 2 sqrt, 1 div per triangle (vsqrtpd ymm ~9.5 cycles), ~48"
         " instructions per part and lane: ~14 cycles per part per core measured; 4e8 on 2"
         " cores needs 12.25", {57, 47, 1, 2}, "three phases through stack scratch: two roots, then the division"},
        {"triangles_conditional", NULL, k_tri_cond, NTRI, 4e8,
         "66 mul, 53 add, 2 sqrt, 1 div per triangle, ~55 instructions per part and lane:"
         " ~16 cycles per part per core measured; 4e8 on 2 cores needs 12.25", {66, 53, 1, 2}, "three phases through stack scratch: two roots, then the division"},
        {"points", NULL, k_points, NSEG, 1e9, NULL, {5, 7, 1, 0}, NULL},
        {"regions", NULL, k_regions, NREG, 1e9,
         "23 mul, 1 div per square (multiply floor 2.9 cycles), ~30 instructions per part and"
         " lane: ~7 cycles per part per core measured; 1e9 on 2 cores needs 4.9", {0, 0, 0, 0}, NULL},
        {"mixed2", NULL, k_mixed2, NSEG + NSEG / 10 + NREG / 4, 1e9,
         "the sum of the disk, point and region kernels (the regions' edge loops); ~5 cycles/part/core measured", {0, 0, 0, 0}, NULL},
    };
    for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        const kind_row *k = &rows[i];
        dfl_field fast, slow;
        dfl_err err;
        if (k->build(true, &fast, &err) || k->build(false, &slow, &err)) {
            fprintf(stderr, "bench_rfunc: kind %s: %s\n", k->name, err.msg);
            abort();
        }
        const bool batched = dfl_rfield_is_fast(&fast);
        char name[160], unit[160];
        const int n = batched ? 160 : 48;
        const int threads = omp_get_max_threads();
        const double rf = kind_rate(&fast, k->parts, n, 3, threads);
        const double rs = batched ? kind_rate(&slow, k->parts, 48, 3, threads) : rf;
        snprintf(name, sizeof name, "bs04.rfunc.kind.%s.p2.part_evals", k->name);
        snprintf(unit, sizeof unit, "part-evals/s (%s; aim: >= %.0e, %s)",
                 batched ? "batched" : "per-point path", k->aim,
                 rf >= k->aim ? "met" : "not met");
        bench_report(name, rf, unit);
        snprintf(name, sizeof name, "bs04.rfunc.kind.%s.p2.per_point", k->name);
        bench_report(name, rs, "part-evals/s");
        if (batched) {
            snprintf(name, sizeof name, "bs04.rfunc.kind.%s.p2.vs_per_point", k->name);
            bench_report(name, rf / rs, "x");
            if (rf < k->aim && k->why) printf("# %s below its aim: %s\n", k->name, k->why);
            /* the gap to the floor: one thread, as disk2's rows above */
            const double r1 = kind_rate(&fast, k->parts, n, 3, 1);
            snprintf(name, sizeof name, "bs04.rfunc.kind.%s.p2.part_evals.one_thread", k->name);
            bench_report(name, r1, "part-evals/s");
            if (k->op.mul + k->op.add + k->op.div + k->op.sqrt > 0) {
                bench_kernel_floor(c, name, r1, &k->op);
            } else {
                printf("# %s: operations not counted, no floor fraction\n", k->name);
            }
            if (k->chain) printf("# %s: dependency chain: %s\n", k->name, k->chain);
        } else {
            printf("# %s stays on the per-point path: %s\n", k->name,
                   k->why ? k->why : "no batched kernel takes it");
        }
        if (k->numpy) {
            const double np = numpy_rate_kind(&fast, k->numpy, 2, 96);
            snprintf(name, sizeof name, "bs04.rfunc.kind.%s.p2.numpy", k->name);
            bench_report(name, np, "part-evals/s");
            snprintf(name, sizeof name, "bs04.rfunc.kind.%s.p2.vs_numpy", k->name);
            bench_report(name, rf / np, "x");
        }
        dfl_field_destroy(&fast);
        dfl_field_destroy(&slow);
    }
}

void bench_rfunc(bench_ctx *c)
{
    printf("# bs04 rfunc benchmark: kernels' ISA %s (vector width %d doubles)\n",
           bench_level_name(bench_active_level()), dfl_rfunc_batch_simd_width());
    bench_order(2, c);
    bench_order(7, c);
    bench_kinds(c);
    printf("# Gap to the floor.  floor_fraction: the kernel's multiplications and additions\n"
           "# (no contraction: FMA is not used, core/isa.h) and divisions at the one-thread\n"
           "# rate against the measured mul/add and divide throughput of the kernels' ISA\n"
           "# (floor.* above); fma_peak_fraction: all its operations against the measured FMA\n"
           "# peak of the widest ISA.  Odd p pay 13 multiplications for 1/h (Newton steps for\n"
           "# 1/sqrt), even p one division.  The rest of the gap: the per-point tail (pow,\n"
           "# fallback check), OpenMP chunking, and the machine's load.\n");
}
