/* The runner: load and validate a sweep, compute its points (or one),
 * merge.  Points are the unit of work everywhere, so a one-process run,
 * GNU parallel and a Slurm array produce the same folders and the merge
 * makes the same files from them. */
#include "harness/runner.h"

#include <omp.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "core/sha256.h"
#include "harness/nonfinite.h"
#include "harness/probe.h"
#include "harness/sweep.h"
#include "io/dirs.h"
#include "io/manifest.h"
#include "io/path.h"
#include "io/table.h"

const char *dfl_sweep_label(const dfl_sweep *s, const dfl_cfg *pt, char *buf, size_t size)
{
    size_t ll = 0;
    if (size) buf[0] = '\0';
    for (size_t a = 0; a < s->na && ll < size; a++)
        ll += (size_t)snprintf(buf + ll, size - ll, "%s%s=%s", a ? " " : "",
                               dfl_cfg_sweep_axis_name(s->cfg, a), dfl_cfg_axis_value(pt, a));
    return buf;
}

static int isalnum_ascii(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
}

/* Hydra-style: the overrides name the folder, so two --set runs never
 * share one and never touch the paper folder results/<stem>/. */
void dfl_sweep_outdir(const dfl_run_opts *o, char *buf, size_t size)
{
    char stem[512];
    dfl_path_stem(o->config, stem, sizeof stem);
    if (o->outdir) {
        snprintf(buf, size, "%s", o->outdir);
    } else if (o->nsets == 0) {
        snprintf(buf, size, "results/%s", stem);
    } else {
        char name[4096] = "";
        size_t n = 0;
        for (int i = 0; i < o->nsets && n < sizeof name; i++)
            n += (size_t)snprintf(name + n, sizeof name - n, "%s%s", i ? "," : "", o->sets[i]);
        for (char *c = name; *c; c++)
            if (!(isalnum_ascii(*c) || strchr("._=+-,", *c))) *c = '_';
        if (strlen(name) > 120) {
            char hex[65];
            dfl_sha256_hex(name, strlen(name), hex);
            snprintf(name + 100, sizeof name - 100, "-%.12s", hex);
        }
        snprintf(buf, size, "results/runs/%s/%s", stem, name);
    }
    size_t ol = strlen(buf);
    while (ol > 1 && buf[ol - 1] == '/') buf[--ol] = '\0';
}

const char *dfl_point_dir(const dfl_sweep *s, size_t k, char *buf, size_t size)
{
    snprintf(buf, size, "%s/pt%03zu", s->points, k);
    return buf;
}

/* Every point's estimate against the budgets (sweep.h), all before the
 * first point's validation pass may build anything. */
static dfl_status estimate_points(const dfl_sweep *s, dfl_err *err)
{
    dfl_status st = DFL_OK;
    for (size_t i = 0; i < s->np && st == DFL_OK; i++) {
        dfl_cfg *pt = NULL;
        st = dfl_cfg_sweep_point(s->cfg, i, &pt, err);
        if (st != DFL_OK) break;
        char tag[32], label[2048];
        dfl_study_tag(i, s->np, tag, sizeof tag);
        dfl_study_ctx ctx = {.stage_dir = "/nonexistent/dflab-validation", .tag = tag, .point = i,
                             .npoints = s->np, .threads = s->threads};
        st = dfl_sweep_check_budget(s, pt, &ctx, err);
        if (st != DFL_OK && s->np > 1)
            dfl_err_prefix(err, "sweep point %zu (%s)", i,
                           dfl_sweep_label(s, pt, label, sizeof label));
        dfl_cfg_free(pt);
    }
    return st;
}

/* Runs every point's study with a validation-only config: the getters and
 * dfl_cfg_check_used run, nothing computes, so a bad value at point 17
 * fails at once, named by point and key. */
static dfl_status validate_points(const dfl_sweep *s, dfl_err *err)
{
    dfl_status est = estimate_points(s, err);
    if (est != DFL_OK) return est;
    dfl_table *t = dfl_table_new();
    if (!t) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    dfl_status st = DFL_OK;
    const double t0 = dfl_wall_seconds();
    double last = t0;
    for (size_t i = 0; i < s->np && st == DFL_OK; i++) {
        const double now = dfl_wall_seconds();
        if (!s->o->quiet && now - last >= 2.0) { /* a slow validation is not silent */
            fprintf(stderr, "dflab: %s: validating point %zu/%zu (%.1f s elapsed)\n",
                    s->study->name, i + 1, s->np, now - t0);
            last = now;
        }
        dfl_cfg *pt = NULL;
        st = dfl_cfg_sweep_point(s->cfg, i, &pt, err);
        if (st != DFL_OK) break;
        dfl_cfg_validate_only(pt);
        dfl_probe_sections_defer(pt);
        const char *dummy;
        dfl_cfg_string(pt, "study", "name", &dummy, NULL); /* mark used */
        double mem_budget, work_budget; /* the runner's keys: estimate_points checked them */
        dfl_sweep_budgets(pt, &mem_budget, &work_budget, NULL);
        char tag[32], label[2048];
        dfl_study_tag(i, s->np, tag, sizeof tag);
        dfl_study_ctx ctx = {.stage_dir = "/nonexistent/dflab-validation", .tag = tag, .point = i,
                             .npoints = s->np, .threads = s->threads};
        dfl_err e2;
        dfl_err_clear(&e2);
        bool allow;
        st = dfl_study_allow_nonfinite(pt, &allow, &e2);
        if (st == DFL_OK) st = s->study->run(pt, &ctx, t, &e2);
        if (!dfl_cfg_validated(pt) && st == DFL_OK) st = dfl_cfg_check_used(pt, &e2);
        if (dfl_cfg_validated(pt)) st = DFL_OK;
        if (st == DFL_OK) st = dfl_probe_sections_check(pt, &e2);
        if (st != DFL_OK) {
            *err = e2;
            if (s->np > 1) dfl_err_prefix(err, "sweep point %zu (%s)", i,
                                          dfl_sweep_label(s, pt, label, sizeof label));
        }
        dfl_cfg_free(pt);
    }
    dfl_table_free(t);
    return st;
}

dfl_status dfl_sweep_open(const dfl_run_opts *o, dfl_sweep *s, dfl_err *err)
{
    memset(s, 0, sizeof *s);
    s->o = o;
    dfl_status st = dfl_cfg_load(o->config, &s->cfg, err);
    for (int i = 0; i < o->nsets && st == DFL_OK; i++) st = dfl_cfg_set(s->cfg, o->sets[i], err);
    const char *study_name = NULL;
    if (st == DFL_OK) st = dfl_cfg_string(s->cfg, "study", "name", &study_name, err);
    if (st == DFL_OK && !(s->study = dfl_study_find(study_name)))
        st = dfl_cfg_reject(s->cfg, "study", "name", err, "unknown study '%s' (see `dflab list`)",
                            study_name);
    if (st != DFL_OK) return st;
    s->np = dfl_cfg_sweep_points(s->cfg);
    s->na = dfl_cfg_sweep_axes(s->cfg);
    for (size_t a = 0; a < s->na; a++)
        if (strcmp(dfl_cfg_sweep_axis_name(s->cfg, a), "study.name") == 0)
            return dfl_err_set(err, DFL_E_INPUT, "%s: [study] name cannot be a sweep", o->config);
    const long last = o->point_last > o->point ? o->point_last : o->point;
    if (o->has_point && (o->point < 0 || (size_t)last >= s->np))
        return dfl_err_set(err, DFL_E_INPUT,
                           "--point %ld: out of range: %s has %zu sweep point%s (0..%zu)",
                           (size_t)o->point >= s->np ? o->point : last, o->config, s->np,
                           s->np == 1 ? "" : "s", s->np - 1);
    s->threads = o->threads > 0 ? o->threads : omp_get_max_threads();
    dfl_sweep_outdir(o, s->outdir, sizeof s->outdir);
    snprintf(s->points, sizeof s->points, "%s.points", s->outdir);
    /* a config "..ini" or "...ini" would name results/. or results/.. */
    char stem[512];
    dfl_path_stem(o->config, stem, sizeof stem);
    if (!o->outdir && (strcmp(stem, ".") == 0 || strcmp(stem, "..") == 0))
        return dfl_err_set(err, DFL_E_INPUT,
                           "%s: the config's name '%s' cannot name its results folder; rename "
                           "the config or give --out",
                           o->config, stem);
    st = dfl_dir_check_name(s->outdir, "--out", err);
    if (st != DFL_OK) return st;
    dfl_cfg_sweep_hash(s->cfg, s->sweep_sha);
    st = dfl_path_stamp(o->config, s->config_stamp, sizeof s->config_stamp, err);
    if (st == DFL_OK) st = dfl_sha256_file("/proc/self/exe", s->binary_sha, err);
    if (st == DFL_OK) st = validate_points(s, err);
    return st;
}

void dfl_sweep_close(dfl_sweep *s)
{
    dfl_cfg_free(s->cfg);
    s->cfg = NULL;
}

/* Line-based progress for logs (a Slurm log reads like a terminal): a line
 * when the first point starts, then one every 2 s from a ticker thread, so
 * a long point is not silent; --quiet: none. */
typedef struct progress {
    const dfl_sweep *s;
    pthread_mutex_t mu;
    pthread_cond_t cv;
    pthread_t thread;
    int running, stop;
    double t0, tpoint;
    size_t k, done, todo;
} progress;

static void progress_print(progress *p)
{
    const double now = dfl_wall_seconds(), el = now - p->t0;
    char eta[64] = "";
    if (p->done > 0 && p->done < p->todo)
        snprintf(eta, sizeof eta, ", about %.0f s left",
                 el / (double)p->done * (double)(p->todo - p->done));
    fprintf(stderr, "dflab: %s point %zu/%zu (%.1f s on it; %zu of %zu to compute done, %.1f s "
                    "elapsed%s)\n",
            p->s->study->name, p->k + 1, p->s->np, now - p->tpoint, p->done, p->todo, el, eta);
}

static void *progress_tick(void *arg)
{
    progress *p = arg;
    pthread_mutex_lock(&p->mu);
    while (!p->stop) {
        struct timespec ts;
        clock_gettime(CLOCK_REALTIME, &ts);
        ts.tv_sec += 2;
        if (pthread_cond_timedwait(&p->cv, &p->mu, &ts) != 0 && !p->stop) progress_print(p);
    }
    pthread_mutex_unlock(&p->mu);
    return NULL;
}

/* Point k starts (done points finished before it). */
static void progress_point(progress *p, size_t k)
{
    if (p->s->o->quiet) return;
    pthread_mutex_lock(&p->mu);
    const int first = p->k == (size_t)-1;
    p->k = k;
    p->tpoint = dfl_wall_seconds();
    if (first) progress_print(p);
    pthread_mutex_unlock(&p->mu);
    if (first && !p->running)
        p->running = pthread_create(&p->thread, NULL, progress_tick, p) == 0;
}

static void progress_done(progress *p)
{
    pthread_mutex_lock(&p->mu);
    p->done++;
    pthread_mutex_unlock(&p->mu);
}

static void progress_stop(progress *p)
{
    if (p->running) {
        pthread_mutex_lock(&p->mu);
        p->stop = 1;
        pthread_cond_signal(&p->cv);
        pthread_mutex_unlock(&p->mu);
        pthread_join(p->thread, NULL);
    }
    pthread_mutex_destroy(&p->mu);
    pthread_cond_destroy(&p->cv);
}

/* The exit-status rule of harness/nonfinite.h over the folder just
 * written (a point's or the merged one): each point's own allow_nonfinite. */
static dfl_status check_nonfinite(const dfl_sweep *s, const char *dir, dfl_err *err)
{
    bool *allow = calloc(s->np ? s->np : 1, sizeof *allow);
    if (!allow) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    dfl_status st = DFL_OK;
    for (size_t k = 0; k < s->np && st == DFL_OK; k++) {
        dfl_cfg *pt = NULL;
        st = dfl_cfg_sweep_point(s->cfg, k, &pt, err);
        if (st == DFL_OK) st = dfl_study_allow_nonfinite(pt, &allow[k], err);
        dfl_cfg_free(pt);
    }
    if (st == DFL_OK) st = dfl_nonfinite_check(dir, allow, s->np, err);
    free(allow);
    return st;
}

dfl_status dfl_run(const dfl_run_opts *o, dfl_err *err)
{
    dfl_sweep s;
    dfl_status st = dfl_sweep_open(o, &s, err);
    if (st == DFL_OK) st = dfl_dir_check_name(s.outdir, "--out", err);
    if (st == DFL_OK) st = dfl_dir_check_writable(s.outdir, "--out", err);
    if (st == DFL_OK) st = dfl_dir_check_replaceable(s.outdir, "manifest.json", "--out", err);
    if (st != DFL_OK) {
        dfl_sweep_close(&s);
        return st;
    }
    dfl_sweep_clean_stale(s.outdir);
    const size_t lo = o->has_point ? (size_t)o->point : 0;
    const size_t hi = !o->has_point ? s.np
                      : o->point_last > o->point ? (size_t)o->point_last + 1 : lo + 1;
    progress p = {.s = &s, .t0 = dfl_wall_seconds(), .k = (size_t)-1};
    pthread_mutex_init(&p.mu, NULL);
    pthread_cond_init(&p.cv, NULL);
    /* what exists before the points compute is not this run's to remove */
    struct stat pre;
    const bool had_points = lstat(s.points, &pre) == 0, had_out = lstat(s.outdir, &pre) == 0;
    bool *skip = calloc(s.np, sizeof *skip);
    if (!skip) st = dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    for (size_t k = lo; k < hi && st == DFL_OK; k++) {
        bool cur = false;
        if (!o->force) st = dfl_point_check(&s, k, o->quiet, &cur, err);
        skip[k] = cur;
        p.todo += !skip[k];
        /* a job's log says which of its points it did not compute */
        if (cur && o->has_point)
            fprintf(stderr, "dflab: %s: point %zu up to date in %s, skipped (--force "
                            "recomputes)\n", s.study->name, k, s.points);
    }
    /* a large sweep says what it is about to do, even with --quiet */
    if (st == DFL_OK && p.todo >= 1000)
        fprintf(stderr, "dflab: %s: running %zu sweep points\n", s.study->name, p.todo);
    if (st == DFL_OK && !o->quiet && p.todo < hi - lo)
        fprintf(stderr, "dflab: %s: %zu of %zu point%s up to date in %s (--force recomputes)\n",
                s.study->name, hi - lo - p.todo, hi - lo, hi - lo == 1 ? "" : "s", s.points);
    for (size_t k = lo; k < hi && st == DFL_OK; k++) {
        if (skip[k]) continue;
        progress_point(&p, k);
        double sec;
        st = dfl_point_run(&s, k, &sec, err);
        progress_done(&p);
    }
    progress_stop(&p);
    free(skip);
    if (st != DFL_OK) { /* folders this run made and left empty go */
        if (!had_points) rmdir(s.points);
        if (!had_out) rmdir(s.outdir);
    }
    if (st == DFL_OK && !o->has_point)
        st = dfl_merge_into(s.outdir, &s, o->quiet, o->cmdline, err);
    if (st == DFL_OK && !o->quiet) {
        char pd[4400];
        if (o->has_point && hi > lo + 1)
            fprintf(stderr, "dflab: wrote points %zu-%zu into %s/\n", lo, hi - 1, s.points);
        else
            fprintf(stderr, "dflab: wrote %s/\n", o->has_point ? dfl_point_dir(&s, lo, pd, sizeof pd)
                                                                : s.outdir);
    }
    /* after the outputs are written: exit 1 for a non-finite error */
    for (size_t k = lo; st == DFL_OK && k < (o->has_point ? hi : lo + 1); k++) {
        char pd[4400];
        st = check_nonfinite(&s, o->has_point ? dfl_point_dir(&s, k, pd, sizeof pd) : s.outdir,
                             err);
    }
    dfl_sweep_close(&s);
    return st;
}
