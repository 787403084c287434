/* Name tables: the string side of an enum whose codes and names come from
 * one X-macro list (e.g. DFL_RFUNC_JOIN_LIST in rfunc/join.h), so that a
 * module states its names once and every reader, writer and message takes
 * them from there.
 *
 *   dfl_names_find(names, count, name)          index of name, or -1
 *   dfl_names_list(names, count, buf, size)     "a|b|c" (the config style)
 *   dfl_names_parse(what, names, count, name, &i, err)   find or a message
 *
 * names[0..count-1] are non-NULL, distinct strings; matching is exact and
 * case-sensitive.  Pure functions, no allocation.
 */
#ifndef DFL_CORE_NAMES_H
#define DFL_CORE_NAMES_H

#include <stddef.h>

#include "core/status.h"

/* Index i with strcmp(names[i], name) == 0, or -1 when there is none. */
int dfl_names_find(const char *const *names, int count, const char *name);

/* The names separated by '|' into buf (truncated to size - 1 characters,
 * always terminated when size > 0).  Returns buf. */
const char *dfl_names_list(const char *const *names, int count, char *buf, size_t size);

/* dfl_names_find into *out; DFL_E_INPUT "unknown <what> '<name>' (expected
 * one of a|b|c)" when name is not in the table (*out untouched). */
dfl_status dfl_names_parse(const char *what, const char *const *names, int count,
                           const char *name, int *out, dfl_err *err);

#endif
