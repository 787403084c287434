/* Locations and the messages built on them.  Every config message starts
 * with where the key was written, so that a user can go to it: the file and
 * line, the --set that gave it, or for an included key the shape file's
 * line and the include that brought it. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/config_impl.h"

void dfl_cfgi_where(const dfl_cfg_entry *en, char *buf, size_t size)
{
    if (en->via)
        snprintf(buf, size, "%s:%d: [shape] %s (included as [%s] at %s)", en->file, en->line,
                 en->key, en->sec, en->via);
    else if (en->line > 0)
        snprintf(buf, size, "%s:%d: [%s] %s", en->file, en->line, en->sec, en->key);
    else
        snprintf(buf, size, "%s %s.%s", en->file, en->sec, en->key);
}

const char *dfl_cfg_where(const dfl_cfg *c, const char *sec, const char *key, char *buf,
                          size_t size)
{
    ssize_t i = dfl_cfgi_find(c, sec, key);
    if (i >= 0)
        dfl_cfgi_where(&c->e[i], buf, size);
    else
        snprintf(buf, size, "%s: [%s] %s", c->path, sec, key);
    return buf;
}

dfl_status dfl_cfg_err_at(const dfl_cfg *c, const char *sec, const char *key, dfl_status st,
                          dfl_err *err)
{
    char w[1024];
    dfl_cfg_where(c, sec, key, w, sizeof w);
    dfl_err_prefix(err, "%s", w);
    return st;
}

dfl_status dfl_cfgi_missing(const dfl_cfg *c, const char *sec, const char *key,
                            const char *expect, dfl_err *err)
{
    return dfl_err_set(err, DFL_E_INPUT, "%s: [%s] %s: missing key (expected %s)", c->path, sec,
                       key, expect);
}

dfl_status dfl_cfgi_bad(const dfl_cfg_entry *en, const char *expect, dfl_err *err)
{
    char w[1024];
    dfl_cfgi_where(en, w, sizeof w);
    return dfl_err_set(err, DFL_E_INPUT, "%s: expected %s, got '%.200s'", w, expect, en->value);
}

/* Section sec is deferred (dfl_cfg_defer_sections): NAME or NAME_*. */
static bool deferred(const dfl_cfg *c, const char *sec)
{
    const size_t n = strlen(c->defer);
    return n > 0 && strncmp(sec, c->defer, n) == 0 && (sec[n] == '\0' || sec[n] == '_');
}

void dfl_cfg_claim_section(const dfl_cfg *c, const char *sec)
{
    for (size_t i = 0; i < c->n; i++)
        if (strcmp(c->e[i].sec, sec) == 0) c->used[i] = 1;
}

void dfl_cfg_claim_read(const dfl_cfg *c, const dfl_cfg *point)
{
    /* a sweep point copies c's entries in order; dfl_cfg_set replaces
     * values in place or appends, so position, section and key agree for
     * every entry that is c's */
    for (size_t i = 0; i < c->n && i < point->n; i++)
        if (point->used[i] && strcmp(c->e[i].sec, point->e[i].sec) == 0 &&
            strcmp(c->e[i].key, point->e[i].key) == 0)
            c->used[i] = 1;
    /* and what the point's reader read, for c's help and manifest: a key c
     * holds, or a default (the key absent from the point, hence from c,
     * whose entries the point copies); not a key the point added (present
     * in the point, absent from c) */
    const dfl_cfg_log *l = point->log;
    for (size_t i = 0; l && i < l->n; i++) {
        const dfl_cfg_readrec *r = &l->r[i];
        if (!r->def && dfl_cfgi_find(c, r->sec, r->key) < 0) continue;
        dfl_cfgi_log(c, r->sec, r->key, r->expect, r->def);
    }
}

void dfl_cfg_defer_sections(dfl_cfg *c, const char *name)
{
    snprintf(c->defer, sizeof c->defer, "%s", name ? name : "");
}

const char *dfl_cfg_unused_deferred(const dfl_cfg *c)
{
    for (size_t i = 0; i < c->n; i++)
        if (!c->used[i] && deferred(c, c->e[i].sec)) return c->e[i].sec;
    return NULL;
}

/* Whether word w (a section name) is one of the words of text (split at
 * blanks, commas and semicolons). */
static bool has_word(const char *text, const char *w)
{
    const size_t n = strlen(w);
    for (const char *s = text; s && *s;) {
        s += strspn(s, " \t,;");
        const size_t l = strcspn(s, " \t,;");
        if (l == n && strncmp(s, w, n) == 0) return true;
        s += l;
    }
    return false;
}

/* No key of section sec was read. */
static bool untouched(const dfl_cfg *c, const char *sec)
{
    for (size_t i = 0; i < c->n; i++)
        if (c->used[i] && strcmp(c->e[i].sec, sec) == 0) return false;
    return true;
}

/* Entry j names section sec: a word of its value or of a value it had
 * before (a list --set narrowed, a sweep's other items). */
static bool names(const dfl_cfg_entry *e, const char *sec)
{
    return has_word(e->value, sec) || has_word(e->named, sec);
}

/* Marks in ex[] the entries of every section that is the config's though
 * the study read none of it: a case the run did not select, not a typo.
 * Such a section has no key read and is named by a key the study read, or
 * by a key of a section so excused (the shape section of an unselected
 * case), to any depth: rounds until nothing changes, at most one per
 * section.  Sections are marked whole. */
static void mark_unselected(const dfl_cfg *c, unsigned char *ex)
{
    memset(ex, 0, c->n);
    for (size_t round = 0; round <= c->n; round++) {
        bool changed = false;
        for (size_t i = 0; i < c->n; i++) {
            if (c->used[i] || ex[i] || !untouched(c, c->e[i].sec)) continue;
            bool named = false;
            for (size_t j = 0; j < c->n && !named; j++)
                named = (c->used[j] || ex[j]) && strcmp(c->e[j].sec, c->e[i].sec) != 0 &&
                        names(&c->e[j], c->e[i].sec);
            if (!named) continue;
            for (size_t k = 0; k < c->n; k++)
                if (strcmp(c->e[k].sec, c->e[i].sec) == 0) ex[k] = 1;
            changed = true;
        }
        if (!changed) break;
    }
}

/* The first unread key of section sec (any section but the deferred ones
 * and the unselected ones when sec is NULL). */
static dfl_status first_unused(const dfl_cfg *c, const char *sec, const char *what,
                               dfl_err *err)
{
    unsigned char *ex = NULL;
    if (!sec) {
        ex = malloc(c->n ? c->n : 1);
        if (!ex) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
        mark_unselected(c, ex);
    }
    for (size_t i = 0; i < c->n; i++) {
        if (c->used[i] || (sec && strcmp(c->e[i].sec, sec) != 0)) continue;
        if (!sec && (deferred(c, c->e[i].sec) || ex[i])) continue;
        char w[1024];
        dfl_cfgi_where(&c->e[i], w, sizeof w);
        free(ex);
        return dfl_err_set(err, DFL_E_INPUT, "%s: %s", w, what);
    }
    free(ex);
    return DFL_OK;
}

dfl_status dfl_cfg_check_used(const dfl_cfg *c, dfl_err *err)
{
    dfl_status st = first_unused(c, NULL, "unknown key (not used by this study)", err);
    return st == DFL_OK ? dfl_cfgi_stop_if_validating(c, err) : st;
}

dfl_status dfl_cfg_check_used_in(const dfl_cfg *c, const char *sec, dfl_err *err)
{
    return first_unused(c, sec, "unknown key", err);
}

bool dfl_cfg_used(const dfl_cfg *c, const char *sec, const char *key)
{
    const ssize_t k = dfl_cfgi_find(c, sec, key);
    return k >= 0 && c->used[k];
}

dfl_status dfl_cfg_reject(const dfl_cfg *c, const char *sec, const char *key, dfl_err *err,
                          const char *fmt, ...)
{
    char w[1024], msg[DFL_ERR_MSG_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return dfl_err_set(err, DFL_E_INPUT, "%s: %s", dfl_cfg_where(c, sec, key, w, sizeof w), msg);
}
