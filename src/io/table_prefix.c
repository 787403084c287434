/* Leading columns for a CSV file someone else wrote (a study's profile
 * table): the runner gives every CSV of a sweep point its `point` and
 * swept-key columns without the study doing anything.  Records are split
 * at newlines outside quotes (RFC 4180), so quoted cells may hold any
 * text. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/atomic.h"
#include "io/table.h"

static char *slurp(const char *path, size_t *len)
{
    FILE *fp = fopen(path, "rb");
    if (!fp) return NULL;
    char *buf = NULL;
    size_t cap = 0, n = 0, k;
    do {
        if (n + 65536 > cap) {
            char *b = realloc(buf, cap = 2 * cap + 65536);
            if (!b) {
                free(buf), fclose(fp);
                return NULL;
            }
            buf = b;
        }
        k = fread(buf + n, 1, cap - n - 1, fp);
        n += k;
    } while (k > 0);
    fclose(fp);
    buf[n] = '\0';
    *len = n;
    return buf;
}

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

dfl_status dfl_table_csv_prepend(const char *path, size_t n, const char *const *cols,
                                 const char *const *values, dfl_err *err)
{
    size_t len;
    char *text = slurp(path, &len);
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
