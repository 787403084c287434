/* The configuration's storage: a flat list of entries in file order, and
 * the resolved INI text written from it.  Lists hold tens of keys, so
 * linear lookup is simpler than a hash and fast enough. */
#define _DEFAULT_SOURCE /* realpath */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/atomic.h"
#include "io/config_impl.h"
#include "io/lines.h"
#include "io/path.h"

dfl_cfg *dfl_cfgi_new(const char *name)
{
    dfl_cfg *c = calloc(1, sizeof *c);
    if (!c) return NULL;
    c->log = calloc(1, sizeof *c->log);
    c->path = strdup(name);
    if (!c->path || !c->log) {
        free(c->path);
        free(c->log);
        free(c);
        return NULL;
    }
    return c;
}

static dfl_status nomem(dfl_err *err)
{
    return dfl_err_set(err, DFL_E_NOMEM, "out of memory reading config");
}

dfl_status dfl_cfgi_insert(dfl_cfg *c, size_t at, const char *sec, const char *key,
                           const char *value, const char *file, int line, const char *via,
                           dfl_err *err)
{
    if (c->n == c->cap) {
        size_t cap = c->cap ? 2 * c->cap : 32;
        dfl_cfg_entry *e = realloc(c->e, cap * sizeof *e);
        if (!e) return nomem(err);
        c->e = e;
        unsigned char *u = realloc(c->used, cap);
        if (!u) return nomem(err);
        c->used = u;
        c->cap = cap;
    }
    dfl_cfg_entry en = {strdup(sec), strdup(key), strdup(value), strdup(file), line,
                        via ? strdup(via) : NULL, NULL};
    if (!en.sec || !en.key || !en.value || !en.file || (via && !en.via)) {
        free(en.sec), free(en.key), free(en.value), free(en.file), free(en.via);
        return nomem(err);
    }
    memmove(c->e + at + 1, c->e + at, (c->n - at) * sizeof *c->e);
    memmove(c->used + at + 1, c->used + at, c->n - at);
    c->e[at] = en;
    c->used[at] = 0;
    c->n++;
    return DFL_OK;
}

dfl_status dfl_cfgi_add(dfl_cfg *c, const char *sec, const char *key, const char *value,
                        const char *file, int line, const char *via, dfl_err *err)
{
    return dfl_cfgi_insert(c, c->n, sec, key, value, file, line, via, err);
}

ssize_t dfl_cfgi_find(const dfl_cfg *c, const char *sec, const char *key)
{
    for (size_t i = 0; i < c->n; i++)
        if (strcmp(c->e[i].sec, sec) == 0 && strcmp(c->e[i].key, key) == 0) return (ssize_t)i;
    return -1;
}

dfl_status dfl_cfgi_set_value(dfl_cfg_entry *en, const char *value, const char *file, int line,
                              dfl_err *err)
{
    char *nv = strdup(value), *nf = strdup(file);
    if (!nv || !nf) {
        free(nv), free(nf);
        return nomem(err);
    }
    /* the value replaced stays known as one the config wrote */
    const size_t nl = (en->named ? strlen(en->named) + 1 : 0) + strlen(en->value) + 1;
    char *named = malloc(nl);
    if (!named) {
        free(nv), free(nf);
        return nomem(err);
    }
    snprintf(named, nl, "%s%s%s", en->named ? en->named : "", en->named ? " " : "", en->value);
    free(en->named);
    en->named = named;
    free(en->value);
    free(en->file);
    free(en->via);
    en->value = nv;
    en->file = nf;
    en->line = line;
    en->via = NULL;
    return DFL_OK;
}

char *dfl_cfgi_trim(char *s)
{
    while (isspace((unsigned char)*s)) s++;
    size_t n = strlen(s);
    while (n > 0 && isspace((unsigned char)s[n - 1])) s[--n] = '\0';
    return s;
}

void dfl_cfg_free(dfl_cfg *c)
{
    if (!c) return;
    for (size_t i = 0; i < c->n; i++) {
        free(c->e[i].sec);
        free(c->e[i].key);
        free(c->e[i].value);
        free(c->e[i].file);
        free(c->e[i].via);
        free(c->e[i].named);
    }
    free(c->e);
    free(c->used);
    dfl_cfgi_free_axes(c);
    dfl_cfgi_free_log(c);
    free(c->path);
    free(c);
}

const char *dfl_cfg_path(const dfl_cfg *c) { return c->path; }

bool dfl_cfg_has(const dfl_cfg *c, const char *sec, const char *key)
{
    return dfl_cfgi_find(c, sec, key) >= 0;
}

bool dfl_cfg_has_section(const dfl_cfg *c, const char *sec)
{
    return dfl_cfg_section_name(c, sec) != NULL;
}

const char *dfl_cfg_section_name(const dfl_cfg *c, const char *sec)
{
    for (size_t i = 0; sec && i < c->n; i++)
        if (strcmp(c->e[i].sec, sec) == 0) return c->e[i].sec;
    return NULL;
}

bool dfl_cfgi_is_path_key(const char *key)
{
    static const char *const keys[] = DFL_CFG_PATH_KEYS;
    for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++)
        if (strcmp(keys[i], key) == 0) return true;
    return false;
}

/* One item of a file-name value, resolved against the entry's origin and
 * made absolute, to fp. */
static void put_path(FILE *fp, const dfl_cfg_entry *en, const char *item, size_t len)
{
    char rel[4096], lex[4096], cwd[4096];
    snprintf(rel, sizeof rel, "%.*s", (int)len, item);
    const char *base = en->line > 0 ? en->file : "";
    if (!dfl_path_beside(base, dfl_cfgi_trim(rel), lex, sizeof lex)) {
        fputs(rel, fp); /* too long to resolve: as written */
        return;
    }
    char *real = realpath(lex, NULL);
    if (real) {
        fputs(real, fp);
        free(real);
    } else if (lex[0] != '/' && getcwd(cwd, sizeof cwd)) {
        fprintf(fp, "%s/%s", cwd, lex);
    } else {
        fputs(lex, fp);
    }
}

/* Whether an entry before i has the section of entry i. */
static bool section_seen_before(const dfl_cfg *c, size_t i)
{
    for (size_t j = 0; j < i; j++)
        if (!strcmp(c->e[j].sec, c->e[i].sec)) return true;
    return false;
}

/* One "key = value" line; a file-name key's items resolved (put_path). */
static void put_entry(FILE *fp, const dfl_cfg_entry *en)
{
    if (!dfl_cfgi_is_path_key(en->key)) {
        fprintf(fp, "%s = %s\n", en->key, en->value);
        return;
    }
    fprintf(fp, "%s = ", en->key);
    for (const char *v = en->value;;) {
        const size_t len = strcspn(v, ",");
        put_path(fp, en, v, len);
        if (!v[len]) break;
        fputs(", ", fp);
        v += len + 1;
    }
    fputc('\n', fp);
}

/* Included keys are written as the section's own: the file reruns without
 * the shape files it was made from; file names are written resolved, so it
 * reruns from its own folder. */
dfl_status dfl_cfg_write(const dfl_cfg *c, const char *origin, const char *path, dfl_err *err)
{
    dfl_atomic_file af;
    dfl_status st = dfl_atomic_open(path, &af, err);
    if (st != DFL_OK) return st;
    /* the origin is a path, which may hold a newline: escaped, it stays one
     * comment line and the file still parses */
    const char *o = origin ? origin : c->path;
    const size_t osize = 4 * strlen(o) + 1;
    char *oesc = malloc(osize);
    if (!oesc) {
        dfl_atomic_abort(&af);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    }
    fprintf(af.fp, "# resolved configuration of %s\n", dfl_text_escape(o, oesc, osize));
    free(oesc);
    /* each section once (the loader refuses a repeated header), at its first
     * entry, with every entry of it in entry order: a --set of a key new to
     * an earlier section is appended to the entries, not to its section */
    bool first_sec = true;
    for (size_t i = 0; i < c->n; i++) {
        if (section_seen_before(c, i)) continue;
        fprintf(af.fp, "%s[%s]\n", first_sec ? "" : "\n", c->e[i].sec);
        first_sec = false;
        for (size_t k = i; k < c->n; k++)
            if (!strcmp(c->e[k].sec, c->e[i].sec)) put_entry(af.fp, &c->e[k]);
    }
    return dfl_atomic_commit(&af, err);
}
