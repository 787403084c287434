/* Config storage: a flat list of entries in file order.  Lists are tiny
 * (tens of keys), so linear lookup is simpler and fast enough.
 *
 * libinih does the INI syntax.  We feed it through ini_parse_stream with our
 * own line reader so that every handler call knows its line number and
 * whether the line was an indented continuation (multi-line values are
 * joined with a blank).  Debian's libinih exposes its limits as library
 * globals; we raise the line limit once (process-wide, idempotent) so that
 * long point lists are not cut at 200 characters, and make '#' the only
 * inline-comment prefix so that ';' can separate points. */
#include "io/config.h"

#include <assert.h>
#include <ctype.h>
#include <errno.h>
#include <ini.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/types.h>

#include "io/atomic.h"

#define CFG_LINE_MAX 65536

typedef struct cfg_entry {
    char *sec;
    char *key;
    char *value;
    char *file;   /* origin: config path or "--set" */
    int line;     /* 0 for --set */
} cfg_entry;

struct dfl_cfg {
    char *path;
    cfg_entry *e;
    size_t n, cap;
    unsigned char *used;  /* separate block so const getters can mark keys */
    /* sweep axes: indices into e[] of multi-valued entries, file order */
    size_t *axis;
    char **axis_name;  /* "section.key" of each axis */
    size_t naxes;
    /* for a sweep point: the axis values chosen (pointers into e[].value) */
    int is_point;
};

static char *xstrdup(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d) memcpy(d, s, n);
    return d;
}

static char *trim_inplace(char *s)
{
    while (isspace((unsigned char)*s)) s++;
    size_t n = strlen(s);
    while (n > 0 && isspace((unsigned char)s[n - 1])) s[--n] = '\0';
    return s;
}

static ssize_t find_entry(const dfl_cfg *c, const char *sec, const char *key)
{
    for (size_t i = 0; i < c->n; i++)
        if (strcmp(c->e[i].sec, sec) == 0 && strcmp(c->e[i].key, key) == 0) return (ssize_t)i;
    return -1;
}

static dfl_status add_entry(dfl_cfg *c, const char *sec, const char *key, const char *value,
                            const char *file, int line, dfl_err *err)
{
    if (c->n == c->cap) {
        size_t cap = c->cap ? 2 * c->cap : 32;
        cfg_entry *e = realloc(c->e, cap * sizeof *e);
        if (!e) return dfl_err_set(err, DFL_E_NOMEM, "out of memory reading config");
        unsigned char *u = realloc(c->used, cap);
        if (!u) {
            c->e = e;
            return dfl_err_set(err, DFL_E_NOMEM, "out of memory reading config");
        }
        c->e = e;
        c->used = u;
        c->cap = cap;
    }
    cfg_entry *en = &c->e[c->n];
    en->sec = xstrdup(sec);
    en->key = xstrdup(key);
    en->value = xstrdup(value);
    en->file = xstrdup(file);
    en->line = line;
    if (!en->sec || !en->key || !en->value || !en->file) {
        free(en->sec), free(en->key), free(en->value), free(en->file);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory reading config");
    }
    c->used[c->n] = 0;
    c->n++;
    return DFL_OK;
}

static void where_entry(const dfl_cfg *c, const cfg_entry *en, char *buf, size_t size)
{
    (void)c;
    if (en->line > 0)
        snprintf(buf, size, "%s:%d: [%s] %s", en->file, en->line, en->sec, en->key);
    else
        snprintf(buf, size, "%s %s.%s", en->file, en->sec, en->key);
}

/* ---- parsing ----------------------------------------------------------- */

typedef struct parse_state {
    dfl_cfg *c;
    const char *name;
    /* reader state */
    FILE *fp;
    const char *text;   /* when parsing a string */
    size_t pos;
    int line;
    int line_indented;
    int too_long_line;
    /* last handler call, for continuation lines */
    ssize_t last;
    int last_line;
    dfl_err *err;
    dfl_status st;
} parse_state;

static char *reader(char *str, int num, void *stream)
{
    parse_state *ps = stream;
    assert(num > 2);
    size_t k = 0;
    int ch = 0;
    for (;;) {
        if (ps->fp) {
            ch = fgetc(ps->fp);
        } else {
            ch = ps->text[ps->pos] ? (unsigned char)ps->text[ps->pos++] : EOF;
        }
        if (ch == EOF) break;
        if ((int)k < num - 2) {
            str[k++] = (char)ch;
        } else if (ch != '\n') {
            ps->too_long_line = ps->line + 1;
        }
        if (ch == '\n') break;
    }
    if (k == 0 && ch == EOF) return NULL;
    str[k] = '\0';
    ps->line++;
    ps->line_indented = (k > 0 && (str[0] == ' ' || str[0] == '\t'));
    return str;
}

static int handler(void *user, const char *section, const char *name, const char *value)
{
    parse_state *ps = user;
    if (ps->st != DFL_OK) return 0;
    dfl_cfg *c = ps->c;
    if (section[0] == '\0') {
        ps->st = dfl_err_set(ps->err, DFL_E_INPUT, "%s:%d: key '%s' outside any [section]",
                             ps->name, ps->line, name);
        return 0;
    }
    ssize_t i = find_entry(c, section, name);
    if (i >= 0) {
        if (ps->line_indented && i == ps->last) {
            /* continuation line of a multi-line value: join with a blank */
            cfg_entry *en = &c->e[i];
            size_t a = strlen(en->value), b = strlen(value);
            char *v = realloc(en->value, a + b + 2);
            if (!v) {
                ps->st = dfl_err_set(ps->err, DFL_E_NOMEM, "out of memory reading config");
                return 0;
            }
            v[a] = ' ';
            memcpy(v + a + 1, value, b + 1);
            en->value = v;
            return 1;
        }
        ps->st = dfl_err_set(ps->err, DFL_E_INPUT, "%s:%d: [%s] %s: duplicate key (first at line %d)",
                             ps->name, ps->line, section, name, c->e[i].line);
        return 0;
    }
    ps->st = add_entry(c, section, name, value, ps->name, ps->line, ps->err);
    ps->last = (ssize_t)c->n - 1;
    return ps->st == DFL_OK;
}

static dfl_status find_axes(dfl_cfg *c, dfl_err *err);
static void free_axes(dfl_cfg *c);

static void set_inih_limits(void)
{
    /* Library-wide settings of Debian's libinih (see file comment). */
    /* measured: the reader only gets num = CFG_LINE_MAX when the buffer is
     * heap-allocated with this initial size (the stack buffer is fixed) */
    ini_max_line = CFG_LINE_MAX;
    ini_use_stack = false;
    ini_allow_realloc = true;
    ini_initial_alloc = CFG_LINE_MAX;
    ini_inline_comment_prefixes = "#";
    ini_allow_multiline = true;
    ini_stop_on_first_error = true;
}

static dfl_status parse_common(parse_state *ps, dfl_cfg **out, dfl_err *err)
{
    set_inih_limits();
    int rc = ini_parse_stream(reader, ps, handler, ps);
    if (ps->st != DFL_OK) return ps->st;
    if (ps->too_long_line)
        return dfl_err_set(err, DFL_E_INPUT, "%s:%d: line longer than %d characters", ps->name,
                           ps->too_long_line, CFG_LINE_MAX - 2);
    if (rc == -2) return dfl_err_set(err, DFL_E_NOMEM, "%s: out of memory", ps->name);
    if (rc != 0)
        return dfl_err_set(err, DFL_E_INPUT,
                           "%s:%d: syntax error (expected [section], key = value, or a comment)",
                           ps->name, rc);
    dfl_status st = find_axes(ps->c, err);
    if (st != DFL_OK) return st;
    *out = ps->c;
    return DFL_OK;
}

static dfl_cfg *cfg_new(const char *name)
{
    dfl_cfg *c = calloc(1, sizeof *c);
    if (!c) return NULL;
    c->path = xstrdup(name);
    if (!c->path) {
        free(c);
        return NULL;
    }
    return c;
}

dfl_status dfl_cfg_load(const char *path, dfl_cfg **out, dfl_err *err)
{
    *out = NULL;
    FILE *fp = fopen(path, "r");
    if (!fp) return dfl_err_set(err, DFL_E_INPUT, "%s: cannot open config: %s", path, strerror(errno));
    dfl_cfg *c = cfg_new(path);
    if (!c) {
        fclose(fp);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    }
    parse_state ps = {.c = c, .name = path, .fp = fp, .last = -1, .err = err, .st = DFL_OK};
    dfl_status st = parse_common(&ps, out, err);
    if (ferror(fp) && st == DFL_OK) st = dfl_err_set(err, DFL_E_INPUT, "%s: read error", path);
    fclose(fp);
    if (st != DFL_OK) {
        dfl_cfg_free(c);
        *out = NULL;
    }
    return st;
}

dfl_status dfl_cfg_parse_string(const char *name, const char *text, dfl_cfg **out, dfl_err *err)
{
    *out = NULL;
    dfl_cfg *c = cfg_new(name);
    if (!c) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    parse_state ps = {.c = c, .name = name, .text = text, .last = -1, .err = err, .st = DFL_OK};
    dfl_status st = parse_common(&ps, out, err);
    if (st != DFL_OK) {
        dfl_cfg_free(c);
        *out = NULL;
    }
    return st;
}

void dfl_cfg_free(dfl_cfg *c)
{
    if (!c) return;
    for (size_t i = 0; i < c->n; i++) {
        free(c->e[i].sec);
        free(c->e[i].key);
        free(c->e[i].value);
        free(c->e[i].file);
    }
    free(c->e);
    free(c->used);
    free_axes(c);
    free(c->path);
    free(c);
}

const char *dfl_cfg_path(const dfl_cfg *c) { return c->path; }

/* ---- sweeps ----------------------------------------------------------- */

/* Counts the comma-separated items of v; rejects empty items. */
static dfl_status count_items(const dfl_cfg *c, const cfg_entry *en, size_t *count, dfl_err *err)
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
                char w[512];
                where_entry(c, en, w, sizeof w);
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

static void free_axes(dfl_cfg *c)
{
    for (size_t a = 0; c->axis_name && a < c->naxes; a++) free(c->axis_name[a]);
    free(c->axis_name);
    free(c->axis);
    c->axis_name = NULL;
    c->axis = NULL;
    c->naxes = 0;
}

static dfl_status find_axes(dfl_cfg *c, dfl_err *err)
{
    free_axes(c);
    if (c->n == 0) return DFL_OK;
    c->axis = malloc(c->n * sizeof *c->axis);
    c->axis_name = calloc(c->n, sizeof *c->axis_name);
    if (!c->axis || !c->axis_name) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    for (size_t i = 0; i < c->n; i++) {
        const char *v = c->e[i].value;
        if (strchr(v, ',')) {
            size_t k;
            dfl_status st = count_items(c, &c->e[i], &k, err);
            if (st != DFL_OK) return st;
            size_t len = strlen(c->e[i].sec) + strlen(c->e[i].key) + 2;
            char *nm = malloc(len);
            if (!nm) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
            snprintf(nm, len, "%s.%s", c->e[i].sec, c->e[i].key);
            c->axis_name[c->naxes] = nm;
            c->axis[c->naxes++] = i;
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
    char *t = trim_inplace(buf);
    memmove(buf, t, strlen(t) + 1);
}

dfl_status dfl_cfg_sweep_point(const dfl_cfg *c, size_t idx, dfl_cfg **out, dfl_err *err)
{
    *out = NULL;
    size_t np = dfl_cfg_sweep_points(c);
    if (idx >= np) return dfl_err_set(err, DFL_E_INTERNAL, "sweep point %zu of %zu", idx, np);
    dfl_cfg *p = cfg_new(c->path);
    if (!p) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    p->is_point = 1;
    dfl_status st = DFL_OK;
    for (size_t i = 0; i < c->n && st == DFL_OK; i++)
        st = add_entry(p, c->e[i].sec, c->e[i].key, c->e[i].value, c->e[i].file, c->e[i].line, err);
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
        cfg_entry *en = &p->e[c->axis[a]];
        size_t vlen = strlen(en->value) + 1;
        char *item = malloc(vlen);
        if (!item) {
            dfl_cfg_free(p);
            return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
        }
        list_item(en->value, j, item, vlen);
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

/* ---- overrides --------------------------------------------------------- */

dfl_status dfl_cfg_set(dfl_cfg *c, const char *assignment, dfl_err *err)
{
    const char *eq = strchr(assignment, '=');
    const char *dot = strchr(assignment, '.');
    if (!eq || !dot || dot > eq || dot == assignment || eq == dot + 1)
        return dfl_err_set(err, DFL_E_INPUT,
                           "--set %s: expected section.key=value", assignment);
    char sec[256], key[256];
    size_t ls = (size_t)(dot - assignment), lk = (size_t)(eq - dot - 1);
    if (ls >= sizeof sec || lk >= sizeof key)
        return dfl_err_set(err, DFL_E_INPUT, "--set %s: section or key too long", assignment);
    memcpy(sec, assignment, ls);
    sec[ls] = '\0';
    memcpy(key, dot + 1, lk);
    key[lk] = '\0';
    char *s = trim_inplace(sec), *k = trim_inplace(key);
    char *val = xstrdup(eq + 1);
    if (!val) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    char *v = trim_inplace(val);
    if (*v == '\0') {
        free(val);
        return dfl_err_set(err, DFL_E_INPUT, "--set %s: empty value", assignment);
    }
    ssize_t i = find_entry(c, s, k);
    dfl_status st = DFL_OK;
    if (i >= 0) {
        cfg_entry *en = &c->e[i];
        char *nv = xstrdup(v), *nf = xstrdup("--set");
        if (!nv || !nf) {
            free(nv), free(nf), free(val);
            return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
        }
        free(en->value);
        free(en->file);
        en->value = nv;
        en->file = nf;
        en->line = 0;
    } else {
        st = add_entry(c, s, k, v, "--set", 0, err);
    }
    free(val);
    if (st != DFL_OK) return st;
    return find_axes(c, err);
}

/* ---- getters ----------------------------------------------------------- */

static const cfg_entry *lookup(const dfl_cfg *c, const char *sec, const char *key)
{
    ssize_t i = find_entry(c, sec, key);
    if (i < 0) return NULL;
    c->used[i] = 1;
    return &c->e[i];
}

bool dfl_cfg_has(const dfl_cfg *c, const char *sec, const char *key)
{
    return find_entry(c, sec, key) >= 0;
}

bool dfl_cfg_has_section(const dfl_cfg *c, const char *sec)
{
    for (size_t i = 0; i < c->n; i++)
        if (strcmp(c->e[i].sec, sec) == 0) return true;
    return false;
}

const char *dfl_cfg_where(const dfl_cfg *c, const char *sec, const char *key, char *buf,
                          size_t size)
{
    ssize_t i = find_entry(c, sec, key);
    if (i >= 0)
        where_entry(c, &c->e[i], buf, size);
    else
        snprintf(buf, size, "%s: [%s] %s", c->path, sec, key);
    return buf;
}

static dfl_status missing(const dfl_cfg *c, const char *sec, const char *key, const char *expect,
                          dfl_err *err)
{
    return dfl_err_set(err, DFL_E_INPUT, "%s: [%s] %s: missing key (expected %s)", c->path, sec,
                       key, expect);
}

static dfl_status bad(const dfl_cfg *c, const cfg_entry *en, const char *expect, dfl_err *err)
{
    char w[600];
    where_entry(c, en, w, sizeof w);
    return dfl_err_set(err, DFL_E_INPUT, "%s: expected %s, got '%.200s'", w, expect, en->value);
}

/* A sweep list reaching a getter means the caller used the un-expanded
 * config: refuse rather than silently taking the first item. */
static dfl_status single(const dfl_cfg *c, const cfg_entry *en, dfl_err *err)
{
    if (strchr(en->value, ',')) return bad(c, en, "a single value (lists are sweep axes)", err);
    return DFL_OK;
}

dfl_status dfl_cfg_string(const dfl_cfg *c, const char *sec, const char *key, const char **out,
                          dfl_err *err)
{
    const cfg_entry *en = lookup(c, sec, key);
    if (!en) return missing(c, sec, key, "a value", err);
    dfl_status st = single(c, en, err);
    if (st != DFL_OK) return st;
    if (en->value[0] == '\0') return bad(c, en, "a non-empty value", err);
    *out = en->value;
    return DFL_OK;
}

dfl_status dfl_cfg_string_opt(const dfl_cfg *c, const char *sec, const char *key, const char *def,
                              const char **out, dfl_err *err)
{
    if (!dfl_cfg_has(c, sec, key)) {
        *out = def;
        return DFL_OK;
    }
    return dfl_cfg_string(c, sec, key, out, err);
}

static int parse_double(const char *s, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s) return 0;
    while (isspace((unsigned char)*end)) end++;
    if (*end != '\0' || errno == ERANGE || !isfinite(v)) return 0;
    *out = v;
    return 1;
}

static int parse_long(const char *s, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s) return 0;
    while (isspace((unsigned char)*end)) end++;
    if (*end != '\0' || errno == ERANGE) return 0;
    *out = v;
    return 1;
}

dfl_status dfl_cfg_int(const dfl_cfg *c, const char *sec, const char *key, long lo, long hi,
                       long *out, dfl_err *err)
{
    char expect[128];
    snprintf(expect, sizeof expect, "an integer in [%ld, %ld]", lo, hi);
    const cfg_entry *en = lookup(c, sec, key);
    if (!en) return missing(c, sec, key, expect, err);
    dfl_status st = single(c, en, err);
    if (st != DFL_OK) return st;
    long v;
    if (!parse_long(en->value, &v) || v < lo || v > hi) return bad(c, en, expect, err);
    *out = v;
    return DFL_OK;
}

dfl_status dfl_cfg_int_opt(const dfl_cfg *c, const char *sec, const char *key, long def, long lo,
                           long hi, long *out, dfl_err *err)
{
    if (!dfl_cfg_has(c, sec, key)) {
        *out = def;
        return DFL_OK;
    }
    return dfl_cfg_int(c, sec, key, lo, hi, out, err);
}

dfl_status dfl_cfg_double(const dfl_cfg *c, const char *sec, const char *key, double lo, double hi,
                          double *out, dfl_err *err)
{
    char expect[128];
    if (isinf(lo) && isinf(hi))
        snprintf(expect, sizeof expect, "a finite number");
    else if (isinf(hi))
        snprintf(expect, sizeof expect, "a finite number >= %g", lo);
    else if (isinf(lo))
        snprintf(expect, sizeof expect, "a finite number <= %g", hi);
    else
        snprintf(expect, sizeof expect, "a finite number in [%g, %g]", lo, hi);
    const cfg_entry *en = lookup(c, sec, key);
    if (!en) return missing(c, sec, key, expect, err);
    dfl_status st = single(c, en, err);
    if (st != DFL_OK) return st;
    double v;
    if (!parse_double(en->value, &v) || !(v >= lo && v <= hi)) return bad(c, en, expect, err);
    *out = v;
    return DFL_OK;
}

dfl_status dfl_cfg_double_opt(const dfl_cfg *c, const char *sec, const char *key, double def,
                              double lo, double hi, double *out, dfl_err *err)
{
    if (!dfl_cfg_has(c, sec, key)) {
        *out = def;
        return DFL_OK;
    }
    return dfl_cfg_double(c, sec, key, lo, hi, out, err);
}

dfl_status dfl_cfg_bool(const dfl_cfg *c, const char *sec, const char *key, bool *out,
                        dfl_err *err)
{
    static const char *const t[] = {"true", "yes", "on", "1"};
    static const char *const f[] = {"false", "no", "off", "0"};
    const char *expect = "a boolean (true/false, yes/no, on/off, 1/0)";
    const cfg_entry *en = lookup(c, sec, key);
    if (!en) return missing(c, sec, key, expect, err);
    dfl_status st = single(c, en, err);
    if (st != DFL_OK) return st;
    for (int i = 0; i < 4; i++) {
        if (strcasecmp(en->value, t[i]) == 0) {
            *out = true;
            return DFL_OK;
        }
        if (strcasecmp(en->value, f[i]) == 0) {
            *out = false;
            return DFL_OK;
        }
    }
    return bad(c, en, expect, err);
}

dfl_status dfl_cfg_bool_opt(const dfl_cfg *c, const char *sec, const char *key, bool def,
                            bool *out, dfl_err *err)
{
    if (!dfl_cfg_has(c, sec, key)) {
        *out = def;
        return DFL_OK;
    }
    return dfl_cfg_bool(c, sec, key, out, err);
}

static void enum_expect(const char *const *names, int count, char *buf, size_t size)
{
    size_t k = (size_t)snprintf(buf, size, "one of ");
    for (int i = 0; i < count && k < size; i++)
        k += (size_t)snprintf(buf + k, size - k, "%s%s", i ? "|" : "", names[i]);
}

dfl_status dfl_cfg_enum(const dfl_cfg *c, const char *sec, const char *key,
                        const char *const *names, int count, int *out, dfl_err *err)
{
    char expect[512];
    enum_expect(names, count, expect, sizeof expect);
    const cfg_entry *en = lookup(c, sec, key);
    if (!en) return missing(c, sec, key, expect, err);
    dfl_status st = single(c, en, err);
    if (st != DFL_OK) return st;
    for (int i = 0; i < count; i++)
        if (strcmp(en->value, names[i]) == 0) {
            *out = i;
            return DFL_OK;
        }
    return bad(c, en, expect, err);
}

dfl_status dfl_cfg_enum_opt(const dfl_cfg *c, const char *sec, const char *key,
                            const char *const *names, int count, int def, int *out, dfl_err *err)
{
    if (!dfl_cfg_has(c, sec, key)) {
        *out = def;
        return DFL_OK;
    }
    return dfl_cfg_enum(c, sec, key, names, count, out, err);
}

/* Parses blank-separated finite doubles from s[0..len) into out (up to
 * max); returns the count or -1 on a bad token. */
static long parse_doubles(const char *s, size_t len, double *out, size_t max)
{
    long k = 0;
    size_t i = 0;
    char tok[128];
    while (i < len) {
        while (i < len && isspace((unsigned char)s[i])) i++;
        if (i >= len) break;
        size_t j = i;
        while (j < len && !isspace((unsigned char)s[j])) j++;
        if (j - i >= sizeof tok) return -1;
        memcpy(tok, s + i, j - i);
        tok[j - i] = '\0';
        double v;
        if (!parse_double(tok, &v)) return -1;
        if ((size_t)k < max && out) out[k] = v;
        k++;
        i = j;
    }
    return k;
}

dfl_status dfl_cfg_vec(const dfl_cfg *c, const char *sec, const char *key, int dim, double *out,
                       dfl_err *err)
{
    char expect[128];
    snprintf(expect, sizeof expect, "%d blank-separated finite numbers", dim);
    const cfg_entry *en = lookup(c, sec, key);
    if (!en) return missing(c, sec, key, expect, err);
    dfl_status st = single(c, en, err);
    if (st != DFL_OK) return st;
    double tmp[8];
    long k = parse_doubles(en->value, strlen(en->value), tmp, 8);
    if (k != dim) return bad(c, en, expect, err);
    memcpy(out, tmp, (size_t)dim * sizeof *out);
    return DFL_OK;
}

dfl_status dfl_cfg_vec_opt(const dfl_cfg *c, const char *sec, const char *key, int dim,
                           const double *def, double *out, dfl_err *err)
{
    if (!dfl_cfg_has(c, sec, key)) {
        memcpy(out, def, (size_t)dim * sizeof *out);
        return DFL_OK;
    }
    return dfl_cfg_vec(c, sec, key, dim, out, err);
}

dfl_status dfl_cfg_points(const dfl_cfg *c, const char *sec, const char *key, int dim,
                          size_t min_count, double **out, size_t *count, dfl_err *err)
{
    char expect[160];
    snprintf(expect, sizeof expect, "at least %zu points of %d numbers each, written 'x y%s; ...'",
             min_count, dim, dim == 3 ? " z" : "");
    *out = NULL;
    *count = 0;
    const cfg_entry *en = lookup(c, sec, key);
    if (!en) return missing(c, sec, key, expect, err);
    dfl_status st = single(c, en, err);
    if (st != DFL_OK) return st;
    const char *v = en->value;
    size_t npts = 1;
    for (const char *s = v; *s; s++)
        if (*s == ';') npts++;
    /* a trailing ';' is allowed */
    size_t vl = strlen(v);
    while (vl > 0 && isspace((unsigned char)v[vl - 1])) vl--;
    if (vl > 0 && v[vl - 1] == ';') npts--;
    double *pts = malloc((npts ? npts : 1) * (size_t)dim * sizeof *pts);
    if (!pts) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    const char *s = v;
    for (size_t i = 0; i < npts; i++) {
        const char *e = strchr(s, ';');
        size_t len = e ? (size_t)(e - s) : strlen(s);
        double tmp[8];
        long k = parse_doubles(s, len, tmp, 8);
        if (k != dim) {
            free(pts);
            char w[600];
            where_entry(c, en, w, sizeof w);
            return dfl_err_set(err, DFL_E_INPUT, "%s: point %zu: expected %d numbers, got '%.*s'", w,
                               i + 1, dim, (int)(len > 80 ? 80 : len), s);
        }
        memcpy(pts + i * (size_t)dim, tmp, (size_t)dim * sizeof *pts);
        s = e ? e + 1 : s + len;
    }
    if (npts < min_count) {
        free(pts);
        return bad(c, en, expect, err);
    }
    *out = pts;
    *count = npts;
    return DFL_OK;
}

dfl_status dfl_cfg_doubles(const dfl_cfg *c, const char *sec, const char *key, size_t min_count,
                           double **out, size_t *count, dfl_err *err)
{
    char expect[128];
    snprintf(expect, sizeof expect, "at least %zu blank-separated finite numbers", min_count);
    *out = NULL;
    *count = 0;
    const cfg_entry *en = lookup(c, sec, key);
    if (!en) return missing(c, sec, key, expect, err);
    dfl_status st = single(c, en, err);
    if (st != DFL_OK) return st;
    size_t len = strlen(en->value);
    long k = parse_doubles(en->value, len, NULL, 0);
    if (k < 0 || (size_t)k < min_count) return bad(c, en, expect, err);
    double *d = malloc((k ? (size_t)k : 1) * sizeof *d);
    if (!d) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    parse_doubles(en->value, len, d, (size_t)k);
    *out = d;
    *count = (size_t)k;
    return DFL_OK;
}

dfl_status dfl_cfg_check_used(const dfl_cfg *c, dfl_err *err)
{
    for (size_t i = 0; i < c->n; i++) {
        if (!c->used[i]) {
            char w[600];
            where_entry(c, &c->e[i], w, sizeof w);
            return dfl_err_set(err, DFL_E_INPUT, "%s: unknown key (not used by this study)", w);
        }
    }
    return DFL_OK;
}

dfl_status dfl_cfg_err_at(const dfl_cfg *c, const char *sec, const char *key, dfl_status st,
                          dfl_err *err)
{
    char w[600];
    dfl_cfg_where(c, sec, key, w, sizeof w);
    dfl_err_prefix(err, "%s", w);
    return st;
}

int dfl_cfg_point_dim(const char *value)
{
    int n = 0, in = 0;
    for (const char *s = value; *s && *s != ';'; s++) {
        int sp = isspace((unsigned char)*s);
        if (!sp && !in) n++;
        in = !sp;
    }
    return n;
}

dfl_status dfl_cfg_check_used_in(const dfl_cfg *c, const char *sec, dfl_err *err)
{
    for (size_t i = 0; i < c->n; i++) {
        if (!c->used[i] && strcmp(c->e[i].sec, sec) == 0) {
            char w[600];
            where_entry(c, &c->e[i], w, sizeof w);
            return dfl_err_set(err, DFL_E_INPUT, "%s: unknown key", w);
        }
    }
    return DFL_OK;
}

dfl_status dfl_cfg_write(const dfl_cfg *c, const char *path, dfl_err *err)
{
    dfl_atomic_file af;
    dfl_status st = dfl_atomic_open(path, &af, err);
    if (st != DFL_OK) return st;
    fprintf(af.fp, "# resolved configuration of %s\n", c->path);
    const char *cur = NULL;
    for (size_t i = 0; i < c->n; i++) {
        if (!cur || strcmp(cur, c->e[i].sec) != 0) {
            cur = c->e[i].sec;
            fprintf(af.fp, "%s[%s]\n", i ? "\n" : "", cur);
        }
        fprintf(af.fp, "%s = %s\n", c->e[i].key, c->e[i].value);
    }
    return dfl_atomic_commit(&af, err);
}
