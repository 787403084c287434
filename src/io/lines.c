/* The rules are in io/lines.h.  Bytes are read one at a time (through
 * stdio's buffer), so that the line limit stops the read at the first byte
 * beyond it instead of after the line's end, which may never come. */
#include "io/lines.h"

#include <stdio.h>
#include <string.h>

enum { NONE = -2 };

void dfl_lines_open_file(dfl_lines *r, FILE *fp, const char *name, size_t max, long max_lines)
{
    *r = (dfl_lines){.fp = fp, .name = name, .max = max, .max_lines = max_lines, .pending = NONE};
}

void dfl_lines_open_text(dfl_lines *r, const char *text, const char *name, size_t max,
                         long max_lines)
{
    *r = (dfl_lines){.text = text, .name = name, .max = max, .max_lines = max_lines,
                     .pending = NONE};
}

static int get_byte(dfl_lines *r)
{
    if (r->pending != NONE) {
        int c = r->pending;
        r->pending = NONE;
        return c;
    }
    if (r->fp) return fgetc(r->fp);
    if (!r->text[r->pos]) return EOF;
    return (unsigned char)r->text[r->pos++];
}

static dfl_status bad_byte(const dfl_lines *r, int c, size_t col, dfl_err *err)
{
    if (c == 0)
        return dfl_err_set(err, DFL_E_INPUT, "%s:%ld: NUL byte at column %zu (expected text)",
                           r->name, r->line + 1, col);
    return dfl_err_set(err, DFL_E_INPUT,
                       "%s:%ld: control character 0x%02x at column %zu (expected text)", r->name,
                       r->line + 1, (unsigned)c, col);
}

dfl_status dfl_lines_next(dfl_lines *r, char *buf, size_t size, size_t *len, dfl_err *err)
{
    /* the first line may carry a 3-byte BOM beyond the limit */
    const size_t limit = r->max + (r->line == 0 ? 3 : 0);
    if (size < r->max + 4)
        return dfl_err_set(err, DFL_E_INTERNAL, "%s: line buffer too small", r->name);
    size_t k = 0;
    int c = get_byte(r);
    if (c == EOF) {
        if (r->fp && ferror(r->fp)) return dfl_err_set(err, DFL_E_IO, "%s: read error", r->name);
        *len = (size_t)-1;
        return DFL_OK;
    }
    if (r->line >= r->max_lines)
        return dfl_err_set(err, DFL_E_INPUT, "%s:%ld: more than %ld lines", r->name,
                           r->line + 1, r->max_lines);
    for (;; c = get_byte(r)) {
        if (c == EOF || c == '\n') break;
        if (c == '\r') {
            int d = get_byte(r);
            if (d == '\n' || d == EOF) break;
            r->pending = d;
            return bad_byte(r, c, k + 1, err);
        }
        if (k == limit)
            return dfl_err_set(err, DFL_E_INPUT, "%s:%ld: line longer than %zu characters",
                               r->name, r->line + 1, r->max);
        if (c == 0 || (c < 0x20 && c != '\t') || c == 0x7f) return bad_byte(r, c, k + 1, err);
        buf[k++] = (char)c;
    }
    if (r->fp && ferror(r->fp)) return dfl_err_set(err, DFL_E_IO, "%s: read error", r->name);
    if (r->line == 0 && k >= 3 && memcmp(buf, "\xEF\xBB\xBF", 3) == 0) {
        memmove(buf, buf + 3, k - 3);
        k -= 3;
    } else if (k > r->max) {
        return dfl_err_set(err, DFL_E_INPUT, "%s:%ld: line longer than %zu characters", r->name,
                           r->line + 1, r->max);
    }
    buf[k] = '\0';
    size_t bad = dfl_text_utf8_bad(buf, k);
    if (bad < k)
        return dfl_err_set(err, DFL_E_INPUT,
                           "%s:%ld: invalid UTF-8 at column %zu (byte 0x%02x; expected text)",
                           r->name, r->line + 1, bad + 1, (unsigned)(unsigned char)buf[bad]);
    for (size_t i = 0; i + 1 < k; i++)
        if ((unsigned char)buf[i] == 0xC2 && (unsigned char)buf[i + 1] < 0xA0)
            return dfl_err_set(err, DFL_E_INPUT,
                               "%s:%ld: control character U+%04X at column %zu (expected text)",
                               r->name, r->line + 1, (unsigned char)buf[i + 1], i + 1);
    r->line++;
    *len = k;
    return DFL_OK;
}

/* Length of the valid UTF-8 sequence at s (n bytes left), 0 if invalid
 * (RFC 3629: no overlong forms, no surrogates, nothing above U+10FFFF). */
static size_t utf8_seq(const unsigned char *s, size_t n)
{
    const unsigned c = s[0];
    if (c < 0x80) return 1;
    size_t len;
    unsigned lo = 0x80, hi = 0xBF;
    if (c >= 0xC2 && c <= 0xDF) len = 2;
    else if (c >= 0xE0 && c <= 0xEF) {
        len = 3;
        if (c == 0xE0) lo = 0xA0;
        if (c == 0xED) hi = 0x9F;
    } else if (c >= 0xF0 && c <= 0xF4) {
        len = 4;
        if (c == 0xF0) lo = 0x90;
        if (c == 0xF4) hi = 0x8F;
    } else {
        return 0;
    }
    if (n < len) return 0;
    if (s[1] < lo || s[1] > hi) return 0;
    for (size_t i = 2; i < len; i++)
        if (s[i] < 0x80 || s[i] > 0xBF) return 0;
    return len;
}

size_t dfl_text_utf8_bad(const char *s, size_t n)
{
    const unsigned char *u = (const unsigned char *)s;
    size_t i = 0;
    while (i < n) {
        size_t l = utf8_seq(u + i, n - i);
        if (l == 0) return i;
        i += l;
    }
    return n;
}

char *dfl_text_escape(const char *s, char *out, size_t size)
{
    const unsigned char *u = (const unsigned char *)s;
    size_t n = strlen(s), k = 0, i = 0;
    while (i < n) {
        char tmp[16];
        size_t tl;
        size_t l = utf8_seq(u + i, n - i);
        if (l == 1 && (u[i] < 0x20 || u[i] == 0x7f)) {
            tl = (size_t)snprintf(tmp, sizeof tmp, "\\x%02x", u[i]);
        } else if (l == 0 || (l == 2 && u[i] == 0xC2 && u[i + 1] < 0xA0)) {
            /* invalid UTF-8, or a C1 control (U+0080..U+009F) */
            tl = (size_t)snprintf(tmp, sizeof tmp, "\\x%02x", u[i]);
            if (l == 0) l = 1;
            else tl += (size_t)snprintf(tmp + tl, sizeof tmp - tl, "\\x%02x", u[i + 1]);
        } else {
            tl = l, memcpy(tmp, u + i, l);
        }
        if (k + tl + 1 > size) break;
        memcpy(out + k, tmp, tl);
        k += tl;
        i += l;
    }
    out[k] = '\0';
    return out;
}
