/* The checker is a recursive descent over RFC 8259's grammar that stops
 * at the first byte that cannot continue a JSON text and names it; the
 * getters then walk only text that passed it, so they need no checks of
 * their own beyond the member's type. */
#include "io/json.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct parser {
    const char *s;
    size_t n, i, len; /* n: up to the first NUL, len: all bytes */
    const char *name;
    dfl_err *err;
    dfl_status st;
} parser;

static int fail(parser *p, const char *what)
{
    if (p->st == DFL_OK) {
        const unsigned char c = p->i < p->n ? (unsigned char)p->s[p->i] : 0;
        if (p->i >= p->n && p->n < p->len)
            p->st = dfl_err_set(p->err, DFL_E_INPUT, "%s: byte %zu: expected %s, got a NUL byte",
                                p->name, p->i, what);
        else if (p->i >= p->n)
            p->st = dfl_err_set(p->err, DFL_E_INPUT, "%s: byte %zu: expected %s, got the end",
                                p->name, p->i, what);
        else if (c >= 0x21 && c < 0x7f)
            p->st = dfl_err_set(p->err, DFL_E_INPUT, "%s: byte %zu: expected %s, got '%c'",
                                p->name, p->i, what, c);
        else
            p->st = dfl_err_set(p->err, DFL_E_INPUT, "%s: byte %zu: expected %s, got byte 0x%02x",
                                p->name, p->i, what, c);
    }
    return 0;
}

static int peek(const parser *p) { return p->i < p->n ? (unsigned char)p->s[p->i] : -1; }

static void ws(parser *p)
{
    while (p->i < p->n && (p->s[p->i] == ' ' || p->s[p->i] == '\t' || p->s[p->i] == '\n' ||
                           p->s[p->i] == '\r'))
        p->i++;
}

static int hexval(int c)
{
    return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10
         : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
}

/* Four hex digits at p->i into *u. */
static int hex4(parser *p, unsigned *u)
{
    *u = 0;
    for (int k = 0; k < 4; k++, p->i++) {
        const int d = hexval(peek(p));
        if (d < 0) return fail(p, "a hex digit of a \\u escape");
        *u = 16 * *u + (unsigned)d;
    }
    return 1;
}

/* One UTF-8 sequence of 2..4 bytes at p->i (the lead byte >= 0x80). */
static int utf8(parser *p)
{
    const unsigned char *b = (const unsigned char *)p->s + p->i;
    const size_t left = p->n - p->i;
    int len;
    unsigned lo = 0x80, hi = 0xbf; /* range of the second byte */
    if (b[0] >= 0xc2 && b[0] <= 0xdf) len = 2;
    else if (b[0] >= 0xe0 && b[0] <= 0xef) {
        len = 3;
        if (b[0] == 0xe0) lo = 0xa0;      /* overlong */
        else if (b[0] == 0xed) hi = 0x9f; /* surrogates */
    } else if (b[0] >= 0xf0 && b[0] <= 0xf4) {
        len = 4;
        if (b[0] == 0xf0) lo = 0x90;
        else if (b[0] == 0xf4) hi = 0x8f; /* above U+10FFFF */
    } else
        return fail(p, "valid UTF-8 in a string");
    if (left < (size_t)len || b[1] < lo || b[1] > hi) return fail(p, "valid UTF-8 in a string");
    for (int k = 2; k < len; k++)
        if (b[k] < 0x80 || b[k] > 0xbf) return fail(p, "valid UTF-8 in a string");
    p->i += (size_t)len;
    return 1;
}

static int string(parser *p)
{
    if (peek(p) != '"') return fail(p, "'\"' (a string)");
    p->i++;
    for (;;) {
        const int c = peek(p);
        if (c < 0) return fail(p, "'\"' closing the string");
        if (c == '"') {
            p->i++;
            return 1;
        }
        if (c < 0x20) return fail(p, "no control character in a string (\\u escape it)");
        if (c >= 0x80) {
            if (!utf8(p)) return 0;
            continue;
        }
        p->i++;
        if (c != '\\') continue;
        const int e = peek(p);
        if (e == 'u') {
            p->i++;
            unsigned u;
            if (!hex4(p, &u)) return 0;
            if (u >= 0xdc00 && u <= 0xdfff) {
                p->i -= 6;
                return fail(p, "no lone low surrogate");
            }
            if (u >= 0xd800 && u <= 0xdbff) {
                if (peek(p) != '\\' || p->i + 1 >= p->n || p->s[p->i + 1] != 'u')
                    return fail(p, "a \\u low surrogate after a high one");
                p->i += 2;
                if (!hex4(p, &u)) return 0;
                if (u < 0xdc00 || u > 0xdfff) {
                    p->i -= 6;
                    return fail(p, "a \\u low surrogate after a high one");
                }
            }
        } else if (e >= 0 && strchr("\"\\/bfnrt", e)) {
            p->i++;
        } else {
            return fail(p, "an escape (\\\" \\\\ \\/ \\b \\f \\n \\r \\t \\uXXXX)");
        }
    }
}

static int digits(parser *p)
{
    if (peek(p) < '0' || peek(p) > '9') return fail(p, "a digit");
    while (peek(p) >= '0' && peek(p) <= '9') p->i++;
    return 1;
}

static int number(parser *p)
{
    if (peek(p) == '-') p->i++;
    if (peek(p) == '0') p->i++;
    else if (!digits(p)) return 0;
    if (peek(p) == '.') {
        p->i++;
        if (!digits(p)) return 0;
    }
    if (peek(p) == 'e' || peek(p) == 'E') {
        p->i++;
        if (peek(p) == '+' || peek(p) == '-') p->i++;
        if (!digits(p)) return 0;
    }
    return 1;
}

static int literal(parser *p, const char *word)
{
    const size_t l = strlen(word);
    if (p->n - p->i < l || memcmp(p->s + p->i, word, l) != 0) return fail(p, "a JSON value");
    p->i += l;
    return 1;
}

static int value(parser *p, int depth);

/* Whether the keys [a, a+al) and [b, b+bl) (raw, quotes included) are
 * equal: dflab writes keys without escapes, so bytes are compared. */
static int same_raw(const char *a, size_t al, const char *b, size_t bl)
{
    return al == bl && memcmp(a, b, al) == 0;
}

static int object(parser *p, int depth)
{
    p->i++; /* '{' */
    ws(p);
    if (peek(p) == '}') {
        p->i++;
        return 1;
    }
    size_t *keys = NULL, nk = 0; /* the top level's keys: start, length pairs */
    int ok = 1;
    for (;;) {
        ws(p);
        const size_t k0 = p->i;
        if (!string(p)) {
            ok = 0;
            break;
        }
        if (depth == 1) {
            for (size_t j = 0; j < nk; j++)
                if (same_raw(p->s + keys[2 * j], keys[2 * j + 1], p->s + k0, p->i - k0)) {
                    p->i = k0;
                    ok = fail(p, "each top-level key once");
                    break;
                }
            if (!ok) break;
            size_t *nw = realloc(keys, (nk + 1) * 2 * sizeof *nw);
            if (!nw) {
                p->st = dfl_err_set(p->err, DFL_E_NOMEM, "%s: out of memory", p->name);
                ok = 0;
                break;
            }
            keys = nw;
            keys[2 * nk] = k0, keys[2 * nk + 1] = p->i - k0, nk++;
        }
        ws(p);
        if (peek(p) != ':') {
            ok = fail(p, "':' after a key");
            break;
        }
        p->i++;
        if (!value(p, depth)) {
            ok = 0;
            break;
        }
        ws(p);
        if (peek(p) == ',') {
            p->i++;
            continue;
        }
        if (peek(p) == '}') {
            p->i++;
            break;
        }
        ok = fail(p, "',' or '}' in an object");
        break;
    }
    free(keys);
    return ok;
}

static int array(parser *p, int depth)
{
    p->i++; /* '[' */
    ws(p);
    if (peek(p) == ']') {
        p->i++;
        return 1;
    }
    for (;;) {
        if (!value(p, depth)) return 0;
        ws(p);
        if (peek(p) == ',') {
            p->i++;
            continue;
        }
        if (peek(p) == ']') {
            p->i++;
            return 1;
        }
        return fail(p, "',' or ']' in an array");
    }
}

static int value(parser *p, int depth)
{
    ws(p);
    const int c = peek(p);
    if (c == '{' || c == '[') {
        if (depth >= DFL_JSON_DEPTH_MAX) {
            char what[48];
            snprintf(what, sizeof what, "at most %d levels of nesting", DFL_JSON_DEPTH_MAX);
            return fail(p, what);
        }
        return c == '{' ? object(p, depth + 1) : array(p, depth + 1);
    }
    if (c == '"') return string(p);
    if (c == '-' || (c >= '0' && c <= '9')) return number(p);
    if (c == 't') return literal(p, "true");
    if (c == 'f') return literal(p, "false");
    if (c == 'n') return literal(p, "null");
    return fail(p, "a JSON value");
}

dfl_status dfl_json_check(const char *text, size_t len, const char *name, dfl_err *err)
{
    parser p = {.s = text, .n = len, .len = len, .name = name, .err = err, .st = DFL_OK};
    /* a NUL ends the text for every C reader: refuse it where it stands */
    const char *nul = memchr(text, '\0', len);
    if (nul) p.n = (size_t)(nul - text);
    ws(&p);
    if (peek(&p) != '{') fail(&p, "'{' (a JSON object)");
    else if (object(&p, 1)) {
        ws(&p);
        if (p.i < len) fail(&p, "nothing after the object");
    }
    return p.st;
}

/* ---- walking checked text ------------------------------------------- */

/* Past the string starting at the quote s. */
static const char *skip_string(const char *s)
{
    for (s++; *s != '"'; s++)
        if (*s == '\\') s++;
    return s + 1;
}

static const char *skip_ws(const char *s)
{
    while (*s == ' ' || *s == '\t' || *s == '\n' || *s == '\r') s++;
    return s;
}

/* Past the value starting at s. */
static const char *skip_value(const char *s)
{
    if (*s == '"') return skip_string(s);
    if (*s == '{' || *s == '[') {
        int depth = 0;
        for (;;) {
            if (*s == '"') {
                s = skip_string(s);
                continue;
            }
            if (*s == '{' || *s == '[') depth++;
            else if (*s == '}' || *s == ']') {
                if (--depth == 0) return s + 1;
            }
            s++;
        }
    }
    while (*s && !strchr(",}] \t\r\n", *s)) s++;
    return s;
}

int dfl_json_member(const char *text, const char *key, const char **val, size_t *vlen)
{
    const size_t kl = strlen(key);
    const char *s = skip_ws(text);
    if (*s != '{') return 0;
    s = skip_ws(s + 1);
    while (*s == '"') {
        const char *k = s + 1;
        s = skip_string(s);
        const int hit = (size_t)(s - 1 - k) == kl && memcmp(k, key, kl) == 0;
        s = skip_ws(skip_ws(s) + 1); /* ':' */
        const char *v = s;
        s = skip_value(s);
        if (hit) {
            *val = v;
            *vlen = (size_t)(s - v);
            return 1;
        }
        s = skip_ws(s);
        if (*s != ',') break;
        s = skip_ws(s + 1);
    }
    return 0;
}

int dfl_json_each(const char **it, const char **val, size_t *vlen)
{
    if (**it == ']') return 0; /* after the last */
    const char *s = skip_ws(*it + 1); /* past '[' at the start, ',' later */
    if (*s == ']') {
        *it = s; /* stays at the end */
        return 0;
    }
    *val = s;
    s = skip_value(s);
    *vlen = (size_t)(s - *val);
    *it = skip_ws(s); /* at ',' or ']' */
    return 1;
}

static dfl_status bad(const char *text, const char *v, const char *key, const char *name,
                      const char *what, dfl_err *err)
{
    return dfl_err_set(err, DFL_E_INPUT, "%s: byte %zu: %s: expected %s", name,
                       (size_t)(v - text), key, what);
}

static dfl_status find(const char *text, const char *key, const char *name, const char **v,
                       size_t *vl, dfl_err *err)
{
    if (!dfl_json_member(text, key, v, vl))
        return dfl_err_set(err, DFL_E_INPUT, "%s: %s: missing", name, key);
    return DFL_OK;
}

/* UTF-8 of code point u into o; returns the byte count. */
static size_t put_utf8(unsigned u, char *o)
{
    if (u < 0x80) return o[0] = (char)u, 1;
    if (u < 0x800) return o[0] = (char)(0xc0 | u >> 6), o[1] = (char)(0x80 | (u & 0x3f)), 2;
    if (u < 0x10000)
        return o[0] = (char)(0xe0 | u >> 12), o[1] = (char)(0x80 | (u >> 6 & 0x3f)),
               o[2] = (char)(0x80 | (u & 0x3f)), 3;
    return o[0] = (char)(0xf0 | u >> 18), o[1] = (char)(0x80 | (u >> 12 & 0x3f)),
           o[2] = (char)(0x80 | (u >> 6 & 0x3f)), o[3] = (char)(0x80 | (u & 0x3f)), 4;
}

static unsigned hex4_at(const char *s)
{
    unsigned u = 0;
    for (int k = 0; k < 4; k++) u = 16 * u + (unsigned)hexval((unsigned char)s[k]);
    return u;
}

dfl_status dfl_json_get_string(const char *text, const char *key, const char *name, char *buf,
                               size_t size, dfl_err *err)
{
    if (size) buf[0] = '\0';
    const char *v;
    size_t vl;
    dfl_status st = find(text, key, name, &v, &vl, err);
    if (st != DFL_OK) return st;
    if (*v != '"') return bad(text, v, key, name, "a string", err);
    size_t k = 0;
    for (const char *s = v + 1; *s != '"';) {
        char tmp[4];
        size_t n = 1;
        if (*s != '\\') tmp[0] = *s++;
        else {
            const char e = s[1];
            s += 2;
            if (e == 'u') {
                unsigned u = hex4_at(s);
                s += 4;
                if (u >= 0xd800 && u <= 0xdbff) {
                    u = 0x10000 + ((u - 0xd800) << 10) + (hex4_at(s + 2) - 0xdc00);
                    s += 6;
                }
                if (u == 0) return bad(text, v, key, name, "a string without \\u0000", err);
                n = put_utf8(u, tmp);
            } else
                tmp[0] = e == 'b' ? '\b' : e == 'f' ? '\f' : e == 'n' ? '\n' : e == 'r' ? '\r'
                       : e == 't' ? '\t' : e;
        }
        if (k + n >= size) {
            if (size) buf[0] = '\0';
            char what[64];
            snprintf(what, sizeof what, "a string of at most %zu bytes", size ? size - 1 : 0);
            return bad(text, v, key, name, what, err);
        }
        memcpy(buf + k, tmp, n);
        k += n;
    }
    buf[k] = '\0';
    return DFL_OK;
}

dfl_status dfl_json_get_long(const char *text, const char *key, const char *name, long lo,
                             long hi, long *out, dfl_err *err)
{
    const char *v;
    size_t vl;
    dfl_status st = find(text, key, name, &v, &vl, err);
    if (st != DFL_OK) return st;
    char what[96];
    snprintf(what, sizeof what, "an integer in %ld..%ld", lo, hi);
    size_t j = *v == '-';
    if (j == vl) return bad(text, v, key, name, what, err);
    for (; j < vl; j++)
        if (v[j] < '0' || v[j] > '9') return bad(text, v, key, name, what, err);
    errno = 0;
    const long x = strtol(v, NULL, 10);
    if (errno == ERANGE || x < lo || x > hi) return bad(text, v, key, name, what, err);
    *out = x;
    return DFL_OK;
}

dfl_status dfl_json_get_double(const char *text, const char *key, const char *name, double *out,
                               dfl_err *err)
{
    const char *v;
    size_t vl;
    dfl_status st = find(text, key, name, &v, &vl, err);
    if (st != DFL_OK) return st;
    if (*v != '-' && (*v < '0' || *v > '9')) return bad(text, v, key, name, "a number", err);
    const double x = strtod(v, NULL);
    if (!isfinite(x)) return bad(text, v, key, name, "a number within the range of a double", err);
    *out = x;
    return DFL_OK;
}
