/* The manifest is JSON written by hand: an ordered list of (key, JSON
 * text) fields, not worth a dependency.  dflab reads back only what it
 * wrote itself (point records, for merging), so the two finders below look
 * for the fixed `"key": value` spelling of this writer. */
#include "io/manifest.h"

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

static const char *find_key(const char *json, const char *key)
{
    size_t kl = strlen(key);
    for (const char *p = strstr(json, key); p; p = strstr(p + 1, key))
        if (p > json && p[-1] == '"' && p[kl] == '"' && strncmp(p + kl + 1, ": ", 2) == 0)
            return p + kl + 3;
    return NULL;
}

/* Reads only up to the closing quote: an escape is taken only when all of
 * its bytes are there, so a \u near the end of the text stops at the NUL. */
int dfl_json_find_string(const char *json, const char *key, char *buf, size_t size)
{
    if (size) buf[0] = '\0';
    const char *v = find_key(json, key);
    if (!v || *v != '"') return 0;
    size_t k = 0;
    for (v++; *v != '"'; v++) {
        if (*v == '\0') goto bad; /* no closing quote */
        char c = *v;
        if (c == '\\') {
            c = *++v;
            if (c == 'u') {
                unsigned u = 0;
                for (int i = 1; i <= 4; i++) { /* stops at the NUL: not a hex digit */
                    const char h = v[i];
                    const int d = h >= '0' && h <= '9' ? h - '0'
                                : h >= 'a' && h <= 'f' ? h - 'a' + 10
                                : h >= 'A' && h <= 'F' ? h - 'A' + 10 : -1;
                    if (d < 0) goto bad;
                    u = 16 * u + (unsigned)d;
                }
                v += 4;
                c = (char)u; /* dflab escapes only control characters */
            } else if (c == 'n') c = '\n';
            else if (c == 't') c = '\t';
            else if (c == 'r') c = '\r';
            else if (c == 'b') c = '\b';
            else if (c == 'f') c = '\f';
            else if (c != '"' && c != '\\' && c != '/') goto bad;
        }
        if (k + 1 < size) buf[k++] = c;
    }
    if (size) buf[k] = '\0';
    return 1;
bad:
    if (size) buf[0] = '\0';
    return 0;
}

int dfl_json_find_number(const char *json, const char *key, double *out)
{
    const char *v = find_key(json, key);
    if (!v) return 0;
    char *end;
    double d = strtod(v, &end);
    if (end == v) return 0;
    *out = d;
    return 1;
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

static int hexval(char c)
{
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

/* The JSON string literal at *p (after its opening quote) decoded into a
 * malloc'ed string; *p moves past the closing quote.  NULL (and *oom set
 * when memory ran out) on a malformed literal.  Escapes of U+0001..U+FFFF
 * become UTF-8; \u0000 and surrogates are refused (no file has such a
 * name as dflab wrote it). */
static char *json_string(const char **p, int *oom)
{
    const char *s = *p;
    size_t cap = strlen(s) + 1;   /* decoding never grows the text */
    char *o = malloc(cap), *w = o;
    if (!o) {
        *oom = 1;
        return NULL;
    }
    for (; *s && *s != '"'; s++) {
        unsigned char c = (unsigned char)*s;
        if (c < 0x20) break;
        if (c != '\\') {
            *w++ = (char)c;
            continue;
        }
        s++;
        switch (*s) {
        case '"': case '\\': case '/': *w++ = *s; break;
        case 'b': *w++ = '\b'; break;
        case 'f': *w++ = '\f'; break;
        case 'n': *w++ = '\n'; break;
        case 'r': *w++ = '\r'; break;
        case 't': *w++ = '\t'; break;
        case 'u': {
            long u = 0;
            for (int i = 1; i <= 4; i++) {   /* stops at the NUL: hexval('\0') < 0 */
                const int h = hexval(s[i]);
                if (h < 0) goto bad;
                u = 16 * u + h;
            }
            s += 4;
            if (u == 0 || (u >= 0xd800 && u <= 0xdfff)) goto bad;
            if (u < 0x80) {
                *w++ = (char)u;
            } else if (u < 0x800) {
                *w++ = (char)(0xc0 | (u >> 6)), *w++ = (char)(0x80 | (u & 0x3f));
            } else {
                *w++ = (char)(0xe0 | (u >> 12)), *w++ = (char)(0x80 | ((u >> 6) & 0x3f));
                *w++ = (char)(0x80 | (u & 0x3f));
            }
            break;
        }
        default: goto bad;
        }
    }
    if (*s != '"') goto bad;
    *w = '\0';
    *p = s + 1;
    return o;
bad:
    free(o);
    return NULL;
}

static const char *skip_ws(const char *p)
{
    while (*p == ' ' || *p == '\n' || *p == '\t' || *p == '\r') p++;
    return p;
}

int dfl_manifest_results_files(const char *json, char ***names, size_t *n)
{
    *names = NULL;
    *n = 0;
    /* the magic is the object's first field, spelt as put_format writes it */
    static const char magic[] = "{\n  \"format\": \"" DFL_RESULTS_FORMAT "\",\n  \"format_version\": ";
    int kind;
    if (strncmp(json, magic, sizeof magic - 1) == 0) {
        const char *v = json + sizeof magic - 1;
        long ver = 0;
        int digits = 0;
        for (; *v >= '0' && *v <= '9' && digits < 6; v++, digits++) ver = 10 * ver + (*v - '0');
        if (digits == 0 || ver != DFL_RESULTS_FORMAT_VERSION || *v != ',') return -1;
        kind = 1;
    } else if (strncmp(json, "{\n  \"tool\": \"dflab\",\n", 21) == 0 &&
               !strstr(json, "\n  \"format\": ")) {
        kind = 0;
    } else {
        return -1;
    }
    /* "files" is the last field: its last spelling at the top level */
    const char *p = NULL;
    for (const char *q = strstr(json, ",\n  \"files\": ["); q; q = strstr(q + 1, ",\n  \"files\": ["))
        p = q;
    if (!p) return -1;
    p += 14;
    char **list = NULL;
    size_t k = 0;
    int oom = 0;
    for (;;) {
        p = skip_ws(p);
        if (*p == ']') break;
        if (k > 0) {
            if (*p != ',') goto bad;
            p = skip_ws(p + 1);
        }
        if (strncmp(p, "{\"name\": \"", 10) != 0) goto bad;
        p += 10;
        char *name = json_string(&p, &oom);
        if (!name) goto bad;
        char **nl = realloc(list, (k + 1) * sizeof *nl);
        if (!nl) {
            free(name);
            oom = 1;
            goto bad;
        }
        list = nl;
        list[k++] = name;
        /* the rest of the entry: "bytes": N, "sha256": "hex" -- no braces */
        while (*p && *p != '}' && *p != '{' && *p != ']') p++;
        if (*p != '}') goto bad;
        p++;
    }
    p = skip_ws(p + 1);
    if (*p != '}' || *skip_ws(p + 1) != '\0') goto bad;
    *names = list;
    *n = k;
    return kind;
bad:
    for (size_t i = 0; i < k; i++) free(list[i]);
    free(list);
    return oom ? -2 : -1;
}
