/* The manifest is JSON written by hand: a few flat fields and two arrays,
 * not worth a dependency. */
#include "io/manifest.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "io/atomic.h"

#include "dfl_version.h"

typedef struct kv {
    char *k, *v;
    double t;
} kv;

struct dfl_manifest {
    char *config, *study;
    kv *steps;
    size_t nsteps;
    kv *notes;
    size_t nnotes;
};

static char *dup(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d) memcpy(d, s, n);
    return d;
}

double dfl_wall_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

dfl_manifest *dfl_manifest_new(const char *config_path, const char *study)
{
    dfl_manifest *m = calloc(1, sizeof *m);
    if (!m) return NULL;
    m->config = dup(config_path);
    m->study = dup(study);
    if (!m->config || !m->study) {
        dfl_manifest_free(m);
        return NULL;
    }
    return m;
}

void dfl_manifest_free(dfl_manifest *m)
{
    if (!m) return;
    for (size_t i = 0; i < m->nsteps; i++) free(m->steps[i].k);
    for (size_t i = 0; i < m->nnotes; i++) free(m->notes[i].k), free(m->notes[i].v);
    free(m->steps);
    free(m->notes);
    free(m->config);
    free(m->study);
    free(m);
}

dfl_status dfl_manifest_step(dfl_manifest *m, const char *name, double seconds)
{
    kv *s = realloc(m->steps, (m->nsteps + 1) * sizeof *s);
    if (!s) return DFL_E_NOMEM;
    m->steps = s;
    s[m->nsteps].k = dup(name);
    s[m->nsteps].v = NULL;
    s[m->nsteps].t = seconds;
    if (!s[m->nsteps].k) return DFL_E_NOMEM;
    m->nsteps++;
    return DFL_OK;
}

dfl_status dfl_manifest_note(dfl_manifest *m, const char *key, const char *value)
{
    kv *s = realloc(m->notes, (m->nnotes + 1) * sizeof *s);
    if (!s) return DFL_E_NOMEM;
    m->notes = s;
    s[m->nnotes].k = dup(key);
    s[m->nnotes].v = dup(value);
    if (!s[m->nnotes].k || !s[m->nnotes].v) {
        free(s[m->nnotes].k), free(s[m->nnotes].v);
        return DFL_E_NOMEM;
    }
    m->nnotes++;
    return DFL_OK;
}

static void json_str(FILE *fp, const char *s)
{
    fputc('"', fp);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\') fprintf(fp, "\\%c", c);
        else if (c < 0x20) fprintf(fp, "\\u%04x", c);
        else fputc(c, fp);
    }
    fputc('"', fp);
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

dfl_status dfl_manifest_write(const dfl_manifest *m, const char *dir, dfl_err *err)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/manifest.json", dir);
    /* collect the files first (sorted, for stable manifests) */
    DIR *d = opendir(dir);
    if (!d) return dfl_err_set(err, DFL_E_IO, "%s: cannot list directory", dir);
    char **names = NULL;
    size_t nn = 0;
    struct dirent *de;
    while ((de = readdir(d))) {
        if (de->d_name[0] == '.' || strcmp(de->d_name, "manifest.json") == 0) continue;
        if (strstr(de->d_name, ".tmp.")) continue;
        char **nw = realloc(names, (nn + 1) * sizeof *nw);
        if (!nw) break;
        names = nw;
        names[nn] = dup(de->d_name);
        if (names[nn]) nn++;
    }
    closedir(d);
    qsort(names, nn, sizeof *names, cmp_str);

    dfl_atomic_file af;
    dfl_status st = dfl_atomic_open(path, &af, err);
    if (st != DFL_OK) {
        for (size_t i = 0; i < nn; i++) free(names[i]);
        free(names);
        return st;
    }
    FILE *fp = af.fp;
    char date[64];
    time_t now = time(NULL);
    struct tm tmv;
    gmtime_r(&now, &tmv);
    strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", &tmv);
    fprintf(fp, "{\n  \"tool\": \"dflab\",\n  \"version\": \"%s\",\n  \"git_revision\": ", DFL_VERSION);
    json_str(fp, DFL_GIT_REV);
    fprintf(fp, ",\n  \"date\": \"%s\",\n  \"config\": ", date);
    json_str(fp, m->config);
    fprintf(fp, ",\n  \"study\": ");
    json_str(fp, m->study);
    for (size_t i = 0; i < m->nnotes; i++) {
        fprintf(fp, ",\n  ");
        json_str(fp, m->notes[i].k);
        fprintf(fp, ": ");
        json_str(fp, m->notes[i].v);
    }
    fprintf(fp, ",\n  \"steps\": [");
    double total = 0;
    for (size_t i = 0; i < m->nsteps; i++) {
        fprintf(fp, "%s\n    {\"name\": ", i ? "," : "");
        json_str(fp, m->steps[i].k);
        fprintf(fp, ", \"wall_seconds\": %.6f}", m->steps[i].t);
        total += m->steps[i].t;
    }
    fprintf(fp, "\n  ],\n  \"total_wall_seconds\": %.6f,\n  \"files\": [", total);
    for (size_t i = 0; i < nn; i++) {
        char fpth[8192];
        snprintf(fpth, sizeof fpth, "%s/%s", dir, names[i]);
        struct stat sb;
        long long size = stat(fpth, &sb) == 0 ? (long long)sb.st_size : -1;
        fprintf(fp, "%s\n    {\"name\": ", i ? "," : "");
        json_str(fp, names[i]);
        fprintf(fp, ", \"bytes\": %lld}", size);
        free(names[i]);
    }
    free(names);
    fprintf(fp, "\n  ]\n}\n");
    return dfl_atomic_commit(&af, err);
}
