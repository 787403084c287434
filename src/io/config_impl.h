/* Private to src/io/config_*.c: the configuration's storage and the helpers
 * its files share.  Not for use outside src/io.
 *
 *   dfl_cfgi_new(name)                       empty configuration named name
 *   dfl_cfgi_add(c, sec, key, value, ...)    append an entry (copies every string)
 *   dfl_cfgi_insert(c, at, ...)              the same at index at (used by includes)
 *   dfl_cfgi_find(c, sec, key)               index of an entry or -1
 *   dfl_cfgi_set_value(en, value, file, line)  replace an entry's value and origin
 *   dfl_cfgi_trim(s)                         strip blanks in place
 *   dfl_cfgi_load(path, allow_include, ...)  dfl_cfg_load, includes on or off
 *   dfl_cfgi_find_axes(c, err)               recompute the sweep axes
 *   dfl_cfgi_free_axes(c)                    drop them
 *   dfl_cfgi_where(en, buf, size)            "file:line: [sec] key" of an entry
 *   dfl_cfgi_missing / _bad                  the getters' two error messages
 *   dfl_cfgi_resolve_includes(c, incs, n, err)  merge the recorded include lines
 *   dfl_cfgi_log(c, sec, key, expect, def)   record a getter's read (config_log.c)
 *   dfl_cfgi_free_log(c)                     drop the record
 *   dfl_cfgi_stop_if_validating(c, err)      end of a validation pass
 */
#ifndef DFL_IO_CONFIG_IMPL_H
#define DFL_IO_CONFIG_IMPL_H

#include <stdbool.h>
#include <stddef.h>
#include <sys/types.h>

#include "io/config.h"

/* Longest accepted line (libinih's buffer; see config_parse.c). */
#define DFL_CFG_LINE_MAX 65536
/* Lines and bytes per file, and the longest section or key name (libinih
 * keeps names in 50-byte buffers; longer ones are refused, not cut). */
#define DFL_CFG_LINES_MAX 100000
#define DFL_CFG_FILE_MAX (16 * 1024 * 1024)
#define DFL_CFG_NAME_MAX 49
/* Most points a sweep may have (checked when the axes are found). */
#define DFL_CFG_SWEEP_MAX 100000000UL

typedef struct dfl_cfg_entry {
    char *sec;
    char *key;
    char *value;
    char *file; /* origin: config path, included file or "--set" */
    int line;   /* 0 for --set */
    char *via;  /* "file:line" of the include line that brought the key, else NULL */
    char *named; /* the values the key had before: what --set replaced, a sweep point's
                    whole list (blank-joined; NULL: none), for dfl_cfg_check_used */
} dfl_cfg_entry;

/* What the getters read, in the order they first read it (config_log.c):
 * the resolved configuration of a study, defaults included, and what each
 * key expects.  Separate block, like used, so const getters can record. */
typedef struct dfl_cfg_readrec {
    char *sec, *key, *expect;
    char *def; /* the default taken when the key is absent, else NULL */
} dfl_cfg_readrec;

typedef struct dfl_cfg_log {
    dfl_cfg_readrec *r;
    size_t n, cap;
    int validate_only; /* dfl_cfg_check_used stops the study (dfl_cfg_validate_only) */
    int validated;     /* ... and has been reached with every key known */
} dfl_cfg_log;

struct dfl_cfg {
    char *path;
    dfl_cfg_log *log; /* NULL only when out of memory at creation: nothing is recorded */
    dfl_cfg_entry *e; /* file order; lists are tiny, lookups are linear */
    size_t n, cap;
    unsigned char *used; /* separate block so const getters can mark keys */
    /* sweep axes: indices into e[] of multi-valued entries, file order */
    size_t *axis;
    char **axis_name; /* "section.key" of each axis */
    size_t naxes;
    int is_point; /* made by dfl_cfg_sweep_point: values are single */
    /* dfl_cfg_defer_sections: sections NAME and NAME_* that dfl_cfg_check_used
     * leaves to a later reader (empty: none) */
    char defer[DFL_CFG_NAME_MAX + 1];
};

/* One `include = file` line seen while parsing (resolved after the parse). */
typedef struct dfl_cfg_include {
    char *sec;   /* the including section */
    char *value; /* the file name as written */
    int line;    /* line of the include in the including file */
    size_t at;   /* number of entries before it: where its keys go */
} dfl_cfg_include;

/* NULL when out of memory. */
dfl_cfg *dfl_cfgi_new(const char *name);
/* Whether key is one of DFL_CFG_PATH_KEYS (config.h). */
bool dfl_cfgi_is_path_key(const char *key);
/* Appends a copy of the strings (via may be NULL).  DFL_E_NOMEM on failure,
 * c unchanged. */
dfl_status dfl_cfgi_add(dfl_cfg *c, const char *sec, const char *key, const char *value,
                        const char *file, int line, const char *via, dfl_err *err);
/* dfl_cfgi_add, but the entry goes to index at (0 <= at <= c->n); later
 * entries move up by one. */
dfl_status dfl_cfgi_insert(dfl_cfg *c, size_t at, const char *sec, const char *key,
                           const char *value, const char *file, int line, const char *via,
                           dfl_err *err);
ssize_t dfl_cfgi_find(const dfl_cfg *c, const char *sec, const char *key);
/* Replaces value and origin of en (via cleared).  DFL_E_NOMEM leaves en
 * unchanged. */
dfl_status dfl_cfgi_set_value(dfl_cfg_entry *en, const char *value, const char *file, int line,
                              dfl_err *err);
char *dfl_cfgi_trim(char *s);

/* Parses path into a new configuration; allow_include = false makes every
 * `include` key an error (an included file cannot include another). */
dfl_status dfl_cfgi_load(const char *path, bool allow_include, dfl_cfg **out, dfl_err *err);

dfl_status dfl_cfgi_find_axes(dfl_cfg *c, dfl_err *err);
void dfl_cfgi_free_axes(dfl_cfg *c);

/* "file:line: [sec] key" (from a file), "--set sec.key" (from --set) or
 * "file:line: [shape] key (included as [sec] at via)" (from an include). */
void dfl_cfgi_where(const dfl_cfg_entry *en, char *buf, size_t size);
/* DFL_E_INPUT "path: [sec] key: missing key (expected <expect>)". */
dfl_status dfl_cfgi_missing(const dfl_cfg *c, const char *sec, const char *key,
                            const char *expect, dfl_err *err);
/* DFL_E_INPUT "<where>: expected <expect>, got '<value>'". */
dfl_status dfl_cfgi_bad(const dfl_cfg_entry *en, const char *expect, dfl_err *err);

/* Reads the n include lines of c (parsed from c->path) and merges each
 * file's [shape] keys into the including section (config_include.c).  On
 * failure c may hold part of the keys; the caller frees it. */
dfl_status dfl_cfgi_resolve_includes(dfl_cfg *c, const dfl_cfg_include *incs, size_t n,
                                     dfl_err *err);

/* Records that a getter read [sec] key expecting `expect` (the text of its
 * error messages), taking def when the key is absent (NULL when present).
 * The first read of a key counts; out of memory drops the record. */
void dfl_cfgi_log(const dfl_cfg *c, const char *sec, const char *key, const char *expect,
                  const char *def);
void dfl_cfgi_free_log(dfl_cfg *c);
/* DFL_OK, or in a validation pass marks the config validated and returns
 * DFL_E_INTERNAL so that the study stops (dfl_cfg_check_used calls it once
 * every key is known). */
dfl_status dfl_cfgi_stop_if_validating(const dfl_cfg *c, dfl_err *err);

#endif
