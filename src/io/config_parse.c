/* INI loading.  libinih does the syntax; we feed it through ini_parse_stream
 * with our own line reader (io/lines.h: the text rules, shared with the
 * points CSV) so that every handler call knows its line number and whether
 * the line was an indented continuation (multi-line values are joined with
 * a blank), and so that duplicate sections and over-long names are caught
 * on the line that has them.  Debian's libinih exposes its limits as library
 * globals; we raise the line limit (process-wide, idempotent) so that long
 * point lists are not cut at 200 characters, and make '#' the only
 * inline-comment prefix so that ';' can separate points.
 *
 * `include` lines are only recorded here; their files are read after the
 * parse (config_include.c), so libinih is never re-entered from a handler. */
#include <assert.h>
#include <errno.h>
#include <ini.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "io/config_impl.h"
#include "io/rfile.h"
#include "io/lines.h"

typedef struct section_seen {
    char *name;
    int line;
} section_seen;

typedef struct parse_state {
    dfl_cfg *c;
    const char *name;
    bool allow_include;
    /* reader state */
    dfl_lines lines;
    char *buf;       /* DFL_CFG_LINE_MAX + 4 bytes */
    size_t total;    /* bytes read so far */
    int line;
    int line_indented;
    section_seen *secs; /* section headers seen, for duplicates */
    size_t nsecs;
    /* last handler call, for continuation lines */
    ssize_t last;
    /* include lines, in file order */
    dfl_cfg_include *inc;
    size_t ninc;
    dfl_err *err;
    dfl_status st;
} parse_state;

/* A section header written twice is an error: merging the two silently
 * would let a second [grid] far down a file change keys the reader thinks
 * it has read in the first (DESIGN.md, "config").  libinih keeps section
 * and key names in 50-byte buffers and cuts longer ones; refused here so
 * that no name is silently altered. */
static dfl_status check_line(parse_state *ps, const char *s, size_t len)
{
    if (len == 0 || s[0] == ' ' || s[0] == '\t' || s[0] == '#' || s[0] == ';') return DFL_OK;
    if (s[0] == '[') {
        const char *e = memchr(s, ']', len);
        if (!e) return DFL_OK; /* libinih reports the syntax error */
        size_t n = (size_t)(e - s - 1);
        if (n > DFL_CFG_NAME_MAX)
            return dfl_err_set(ps->err, DFL_E_INPUT,
                               "%s:%d: section name longer than %d characters", ps->name,
                               ps->line, DFL_CFG_NAME_MAX);
        for (size_t i = 0; i < ps->nsecs; i++)
            if (strlen(ps->secs[i].name) == n && memcmp(ps->secs[i].name, s + 1, n) == 0)
                return dfl_err_set(ps->err, DFL_E_INPUT,
                                   "%s:%d: [%s]: duplicate section (first at line %d; write "
                                   "each section once)",
                                   ps->name, ps->line, ps->secs[i].name, ps->secs[i].line);
        section_seen *v = realloc(ps->secs, (ps->nsecs + 1) * sizeof *v);
        char *nm = v ? strndup(s + 1, n) : NULL;
        if (v) ps->secs = v;
        if (!nm) return dfl_err_set(ps->err, DFL_E_NOMEM, "out of memory reading config");
        ps->secs[ps->nsecs++] = (section_seen){nm, ps->line};
        return DFL_OK;
    }
    size_t n = strcspn(s, "=:");
    while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t')) n--;
    if (n > DFL_CFG_NAME_MAX)
        return dfl_err_set(ps->err, DFL_E_INPUT, "%s:%d: key name longer than %d characters",
                           ps->name, ps->line, DFL_CFG_NAME_MAX);
    return DFL_OK;
}

/* libinih's line source: io/lines.h's rules, then the checks above.  An
 * error ends the parse (NULL = end of input for libinih); parse_stream
 * reports it. */
static char *reader(char *str, int num, void *stream)
{
    parse_state *ps = stream;
    assert(num >= DFL_CFG_LINE_MAX);
    if (ps->st != DFL_OK) return NULL;
    size_t len;
    ps->st = dfl_lines_next(&ps->lines, ps->buf, DFL_CFG_LINE_MAX + 4, &len, ps->err);
    if (ps->st != DFL_OK || len == (size_t)-1) return NULL;
    ps->line = (int)ps->lines.line;
    ps->total += len + 1;
    if (ps->total > DFL_CFG_FILE_MAX) {
        ps->st = dfl_err_set(ps->err, DFL_E_INPUT, "%s:%d: file larger than %d bytes", ps->name,
                             ps->line, DFL_CFG_FILE_MAX);
        return NULL;
    }
    ps->st = check_line(ps, ps->buf, len);
    if (ps->st != DFL_OK) return NULL;
    memcpy(str, ps->buf, len + 1);
    ps->line_indented = (len > 0 && (str[0] == ' ' || str[0] == '\t'));
    return str;
}

/* Records `include = value` of section; the checks that need only this line
 * are made here, so that they name it. */
static dfl_status record_include(parse_state *ps, const char *section, const char *value)
{
    dfl_err *err = ps->err;
    if (!ps->allow_include)
        return dfl_err_set(err, DFL_E_INPUT,
                           "%s:%d: [%s] include: an included file cannot include another "
                           "(one level only)",
                           ps->name, ps->line, section);
    for (size_t i = 0; i < ps->ninc; i++) {
        if (strcmp(ps->inc[i].sec, section) != 0) continue;
        if (ps->line_indented)
            return dfl_err_set(err, DFL_E_INPUT,
                               "%s:%d: [%s] include: continuation line (the file name goes on "
                               "one line)",
                               ps->name, ps->line, section);
        return dfl_err_set(err, DFL_E_INPUT,
                           "%s:%d: [%s] include: duplicate key (first at line %d; one include "
                           "per section)",
                           ps->name, ps->line, section, ps->inc[i].line);
    }
    if (value[0] == '\0')
        return dfl_err_set(err, DFL_E_INPUT, "%s:%d: [%s] include: expected a file name",
                           ps->name, ps->line, section);
    if (strchr(value, ','))
        return dfl_err_set(err, DFL_E_INPUT,
                           "%s:%d: [%s] include: expected one file name, got '%.200s' (an "
                           "include cannot be a sweep)",
                           ps->name, ps->line, section, value);
    dfl_cfg_include *inc = realloc(ps->inc, (ps->ninc + 1) * sizeof *inc);
    if (!inc) return dfl_err_set(err, DFL_E_NOMEM, "out of memory reading config");
    ps->inc = inc;
    dfl_cfg_include r = {strdup(section), strdup(value), ps->line, ps->c->n};
    if (!r.sec || !r.value) {
        free(r.sec), free(r.value);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory reading config");
    }
    ps->inc[ps->ninc++] = r;
    ps->last = -1;
    return DFL_OK;
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
    if (strcmp(name, "include") == 0) {
        ps->st = record_include(ps, section, value);
        return ps->st == DFL_OK;
    }
    ssize_t i = dfl_cfgi_find(c, section, name);
    if (i >= 0) {
        if (ps->line_indented && i == ps->last) {
            /* continuation line of a multi-line value: join with a blank */
            dfl_cfg_entry *en = &c->e[i];
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
    ps->st = dfl_cfgi_add(c, section, name, value, ps->name, ps->line, NULL, ps->err);
    ps->last = (ssize_t)c->n - 1;
    return ps->st == DFL_OK;
}

static void set_inih_limits(void)
{
    /* Library-wide settings of Debian's libinih (see file comment). */
    /* measured: the reader only gets num = DFL_CFG_LINE_MAX when the buffer
     * is heap-allocated with this initial size (the stack buffer is fixed) */
    ini_max_line = DFL_CFG_LINE_MAX;
    ini_use_stack = false;
    ini_allow_realloc = true;
    ini_initial_alloc = DFL_CFG_LINE_MAX;
    ini_inline_comment_prefixes = "#";
    ini_allow_multiline = true;
    ini_stop_on_first_error = true;
}

static dfl_status parse_stream(parse_state *ps)
{
    dfl_err *err = ps->err;
    set_inih_limits();
    ps->buf = malloc(DFL_CFG_LINE_MAX + 4);
    if (!ps->buf) return dfl_err_set(err, DFL_E_NOMEM, "%s: out of memory", ps->name);
    int rc = ini_parse_stream(reader, ps, handler, ps);
    free(ps->buf);
    ps->buf = NULL;
    for (size_t i = 0; i < ps->nsecs; i++) free(ps->secs[i].name);
    free(ps->secs);
    ps->secs = NULL;
    ps->nsecs = 0;
    if (ps->st != DFL_OK) return ps->st;
    if (rc == -2) return dfl_err_set(err, DFL_E_NOMEM, "%s: out of memory", ps->name);
    if (rc != 0)
        return dfl_err_set(err, DFL_E_INPUT,
                           "%s:%d: syntax error (expected [section], key = value, or a comment)",
                           ps->name, rc);
    return DFL_OK;
}

/* Parses, resolves the includes and finds the sweep axes; frees ps->c on
 * failure.  *out is set only on success. */
static dfl_status parse_common(parse_state *ps, dfl_cfg **out)
{
    dfl_status st = parse_stream(ps);
    if (st == DFL_OK) st = dfl_cfgi_resolve_includes(ps->c, ps->inc, ps->ninc, ps->err);
    if (st == DFL_OK) st = dfl_cfgi_find_axes(ps->c, ps->err);
    for (size_t i = 0; i < ps->ninc; i++) {
        free(ps->inc[i].sec);
        free(ps->inc[i].value);
    }
    free(ps->inc);
    if (st != DFL_OK) {
        dfl_cfg_free(ps->c);
        return st;
    }
    *out = ps->c;
    return DFL_OK;
}

dfl_status dfl_cfgi_load(const char *path, bool allow_include, dfl_cfg **out, dfl_err *err)
{
    *out = NULL;
    FILE *fp;
    if (!allow_include) { /* an included file: never a FIFO that blocks */
        dfl_status st = dfl_rfile_open(path, "config", &fp, err);
        if (st != DFL_OK) return st;
    } else if (!(fp = fopen(path, "r")))
        return dfl_err_set(err, DFL_E_INPUT, "%s: cannot open config: %s", path, strerror(errno));
    struct stat sb;
    if (fstat(fileno(fp), &sb) == 0 && S_ISDIR(sb.st_mode)) {
        fclose(fp);
        return dfl_err_set(err, DFL_E_INPUT, "%s: cannot read config: a directory", path);
    }
    dfl_cfg *c = dfl_cfgi_new(path);
    if (!c) {
        fclose(fp);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    }
    parse_state ps = {.c = c, .name = path, .allow_include = allow_include, .last = -1,
                      .err = err, .st = DFL_OK};
    dfl_lines_open_file(&ps.lines, fp, path, DFL_CFG_LINE_MAX - 2, DFL_CFG_LINES_MAX);
    dfl_status st = parse_common(&ps, out);
    fclose(fp);
    return st;
}

dfl_status dfl_cfg_load(const char *path, dfl_cfg **out, dfl_err *err)
{
    return dfl_cfgi_load(path, true, out, err);
}

dfl_status dfl_cfg_parse_string(const char *name, const char *text, dfl_cfg **out, dfl_err *err)
{
    *out = NULL;
    dfl_cfg *c = dfl_cfgi_new(name);
    if (!c) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    parse_state ps = {.c = c, .name = name, .allow_include = true, .last = -1, .err = err,
                      .st = DFL_OK};
    dfl_lines_open_text(&ps.lines, text, name, DFL_CFG_LINE_MAX - 2, DFL_CFG_LINES_MAX);
    return parse_common(&ps, out);
}
