/* The manifest is JSON written by hand: an ordered list of (key, JSON
 * text) fields, not worth a dependency.  dflab reads back only what it
 * wrote itself (point records, for merging), so the two finders below look
 * for the fixed `"key": value` spelling of this writer. */
#include "io/manifest.h"
#include "io/json.h"

#include <ceres/version.h>
#include <dirent.h>
#include <openexr.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <zlib.h>

#include "core/sha256.h"
#include "io/atomic.h"

#include "dfl_version.h"

#ifndef DFL_INIH_VERSION
#define DFL_INIH_VERSION "unknown"
#endif

typedef struct field {
    char *key, *json;
} field;

struct dfl_manifest {
    field *f;
    size_t n;
};

double dfl_wall_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

dfl_manifest *dfl_manifest_new(void) { return calloc(1, sizeof(dfl_manifest)); }

void dfl_manifest_free(dfl_manifest *m)
{
    if (!m) return;
    for (size_t i = 0; i < m->n; i++) free(m->f[i].key), free(m->f[i].json);
    free(m->f);
    free(m);
}

/* Takes ownership of json (NULL: out of memory). */
static dfl_status put_owned(dfl_manifest *m, const char *key, char *json)
{
    if (!json) return DFL_E_NOMEM;
    for (size_t i = 0; i < m->n; i++)
        if (strcmp(m->f[i].key, key) == 0) {
            free(m->f[i].json);
            m->f[i].json = json;
            return DFL_OK;
        }
    field *f = realloc(m->f, (m->n + 1) * sizeof *f);
    char *k = strdup(key);
    if (!f || !k) {
        if (f) m->f = f;
        free(k), free(json);
        return DFL_E_NOMEM;
    }
    m->f = f;
    m->f[m->n++] = (field){k, json};
    return DFL_OK;
}

dfl_status dfl_manifest_put_raw(dfl_manifest *m, const char *key, const char *json)
{
    return put_owned(m, key, strdup(json));
}

dfl_status dfl_manifest_put_string(dfl_manifest *m, const char *key, const char *value)
{
    return put_owned(m, key, dfl_json_quote(value));
}

dfl_status dfl_manifest_put_int(dfl_manifest *m, const char *key, long value)
{
    char b[32];
    snprintf(b, sizeof b, "%ld", value);
    return put_owned(m, key, strdup(b));
}

dfl_status dfl_manifest_put_double(dfl_manifest *m, const char *key, double value)
{
    char b[64];
    snprintf(b, sizeof b, "%.6f", value);
    return put_owned(m, key, strdup(b));
}

dfl_status dfl_manifest_put_strings(dfl_manifest *m, const char *key, size_t n,
                                    const char *const *values)
{
    size_t cap = 3, len = 1;
    for (size_t i = 0; i < n; i++) cap += 6 * strlen(values[i]) + 4;
    char *s = malloc(cap);
    if (!s) return DFL_E_NOMEM;
    s[0] = '[';
    for (size_t i = 0; i < n; i++) {
        char *q = dfl_json_quote(values[i]);
        if (!q) {
            free(s);
            return DFL_E_NOMEM;
        }
        len += (size_t)snprintf(s + len, cap - len, "%s%s", i ? ", " : "", q);
        free(q);
    }
    snprintf(s + len, cap - len, "]");
    return put_owned(m, key, s);
}

char *dfl_json_quote(const char *s)
{
    char *q = malloc(6 * strlen(s) + 3), *o = q;
    if (!q) return NULL;
    *o++ = '"';
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\') *o++ = '\\', *o++ = (char)c;
        else if (c < 0x20) o += sprintf(o, "\\u%04x", c);
        else *o++ = (char)c;
    }
    *o++ = '"';
    *o = '\0';
    return q;
}

const char *dfl_manifest_libraries(char *buf, size_t size)
{
    int maj = 0, min = 0, patch = 0;
    const char *extra = "";
    exr_get_library_version(&maj, &min, &patch, &extra);
    snprintf(buf, size,
             "{\"dflab\": \"%s\", \"inih\": \"%s\", \"ceres\": \"%d.%d.%d\", "
             "\"openexr\": \"%d.%d.%d%s\", \"zlib\": \"%s\"}",
             DFL_VERSION, DFL_INIH_VERSION, CERES_VERSION_MAJOR, CERES_VERSION_MINOR,
             CERES_VERSION_REVISION, maj, min, patch, extra ? extra : "", zlibVersion());
    return buf;
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Sorted names of the regular files of dir (not manifest.json, not
 * temporaries); *n of them, NULL when none or out of memory. */
static char **list_files(const char *dir, size_t *n)
{
    *n = 0;
    DIR *d = opendir(dir);
    if (!d) return NULL;
    char **names = NULL;
    struct dirent *de;
    while ((de = readdir(d))) {
        if (de->d_name[0] == '.' || strcmp(de->d_name, "manifest.json") == 0) continue;
        if (strstr(de->d_name, ".tmp.")) continue;
        char p[8192];
        struct stat sb;
        snprintf(p, sizeof p, "%s/%s", dir, de->d_name);
        if (stat(p, &sb) != 0 || !S_ISREG(sb.st_mode)) continue;
        char **nw = realloc(names, (*n + 1) * sizeof *nw);
        if (!nw) break;
        names = nw;
        if ((names[*n] = strdup(de->d_name))) (*n)++;
    }
    closedir(d);
    if (names) qsort(names, *n, sizeof *names, cmp_str);
    return names;
}

dfl_status dfl_manifest_write(const dfl_manifest *m, const char *path, const char *files_dir,
                              dfl_err *err)
{
    size_t nn;
    char **names = list_files(files_dir, &nn);
    dfl_atomic_file af;
    dfl_status st = dfl_atomic_open(path, &af, err);
    FILE *fp = af.fp;
    if (st == DFL_OK) {
        fputs("{", fp);
        for (size_t i = 0; i < m->n; i++) {
            char *k = dfl_json_quote(m->f[i].key);
            fprintf(fp, "%s\n  %s: %s", i ? "," : "", k ? k : "\"?\"", m->f[i].json);
            free(k);
        }
        fprintf(fp, "%s\n  \"files\": [", m->n ? "," : "");
    }
    for (size_t i = 0; i < nn; i++) {
        char fpth[8192], hex[65];
        snprintf(fpth, sizeof fpth, "%s/%s", files_dir, names[i]);
        struct stat sb;
        long long size = stat(fpth, &sb) == 0 ? (long long)sb.st_size : -1;
        if (st == DFL_OK) st = dfl_sha256_file(fpth, hex, err);
        if (st == DFL_OK) {
            char *q = dfl_json_quote(names[i]);
            fprintf(fp, "%s\n    {\"name\": %s, \"bytes\": %lld, \"sha256\": \"%s\"}", i ? "," : "",
                    q ? q : "\"?\"", size, hex);
            free(q);
        }
        free(names[i]);
    }
    free(names);
    if (st != DFL_OK) {
        dfl_atomic_abort(&af);
        return st;
    }
    fprintf(fp, "\n  ]\n}\n");
    return dfl_atomic_commit(&af, err);
}

dfl_status dfl_manifest_put_format(dfl_manifest *m)
{
    dfl_status st = dfl_manifest_put_string(m, "format", DFL_RESULTS_FORMAT);
    return st == DFL_OK ? dfl_manifest_put_int(m, "format_version", DFL_RESULTS_FORMAT_VERSION)
                        : st;
}

/* On io/json.h's strict reader: a manifest is one JSON object, so a
 * truncated, padded or re-spelt one is refused as a whole, and a name is
 * unescaped exactly as any JSON reader would. */
int dfl_manifest_results_files(const char *json, char ***names, size_t *n)
{
    *names = NULL;
    *n = 0;
    dfl_err e;
    if (dfl_json_check(json, strlen(json), "manifest.json", &e) != DFL_OK) return -1;
    char fmt[64];
    long ver;
    int kind;
    const char *v;
    size_t vl;
    if (dfl_json_member(json, "format", &v, &vl)) {
        if (dfl_json_get_string(json, "format", "", fmt, sizeof fmt, &e) != DFL_OK ||
            strcmp(fmt, DFL_RESULTS_FORMAT) != 0 ||
            dfl_json_get_long(json, "format_version", "", 0, 1000000, &ver, &e) != DFL_OK ||
            ver != DFL_RESULTS_FORMAT_VERSION)
            return -1;
        kind = 1;
    } else {
        if (dfl_json_get_string(json, "tool", "", fmt, sizeof fmt, &e) != DFL_OK ||
            strcmp(fmt, "dflab") != 0)
            return -1;
        kind = 0;
    }
    if (!dfl_json_member(json, "files", &v, &vl) || *v != '[') return -1;
    char **list = NULL;
    size_t k = 0;
    const char *el;
    size_t el_len;
    while (dfl_json_each(&v, &el, &el_len)) {
        /* unescaping never lengthens a string, so el_len + 1 bytes hold it */
        char *name = malloc(el_len + 1);
        char **nl = name ? realloc(list, (k + 1) * sizeof *nl) : NULL;
        if (!nl) {
            free(name);
            for (size_t i = 0; i < k; i++) free(list[i]);
            free(list);
            return -2;
        }
        list = nl;
        if (dfl_json_get_string(el, "name", "", name, el_len + 1, &e) != DFL_OK) {
            free(name);
            for (size_t i = 0; i < k; i++) free(list[i]);
            free(list);
            return -1;
        }
        list[k++] = name;
    }
    *names = list;
    *n = k;
    return kind;
}
