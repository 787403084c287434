/* Sweeps: every value holding a comma is an axis; a sweep point is a copy
 * of the configuration with each axis cut down to one item.  Axes keep
 * file order and the last axis runs fastest, so point numbers (and the
 * _ptNNN file tags built from them) follow the order a reader expects. */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/sha256.h"
#include "io/config_impl.h"

/* Counts the comma-separated items of en's value; rejects empty items. */
static dfl_status count_items(const dfl_cfg_entry *en, size_t *count, dfl_err *err)
{
    size_t k = 1;
    const char *s = en->value;
    const char *start = s;
    for (;; s++) {
        if (*s == ',' || *s == '\0') {
            const char *a = start, *b = s;
            while (a < b && isspace((unsigned char)*a)) a++;
            while (b > a && isspace((unsigned char)b[-1])) b--;
            if (a == b) {
                char w[1024];
                dfl_cfgi_where(en, w, sizeof w);
                return dfl_err_set(err, DFL_E_INPUT, "%s: empty item in list '%s'", w, en->value);
            }
            if (*s == '\0') break;
            k++;
            start = s + 1;
        }
    }
    *count = k;
    return DFL_OK;
}

void dfl_cfgi_free_axes(dfl_cfg *c)
{
    for (size_t a = 0; c->axis_name && a < c->naxes; a++) free(c->axis_name[a]);
    free(c->axis_name);
    free(c->axis);
    c->axis_name = NULL;
    c->axis = NULL;
    c->naxes = 0;
}

dfl_status dfl_cfgi_find_axes(dfl_cfg *c, dfl_err *err)
{
    dfl_cfgi_free_axes(c);
    if (c->n == 0) return DFL_OK;
    c->axis = malloc(c->n * sizeof *c->axis);
    c->axis_name = calloc(c->n, sizeof *c->axis_name);
    if (!c->axis || !c->axis_name) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    size_t np = 1;
    for (size_t i = 0; i < c->n; i++) {
        const char *v = c->e[i].value;
        if (strchr(v, ',')) {
            size_t k = 0;
            dfl_status st = count_items(&c->e[i], &k, err);
            if (st != DFL_OK) return st;
            size_t len = strlen(c->e[i].sec) + strlen(c->e[i].key) + 2;
            char *nm = malloc(len);
            if (!nm) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
            snprintf(nm, len, "%s.%s", c->e[i].sec, c->e[i].key);
            c->axis_name[c->naxes] = nm;
            c->axis[c->naxes++] = i;
            /* the product is bounded here, so dfl_cfg_sweep_points cannot
             * overflow */
            if (np > DFL_CFG_SWEEP_MAX / k) {
                char w[1024];
                dfl_cfgi_where(&c->e[i], w, sizeof w);
                return dfl_err_set(err, DFL_E_INPUT,
                                   "%s: the sweep would have more than %lu points (the "
                                   "product of the list lengths; split it with --set)",
                                   w, (unsigned long)DFL_CFG_SWEEP_MAX);
            }
            np *= k;
        }
    }
    return DFL_OK;
}

size_t dfl_cfg_sweep_axes(const dfl_cfg *c) { return c->is_point ? 0 : c->naxes; }

static size_t axis_len(const dfl_cfg *c, size_t a)
{
    size_t k = 1;
    for (const char *s = c->e[c->axis[a]].value; *s; s++)
        if (*s == ',') k++;
    return k;
}

size_t dfl_cfg_sweep_points(const dfl_cfg *c)
{
    if (c->is_point) return 1;
    size_t n = 1;
    for (size_t a = 0; a < c->naxes; a++) n *= axis_len(c, a);
    return n;
}

const char *dfl_cfg_sweep_axis_name(const dfl_cfg *c, size_t a)
{
    if (a >= c->naxes || !c->axis_name) return "?";
    return c->axis_name[a];
}

/* Copies item j of a comma list into buf, trimmed. */
static void list_item(const char *v, size_t j, char *buf, size_t size)
{
    const char *s = v;
    for (size_t k = 0; k < j; k++) s = strchr(s, ',') + 1;
    const char *e = strchr(s, ',');
    size_t len = e ? (size_t)(e - s) : strlen(s);
    if (len >= size) len = size - 1;
    memcpy(buf, s, len);
    buf[len] = '\0';
    char *t = dfl_cfgi_trim(buf);
    memmove(buf, t, strlen(t) + 1);
}

dfl_status dfl_cfg_sweep_point(const dfl_cfg *c, size_t idx, dfl_cfg **out, dfl_err *err)
{
    *out = NULL;
    size_t np = dfl_cfg_sweep_points(c);
    if (idx >= np) return dfl_err_set(err, DFL_E_INTERNAL, "sweep point %zu of %zu", idx, np);
    dfl_cfg *p = dfl_cfgi_new(c->path);
    if (!p) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    p->is_point = 1;
    dfl_status st = DFL_OK;
    for (size_t i = 0; i < c->n && st == DFL_OK; i++) {
        const dfl_cfg_entry *e = &c->e[i];
        st = dfl_cfgi_add(p, e->sec, e->key, e->value, e->file, e->line, e->via, err);
        if (st == DFL_OK && e->named && !(p->e[p->n - 1].named = strdup(e->named)))
            st = dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    }
    if (st != DFL_OK) {
        dfl_cfg_free(p);
        return st;
    }
    /* last axis fastest */
    p->axis = malloc((c->naxes ? c->naxes : 1) * sizeof *p->axis);
    if (!p->axis) {
        dfl_cfg_free(p);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    }
    size_t rem = idx;
    for (size_t a = c->naxes; a-- > 0;) {
        size_t len = axis_len(c, a);
        size_t j = rem % len;
        rem /= len;
        dfl_cfg_entry *en = &p->e[c->axis[a]];
        size_t vlen = strlen(en->value) + 1;
        char *item = malloc(vlen);
        if (!item) {
            dfl_cfg_free(p);
            return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
        }
        list_item(en->value, j, item, vlen);
        /* the whole list: sections it names stay the config's (check_used) */
        const size_t nl = (en->named ? strlen(en->named) + 1 : 0) + vlen;
        char *named = malloc(nl);
        if (!named) {
            free(item);
            dfl_cfg_free(p);
            return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
        }
        snprintf(named, nl, "%s%s%s", en->named ? en->named : "", en->named ? " " : "", en->value);
        free(en->named);
        en->named = named;
        free(en->value);
        en->value = item;
        p->axis[a] = c->axis[a];
    }
    p->naxes = c->naxes;
    *out = p;
    return DFL_OK;
}

const char *dfl_cfg_axis_value(const dfl_cfg *point, size_t a)
{
    if (a >= point->naxes) return "";
    return point->e[point->axis[a]].value;
}

/* Entry order is file order, so the same file with the same overrides
 * hashes the same from any directory; origins (file, line) do not count. */
void dfl_cfg_sweep_hash(const dfl_cfg *c, char hex[65])
{
    dfl_sha256 h;
    dfl_sha256_init(&h);
    for (size_t i = 0; i < c->n; i++) {
        const dfl_cfg_entry *e = &c->e[i];
        dfl_sha256_update(&h, e->sec, strlen(e->sec) + 1);
        dfl_sha256_update(&h, e->key, strlen(e->key) + 1);
        dfl_sha256_update(&h, e->value, strlen(e->value) + 1);
    }
    unsigned char d[32];
    dfl_sha256_final(&h, d);
    for (int i = 0; i < 32; i++) snprintf(hex + 2 * i, 3, "%02x", d[i]);
}
