/* `--set` overrides, applied after the file (and its includes) has been
 * read, in command-line order:
 *   section.key=value   a key that exists takes the new value and the
 *                       origin "--set"; a new key is appended.  A new
 *                       `kind` sharing no item with the old one is a switch
 *                       of kind: the file's other keys of the section were
 *                       written for the old kind and are dropped.
 *   section=@FILE       the section replaced by FILE's [section] (a config
 *                       group, as Hydra has them).
 * Dropped values stay known to dfl_cfg_check_used as values the config
 * named (they may name sub-sections, now unselected, not typos).  Axes are
 * recomputed, since the value may start or end a sweep. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/config_impl.h"

static dfl_status nomem(dfl_err *err) { return dfl_err_set(err, DFL_E_NOMEM, "out of memory"); }

/* Appends word (may be NULL) to *acc, blank-separated. */
static dfl_status append_word(char **acc, const char *word, dfl_err *err)
{
    if (!word || !*word) return DFL_OK;
    const size_t a = *acc ? strlen(*acc) : 0, n = a + (a > 0) + strlen(word) + 1;
    char *s = realloc(*acc, n);
    if (!s) return nomem(err);
    snprintf(s + a, n - a, "%s%s", a ? " " : "", word);
    *acc = s;
    return DFL_OK;
}

/* Removes entry i (its strings freed), keeping used[] aligned. */
static void remove_entry(dfl_cfg *c, size_t i)
{
    dfl_cfg_entry *en = &c->e[i];
    free(en->sec), free(en->key), free(en->value), free(en->file), free(en->via), free(en->named);
    memmove(c->e + i, c->e + i + 1, (c->n - i - 1) * sizeof *c->e);
    memmove(c->used + i, c->used + i + 1, c->n - i - 1);
    c->n--;
}

/* Removes the entries of sec but those of key keep (NULL: none; with
 * file_only, also those from --set stay), their values and earlier values
 * appended to *dropped; *first (may be NULL) receives the index the first
 * removed one had (c->n: none). */
static dfl_status drop_keys(dfl_cfg *c, const char *sec, const char *keep, int file_only,
                            char **dropped, size_t *first, dfl_err *err)
{
    dfl_status st = DFL_OK;
    if (first) *first = c->n;
    for (size_t i = 0; i < c->n && st == DFL_OK;) {
        const dfl_cfg_entry *en = &c->e[i];
        if (strcmp(en->sec, sec) != 0 || (keep && strcmp(en->key, keep) == 0) ||
            (file_only && strcmp(en->file, "--set") == 0)) {
            i++;
            continue;
        }
        st = append_word(dropped, en->value, err);
        if (st == DFL_OK) st = append_word(dropped, en->named, err);
        if (st != DFL_OK) break;
        if (first && *first == c->n) *first = i;
        remove_entry(c, i);
    }
    if (first && *first > c->n) *first = c->n;
    return st;
}

/* Whether the comma lists a and b share an item (items trimmed). */
static int share_item(const char *a, const char *b)
{
    for (const char *s = a; *s;) {
        s += strspn(s, " \t");
        size_t l = strcspn(s, ",");
        while (l > 0 && (s[l - 1] == ' ' || s[l - 1] == '\t')) l--;
        for (const char *t = b; *t;) {
            t += strspn(t, " \t");
            size_t m = strcspn(t, ",");
            while (m > 0 && (t[m - 1] == ' ' || t[m - 1] == '\t')) m--;
            if (l == m && strncmp(s, t, l) == 0) return 1;
            t += strcspn(t, ",");
            if (*t == ',') t++;
        }
        s += strcspn(s, ",");
        if (*s == ',') s++;
    }
    return 0;
}

/* The dropped values become values entry i named before. */
static dfl_status remember(dfl_cfg *c, size_t i, char *dropped, dfl_err *err)
{
    if (!dropped) return DFL_OK;
    dfl_status st = append_word(&c->e[i].named, dropped, err);
    free(dropped);
    return st;
}

/* section=@FILE */
static dfl_status set_section(dfl_cfg *c, const char *assignment, const char *sec,
                              const char *file, dfl_err *err)
{
    dfl_cfg *g = NULL;
    dfl_err e2;
    dfl_err_clear(&e2);
    dfl_status st = dfl_cfg_load(file, &g, &e2);
    if (st != DFL_OK)
        return dfl_err_set(err, st, "--set %s: %s", assignment, e2.msg);
    size_t have = 0;
    for (size_t i = 0; i < g->n; i++) have += strcmp(g->e[i].sec, sec) == 0;
    if (have == 0) {
        dfl_cfg_free(g);
        return dfl_err_set(err, DFL_E_INPUT, "--set %s: %s has no [%s] section (expected the "
                           "keys that replace [%s])", assignment, file, sec, sec);
    }
    char *dropped = NULL;
    size_t at = c->n;
    st = drop_keys(c, sec, NULL, 0, &dropped, &at, err);
    const size_t first = at;
    for (size_t i = 0; i < g->n && st == DFL_OK; i++) {
        const dfl_cfg_entry *en = &g->e[i];
        if (strcmp(en->sec, sec) != 0) continue;
        st = dfl_cfgi_insert(c, at, en->sec, en->key, en->value, en->file, en->line, en->via, err);
        at++;
    }
    dfl_cfg_free(g);
    if (st == DFL_OK) return remember(c, first, dropped, err);
    free(dropped);
    return st;
}

dfl_status dfl_cfg_set(dfl_cfg *c, const char *assignment, dfl_err *err)
{
    const char *eq = strchr(assignment, '=');
    const char *dot = strchr(assignment, '.');
    if (eq && eq[1] == '@' && (!dot || dot > eq) && eq != assignment) {
        char sec[256], file[4096];
        const size_t ls = (size_t)(eq - assignment);
        if (ls >= sizeof sec || strlen(eq + 2) >= sizeof file)
            return dfl_err_set(err, DFL_E_INPUT, "--set %s: section or file name too long",
                               assignment);
        memcpy(sec, assignment, ls);
        sec[ls] = '\0';
        snprintf(file, sizeof file, "%s", eq + 2);
        char *s = dfl_cfgi_trim(sec), *f = dfl_cfgi_trim(file);
        if (!*s || !*f)
            return dfl_err_set(err, DFL_E_INPUT, "--set %s: expected section=@FILE", assignment);
        dfl_status st = set_section(c, assignment, s, f, err);
        return st == DFL_OK ? dfl_cfgi_find_axes(c, err) : st;
    }
    if (!eq || !dot || dot > eq || dot == assignment || eq == dot + 1)
        return dfl_err_set(err, DFL_E_INPUT,
                           "--set %s: expected section.key=value or section=@FILE", assignment);
    char sec[256], key[256];
    size_t ls = (size_t)(dot - assignment), lk = (size_t)(eq - dot - 1);
    if (ls >= sizeof sec || lk >= sizeof key)
        return dfl_err_set(err, DFL_E_INPUT, "--set %s: section or key too long", assignment);
    memcpy(sec, assignment, ls);
    sec[ls] = '\0';
    memcpy(key, dot + 1, lk);
    key[lk] = '\0';
    char *s = dfl_cfgi_trim(sec), *k = dfl_cfgi_trim(key);
    if (strcmp(k, "include") == 0)
        return dfl_err_set(err, DFL_E_INPUT,
                           "--set %s: include is read with the config file; --set the "
                           "included keys themselves (e.g. %s.order=3), or replace the "
                           "section: --set %s=@FILE",
                           assignment, s, s);
    char *val = strdup(eq + 1);
    if (!val) return nomem(err);
    char *v = dfl_cfgi_trim(val);
    if (*v == '\0') {
        free(val);
        return dfl_err_set(err, DFL_E_INPUT, "--set %s: empty value", assignment);
    }
    ssize_t i = dfl_cfgi_find(c, s, k);
    dfl_status st = DFL_OK;
    char *dropped = NULL;
    if (i >= 0 && strcmp(k, "kind") == 0 && !share_item(c->e[i].value, v)) {
        st = drop_keys(c, s, "kind", 1, &dropped, NULL, err);
        i = dfl_cfgi_find(c, s, k);
    }
    if (st == DFL_OK)
        st = i >= 0 ? dfl_cfgi_set_value(&c->e[i], v, "--set", 0, err)
                    : dfl_cfgi_add(c, s, k, v, "--set", 0, NULL, err);
    if (st == DFL_OK && i < 0) i = (ssize_t)c->n - 1;
    if (st == DFL_OK) st = remember(c, (size_t)i, dropped, err), dropped = NULL;
    free(dropped);
    free(val);
    if (st != DFL_OK) return st;
    return dfl_cfgi_find_axes(c, err);
}
