/* A strict JSON reader for the records dflab reads back (point.json).
 *
 * Function index
 *   dfl_json_check          text is exactly one JSON object
 *   dfl_json_member         the raw text of a top-level member's value
 *   dfl_json_each           the elements of an array value, in order
 *   dfl_json_get_string     a top-level string member, unescaped
 *   dfl_json_get_long       a top-level integer member within [lo, hi]
 *   dfl_json_get_double     a top-level finite number member
 *
 * Debian's JSON C libraries (jansson, json-c) are not build dependencies
 * of dflab and the records are small objects that dflab itself wrote, so
 * this is a recursive-descent reader of RFC 8259, nothing more and
 * nothing less: no comments, no trailing commas, no NaN, no bytes after
 * the value.  Strings must be valid UTF-8 without control characters;
 * nesting is bounded by DFL_JSON_DEPTH_MAX; the top-level object holds each
 * key once.  Everything that passes dfl_json_check is loadable by any JSON
 * reader and may be embedded in other JSON text as is.
 *
 * Errors are DFL_E_INPUT "NAME: byte N: what was expected" (N counts from
 * 0) or, for a member, "NAME: byte N: key: what was expected"; a missing
 * member is "NAME: key: missing".  The getters take text that passed
 * dfl_json_check.
 */
#ifndef DFL_IO_JSON_H
#define DFL_IO_JSON_H

#include <stddef.h>

#include "core/status.h"

#define DFL_JSON_DEPTH_MAX 32

/* DFL_OK when text[0..len) is one JSON object with optional white space
 * around it (a NUL byte inside is an error). */
dfl_status dfl_json_check(const char *text, size_t len, const char *name, dfl_err *err);

/* 1 and *val (into text), *vlen (bytes) for the top-level member key of
 * checked text; 0 when there is none. */
int dfl_json_member(const char *text, const char *key, const char **val, size_t *vlen);

/* Iterates the array value of checked text that starts at *it (the '['):
 * each call puts the next element into *val, *vlen and returns 1; returns
 * 0 after the last.  *it is the iterator's state (advanced by each call). */
int dfl_json_each(const char **it, const char **val, size_t *vlen);

/* The string member key unescaped into buf (size bytes with the NUL);
 * DFL_E_INPUT when missing, not a string, holding \u0000 or longer than
 * size - 1 bytes. */
dfl_status dfl_json_get_string(const char *text, const char *key, const char *name, char *buf,
                               size_t size, dfl_err *err);

/* The member key, an integer written without fraction or exponent, in
 * [lo, hi]; DFL_E_INPUT otherwise (1e300, -5 below lo, 2.5, "3"). */
dfl_status dfl_json_get_long(const char *text, const char *key, const char *name, long lo,
                             long hi, long *out, dfl_err *err);

/* The number member key (finite: JSON has no other); DFL_E_INPUT when
 * missing, not a number, or beyond the range of a double. */
dfl_status dfl_json_get_double(const char *text, const char *key, const char *name, double *out,
                               dfl_err *err);

#endif
