/* One sweep point: computed in a stage folder of its own, its CSVs given
 * the point and swept-key columns, its record (point.json) written last,
 * then renamed into OUT.points/ptNNN as a whole. */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "harness/probe.h"
#include "harness/sweep.h"
#include "io/atomic.h"
#include "io/dirs.h"
#include "io/manifest.h"
#include "io/meta_attrs.h"
#include "harness/nonfinite.h"
#include "io/table.h"

#include "dfl_version.h"

bool dfl_point_current(const dfl_sweep *s, size_t k)
{
    char dir[4400], path[4500];
    snprintf(path, sizeof path, "%s/point.json", dfl_point_dir(s, k, dir, sizeof dir));
    char *j = dfl_file_read_all(path, NULL);
    if (!j) return false;
    char sw[80], bin[80];
    double idx = -1, np = -1;
    bool ok = dfl_json_find_string(j, "sweep_sha256", sw, sizeof sw) &&
              dfl_json_find_string(j, "binary_sha256", bin, sizeof bin) &&
              dfl_json_find_number(j, "index", &idx) && dfl_json_find_number(j, "npoints", &np) &&
              strcmp(sw, s->sweep_sha) == 0 && strcmp(bin, s->binary_sha) == 0 &&
              (size_t)idx == k && (size_t)np == s->np;
    free(j);
    return ok;
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
    const char *names[] = {"dflab_study", "dflab_config", "dflab_point", "dflab_sweep",
                           "dflab_revision"};
    char point[64];
    snprintf(point, sizeof point, "%s of %zu", p->point, s->np);
    const char *values[] = {s->study->name, s->o->config, point, label, DFL_GIT_REV};
    DIR *d = opendir(dir);
    if (!d) return dfl_err_set(err, DFL_E_IO, "%s: cannot list", dir);
    dfl_status st = DFL_OK;
    struct dirent *de;
    while ((de = readdir(d)) && st == DFL_OK) {
        if (strstr(de->d_name, ".tmp.")) continue;
        char path[8192];
        snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
        if (ends_with(de->d_name, ".vti") || ends_with(de->d_name, ".vtp"))
            st = dfl_vtk_add_field_data(path, 5, names, values, err);
        else if (ends_with(de->d_name, ".exr"))
            st = dfl_exr_add_attrs(path, 5, names, values, err);
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
    dfl_manifest_put_string(m, "config", s->o->config);
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
    if (st == DFL_OK) st = dfl_cfg_write(s->cfg, path, err);
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
