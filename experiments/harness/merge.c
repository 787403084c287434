/* The merge: points -> the files a one-process run writes.  A one-process
 * run merges too, so "byte-identical to a one-process run" holds by
 * construction for the tables; the checks here make sure the points being
 * merged belong together. */
#include <dirent.h>
#include <errno.h>
#include <libgen.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "harness/experiment.h"
#include "harness/nonfinite.h"
#include "harness/sweep.h"
#include "io/atomic.h"
#include "io/dirs.h"
#include "io/json.h"
#include "io/manifest.h"
#include "io/table.h"
#include "io/vtk.h"

#include "dfl_version.h"

typedef struct pt_rec {
    dfl_point_rec rec; /* rec.json NULL: no point */
    char dir[8192];
    long named; /* the folder's number */
} pt_rec;

/* "ptNNN" -> NNN, else -1 (stage folders and other names). */
static long point_name(const char *name)
{
    if (strncmp(name, "pt", 2) != 0 || !name[2]) return -1;
    for (const char *c = name + 2; *c; c++)
        if (*c < '0' || *c > '9') return -1;
    return strtol(name + 2, NULL, 10);
}

/* point.json of dir, strictly parsed (malformed: exit 2 naming the byte). */
static dfl_status load_rec(const char *dir, pt_rec *r, dfl_err *err)
{
    snprintf(r->dir, sizeof r->dir, "%s", dir);
    return dfl_point_load(dir, &r->rec, err);
}

static void free_recs(pt_rec *r, size_t n)
{
    for (size_t i = 0; r && i < n; i++) dfl_point_rec_free(&r[i].rec);
    free(r);
}

static int by_name(const void *a, const void *b)
{
    const long x = ((const pt_rec *)a)->named, y = ((const pt_rec *)b)->named;
    return (x > y) - (x < y);
}

/* Whether r belongs to the sweep `expect` (or, without one, to ref). */
static const char *foreign(const pt_rec *pr, const pt_rec *pref, const dfl_sweep *expect)
{
    const dfl_point_rec *r = &pr->rec, *ref = &pref->rec;
    if (expect) {
        if (strcmp(r->sweep, expect->sweep_sha) != 0) return "another config";
        if (strcmp(r->binary, expect->binary_sha) != 0) return "another dflab binary";
        if (r->np != (long)expect->np) return "a sweep of another size";
        return NULL;
    }
    if (strcmp(r->study, ref->study) != 0) return "another study";
    if (strcmp(r->sweep, ref->sweep) != 0) return "another config";
    if (strcmp(r->binary, ref->binary) != 0) return "another dflab binary";
    if (r->np != ref->np) return "a sweep of another size";
    return NULL;
}

/* DFL_E_INPUT naming the first missing indices of 0..np-1, given the n
 * folders of all sorted by number. */
static dfl_status missing(const char *pdir, const pt_rec *all, size_t n, size_t np, dfl_err *err)
{
    char miss[512] = "";
    size_t nm = 0, ml = 0, j = 0;
    for (size_t k = 0; k < np; k++) {
        while (j < n && all[j].named < (long)k) j++;
        if (j < n && all[j].named == (long)k) continue;
        if (nm++ < 12) ml += (size_t)snprintf(miss + ml, sizeof miss - ml, "%s%zu", ml ? ", " : "", k);
        else if (j >= n) { /* the rest are all missing */
            nm += np - k - 1;
            break;
        }
    }
    return dfl_err_set(err, DFL_E_INPUT, "%s: %zu of %zu sweep points missing: %s%s (run them "
                                         "with `dflab run CONFIG --point K`)", pdir, nm, np, miss,
                       nm > 12 ? ", ..." : "");
}

/* The committed points of dir/points in index order, checked: complete,
 * each index once, all from one sweep (expect's, when given: other points
 * are then stale and left out). */
static dfl_status collect(const char *dir, const dfl_sweep *expect, pt_rec **out, size_t *nout,
                          dfl_err *err)
{
    char pdir[4200];
    snprintf(pdir, sizeof pdir, "%s.points", dir);
    DIR *d = opendir(pdir);
    if (!d)
        return dfl_err_set(err, DFL_E_INPUT, "%s: no sweep points to merge (run `dflab run CONFIG "
                                             "--point K --out %s` first)", pdir, dir);
    pt_rec *all = NULL;
    size_t n = 0;
    dfl_status st = DFL_OK;
    struct dirent *de;
    while ((de = readdir(d)) && st == DFL_OK) {
        if (point_name(de->d_name) < 0) continue;
        pt_rec *a = realloc(all, (n + 1) * sizeof *a);
        if (!a) {
            st = dfl_err_set(err, DFL_E_NOMEM, "out of memory");
            break;
        }
        all = a;
        memset(&all[n], 0, sizeof all[n]);
        char sub[8192];
        snprintf(sub, sizeof sub, "%s/%s", pdir, de->d_name);
        st = load_rec(sub, &all[n], err);
        all[n++].named = point_name(de->d_name);
    }
    closedir(d);
    if (n > 1) qsort(all, n, sizeof *all, by_name);
    size_t np = expect ? expect->np : (n ? (size_t)all[0].rec.np : 0);
    /* fewer folders than points: say which are missing before allocating
     * np records (np may be up to DFL_POINT_NP_MAX) */
    if (st == DFL_OK && n && n < np) st = missing(pdir, all, n, np, err);
    pt_rec *ord = st == DFL_OK ? calloc(np ? np : 1, sizeof *ord) : NULL;
    if (st == DFL_OK && !ord) st = dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    if (st == DFL_OK && n == 0)
        st = dfl_err_set(err, DFL_E_INPUT, "%s: no sweep points to merge", pdir);
    for (size_t i = 0; i < n && st == DFL_OK; i++) {
        const char *why = foreign(&all[i], &all[0], expect);
        if (why && expect) continue; /* stale: the swap removes it */
        if (why)
            st = dfl_err_set(err, DFL_E_INPUT, "%s: a point of %s than %s (merge only the points "
                                               "of one sweep)", all[i].dir, why, all[0].dir);
        else if (all[i].rec.index != all[i].named)
            st = dfl_err_set(err, DFL_E_INPUT, "%s: holds point %ld (a copied or renamed folder: "
                                               "each point must be merged once)", all[i].dir,
                             all[i].rec.index);
        else if ((size_t)all[i].rec.index >= np) /* index < its own np <= the sweep's */
            st = dfl_err_set(err, DFL_E_INPUT, "%s: point %ld outside the sweep's 0..%zu",
                             all[i].dir, all[i].rec.index, np - 1);
        else if (ord[all[i].rec.index].rec.json)
            st = dfl_err_set(err, DFL_E_INPUT, "%s: duplicate of point %ld (%s)", all[i].dir,
                             all[i].rec.index, ord[all[i].rec.index].dir);
        else if ((st = dfl_point_verify(all[i].dir, &all[i].rec, NULL, err)) == DFL_OK) {
            ord[all[i].rec.index] = all[i];
            all[i].rec.json = NULL;
        }
    }
    if (st == DFL_OK) {
        char miss[512] = "";
        size_t nm = 0, ml = 0;
        for (size_t k = 0; k < np; k++)
            if (!ord[k].rec.json && nm++ < 12 && ml < sizeof miss)
                ml += (size_t)snprintf(miss + ml, sizeof miss - ml, "%s%zu", ml ? ", " : "", k);
        if (nm)
            st = dfl_err_set(err, DFL_E_INPUT, "%s: %zu of %zu sweep points missing: %s%s (run them "
                                               "with `dflab run CONFIG --point K`)", pdir, nm, np,
                             miss, nm > 12 ? ", ..." : "");
    }
    free_recs(all, n);
    if (st != DFL_OK) {
        free_recs(ord, np);
        return st;
    }
    *out = ord;
    *nout = np;
    return DFL_OK;
}

/* ---- assembling ------------------------------------------------------- */

static int is_point_meta(const char *name, const char *table)
{
    return strcmp(name, "point.json") == 0 || strcmp(name, "config.ini") == 0 ||
           strcmp(name, table) == 0;
}

static dfl_status link_files(const pt_rec *r, const char *stage, const char *table, dfl_err *err)
{
    DIR *d = opendir(r->dir);
    if (!d) return dfl_err_set(err, DFL_E_IO, "%s: cannot list: %s", r->dir, strerror(errno));
    dfl_status st = DFL_OK;
    struct dirent *de;
    while ((de = readdir(d)) && st == DFL_OK) {
        if (de->d_name[0] == '.' || is_point_meta(de->d_name, table)) continue;
        char a[8600], b[8192];
        snprintf(a, sizeof a, "%s/%s", r->dir, de->d_name);
        snprintf(b, sizeof b, "%s/%s", stage, de->d_name);
        if (access(b, F_OK) == 0)
            st = dfl_err_set(err, DFL_E_INTERNAL, "%s: written by two sweep points (the study "
                                                  "must name per-point files with its tag)", a);
        else
            st = dfl_dir_link_or_copy(a, b, err);
    }
    closedir(d);
    return st;
}

/* ---- the sweep's collections: <stem>.pvd per <stem>_ptNNN.vti|.vtp ---- */

typedef struct stem_list {
    char (*name)[600];
    char ext[64][4];
    size_t n;
} stem_list;

/* Adds the stems of point k's VTK files (<stem><tag>.vti / .vtp) to l. */
static void add_stems(const pt_rec *r, size_t k, size_t n, stem_list *l)
{
    char tag[64];
    dfl_study_tag(k, n, tag, sizeof tag);
    DIR *d = opendir(r->dir);
    if (!d) return;
    struct dirent *de;
    while ((de = readdir(d)) && l->n < 64) {
        const size_t len = strlen(de->d_name), tl = strlen(tag);
        if (len < tl + 5 || len - tl - 4 >= sizeof l->name[0]) continue;
        const char *ext = de->d_name + len - 4;
        if (strcmp(ext, ".vti") != 0 && strcmp(ext, ".vtp") != 0) continue;
        if (strncmp(ext - tl, tag, tl) != 0) continue;
        char stem[600];
        snprintf(stem, sizeof stem, "%.*s", (int)(len - tl - 4), de->d_name);
        size_t i = 0;
        while (i < l->n && !(strcmp(l->name[i], stem) == 0 && strcmp(l->ext[i], ext + 1) == 0))
            i++;
        if (i == l->n) {
            snprintf(l->name[l->n], sizeof l->name[0], "%s", stem);
            snprintf(l->ext[l->n], sizeof l->ext[0], "%s", ext + 1);
            l->n++;
        }
    }
    closedir(d);
}

/* A sweep's VTK files as ParaView collections: for every stem, <stem>.pvd
 * (<stem>_<ext>.pvd when a .vti and a .vtp share the stem) listing
 * <stem>_ptNNN.<ext> of the points that wrote one, time = the point index,
 * so the time slider steps through the sweep (the CSV's point column says
 * what each point sets).  Nothing for a run of one point, nor for a stem
 * that fewer than two points wrote. */
static dfl_status write_collections(const pt_rec *r, size_t n, const char *stage, dfl_err *err)
{
    if (n < 2) return DFL_OK;
    stem_list l = {.name = malloc(64 * sizeof *l.name)};
    if (!l.name) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    for (size_t k = 0; k < n; k++) add_stems(&r[k], k, n, &l);
    dfl_pvd_entry *e = malloc(n * sizeof *e);
    char (*files)[700] = malloc(n * sizeof *files);
    dfl_status st = e && files ? DFL_OK : dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    for (size_t i = 0; i < l.n && st == DFL_OK; i++) {
        size_t m = 0;
        for (size_t k = 0; k < n; k++) {
            char tag[64], p[8192];
            dfl_study_tag(k, n, tag, sizeof tag);
            snprintf(files[m], sizeof files[0], "%s%s.%s", l.name[i], tag, l.ext[i]);
            snprintf(p, sizeof p, "%s/%s", stage, files[m]);
            if (access(p, F_OK) == 0) e[m] = (dfl_pvd_entry){files[m], (double)k}, m++;
        }
        if (m < 2) continue; /* a file of one point (e.g. written once per run) */
        int shared = 0;
        for (size_t j = 0; j < l.n; j++) shared |= j != i && strcmp(l.name[j], l.name[i]) == 0;
        char path[8192];
        if (shared)
            snprintf(path, sizeof path, "%s/%s_%s.pvd", stage, l.name[i], l.ext[i]);
        else
            snprintf(path, sizeof path, "%s/%s.pvd", stage, l.name[i]);
        st = dfl_pvd_write(path, e, m, err);
    }
    free(e);
    free(files);
    free(l.name);
    return st;
}

static dfl_status write_manifest(const pt_rec *r, size_t n, const char *stage,
                                 const char *cmdline, dfl_err *err)
{
    dfl_manifest *m = dfl_manifest_new();
    if (!m) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    char host[256] = "", date[64], libs[512];
    gethostname(host, sizeof host - 1);
    time_t now = time(NULL);
    struct tm tmv;
    gmtime_r(&now, &tmv);
    strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", &tmv);
    dfl_manifest_put_format(m); /* first: it tells a dflab folder from others */
    dfl_manifest_put_string(m, "tool", "dflab");
    dfl_manifest_put_string(m, "version", DFL_VERSION);
    dfl_manifest_put_string(m, "git_revision", DFL_GIT_REV);
    dfl_manifest_put_string(m, "date", date);
    dfl_manifest_put_string(m, "config", r[0].rec.config);
    dfl_manifest_put_string(m, "study", r[0].rec.study);
    /* the overrides, sweep and binary are the points' (all equal); the
     * record passed the strict reader, so its text is JSON to embed */
    const char *ov;
    size_t ovl;
    if (dfl_json_member(r[0].rec.json, "overrides", &ov, &ovl)) {
        char *raw = strndup(ov, ovl);
        if (raw) dfl_manifest_put_raw(m, "overrides", raw);
        free(raw);
    }
    dfl_manifest_put_string(m, "sweep_sha256", r[0].rec.sweep);
    dfl_manifest_put_string(m, "binary_sha256", r[0].rec.binary);
    dfl_manifest_put_int(m, "npoints", (long)n);
    /* the command that assembled the folder: the run itself, or merge */
    dfl_manifest_put_string(m, "command_line", cmdline ? cmdline : "");
    if (r[0].rec.threads > 0) dfl_manifest_put_int(m, "threads", r[0].rec.threads);
    dfl_manifest_put_string(m, "host", host);
    dfl_manifest_put_raw(m, "libraries", dfl_manifest_libraries(libs, sizeof libs));
    double total = 0;
    size_t cap = 8;
    for (size_t k = 0; k < n; k++) total += r[k].rec.wall, cap += strlen(r[k].rec.json) + 4;
    char *pts = malloc(cap);
    if (pts) {
        size_t len = (size_t)snprintf(pts, cap, "[");
        for (size_t k = 0; k < n; k++) {
            const char *j = r[k].rec.json;
            size_t jl = strlen(j);
            while (jl && strchr(" \t\r\n", j[jl - 1])) jl--;
            len += (size_t)snprintf(pts + len, cap - len, "%s%.*s", k ? ", " : "", (int)jl, j);
        }
        snprintf(pts + len, cap - len, "]");
        dfl_manifest_put_raw(m, "points", pts);
        free(pts);
    }
    dfl_manifest_put_double(m, "total_wall_seconds", total);
    char path[8192];
    snprintf(path, sizeof path, "%s/manifest.json", stage);
    dfl_status st = dfl_manifest_write(m, path, stage, err);
    dfl_manifest_free(m);
    return st;
}

/* Removes dead runs' leftovers "<prefix>stage.*" and "<prefix>old.*" in
 * dir.  A dead run's backup "<out>.old.*" of a folder that is missing is
 * the only copy of it (a replacement cut off between its two renames):
 * it is put back at out, never removed. */
static void clean_in(const char *dir, const char *prefix, const char *out)
{
    DIR *d = opendir(dir);
    if (!d) return;
    const size_t pl = strlen(prefix);
    struct dirent *de;
    while ((de = readdir(d))) {
        if (strncmp(de->d_name, prefix, pl) != 0) continue;
        if (!dfl_dir_owner_dead(de->d_name, "stage") && !dfl_dir_owner_dead(de->d_name, "old"))
            continue;
        char p[8192];
        snprintf(p, sizeof p, "%s/%s", dir, de->d_name);
        if (out && dfl_dir_owner_dead(de->d_name, "old") && dfl_dir_restore_stale(p, out)) continue;
        if (out && dfl_dir_owner_dead(de->d_name, "old") && access(out, F_OK) != 0) continue;
        dfl_dir_remove_tree(p, NULL);
    }
    closedir(d);
}

void dfl_sweep_clean_stale(const char *outdir)
{
    char parent[4096], base[4096], prefix[4200], pdir[4200];
    snprintf(parent, sizeof parent, "%s", outdir);
    snprintf(base, sizeof base, "%s", outdir);
    snprintf(prefix, sizeof prefix, "%s.", basename(base));
    clean_in(dirname(parent), prefix, outdir);
    snprintf(pdir, sizeof pdir, "%s.points", outdir);
    clean_in(pdir, "pt", NULL);
}

/* Removes the committed points of pdir that the merge did not take (an
 * earlier sweep's), so the folder holds one sweep. */
static void drop_stale(const char *pdir, const pt_rec *r, size_t n)
{
    DIR *d = opendir(pdir);
    if (!d) return;
    struct dirent *de;
    while ((de = readdir(d))) {
        const long k = point_name(de->d_name);
        if (k < 0) continue;
        char p[8192];
        snprintf(p, sizeof p, "%s/%s", pdir, de->d_name);
        if ((size_t)k < n && strcmp(r[k].dir, p) == 0) continue;
        dfl_dir_remove_tree(p, NULL);
    }
    closedir(d);
}

dfl_status dfl_merge_into(const char *dir, const dfl_sweep *expect, int quiet,
                          const char *cmdline, dfl_err *err)
{
    pt_rec *r = NULL;
    size_t n = 0;
    dfl_status st = collect(dir, expect, &r, &n, err);
    if (st != DFL_OK) return st;
    char stage[4400], table[600], path[9000], pdir[4600];
    dfl_dir_owned_name(dir, "stage", stage, sizeof stage);
    snprintf(table, sizeof table, "%s.csv", r[0].rec.study);
    dfl_table *t = dfl_table_new();
    if (!t) st = dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    if (st == DFL_OK) st = dfl_mkdir_p(stage, err);
    for (size_t k = 0; k < n && st == DFL_OK; k++) {
        snprintf(path, sizeof path, "%s/%s", r[k].dir, table);
        st = dfl_table_append_csv(t, path, err);
        if (st == DFL_E_IO)
            st = dfl_err_set(err, DFL_E_INPUT, "%s: missing (an incomplete point?)", path);
        if (st == DFL_OK) st = link_files(&r[k], stage, table, err);
    }
    snprintf(path, sizeof path, "%s/%s", stage, table);
    if (st == DFL_OK) st = dfl_table_write_csv(t, path, err);
    dfl_table_free(t);
    char a[8300];
    snprintf(a, sizeof a, "%s/config.ini", r[0].dir);
    snprintf(path, sizeof path, "%s/config.ini", stage);
    if (st == DFL_OK) st = dfl_dir_link_or_copy(a, path, err);
    if (st == DFL_OK) st = write_collections(r, n, stage, err);
    if (st == DFL_OK) st = write_manifest(r, n, stage, cmdline, err);
    if (st == DFL_OK) st = dfl_dir_replace(stage, dir, err);
    if (st != DFL_OK) {
        dfl_dir_remove_tree(stage, NULL);
    } else if (expect) {
        snprintf(pdir, sizeof pdir, "%s.points", dir);
        drop_stale(pdir, r, n);
    } else if (!quiet) {
        fprintf(stderr, "dflab: merged %zu point%s into %s/\n", n, n == 1 ? "" : "s", dir);
    }
    free_recs(r, n);
    return st;
}

/* The run's exit-status rule of harness/nonfinite.h over a folder `dflab
 * merge` assembled: each point's allow_nonfinite from the sweep's own
 * config.ini, as the run of that config would have read it. */
static dfl_status merged_nonfinite(const char *dir, dfl_err *err)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/config.ini", dir);
    dfl_cfg *c = NULL;
    dfl_status st = dfl_cfg_load(path, &c, err);
    if (st != DFL_OK) return st;
    const size_t np = dfl_cfg_sweep_points(c);
    bool *allow = calloc(np ? np : 1, sizeof *allow);
    if (!allow) st = dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    for (size_t k = 0; k < np && st == DFL_OK; k++) {
        dfl_cfg *pt = NULL;
        st = dfl_cfg_sweep_point(c, k, &pt, err);
        if (st == DFL_OK) st = dfl_study_allow_nonfinite(pt, &allow[k], err);
        dfl_cfg_free(pt);
    }
    if (st == DFL_OK) st = dfl_nonfinite_check(dir, allow, np, err);
    free(allow);
    dfl_cfg_free(c);
    return st;
}

dfl_status dfl_merge(const char *dir, int quiet, const char *cmdline, dfl_err *err)
{
    char d[4096];
    snprintf(d, sizeof d, "%s", dir);
    size_t l = strlen(d);
    while (l > 1 && d[l - 1] == '/') d[--l] = '\0';
    dfl_status st = dfl_dir_check_name(d, "merge", err);
    if (st == DFL_OK) st = dfl_dir_check_replaceable(d, "manifest.json", "merge", err);
    if (st != DFL_OK) return st;
    dfl_sweep_clean_stale(d);
    st = dfl_merge_into(d, NULL, quiet, cmdline, err);
    return st == DFL_OK ? merged_nonfinite(d, err) : st;
}
