/* Cells are stored as text: every value is formatted once when set (the
 * shortest decimal that reads back to the same double), which keeps the
 * table simple and the CSV exact. */
#include "io/table.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/atomic.h"
#include "io/dirs.h"

struct dfl_table {
    char **cols;
    size_t ncols, capcols;
    char ***rows;      /* rows[i][j]: NULL when absent */
    size_t *rowcap;    /* allocated cells per row */
    size_t nrows, caprows;
    char **pcol, **pval;  /* prefix cells */
    size_t npre;
};

dfl_table *dfl_table_new(void) { return calloc(1, sizeof(dfl_table)); }

void dfl_table_free(dfl_table *t)
{
    if (!t) return;
    for (size_t i = 0; i < t->nrows; i++) {
        for (size_t j = 0; j < t->rowcap[i]; j++) free(t->rows[i][j]);
        free(t->rows[i]);
    }
    free(t->rows);
    free(t->rowcap);
    for (size_t j = 0; j < t->ncols; j++) free(t->cols[j]);
    free(t->cols);
    dfl_table_prefix_clear(t);
    free(t);
}

void dfl_table_prefix_clear(dfl_table *t)
{
    for (size_t i = 0; i < t->npre; i++) {
        free(t->pcol[i]);
        free(t->pval[i]);
    }
    free(t->pcol);
    free(t->pval);
    t->pcol = t->pval = NULL;
    t->npre = 0;
}

static dfl_status no_memory(dfl_err *err, const char *col)
{
    return dfl_err_set(err, DFL_E_NOMEM, "table: out of memory for column %s", col);
}

dfl_status dfl_table_prefix_string(dfl_table *t, const char *col, const char *value,
                                   dfl_err *err)
{
    char **pc = realloc(t->pcol, (t->npre + 1) * sizeof *pc);
    if (!pc) return no_memory(err, col);
    t->pcol = pc;
    char **pv = realloc(t->pval, (t->npre + 1) * sizeof *pv);
    if (!pv) return no_memory(err, col);
    t->pval = pv;
    t->pcol[t->npre] = strdup(col);
    t->pval[t->npre] = strdup(value);
    if (!t->pcol[t->npre] || !t->pval[t->npre]) {
        free(t->pcol[t->npre]);
        free(t->pval[t->npre]);
        return no_memory(err, col);
    }
    t->npre++;
    return DFL_OK;
}

static long col_index(dfl_table *t, const char *col, int create)
{
    for (size_t j = 0; j < t->ncols; j++)
        if (strcmp(t->cols[j], col) == 0) return (long)j;
    if (!create) return -1;
    if (t->ncols == t->capcols) {
        size_t cap = t->capcols ? 2 * t->capcols : 16;
        char **c = realloc(t->cols, cap * sizeof *c);
        if (!c) return -1;
        t->cols = c;
        t->capcols = cap;
    }
    t->cols[t->ncols] = strdup(col);
    if (!t->cols[t->ncols]) return -1;
    return (long)t->ncols++;
}

static dfl_status set_text(dfl_table *t, const char *col, const char *text, dfl_err *err)
{
    if (t->nrows == 0)
        return dfl_err_set(err, DFL_E_INTERNAL, "table: column %s set before the first row", col);
    long j = col_index(t, col, 1);
    if (j < 0) return no_memory(err, col);
    size_t i = t->nrows - 1;
    if ((size_t)j >= t->rowcap[i]) {
        size_t cap = (size_t)j + 8;
        char **r = realloc(t->rows[i], cap * sizeof *r);
        if (!r) return no_memory(err, col);
        for (size_t k = t->rowcap[i]; k < cap; k++) r[k] = NULL;
        t->rows[i] = r;
        t->rowcap[i] = cap;
    }
    char *d = strdup(text);
    if (!d) return no_memory(err, col);
    free(t->rows[i][j]);
    t->rows[i][j] = d;
    return DFL_OK;
}

dfl_status dfl_table_row(dfl_table *t, dfl_err *err)
{
    if (t->nrows == t->caprows) {
        size_t cap = t->caprows ? 2 * t->caprows : 16;
        char ***r = realloc(t->rows, cap * sizeof *r);
        if (!r) return dfl_err_set(err, DFL_E_NOMEM, "table: out of memory for row %zu", t->nrows);
        t->rows = r;
        size_t *rc = realloc(t->rowcap, cap * sizeof *rc);
        if (!rc) return dfl_err_set(err, DFL_E_NOMEM, "table: out of memory for row %zu", t->nrows);
        t->rowcap = rc;
        t->caprows = cap;
    }
    t->rows[t->nrows] = NULL;
    t->rowcap[t->nrows] = 0;
    t->nrows++;
    for (size_t k = 0; k < t->npre; k++) {
        dfl_status st = set_text(t, t->pcol[k], t->pval[k], err);
        if (st != DFL_OK) return st;
    }
    return DFL_OK;
}

static int round_trips(double v, int prec, char *buf, size_t size)
{
    snprintf(buf, size, "%.*g", prec, v);
    return strtod(buf, NULL) == v;
}

/* %.17g always reads back; fewer digits usually do.  Reading back is
 * monotone in the precision (a correctly rounded longer decimal is never
 * farther from v), so a bisection over 1..17 finds the fewest digits. */
const char *dfl_table_format_double(double v, char *buf, size_t size)
{
    if (!isfinite(v) || v == 0.0) {
        snprintf(buf, size, "%.17g", v); /* nan, inf, 0, -0 as before */
        return buf;
    }
    int lo = 1, hi = 17;
    while (lo < hi) {
        const int mid = (lo + hi) / 2;
        if (round_trips(v, mid, buf, size)) hi = mid;
        else lo = mid + 1;
    }
    snprintf(buf, size, "%.*g", lo, v);
    /* %g writes 10 as 1e+01 at one digit; with exponent X below 17 the plain
     * form needs X + 1 digits, and the shorter text wins (10, not 1e+01). */
    const char *e = strchr(buf, 'e');
    const int x = e ? atoi(e + 1) : -1;
    if (x >= lo && x < 17) {
        char plain[64];
        snprintf(plain, sizeof plain, "%.*g", x + 1, v);
        if (strlen(plain) < strlen(buf) && strlen(plain) < size) strcpy(buf, plain);
    }
    return buf;
}

dfl_status dfl_table_set_double(dfl_table *t, const char *col, double v, dfl_err *err)
{
    char buf[64];
    return set_text(t, col, dfl_table_format_double(v, buf, sizeof buf), err);
}

dfl_status dfl_table_set_int(dfl_table *t, const char *col, long v, dfl_err *err)
{
    char buf[32];
    snprintf(buf, sizeof buf, "%ld", v);
    return set_text(t, col, buf, err);
}

dfl_status dfl_table_set_string(dfl_table *t, const char *col, const char *v, dfl_err *err)
{
    return set_text(t, col, v, err);
}

dfl_status dfl_table_add_col(dfl_table *t, const char *col, dfl_err *err)
{
    return col_index(t, col, 1) < 0 ? no_memory(err, col) : DFL_OK;
}

size_t dfl_table_rows(const dfl_table *t) { return t->nrows; }
size_t dfl_table_cols(const dfl_table *t) { return t->ncols; }
const char *dfl_table_col_name(const dfl_table *t, size_t j)
{
    return j < t->ncols ? t->cols[j] : NULL;
}

const char *dfl_table_get(const dfl_table *t, size_t i, const char *col)
{
    long j = col_index((dfl_table *)t, col, 0);
    if (j < 0 || i >= t->nrows) return NULL;
    if ((size_t)j >= t->rowcap[i] || !t->rows[i][j]) return "";
    return t->rows[i][j];
}

/* RFC 4180 quoting for text cells that need it. */
static void put_cell(FILE *fp, const char *s)
{
    if (!strpbrk(s, ",\"\n\r")) {
        fputs(s, fp);
        return;
    }
    fputc('"', fp);
    for (; *s; s++) {
        if (*s == '"') fputc('"', fp);
        fputc(*s, fp);
    }
    fputc('"', fp);
}

dfl_status dfl_table_write_csv(const dfl_table *t, const char *path, dfl_err *err)
{
    dfl_atomic_file af;
    dfl_status st = dfl_atomic_open(path, &af, err);
    if (st != DFL_OK) return st;
    for (size_t j = 0; j < t->ncols; j++) {
        if (j) fputc(',', af.fp);
        put_cell(af.fp, t->cols[j]);
    }
    fputc('\n', af.fp);
    for (size_t i = 0; i < t->nrows; i++) {
        for (size_t j = 0; j < t->ncols; j++) {
            if (j) fputc(',', af.fp);
            if (j < t->rowcap[i] && t->rows[i][j]) put_cell(af.fp, t->rows[i][j]);
        }
        fputc('\n', af.fp);
    }
    return dfl_atomic_commit(&af, err);
}

/* Leading columns for a CSV file someone else wrote (a study's profile
 * table): the runner gives every CSV of a sweep point its `point` and
 * swept-key columns without the study doing anything.  Records are split
 * at newlines outside quotes (RFC 4180), so quoted cells may hold any
 * text. */
/* Length of the record starting at s (up to, not including, its '\n'). */
static size_t record_len(const char *s, const char *end)
{
    int q = 0;
    const char *p = s;
    for (; p < end; p++) {
        if (*p == '"') q = !q;
        else if (*p == '\n' && !q) break;
    }
    return (size_t)(p - s);
}

/* Whether the header record h (length n) has a cell exactly equal to col
 * (header cells dflab writes are plain names). */
static int has_col(const char *h, size_t n, const char *col)
{
    size_t cl = strlen(col);
    for (size_t i = 0; i <= n;) {
        size_t j = i;
        while (j < n && h[j] != ',') j++;
        size_t e = j;
        if (e > i && h[e - 1] == '\r') e--;
        if (e - i == cl && strncmp(h + i, col, cl) == 0) return 1;
        i = j + 1;
    }
    return 0;
}

dfl_status dfl_table_csv_prepend(const char *path, size_t n, const char *const *cols,
                                 const char *const *values, dfl_err *err)
{
    size_t len;
    char *text = dfl_file_read_all(path, &len);
    if (!text) return dfl_err_set(err, DFL_E_IO, "%s: cannot read", path);
    const char *end = text + len;
    if (len == 0) {
        free(text);
        return DFL_OK;
    }
    const size_t hl = record_len(text, end);
    int *keep = calloc(n ? n : 1, sizeof *keep);
    if (!keep) {
        free(text);
        return dfl_err_set(err, DFL_E_NOMEM, "%s: out of memory", path);
    }
    size_t nkeep = 0;
    for (size_t k = 0; k < n; k++) nkeep += keep[k] = !has_col(text, hl, cols[k]);
    dfl_status st = DFL_OK;
    if (nkeep > 0) {
        dfl_atomic_file af;
        st = dfl_atomic_open(path, &af, err);
        for (const char *s = text; st == DFL_OK && s < end;) {
            const size_t rl = record_len(s, end);
            for (size_t k = 0; k < n; k++)
                if (keep[k]) {
                    put_cell(af.fp, s == text ? cols[k] : values[k]);
                    fputc(',', af.fp);
                }
            fwrite(s, 1, rl, af.fp);
            s += rl;
            if (s < end) fputc(*s++, af.fp); /* the newline */
        }
        if (st == DFL_OK) st = dfl_atomic_commit(&af, err);
    }
    free(keep);
    free(text);
    return st;
}

/* ---- reading back (the writer's own format, RFC 4180) ---------------- */

/* Next cell of the record at *p into a malloc'ed string; *eol set when the
 * record ends after it. */
static char *next_cell(const char **p, int *eol)
{
    const char *s = *p;
    size_t cap = 64, n = 0;
    char *c = malloc(cap);
    if (!c) return NULL;
    int q = 0;
    if (*s == '"') q = 1, s++;
    for (;; s++) {
        if (n + 2 > cap) {
            char *b = realloc(c, cap *= 2);
            if (!b) return free(c), NULL;
            c = b;
        }
        if (q) {
            if (*s == '\0') break;
            if (*s == '"' && s[1] == '"') c[n++] = '"', s++;
            else if (*s == '"') q = 0;
            else c[n++] = *s;
            continue;
        }
        if (*s == ',' || *s == '\n' || *s == '\0') break;
        c[n++] = *s;
    }
    c[n] = '\0';
    *eol = *s != ',';
    *p = *s ? s + 1 : s;
    return c;
}

dfl_status dfl_table_append_csv(dfl_table *t, const char *path, dfl_err *err)
{
    char *text = dfl_file_read_all(path, NULL);
    if (!text) return dfl_err_set(err, DFL_E_IO, "%s: cannot read", path);
    const char *p = text;
    char **cols = NULL;
    size_t nc = 0;
    dfl_status st = DFL_OK;
    int eol = 0;
    while (*p && *p != '\n' && !eol && st == DFL_OK) {
        char *c = next_cell(&p, &eol);
        char **nw = c ? realloc(cols, (nc + 1) * sizeof *nw) : NULL;
        if (!nw) {
            free(c);
            st = dfl_err_set(err, DFL_E_NOMEM, "out of memory");
            break;
        }
        cols = nw;
        cols[nc++] = c;
        st = dfl_table_add_col(t, c, err);
    }
    if (*p == '\n') p++;
    while (*p && st == DFL_OK) {
        st = dfl_table_row(t, err);
        for (size_t j = 0; st == DFL_OK; j++) {
            char *c = next_cell(&p, &eol);
            if (!c) {
                st = dfl_err_set(err, DFL_E_NOMEM, "out of memory");
                break;
            }
            if (c[0] && j < nc) st = dfl_table_set_string(t, cols[j], c, err);
            free(c);
            if (eol) break;
        }
    }
    for (size_t j = 0; j < nc; j++) free(cols[j]);
    free(cols);
    free(text);
    return st;
}
