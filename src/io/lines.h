/* Text lines read from untrusted files: the one line reader of the INI and
 * CSV readers, so that both apply the same rules.
 *
 * Function index
 *   dfl_lines_open_file(r, fp, name, max, max_lines)  read from fp
 *   dfl_lines_open_text(r, text, name, max, max_lines) read from a C string
 *   dfl_lines_next(r, buf, size, &len, err)            the next line
 *   dfl_text_utf8_bad(s, n)                            first invalid UTF-8 byte
 *   dfl_text_escape(s, out, size)                      printable copy for messages
 *
 * Rules (one place, io/lines.c):
 *   - A line holds at most max bytes, not counting its end ("\n", "\r\n" or
 *     the end of the file).  A longer line is refused after reading max + 1
 *     bytes of it, so an endless line (e.g. /dev/zero) ends promptly.  The
 *     last line needs no newline (a final line of exactly max bytes is
 *     accepted).
 *   - At most max_lines lines are read; the next one is refused.
 *   - A UTF-8 byte-order mark at the start of the first line is skipped
 *     (INI and CSV alike).
 *   - NUL bytes, control characters (below 0x20 except TAB; DEL 0x7f; a CR
 *     not followed by the line end; the C1 range U+0080..U+009F) and
 *     invalid UTF-8 (overlong forms,
 *     surrogates, code points above U+10FFFF, truncated sequences) are
 *     refused, naming the line and column.  Every error is DFL_E_INPUT
 *     "name:line: ..."; a read error of fp is DFL_E_IO.
 */
#ifndef DFL_IO_LINES_H
#define DFL_IO_LINES_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "core/status.h"

typedef struct dfl_lines {
    FILE *fp;          /* source file, or NULL */
    const char *text;  /* source string when fp is NULL */
    size_t pos;        /* read position in text */
    const char *name;  /* for messages */
    size_t max;        /* bytes per line */
    long max_lines;    /* lines per file */
    long line;         /* number of the line last returned (1-based) */
    int pending;       /* a byte read ahead (or -2: none) */
} dfl_lines;

void dfl_lines_open_file(dfl_lines *r, FILE *fp, const char *name, size_t max, long max_lines);
void dfl_lines_open_text(dfl_lines *r, const char *text, const char *name, size_t max,
                         long max_lines);

/* Reads the next line into buf (size >= r->max + 4), without its end, NUL
 * terminated; *len receives its length.  Returns DFL_OK with *len set and
 * r->line advanced, DFL_OK with *len == (size_t)-1 at the end of input, or
 * an error by the rules above. */
dfl_status dfl_lines_next(dfl_lines *r, char *buf, size_t size, size_t *len, dfl_err *err);

/* Index of the first byte of s[0..n) that is not part of valid UTF-8, or n
 * when all of it is valid. */
size_t dfl_text_utf8_bad(const char *s, size_t n);

/* Copies s into out (size >= 1) with every byte that is not printable
 * (control characters incl. DEL and the C1 range U+0080..U+009F, invalid
 * UTF-8) written as \xNN; valid printable UTF-8 is kept.  Truncated at a
 * character boundary to fit, always NUL-terminated.  Returns out. */
char *dfl_text_escape(const char *s, char *out, size_t size);

#endif
