/* Typed getters.  Each one looks its key up through fetch(), which marks it
 * used (for dfl_cfg_check_used) before any check, so that a rejected value
 * is never also reported as unknown; then parses and range-checks it, and
 * on failure names the key's location, what was expected and what was
 * found.  The _opt forms return the default without inventing the key.
 * Every read goes to the config's read record (dfl_cfgi_log) with the
 * same `expect` text the messages use, and the default when one is taken. */
#include <assert.h>
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "core/domain.h"
#include "io/config_impl.h"
#include "io/path.h"
#include "io/table.h"

/* The entry of a required single value, marked used.  DFL_E_INPUT when it
 * is absent, or still a sweep list: a list reaching a getter means the
 * caller read the un-expanded config, and taking its first item silently
 * would hide that. */
static dfl_status fetch(const dfl_cfg *c, const char *sec, const char *key, const char *expect,
                        const dfl_cfg_entry **en, dfl_err *err)
{
    ssize_t i = dfl_cfgi_find(c, sec, key);
    if (i < 0) return dfl_cfgi_missing(c, sec, key, expect, err);
    c->used[i] = 1;
    dfl_cfgi_log(c, sec, key, expect, NULL);
    *en = &c->e[i];
    if (strchr((*en)->value, ','))
        return dfl_cfgi_bad(*en, "a single value (lists are sweep axes)", err);
    return DFL_OK;
}

dfl_status dfl_cfg_string(const dfl_cfg *c, const char *sec, const char *key, const char **out,
                          dfl_err *err)
{
    const dfl_cfg_entry *en;
    dfl_status st = fetch(c, sec, key, "a value", &en, err);
    if (st != DFL_OK) return st;
    if (en->value[0] == '\0') return dfl_cfgi_bad(en, "a non-empty value", err);
    *out = en->value;
    return DFL_OK;
}

dfl_status dfl_cfg_path_value(const dfl_cfg *c, const char *sec, const char *key, char *buf,
                              size_t size, dfl_err *err)
{
    assert(dfl_cfgi_is_path_key(key)); /* else config.ini would not rerun */
    const dfl_cfg_entry *en;
    dfl_status st = fetch(c, sec, key, "a file name", &en, err);
    if (st != DFL_OK) return st;
    if (en->value[0] == '\0') return dfl_cfgi_bad(en, "a file name", err);
    /* --set entries have no line and their "file" is the word "--set" */
    const char *base = en->line > 0 ? en->file : "";
    if (!dfl_path_beside(base, en->value, buf, size))
        return dfl_cfgi_bad(en, "a shorter file name", err);
    return DFL_OK;
}

dfl_status dfl_cfg_string_opt(const dfl_cfg *c, const char *sec, const char *key, const char *def,
                              const char **out, dfl_err *err)
{
    if (!dfl_cfg_has(c, sec, key)) {
        *out = def;
        dfl_cfgi_log(c, sec, key, "a value", def ? def : "(none)");
        return DFL_OK;
    }
    return dfl_cfg_string(c, sec, key, out, err);
}

/* What strtod made of a value: a finite double, or why not. */
enum { NUM_OK = 1, NUM_BAD = 0, NUM_OVERFLOW = -1, NUM_UNDERFLOW = -2 };

/* strtod's ERANGE means two things: overflow (the result is +-HUGE_VAL,
 * i.e. inf: out of range) and underflow (the result is subnormal or zero).
 * A subnormal is a finite double (config.h) and the value; a non-zero
 * number that rounds to zero (below 4.9e-324) is out of range. */
static int classify_double(const char *s, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    const int erange = errno == ERANGE;
    if (end == s) return NUM_BAD;
    while (isspace((unsigned char)*end)) end++;
    if (*end != '\0' || isnan(v)) return NUM_BAD;
    if (isinf(v)) return erange ? NUM_OVERFLOW : NUM_BAD; /* "inf" written is not a number */
    if (erange && v == 0.0) return NUM_UNDERFLOW;
    *out = v;
    return NUM_OK;
}

static int parse_double(const char *s, double *out)
{
    return classify_double(s, out) == NUM_OK;
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

static void int_expect(long lo, long hi, char *buf, size_t size)
{
    snprintf(buf, size, "an integer in [%ld, %ld]", lo, hi);
}

dfl_status dfl_cfg_int(const dfl_cfg *c, const char *sec, const char *key, long lo, long hi,
                       long *out, dfl_err *err)
{
    char expect[128];
    int_expect(lo, hi, expect, sizeof expect);
    const dfl_cfg_entry *en;
    dfl_status st = fetch(c, sec, key, expect, &en, err);
    if (st != DFL_OK) return st;
    long v;
    if (!parse_long(en->value, &v) || v < lo || v > hi) return dfl_cfgi_bad(en, expect, err);
    *out = v;
    return DFL_OK;
}

dfl_status dfl_cfg_int_opt(const dfl_cfg *c, const char *sec, const char *key, long def, long lo,
                           long hi, long *out, dfl_err *err)
{
    if (!dfl_cfg_has(c, sec, key)) {
        *out = def;
        char expect[128], d[32];
        int_expect(lo, hi, expect, sizeof expect);
        snprintf(d, sizeof d, "%ld", def);
        dfl_cfgi_log(c, sec, key, expect, d);
        return DFL_OK;
    }
    return dfl_cfg_int(c, sec, key, lo, hi, out, err);
}

/* dfl_cfgi_bad with the reason after the value. */
static dfl_status bad_why(const dfl_cfg_entry *en, const char *expect, const char *why,
                          dfl_err *err)
{
    char w[1024];
    dfl_cfgi_where(en, w, sizeof w);
    return dfl_err_set(err, DFL_E_INPUT, "%s: expected %s, got '%.200s' (%s)", w, expect,
                       en->value, why);
}

static void double_expect(double lo, double hi, char *expect, size_t size)
{
    if (isinf(lo) && isinf(hi))
        snprintf(expect, size, "a finite number");
    else if (isinf(hi))
        snprintf(expect, size, "a finite number >= %g", lo);
    else if (isinf(lo))
        snprintf(expect, size, "a finite number <= %g", hi);
    else
        snprintf(expect, size, "a finite number in [%g, %g]", lo, hi);
}

dfl_status dfl_cfg_double(const dfl_cfg *c, const char *sec, const char *key, double lo, double hi,
                          double *out, dfl_err *err)
{
    char expect[128];
    double_expect(lo, hi, expect, sizeof expect);
    const dfl_cfg_entry *en;
    dfl_status st = fetch(c, sec, key, expect, &en, err);
    if (st != DFL_OK) return st;
    double v;
    const int k = classify_double(en->value, &v);
    if (k == NUM_OVERFLOW)
        return bad_why(en, expect, "out of range: beyond the largest double, 1.8e308", err);
    if (k == NUM_UNDERFLOW)
        return bad_why(en, expect, "out of range: not zero, but below the smallest double, 4.9e-324",
                       err);
    if (k != NUM_OK) return dfl_cfgi_bad(en, expect, err);
    if (!(v >= lo && v <= hi)) { /* a finite number out of the key's range: say which end */
        char why[128];
        snprintf(why, sizeof why, "%s %.17g", v < lo ? "below the smallest value accepted,"
                                                     : "above the largest value accepted,",
                 v < lo ? lo : hi);
        return bad_why(en, expect, why, err);
    }
    *out = v;
    return DFL_OK;
}

dfl_status dfl_cfg_double_opt(const dfl_cfg *c, const char *sec, const char *key, double def,
                              double lo, double hi, double *out, dfl_err *err)
{
    if (!dfl_cfg_has(c, sec, key)) {
        *out = def;
        char expect[128], d[32];
        double_expect(lo, hi, expect, sizeof expect);
        dfl_cfgi_log(c, sec, key, expect, dfl_table_format_double(def, d, sizeof d));
        return DFL_OK;
    }
    return dfl_cfg_double(c, sec, key, lo, hi, out, err);
}

#define BOOL_EXPECT "a boolean (true/false, yes/no, on/off, 1/0)"

dfl_status dfl_cfg_bool(const dfl_cfg *c, const char *sec, const char *key, bool *out,
                        dfl_err *err)
{
    static const char *const t[] = {"true", "yes", "on", "1"};
    static const char *const f[] = {"false", "no", "off", "0"};
    const char *expect = BOOL_EXPECT;
    const dfl_cfg_entry *en;
    dfl_status st = fetch(c, sec, key, expect, &en, err);
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
    return dfl_cfgi_bad(en, expect, err);
}

dfl_status dfl_cfg_bool_opt(const dfl_cfg *c, const char *sec, const char *key, bool def,
                            bool *out, dfl_err *err)
{
    if (!dfl_cfg_has(c, sec, key)) {
        *out = def;
        dfl_cfgi_log(c, sec, key, BOOL_EXPECT, def ? "true" : "false");
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
    const dfl_cfg_entry *en;
    dfl_status st = fetch(c, sec, key, expect, &en, err);
    if (st != DFL_OK) return st;
    for (int i = 0; i < count; i++)
        if (strcmp(en->value, names[i]) == 0) {
            *out = i;
            return DFL_OK;
        }
    return dfl_cfgi_bad(en, expect, err);
}

dfl_status dfl_cfg_enum_opt(const dfl_cfg *c, const char *sec, const char *key,
                            const char *const *names, int count, int def, int *out, dfl_err *err)
{
    if (!dfl_cfg_has(c, sec, key)) {
        *out = def;
        char expect[512];
        enum_expect(names, count, expect, sizeof expect);
        dfl_cfgi_log(c, sec, key, expect, def >= 0 && def < count ? names[def] : "(none)");
        return DFL_OK;
    }
    return dfl_cfg_enum(c, sec, key, names, count, out, err);
}

/* Parses blank-separated finite doubles from s[0..len) into out (up to
 * max); returns the count or -1 on a bad token.  These lists are
 * coordinates, so a magnitude above DFL_COORD_MAX (core/domain.h) is a bad
 * token too. */
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
        if (!parse_double(tok, &v) || !dfl_coord_ok(v)) return -1;
        if ((size_t)k < max && out) out[k] = v;
        k++;
        i = j;
    }
    return k;
}

static void vec_expect(int dim, char *buf, size_t size)
{
    snprintf(buf, size, "%d blank-separated finite numbers (|v| <= 1e150)", dim);
}

dfl_status dfl_cfg_vec(const dfl_cfg *c, const char *sec, const char *key, int dim, double *out,
                       dfl_err *err)
{
    char expect[128];
    vec_expect(dim, expect, sizeof expect);
    const dfl_cfg_entry *en;
    dfl_status st = fetch(c, sec, key, expect, &en, err);
    if (st != DFL_OK) return st;
    double tmp[8];
    long k = parse_doubles(en->value, strlen(en->value), tmp, 8);
    if (k != dim) return dfl_cfgi_bad(en, expect, err);
    memcpy(out, tmp, (size_t)dim * sizeof *out);
    return DFL_OK;
}

dfl_status dfl_cfg_vec_opt(const dfl_cfg *c, const char *sec, const char *key, int dim,
                           const double *def, double *out, dfl_err *err)
{
    if (!dfl_cfg_has(c, sec, key)) {
        memcpy(out, def, (size_t)dim * sizeof *out);
        char expect[128], d[8 * 32] = "";
        vec_expect(dim, expect, sizeof expect);
        for (int i = 0; i < dim && i < 8; i++) {
            char one[32];
            strcat(d, i ? " " : "");
            strcat(d, dfl_table_format_double(def[i], one, sizeof one));
        }
        dfl_cfgi_log(c, sec, key, expect, d);
        return DFL_OK;
    }
    return dfl_cfg_vec(c, sec, key, dim, out, err);
}

dfl_status dfl_cfg_points(const dfl_cfg *c, const char *sec, const char *key, int dim,
                          size_t min_count, double **out, size_t *count, dfl_err *err)
{
    char expect[160];
    snprintf(expect, sizeof expect, "at least %zu points of %d numbers each (|v| <= 1e150), written 'x y%s; ...'",
             min_count, dim, dim == 3 ? " z" : "");
    *out = NULL;
    *count = 0;
    const dfl_cfg_entry *en;
    dfl_status st = fetch(c, sec, key, expect, &en, err);
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
            char w[1024];
            dfl_cfgi_where(en, w, sizeof w);
            return dfl_err_set(err, DFL_E_INPUT,
                               "%s: point %zu: expected %d numbers, got '%.*s' (each finite, |v| <= 1e150)", w,
                               i + 1, dim, (int)(len > 80 ? 80 : len), s);
        }
        memcpy(pts + i * (size_t)dim, tmp, (size_t)dim * sizeof *pts);
        s = e ? e + 1 : s + len;
    }
    if (npts < min_count) {
        free(pts);
        return dfl_cfgi_bad(en, expect, err);
    }
    *out = pts;
    *count = npts;
    return DFL_OK;
}

dfl_status dfl_cfg_doubles(const dfl_cfg *c, const char *sec, const char *key, size_t min_count,
                           double **out, size_t *count, dfl_err *err)
{
    char expect[128];
    snprintf(expect, sizeof expect, "at least %zu blank-separated finite numbers (|v| <= 1e150)", min_count);
    *out = NULL;
    *count = 0;
    const dfl_cfg_entry *en;
    dfl_status st = fetch(c, sec, key, expect, &en, err);
    if (st != DFL_OK) return st;
    size_t len = strlen(en->value);
    long k = parse_doubles(en->value, len, NULL, 0);
    if (k < 0 || (size_t)k < min_count) return dfl_cfgi_bad(en, expect, err);
    double *d = malloc((k ? (size_t)k : 1) * sizeof *d);
    if (!d) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    parse_doubles(en->value, len, d, (size_t)k);
    *out = d;
    *count = (size_t)k;
    return DFL_OK;
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
