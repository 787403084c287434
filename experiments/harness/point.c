/* One sweep point: computed in a stage folder of its own, its CSVs given
 * the point and swept-key columns, its record (point.json) written last,
 * then renamed into OUT.points/ptNNN as a whole. */
#include <dirent.h>
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "core/isa.h"
#include "core/sha256.h"
#include "harness/probe.h"
#include "harness/sweep.h"
#include "io/atomic.h"
#include "io/dirs.h"
#include "io/json.h"
#include "io/manifest.h"
#include "io/meta_attrs.h"
#include "io/rfile.h"
#include "harness/nonfinite.h"
#include "io/table.h"

#include "dfl_version.h"

/* ---- committed points: reading and verifying ------------------------ */

void dfl_point_rec_free(dfl_point_rec *r)
{
    free(r->json);
    r->json = NULL;
}

/* A file name a point may list: one path component, not point.json. */
static bool plain_name(const char *n)
{
    return n[0] && strcmp(n, ".") != 0 && strcmp(n, "..") != 0 && !strchr(n, '/') &&
           strcmp(n, "point.json") != 0;
}

static bool is_hex64(const char *h)
{
    size_t i = 0;
    for (; h[i]; i++)
        if (!((h[i] >= '0' && h[i] <= '9') || (h[i] >= 'a' && h[i] <= 'f'))) return false;
    return i == 64;
}

/* One element of "files" (checked JSON text at e): its name, bytes, sha256. */
static dfl_status file_entry(const char *text, const char *e, const char *name, char *fname,
                             size_t fsize, long *bytes, char *sha, dfl_err *err)
{
    if (*e != '{')
        return dfl_err_set(err, DFL_E_INPUT, "%s: byte %zu: files: expected an object {\"name\", "
                                             "\"bytes\", \"sha256\"}", name, (size_t)(e - text));
    char where[4200];
    snprintf(where, sizeof where, "%s: byte %zu: files", name, (size_t)(e - text));
    dfl_status st = dfl_json_get_string(e, "name", where, fname, fsize, err);
    if (st == DFL_OK && !plain_name(fname))
        st = dfl_err_set(err, DFL_E_INPUT, "%s: name: expected a file name of the point folder, "
                                           "got '%.80s'", where, fname);
    if (st == DFL_OK) st = dfl_json_get_long(e, "bytes", where, 0, LONG_MAX, bytes, err);
    if (st == DFL_OK) st = dfl_json_get_string(e, "sha256", where, sha, 65, err);
    if (st == DFL_OK && !is_hex64(sha))
        st = dfl_err_set(err, DFL_E_INPUT, "%s: sha256: expected 64 lower-case hex digits", where);
    return st;
}

/* Calls fn for each element of the files array of r (stops at a failure). */
typedef dfl_status (*file_fn)(void *ctx, const char *fname, long bytes, const char *sha,
                              dfl_err *err);

static dfl_status each_file(const dfl_point_rec *r, const char *name, file_fn fn, void *ctx,
                            dfl_err *err)
{
    const char *v, *e;
    size_t vl, el;
    if (!dfl_json_member(r->json, "files", &v, &vl))
        return dfl_err_set(err, DFL_E_INPUT, "%s: files: missing", name);
    if (*v != '[')
        return dfl_err_set(err, DFL_E_INPUT, "%s: byte %zu: files: expected an array", name,
                           (size_t)(v - r->json));
    dfl_status st = DFL_OK;
    for (const char *it = v; st == DFL_OK && dfl_json_each(&it, &e, &el);) {
        char fname[1024], sha[65];
        long bytes = 0;
        st = file_entry(r->json, e, name, fname, sizeof fname, &bytes, sha, err);
        if (st == DFL_OK && fn) st = fn(ctx, fname, bytes, sha, err);
    }
    return st;
}

dfl_status dfl_point_parse(char *text, size_t len, const char *name, dfl_point_rec *r,
                           dfl_err *err)
{
    *r = (dfl_point_rec){.threads = -1};
    dfl_status st = dfl_json_check(text, len, name, err);
    if (st == DFL_OK) st = dfl_json_get_long(text, "npoints", name, 1, DFL_POINT_NP_MAX, &r->np, err);
    if (st == DFL_OK) st = dfl_json_get_long(text, "index", name, 0, r->np - 1, &r->index, err);
    if (st == DFL_OK) st = dfl_json_get_string(text, "study", name, r->study, sizeof r->study, err);
    if (st == DFL_OK)
        st = dfl_json_get_string(text, "sweep_sha256", name, r->sweep, sizeof r->sweep, err);
    if (st == DFL_OK)
        st = dfl_json_get_string(text, "binary_sha256", name, r->binary, sizeof r->binary, err);
    const char *v;
    size_t vl;
    if (st == DFL_OK && dfl_json_member(text, "config", &v, &vl))
        st = dfl_json_get_string(text, "config", name, r->config, sizeof r->config, err);
    if (st == DFL_OK && dfl_json_member(text, "threads", &v, &vl))
        st = dfl_json_get_long(text, "threads", name, 1, 1L << 20, &r->threads, err);
    if (st == DFL_OK && dfl_json_member(text, "wall_seconds", &v, &vl))
        st = dfl_json_get_double(text, "wall_seconds", name, &r->wall, err);
    if (st == DFL_OK && dfl_json_member(text, "overrides", &v, &vl) && *v != '[')
        st = dfl_err_set(err, DFL_E_INPUT, "%s: byte %zu: overrides: expected an array of "
                                           "strings", name, (size_t)(v - text));
    r->json = text;
    if (st == DFL_OK) st = each_file(r, name, NULL, NULL, err);
    if (st != DFL_OK) {
        dfl_point_rec_free(r);
        *r = (dfl_point_rec){.threads = -1};
    }
    return st;
}

dfl_status dfl_point_load(const char *dir, dfl_point_rec *r, dfl_err *err)
{
    *r = (dfl_point_rec){.threads = -1};
    char path[8300];
    snprintf(path, sizeof path, "%s/point.json", dir);
    char *text;
    size_t len;
    dfl_status st = dfl_rfile_read(path, "", (size_t)16 << 20, &text, &len, err);
    if (st != DFL_OK) return st;
    return dfl_point_parse(text, len, path, r, err);
}

typedef struct verify_ctx {
    const char *dir;
    bool *changed;
    char **listed;
    size_t n;
} verify_ctx;

static dfl_status verify_one(void *vc, const char *fname, long bytes, const char *sha,
                             dfl_err *err)
{
    verify_ctx *c = vc;
    char path[8300], hex[65];
    snprintf(path, sizeof path, "%s/%s", c->dir, fname);
    char **nw = realloc(c->listed, (c->n + 1) * sizeof *nw);
    if (!nw) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    c->listed = nw;
    if (!(c->listed[c->n] = strdup(fname))) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    c->n++;
    struct stat sb;
    if (lstat(path, &sb) != 0) {
        *c->changed = true;
        return dfl_err_set(err, DFL_E_INPUT, "%s: missing (its point.json lists it)", path);
    }
    if (!S_ISREG(sb.st_mode))
        return dfl_err_set(err, DFL_E_INPUT, "%s: not a regular file (sweep points hold only "
                                             "the files dflab wrote)", path);
    dfl_status st = DFL_OK;
    if ((long long)sb.st_size != (long long)bytes) {
        *c->changed = true;
        return dfl_err_set(err, DFL_E_INPUT, "%s: %lld bytes, its point.json records %ld (changed "
                                             "after the point was computed)", path,
                           (long long)sb.st_size, bytes);
    }
    st = dfl_sha256_file(path, hex, err);
    if (st != DFL_OK) return st;
    if (strcmp(hex, sha) != 0) {
        *c->changed = true;
        return dfl_err_set(err, DFL_E_INPUT, "%s: sha256 differs from the one its point.json "
                                             "records (changed after the point was computed)",
                           path);
    }
    return DFL_OK;
}

dfl_status dfl_point_verify(const char *dir, const dfl_point_rec *r, bool *changed, dfl_err *err)
{
    bool ch = false;
    verify_ctx c = {.dir = dir, .changed = &ch};
    char name[8300];
    snprintf(name, sizeof name, "%s/point.json", dir);
    /* the entries first: a FIFO or folder is refused before any hashing */
    DIR *d = opendir(dir);
    if (!d) return dfl_err_set(err, DFL_E_INPUT, "%s: cannot list: %s", dir, strerror(errno));
    dfl_status st = DFL_OK;
    struct dirent *de;
    while (st == DFL_OK && (de = readdir(d))) {
        if (strcmp(de->d_name, ".") == 0 || strcmp(de->d_name, "..") == 0) continue;
        char p[8300];
        snprintf(p, sizeof p, "%s/%s", dir, de->d_name);
        struct stat sb;
        if (lstat(p, &sb) != 0) st = dfl_err_set(err, DFL_E_IO, "%s: cannot stat: %s", p, strerror(errno));
        else if (!S_ISREG(sb.st_mode))
            st = dfl_err_set(err, DFL_E_INPUT, "%s: not a regular file (%s; sweep points hold "
                                               "only the files dflab wrote)", p,
                             S_ISDIR(sb.st_mode) ? "a folder" : S_ISFIFO(sb.st_mode) ? "a FIFO"
                             : S_ISLNK(sb.st_mode) ? "a symbolic link" : "a device or socket");
    }
    closedir(d);
    if (st == DFL_OK) st = each_file(r, name, verify_one, &c, err);
    /* then nothing unlisted: a file put into the point would be merged */
    d = st == DFL_OK ? opendir(dir) : NULL;
    while (d && st == DFL_OK && (de = readdir(d))) {
        if (strcmp(de->d_name, ".") == 0 || strcmp(de->d_name, "..") == 0 ||
            strcmp(de->d_name, "point.json") == 0)
            continue;
        bool found = false;
        for (size_t i = 0; i < c.n && !found; i++) found = strcmp(c.listed[i], de->d_name) == 0;
        if (!found)
            st = dfl_err_set(err, DFL_E_INPUT, "%s/%s: not listed in its point.json (sweep points "
                                               "hold only the files dflab wrote)", dir, de->d_name);
    }
    if (d) closedir(d);
    for (size_t i = 0; i < c.n; i++) free(c.listed[i]);
    free(c.listed);
    if (changed) *changed = st != DFL_OK && ch;
    return st;
}

dfl_status dfl_point_check(const dfl_sweep *s, size_t k, int quiet, bool *current, dfl_err *err)
{
    *current = false;
    char dir[4400], path[4500];
    dfl_point_dir(s, k, dir, sizeof dir);
    snprintf(path, sizeof path, "%s/point.json", dir);
    struct stat sb;
    if (lstat(dir, &sb) != 0) return DFL_OK; /* not run yet */
    if (!S_ISDIR(sb.st_mode))
        return dfl_err_set(err, DFL_E_INPUT, "%s: not a folder (a sweep point is one)", dir);
    if (lstat(path, &sb) != 0) return DFL_OK; /* no record: recomputed */
    dfl_point_rec r;
    dfl_status st = dfl_point_load(dir, &r, err);
    if (st != DFL_OK) return st;
    if (strcmp(r.sweep, s->sweep_sha) == 0 && strcmp(r.binary, s->binary_sha) == 0 &&
        r.index == (long)k && r.np == (long)s->np) {
        bool changed = false;
        dfl_err e2 = {0};
        st = dfl_point_verify(dir, &r, &changed, &e2);
        if (st == DFL_OK) *current = true;
        else if (changed) { /* recomputed: the files are dflab's to replace */
            if (!quiet) fprintf(stderr, "dflab: %s; recomputing point %zu\n", e2.msg, k);
            st = DFL_OK;
        } else if (err) {
            *err = e2;
        }
    }
    dfl_point_rec_free(&r);
    return st;
}

/* "point" and the swept keys, for the study's table and every other CSV. */
typedef struct prefix {
    const char *cols[64];
    const char *vals[64];
    char point[32];
    size_t n;
} prefix;

static void make_prefix(const dfl_sweep *s, const dfl_cfg *pt, size_t k, prefix *p)
{
    snprintf(p->point, sizeof p->point, "%zu", k);
    p->cols[0] = "point";
    p->vals[0] = p->point;
    p->n = 1;
    for (size_t a = 0; a < s->na && p->n < 64; a++, p->n++) {
        p->cols[p->n] = dfl_cfg_sweep_axis_name(s->cfg, a);
        p->vals[p->n] = dfl_cfg_axis_value(pt, a);
    }
}

static int ends_with(const char *s, const char *suffix)
{
    const size_t n = strlen(s), k = strlen(suffix);
    return n > k && strcmp(s + n - k, suffix) == 0;
}

/* Study, config, sweep point and revision into every .vti/.vtp (FieldData)
 * and .exr (header attributes) of the point, so a file opened in ParaView
 * or an EXR viewer says where it came from. */
static dfl_status annotate(const dfl_sweep *s, const char *dir, const prefix *p, const char *label,
                           dfl_err *err)
{
    const char *names[] = {"dflab_study",  "dflab_config",  "dflab_config_sha256",
                           "dflab_point",  "dflab_sweep",   "dflab_revision"};
    char point[64];
    snprintf(point, sizeof point, "%s of %zu", p->point, s->np);
    const char *values[] = {s->study->name, s->config_stamp, s->sweep_sha,
                            point,          label,           DFL_GIT_REV};
    enum { NATTR = sizeof names / sizeof names[0] };
    DIR *d = opendir(dir);
    if (!d) return dfl_err_set(err, DFL_E_IO, "%s: cannot list", dir);
    dfl_status st = DFL_OK;
    struct dirent *de;
    while ((de = readdir(d)) && st == DFL_OK) {
        if (strstr(de->d_name, ".tmp.")) continue;
        char path[8192];
        snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
        if (ends_with(de->d_name, ".vti") || ends_with(de->d_name, ".vtp"))
            st = dfl_vtk_add_field_data(path, NATTR, names, values, err);
        else if (ends_with(de->d_name, ".exr"))
            st = dfl_exr_add_attrs(path, NATTR, names, values, err);
    }
    closedir(d);
    return st;
}

static dfl_status prefix_csvs(const char *dir, const char *table_name, const prefix *p,
                              dfl_err *err)
{
    DIR *d = opendir(dir);
    if (!d) return dfl_err_set(err, DFL_E_IO, "%s: cannot list", dir);
    dfl_status st = DFL_OK;
    struct dirent *de;
    while ((de = readdir(d)) && st == DFL_OK) {
        const size_t n = strlen(de->d_name);
        if (n < 5 || strcmp(de->d_name + n - 4, ".csv") != 0 || strstr(de->d_name, ".tmp."))
            continue;
        if (strcmp(de->d_name, table_name) == 0) continue;
        char path[8192];
        snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
        st = dfl_table_csv_prepend(path, p->n, p->cols, p->vals, err);
    }
    closedir(d);
    return st;
}

/* JSON object of what the study read, and the keys that took defaults. */
static char *resolved_json(const dfl_cfg *pt, dfl_manifest *rec)
{
    size_t cap = 64, n = 0;
    const size_t nr = dfl_cfg_reads(pt);
    for (size_t i = 0; i < nr; i++) {
        dfl_cfg_read r;
        dfl_cfg_read_at(pt, i, &r);
        cap += 6 * (strlen(r.sec) + strlen(r.key) + strlen(r.value)) + 16;
    }
    char *s = malloc(cap);
    const char **defs = malloc((nr ? nr : 1) * sizeof *defs);
    char **names = calloc(nr ? nr : 1, sizeof *names);
    if (!s || !defs || !names) {
        free(s), free(defs), free(names);
        return NULL;
    }
    size_t nd = 0;
    n += (size_t)snprintf(s + n, cap - n, "{");
    for (size_t i = 0; i < nr; i++) {
        dfl_cfg_read r;
        dfl_cfg_read_at(pt, i, &r);
        size_t kl = strlen(r.sec) + strlen(r.key) + 2;
        names[i] = malloc(kl);
        if (!names[i]) continue;
        snprintf(names[i], kl, "%s.%s", r.sec, r.key);
        char *qk = dfl_json_quote(names[i]), *qv = dfl_json_quote(r.value);
        if (qk && qv) n += (size_t)snprintf(s + n, cap - n, "%s%s: %s", i ? ", " : "", qk, qv);
        free(qk), free(qv);
        if (r.is_default) defs[nd++] = names[i];
    }
    snprintf(s + n, cap - n, "}");
    dfl_manifest_put_strings(rec, "defaults", nd, defs);
    for (size_t i = 0; i < nr; i++) free(names[i]);
    free(names);
    free(defs);
    return s;
}

static char *values_json(const prefix *p)
{
    size_t cap = 16;
    for (size_t i = 1; i < p->n; i++) cap += 6 * (strlen(p->cols[i]) + strlen(p->vals[i])) + 12;
    char *s = malloc(cap);
    if (!s) return NULL;
    size_t n = (size_t)snprintf(s, cap, "{");
    for (size_t i = 1; i < p->n; i++) {
        char *qk = dfl_json_quote(p->cols[i]), *qv = dfl_json_quote(p->vals[i]);
        if (qk && qv) n += (size_t)snprintf(s + n, cap - n, "%s%s: %s", i > 1 ? ", " : "", qk, qv);
        free(qk), free(qv);
    }
    snprintf(s + n, cap - n, "}");
    return s;
}

static dfl_status write_record(const dfl_sweep *s, const dfl_cfg *pt, size_t k, const prefix *p,
                               double seconds, const char *stage, dfl_err *err)
{
    dfl_manifest *m = dfl_manifest_new();
    if (!m) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    char host[256] = "", date[64], libs[512], hex[65];
    gethostname(host, sizeof host - 1);
    time_t now = time(NULL);
    struct tm tmv;
    gmtime_r(&now, &tmv);
    strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", &tmv);
    dfl_cfg_sweep_hash(pt, hex);
    dfl_manifest_put_int(m, "index", (long)k);
    dfl_manifest_put_int(m, "npoints", (long)s->np);
    dfl_manifest_put_string(m, "study", s->study->name);
    dfl_manifest_put_string(m, "config", s->config_stamp);
    dfl_manifest_put_strings(m, "overrides", (size_t)s->o->nsets, s->o->sets);
    dfl_manifest_put_string(m, "sweep_sha256", s->sweep_sha);
    dfl_manifest_put_string(m, "binary_sha256", s->binary_sha);
    dfl_manifest_put_string(m, "config_sha256", hex);
    char *vj = values_json(p);
    dfl_manifest_put_raw(m, "sweep_values", vj ? vj : "{}");
    free(vj);
    char *rj = resolved_json(pt, m); /* also puts "defaults" */
    dfl_manifest_put_raw(m, "resolved", rj ? rj : "{}");
    free(rj);
    dfl_manifest_put_double(m, "wall_seconds", seconds);
    dfl_manifest_put_int(m, "exit_status", 0);
    dfl_manifest_put_string(m, "host", host);
    dfl_manifest_put_int(m, "threads", s->threads);
    /* the instruction set the hot kernels ran (core/isa.h; the same bytes
     * on every one, recorded so that a check of that can be traced) */
    dfl_manifest_put_string(m, "isa", dfl_isa_name(dfl_isa_active()));
    dfl_manifest_put_string(m, "command_line", s->o->cmdline ? s->o->cmdline : "");
    dfl_manifest_put_string(m, "date", date);
    dfl_manifest_put_string(m, "version", DFL_VERSION);
    dfl_manifest_put_string(m, "git_revision", DFL_GIT_REV);
    dfl_manifest_put_raw(m, "libraries", dfl_manifest_libraries(libs, sizeof libs));
    char path[8192];
    snprintf(path, sizeof path, "%s/point.json", stage);
    dfl_status st = dfl_manifest_write(m, path, stage, err);
    dfl_manifest_free(m);
    return st;
}

static dfl_status compute(const dfl_sweep *s, dfl_cfg *pt, size_t k, const char *stage,
                          double *seconds, dfl_err *err)
{
    prefix p;
    make_prefix(s, pt, k, &p);
    dfl_table *t = dfl_table_new();
    if (!t) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    dfl_status st = DFL_OK;
    for (size_t i = 0; i < p.n && st == DFL_OK; i++)
        st = dfl_table_prefix_string(t, p.cols[i], p.vals[i], err);
    const char *dummy;
    dfl_cfg_string(pt, "study", "name", &dummy, NULL); /* mark used */
    double mem_budget, work_budget; /* the runner's keys; validation checked them */
    dfl_sweep_budgets(pt, &mem_budget, &work_budget, NULL);
    bool allow; /* read by the runner after the run (harness/nonfinite.h) */
    dfl_study_allow_nonfinite(pt, &allow, NULL);
    char tag[32];
    dfl_study_tag(k, s->np, tag, sizeof tag);
    dfl_study_ctx ctx = {.stage_dir = stage, .tag = tag, .point = k, .npoints = s->np,
                         .threads = s->threads};
    const double t0 = dfl_wall_seconds();
    dfl_probe_sections_defer(pt);
    if (st == DFL_OK) st = s->study->run(pt, &ctx, t, err);
    if (st == DFL_OK) st = dfl_cfg_check_used(pt, err);
    if (st == DFL_OK) st = dfl_probe_sections_check(pt, err);
    *seconds = dfl_wall_seconds() - t0;
    char name[600], path[8192];
    snprintf(name, sizeof name, "%s.csv", s->study->name);
    snprintf(path, sizeof path, "%s/%s", stage, name);
    if (st == DFL_OK) st = dfl_table_write_csv(t, path, err);
    dfl_table_free(t);
    if (st == DFL_OK) st = prefix_csvs(stage, name, &p, err);
    char label[2048];
    dfl_sweep_label(s, pt, label, sizeof label);
    if (st == DFL_OK) st = annotate(s, stage, &p, label, err);
    snprintf(path, sizeof path, "%s/config.ini", stage);
    if (st == DFL_OK) st = dfl_cfg_write(s->cfg, s->config_stamp, path, err);
    if (st == DFL_OK) st = write_record(s, pt, k, &p, *seconds, stage, err);
    return st;
}

dfl_status dfl_point_run(const dfl_sweep *s, size_t k, double *seconds, dfl_err *err)
{
    char dir[4400], stage[4600], label[2048];
    dfl_point_dir(s, k, dir, sizeof dir);
    dfl_dir_owned_name(dir, "stage", stage, sizeof stage);
    dfl_cfg *pt = NULL;
    dfl_status st = dfl_cfg_sweep_point(s->cfg, k, &pt, err);
    if (st == DFL_OK) st = dfl_mkdir_p(stage, err);
    if (st == DFL_OK) st = compute(s, pt, k, stage, seconds, err);
    if (st == DFL_OK) st = dfl_dir_replace(stage, dir, err);
    if (st != DFL_OK) {
        dfl_dir_remove_tree(stage, NULL);
        if (s->np > 1 && pt)
            dfl_err_prefix(err, "sweep point %zu (%s)", k, dfl_sweep_label(s, pt, label, sizeof label));
    }
    dfl_cfg_free(pt);
    return st;
}
