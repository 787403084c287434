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
 *   pht.eval.{circle,torus}.vs_scipy_per_cpu_second
 *                                   the batched rate per CPU-second against SciPy
 *                                   at equal stored coefficients, one thread
 *                                   (scripts/bench_pht_scipy.py: RectBivariateSpline
 *                                   value + gradient; map_coordinates order 3, value
 *                                   only): the summary's pht2d_eval, pht3d_eval
 *   pht.fit_vs_fitpack.convex.*     the sjp10 convex curve's fit against FITPACK at
 *                                   equal error off the medial band (fit_vs_fitpack
 *                                   below): the summary's sjp10_fit_convex
 * Aims (issue 8): 2D fits <= 1 s, >= 3e7 evaluations/s on 2 cores. */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "bench.h"
#include "cfg/pht_cfg.h"
#include "cfg/shape_cfg.h"
#include "core/rng.h"
#include "field/exact.h"
#include "geom/param_shape.h"
#include "geom/shape.h"
#include "io/config.h"
#include "io/manifest.h"
#include "pht/fit.h"
#include "pht/pht_field.h"
#include "sjp10/sjp10_common.h"

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

/* Fits s, reports, and returns the spline as a field; *cells (may be NULL)
 * gets its leaf cells. */
static dfl_field fit_report(const char *name, const dfl_shape *s, double eps, int max_level,
                            size_t *cells)
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
    if (cells) *cells = last->cells;
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

/* The SciPy peer (scripts/bench_pht_scipy.py, through $DFL_PYTHON,
 * default /usr/bin/python3): peer "rbs" (RectBivariateSpline, value and
 * gradient) or "mapc" (map_coordinates order 3, value only) on an n^dim
 * grid, one thread, points per CPU-second; *maxerr its error at the timed
 * points.  NAN if the script failed (its lines go to stderr). */
static double scipy_rate(const char *peer, int n, int points, double *maxerr)
{
    const char *py = getenv("DFL_PYTHON");
    if (!py || !*py) py = "/usr/bin/python3";
    char cmd[1024], tmp[] = "/tmp/dflab_bench_scipy_XXXXXX";
    *maxerr = NAN;
    if (strchr(py, '\'')) return NAN; /* it is single-quoted below */
    int fd = mkstemp(tmp);
    if (fd < 0) return NAN;
    close(fd);
    snprintf(cmd, sizeof cmd,
             "'%s' scripts/bench_pht_scipy.py --peer %s --n %d --points %d --reps 3 > '%s' 2>&1", py,
             peer, n, points, tmp);
    const int rc = system(cmd);
    FILE *fp = fopen(tmp, "r");
    double rate = NAN;
    char line[512];
    *maxerr = NAN;
    while (fp && fgets(line, sizeof line, fp)) {
        long nc;
        if (sscanf(line, "rate: %lf", &rate) == 1 || sscanf(line, "maxerr: %lf", maxerr) == 1 ||
            sscanf(line, "coefficients: %ld", &nc) == 1)
            continue;
        fprintf(stderr, "bench_pht: scipy: %s", line);
    }
    if (fp) fclose(fp);
    remove(tmp);
    return rc == 0 ? rate : NAN;
}

/* ncoef: the spline's stored coefficients (16 or 64 per cell), the size of
 * the SciPy peer's grid (n^dim of them, n rounded) for circle and torus. */
static void eval_report(bench_ctx *c, const char *name, const dfl_field *f,
                        const dfl_field *exact, size_t ncoef)
{
    eval_job j = {f, random_points(f->dim, NEVAL, 11), NULL, NULL, NEVAL};
    j.val = malloc(NEVAL * sizeof *j.val);
    j.grad = malloc(NEVAL * (size_t)f->dim * sizeof *j.grad);
    double t = bench_best(5, run_batched, &j);
    /* CPU time of batched runs on one thread, best of 3: the machine is
     * shared, so wall-clock rates undercount, and an OpenMP team's CPU time
     * counts its barrier spinning (1.4-1.9x on a loaded machine); points
     * per CPU-second times the threads is what the cores deliver when they
     * are ours.  The peer runs on one thread too. */
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    double cpu = INFINITY;
    for (int r = 0; r < 3; r++) {
        const double c0 = cpu_seconds();
        run_batched(&j);
        cpu = fmin(cpu, cpu_seconds() - c0);
    }
    omp_set_num_threads(threads);
    char buf[160];
    snprintf(buf, sizeof buf, "pht.eval.%s.value_grad.per_cpu_second", name);
    bench_report(buf, NEVAL / cpu, "points/s");
    snprintf(buf, sizeof buf, "pht.eval.%s.value_grad.per_cpu_second", name);
    const bench_ops op = eval_ops(f->dim);
    const double fp = bench_kernel_floor(c, buf, NEVAL / cpu, &op);
    if (strcmp(name, "circle") == 0 || strcmp(name, "torus") == 0) {
        /* the peer at equal stored coefficients, on one thread against
         * dflab's points per CPU-second (per core) */
        const int d2 = f->dim == 2;
        const int n = (int)lround(pow((double)ncoef, 1.0 / f->dim));
        double perr;
        const double peer = scipy_rate(d2 ? "rbs" : "mapc", n, 1 << 18, &perr);
        char pname[160];
        snprintf(pname, sizeof pname,
                 d2 ? "SciPy RectBivariateSpline.ev value+grad %d^2 coefs 1 thread"
                    : "SciPy map_coordinates order 3 value only %d^3 coefs 1 thread",
                 n);
        snprintf(buf, sizeof buf, "pht.eval.%s.vs_scipy_per_cpu_second", name);
        bench_pair(buf, NEVAL / cpu, peer, "points/s");
        snprintf(buf, sizeof buf, "pht.eval.%s.scipy_n", name);
        bench_report(buf, n, d2 ? "nodes per axis (RectBivariateSpline, s = 0)"
                                : "nodes per axis (map_coordinates, order 3)");
        snprintf(buf, sizeof buf, "pht.eval.%s.scipy_maxerr", name);
        bench_report(buf, perr, "max |s - d| at the peer's points");
        bench_summary_add(c, d2 ? "pht2d_eval" : "pht3d_eval", NEVAL / cpu, pname, peer,
                          NEVAL / cpu / peer, fp);
    }
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

/* sjp10_fit_convex (the summary's FITPACK row): the sjp10 convex curve
 * fitted with the options of CELLS_INI ([fit], the dflab rule, eps 1e-4)
 * against FITPACK's bicubic interpolant (scripts/bench_fitpack.py,
 * RectBivariateSpline s = 0) on the smallest n x n grid of FITPACK_NS
 * whose error off the medial band is at most the PHT's, on the points of
 * that config's grid protocol (val_n^2 nodes and midpoints, band [study]
 * band).  Both are charged their exact distances, in CPU-seconds of one
 * thread: the PHT fit's are inside its time (best of 3); FITPACK's are the
 * n^2 exact distances, timed here the same way, plus its fit's time (best
 * of 3).  ratio = FITPACK / PHT (> 1: the
 * PHT fit is cheaper at equal honest error); NAN when no grid of the list
 * reaches the PHT's error. */
#define CELLS_INI "configs/paper/sjp10/sjp10_cells.ini"
static const int FITPACK_NS[] = {51, 76, 101, 126, 151, 201, 251, 301, 401};
#define NNS ((int)(sizeof FITPACK_NS / sizeof FITPACK_NS[0]))

static int write_doubles(const char *dir, const char *name, const double *v, size_t n)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *fp = fopen(path, "wb");
    if (!fp) return -1;
    const size_t w = fwrite(v, sizeof *v, n, fp);
    return fclose(fp) != 0 || w != n ? -1 : 0;
}

static void fit_vs_fitpack(bench_ctx *c)
{
    dfl_cfg *cfg = NULL;
    dfl_err err;
    dfl_shape s;
    dfl_pht_fit_opts o;
    long val_n = 0;
    double band = 0;
    if (dfl_cfg_load(CELLS_INI, &cfg, &err) != DFL_OK ||
        dfl_shape_from_cfg(cfg, "convex", &s, &err) != DFL_OK) {
        fprintf(stderr, "bench_pht: %s\n", err.msg);
        dfl_cfg_free(cfg);
        return;
    }
    if (dfl_pht_opts_from_cfg(cfg, "fit", 2, &o, &err) != DFL_OK ||
        dfl_cfg_int_opt(cfg, "study", "val_n", 301, 2, 4001, &val_n, &err) != DFL_OK ||
        dfl_cfg_double_opt(cfg, "study", "band", 0.02, 0.0, 1e300, &band, &err) != DFL_OK)
        abort();
    dfl_cfg_free(cfg);
    sjp10_rule_apply(0, &o); /* "dflab" */
    o.eps = 1e-4;
    dfl_pht_source *src;
    if (dfl_pht_source_new(&s, &src, &err) != DFL_OK) abort();
    /* one thread on both sides: CPU time of an OpenMP team counts its
     * barriers' spinning, which is not work */
    const int threads_before = omp_get_max_threads(), threads = 1;
    omp_set_num_threads(1);
    dfl_pht_fit fit;
    double tp = INFINITY;
    for (int rep = 0; rep < 3; rep++) {
        if (rep) dfl_pht_fit_free(&fit);
        const double c0 = cpu_seconds();
        if (dfl_pht_fit_run(src, &o, &fit, &err) != DFL_OK) abort();
        tp = fmin(tp, cpu_seconds() - c0);
    }
    double tfoot = 0, twall = fit.t_total;
    for (int k = 0; k < fit.nlevels; k++) tfoot += fit.levels[k].t_foot;
    const size_t pcells = fit.levels[fit.nlevels - 1].cells;
    sjp10_ref ref;
    dfl_field fld;
    dfl_pht_val v;
    if (sjp10_ref_grid(&s, o.lo, o.hi, (int)val_n, 1, band, threads, &ref, &err) != DFL_OK ||
        dfl_pht_field_new(&fit.spline, &fld, &err) != DFL_OK ||
        sjp10_ref_errors(&fld, &ref, threads, &v, &err) != DFL_OK)
        abort();
    const double pht_off = v.off.max;
    dfl_field_destroy(&fld);
    dfl_pht_fit_free(&fit);
    dfl_pht_source_free(src);

    /* the files of scripts/bench_fitpack.py, in a private folder */
    char dir[] = "/tmp/dflab_bench_fitpack_XXXXXX";
    if (!mkdtemp(dir)) abort();
    double *val = malloc(3 * ref.m * sizeof *val);
    size_t nv = 0;
    for (size_t i = 0; i < ref.m; i++)
        if (!ref.near[i] && isfinite(ref.d[i])) {
            val[3 * nv] = ref.pts[2 * i];
            val[3 * nv + 1] = ref.pts[2 * i + 1];
            val[3 * nv + 2] = ref.d[i];
            nv++;
        }
    int bad = write_doubles(dir, "val.bin", val, 3 * nv);
    free(val);
    sjp10_ref_free(&ref);
    double sample_cpu[NNS];
    char ns[256] = "", name[64];
    for (int k = 0; k < NNS && !bad; k++) {
        const int n = FITPACK_NS[k];
        const size_t nn = (size_t)n * (size_t)n;
        double *pts = malloc(2 * nn * sizeof *pts), *d = malloc(nn * sizeof *d);
        for (size_t i = 0; i < nn; i++) {
            pts[2 * i] = o.lo[0] + (o.hi[0] - o.lo[0]) * (double)(i % (size_t)n) / (n - 1);
            pts[2 * i + 1] = o.lo[1] + (o.hi[1] - o.lo[1]) * (double)(i / (size_t)n) / (n - 1);
        }
        sample_cpu[k] = INFINITY;
        for (int rep = 0; rep < 3; rep++) {
            const double c0 = cpu_seconds();
#pragma omp parallel for schedule(static)
            for (size_t b = 0; b < (nn + CHUNK - 1) / CHUNK; b++) {
                const size_t i0 = b * CHUNK, m = nn - i0 < CHUNK ? nn - i0 : CHUNK;
                dfl_shape_eval(&s, m, pts + 2 * i0, d + i0, NULL);
            }
            sample_cpu[k] = fmin(sample_cpu[k], cpu_seconds() - c0);
        }
        snprintf(name, sizeof name, "grid_%d.bin", n);
        bad = write_doubles(dir, name, d, nn);
        snprintf(ns + strlen(ns), sizeof ns - strlen(ns), "%s%d", k ? "," : "", n);
        free(pts);
        free(d);
    }
    dfl_shape_free(&s);
    omp_set_num_threads(threads_before);
    const char *py = getenv("DFL_PYTHON");
    if (!py || !*py) py = "/usr/bin/python3";
    char cmd[1024], line[512];
    /* single quotes around the paths: $DFL_PYTHON is the user's; dir is
     * mkdtemp's (no quote in it) */
    if (strchr(py, '\'')) {
        fprintf(stderr, "bench_pht: DFL_PYTHON holds a single quote; FITPACK peer skipped\n");
        bad = 1;
    }
    snprintf(cmd, sizeof cmd, "'%s' scripts/bench_fitpack.py --dir '%s' --ns %s 2>&1", py, dir, ns);
    FILE *pp = bad ? NULL : popen(cmd, "r");
    double fit_cpu[NNS], off[NNS];
    int got = 0;
    while (pp && fgets(line, sizeof line, pp)) {
        int n;
        double f, e;
        long nc;
        if (sscanf(line, "n %d fit %lf off_max %lf coefficients %ld", &n, &f, &e, &nc) == 4 &&
            got < NNS && n == FITPACK_NS[got]) {
            fit_cpu[got] = f;
            off[got++] = e;
        } else {
            fprintf(stderr, "bench_pht: fitpack: %s", line);
        }
    }
    if (pp && pclose(pp) != 0) got = 0;
    /* only the files written above, then the folder */
    snprintf(name, sizeof name, "%s/val.bin", dir);
    remove(name);
    for (int k = 0; k < NNS; k++) {
        char path[512];
        snprintf(path, sizeof path, "%s/grid_%d.bin", dir, FITPACK_NS[k]);
        remove(path);
    }
    rmdir(dir);
    bench_report("pht.fit_vs_fitpack.convex.eps1e-4.pht_cpu", tp, "CPU-s (fit, exact distances inside)");
    bench_report("pht.fit_vs_fitpack.convex.eps1e-4.pht_footpoint_share", tfoot / twall,
                 "of the fit's time in exact distances and Hermite data");
    bench_report("pht.fit_vs_fitpack.convex.eps1e-4.pht_cells", (double)pcells, "cells");
    bench_report("pht.fit_vs_fitpack.convex.eps1e-4.pht_off_max", pht_off,
                 "max error off the medial band (sjp10_cells protocol)");
    int pick = -1;
    for (int k = 0; k < got; k++) {
        char buf[160];
        snprintf(buf, sizeof buf, "pht.fit_vs_fitpack.convex.fitpack_n%d", FITPACK_NS[k]);
        printf("%s: off_max %.4g, fit %.4g CPU-s + samples %.4g CPU-s\n", buf, off[k], fit_cpu[k],
               sample_cpu[k]);
        if (pick < 0 && off[k] <= pht_off) pick = k;
    }
    const double tf = pick >= 0 ? fit_cpu[pick] + sample_cpu[pick] : NAN;
    bench_report("pht.fit_vs_fitpack.convex.fitpack_n", pick >= 0 ? FITPACK_NS[pick] : NAN,
                 "the smallest grid at the PHT's off-band error or better");
    bench_report("pht.fit_vs_fitpack.convex.fitpack_cpu", tf, "CPU-s (fit + samples)");
    bench_report("pht.fit_vs_fitpack.convex.fitpack_over_pht", tf / tp,
                 "x (FITPACK time / PHT time; aim >= 3)");
    char peer[64];
    snprintf(peer, sizeof peer, "FITPACK s=0 %dx%d grid + samples CPU-s", pick >= 0 ? FITPACK_NS[pick] : 0,
             pick >= 0 ? FITPACK_NS[pick] : 0);
    bench_summary_add(c, "sjp10_fit_convex", tp, peer, tf, tf / tp, NAN);
}

void bench_pht(bench_ctx *c)
{
    bench_report("pht.threads", omp_get_max_threads(), "threads");
    dfl_shape s;
    const double c2[2] = {0.5, 0.5}, c3[3] = {0.5, 0.5, 0.5}, ax[3] = {0, 0, 1};
    if (dfl_shape_circle(c2, 0.3, &s, NULL) != DFL_OK) abort();
    size_t cells = 0;
    dfl_field circle = fit_report("circle.eps1e-5", &s, 1e-5, 22, &cells);
    eval_report(c, "circle", &circle, NULL, 16 * cells);
    dfl_field_destroy(&circle);
    dfl_shape_free(&s);

    s = closed_curve(BLOB);
    dfl_field blob = fit_report("blob.eps1e-5.L10", &s, 1e-5, 10, NULL);
    dfl_field exact;
    dfl_shape s2 = closed_curve(BLOB);
    if (dfl_field_exact_new(&s2, &exact, NULL) != DFL_OK) abort();
    eval_report(c, "blob", &blob, &exact, 0);
    dfl_field_destroy(&exact);
    dfl_field_destroy(&blob);
    dfl_shape_free(&s);

    double oval[16];
    oval_points(oval);
    s = closed_curve(oval);
    dfl_field ov = fit_report("oval.eps1e-5.L10", &s, 1e-5, 10, NULL);
    dfl_field_destroy(&ov);
    dfl_shape_free(&s);

    if (dfl_shape_torus(c3, ax, 0.3, 0.1, &s, NULL) != DFL_OK) abort();
    dfl_field torus = fit_report("torus.eps1e-3", &s, 1e-3, 14, &cells);
    eval_report(c, "torus", &torus, NULL, 64 * cells);
    dfl_field_destroy(&torus);
    dfl_shape_free(&s);

    fit_vs_fitpack(c);
}
