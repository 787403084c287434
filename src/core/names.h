/* Name tables: the string side of an enum whose codes and names come from
 * one X-macro list (e.g. DFL_RFUNC_JOIN_LIST in rfunc/join.h), so that a
 * module states its names once and every reader, writer and message takes
 * them from there.
 *
 *   dfl_names_find(names, count, name)          index of name, or -1
 *   dfl_names_at(names, count, i)               names[i], "?" outside
 *   dfl_names_list(names, count, buf, size)     "a|b|c" (the config style)
 *   dfl_names_parse(what, names, count, name, &i, err)   find or a message
 *   DFL_NAMES_CODE, DFL_NAMES_ONE, DFL_NAMES_NAME   X-macro columns
 *   DFL_NAMES_DEFINE                            a module's names, name(), parse()
 *
 * A list is a macro L(X) of entries X(code, name, ...) with at least one
 * column after the name (a note, or properties the module reads with its
 * own X); codes run 0, 1, ... in list order:
 *     typedef enum t { L(DFL_NAMES_CODE) } t;
 *     enum { T_COUNT = 0 L(DFL_NAMES_ONE) };
 * names[0..count-1] are non-NULL, distinct strings; matching is exact and
 * case-sensitive.  Pure functions, no allocation.
 */
#ifndef DFL_CORE_NAMES_H
#define DFL_CORE_NAMES_H

#include <stddef.h>

#include "core/status.h"

/* X-macro columns: the enumerator, a count term, a designated name. */
#define DFL_NAMES_CODE(code, name, ...) code,
#define DFL_NAMES_ONE(code, name, ...) +1
#define DFL_NAMES_NAME(code, name, ...) [code] = name,

/* Defines a module's table and its two functions, as its header declares
 * them:
 *     const char *const names[count]             by code
 *     const char *name_fn(type)                  dfl_names_at
 *     dfl_status parse_fn(const char *, type *, dfl_err *)   dfl_names_parse
 * what names the kind of value in the parse message ("join", "trim"). */
#define DFL_NAMES_DEFINE(type, list, count, names, name_fn, parse_fn, what)              \
    const char *const names[count] = {list(DFL_NAMES_NAME)};                              \
    const char *name_fn(type v) { return dfl_names_at(names, count, (int)v); }            \
    dfl_status parse_fn(const char *s, type *out, dfl_err *err)                           \
    {                                                                                     \
        int i;                                                                            \
        const dfl_status st = dfl_names_parse(what, names, count, s, &i, err);            \
        if (st == DFL_OK) *out = (type)i;                                                 \
        return st;                                                                        \
    }

/* Index i with strcmp(names[i], name) == 0, or -1 when there is none. */
int dfl_names_find(const char *const *names, int count, const char *name);

/* names[i] for 0 <= i < count, "?" otherwise (never NULL). */
const char *dfl_names_at(const char *const *names, int count, int i);

/* The names separated by '|' into buf (truncated to size - 1 characters,
 * always terminated when size > 0).  Returns buf. */
const char *dfl_names_list(const char *const *names, int count, char *buf, size_t size);

/* dfl_names_find into *out; DFL_E_INPUT "unknown <what> '<name>' (expected
 * one of a|b|c)" when name is not in the table (*out untouched). */
dfl_status dfl_names_parse(const char *what, const char *const *names, int count,
                           const char *name, int *out, dfl_err *err);

#endif
