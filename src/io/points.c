/* The points reader: one pass over io/lines.h's lines; the header fixes
 * which column goes where, every later row must have as many cells. */
#include "io/points.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "io/lines.h"

enum { C_X, C_Y, C_Z, C_DX, C_DY, C_DZ, C_N, MAXF = 16 };
static const char *const colnames[C_N] = {"x", "y", "z", "dx", "dy", "dz"};

static char *trim(char *s)
{
    while (isspace((unsigned char)*s)) s++;
    size_t n = strlen(s);
    while (n && isspace((unsigned char)s[n - 1])) s[--n] = '\0';
    return s;
}

/* Splits line at commas in place; returns the field count (f gets the
 * first maxf). */
static int split(char *line, char **f, int maxf)
{
    int n = 0;
    char *s = line;
    for (;;) {
        char *c = strchr(s, ',');
        if (c) *c = '\0';
        if (n < maxf) f[n] = trim(s);
        n++;
        if (!c) break;
        s = c + 1;
    }
    return n;
}

typedef struct header {
    int ncols, map[MAXF];
} header;

static dfl_status read_header(const dfl_lines *r, char **f, int nf, int dim, bool want_dir,
                              header *h, dfl_err *err)
{
    const char *nm = r->name;
    const long ln = r->line;
    if (nf > MAXF)
        return dfl_err_set(err, DFL_E_INPUT, "%s:%ld: too many columns (expected x,y[,z][,dx,dy[,dz]])", nm, ln);
    int have[C_N] = {0};
    for (int i = 0; i < nf; i++) {
        int k = -1;
        for (int c = 0; c < C_N; c++)
            if (strcmp(f[i], colnames[c]) == 0) k = c;
        if (k < 0)
            return dfl_err_set(err, DFL_E_INPUT,
                               "%s:%ld: unknown column '%.60s' (expected header x,y[,z][,dx,dy[,dz]])",
                               nm, ln, f[i]);
        if (have[k])
            return dfl_err_set(err, DFL_E_INPUT, "%s:%ld: duplicate column '%s'", nm, ln, f[i]);
        have[k] = 1, h->map[i] = k;
    }
    const int need[C_N] = {1, 1, dim == 3, want_dir, want_dir, want_dir && dim == 3};
    for (int c = 0; c < C_N; c++) {
        if (need[c] && !have[c])
            return dfl_err_set(err, DFL_E_INPUT, "%s:%ld: missing column '%s'%s", nm, ln,
                               colnames[c], c >= C_DX ? " (the --jet direction)" : "");
        if (!need[c] && have[c])
            return dfl_err_set(err, DFL_E_INPUT, "%s:%ld: column '%s' not expected for a %dD field%s",
                               nm, ln, colnames[c], dim, want_dir ? "" : " without --jet");
    }
    h->ncols = nf;
    return DFL_OK;
}

static dfl_status read_row(const dfl_lines *r, char **f, int nf, const header *h, dfl_points *p,
                           dfl_err *err)
{
    if (nf != h->ncols)
        return dfl_err_set(err, DFL_E_INPUT, "%s:%ld: expected %d fields, got %d", r->name,
                           r->line, h->ncols, nf);
    if ((long)p->n >= DFL_POINTS_MAX)
        return dfl_err_set(err, DFL_E_INPUT, "%s:%ld: more than %ld points", r->name, r->line,
                           DFL_POINTS_MAX);
    if (p->n == p->cap) {
        size_t cap = p->cap ? 2 * p->cap : 256; /* <= 2^23 rows of 48 bytes: no overflow */
        double *v = realloc(p->v, cap * 6 * sizeof *v);
        if (!v) return dfl_err_set(err, DFL_E_NOMEM, "%s: out of memory", r->name);
        p->v = v;
        p->cap = cap;
    }
    double *row = p->v + 6 * p->n;
    for (int c = 0; c < 6; c++) row[c] = 0.0;
    for (int i = 0; i < nf; i++) {
        char *end;
        errno = 0;
        double x = strtod(f[i], &end);
        if (end == f[i] || *end != '\0' || errno == ERANGE || !isfinite(x))
            return dfl_err_set(err, DFL_E_INPUT,
                               "%s:%ld: column '%s': expected a finite number, got '%.60s'",
                               r->name, r->line, colnames[h->map[i]], f[i]);
        row[h->map[i]] = x;
    }
    p->n++;
    return DFL_OK;
}

dfl_status dfl_points_read(FILE *fp, const char *name, int dim, bool want_dir, dfl_points *p,
                           dfl_err *err)
{
    *p = (dfl_points){0};
    dfl_lines r;
    dfl_lines_open_file(&r, fp, name, DFL_POINTS_LINE_MAX, DFL_POINTS_MAX + 1000000L);
    char line[DFL_POINTS_LINE_MAX + 4];
    char *f[MAXF];
    header h = {0};
    dfl_status st = DFL_OK;
    for (;;) {
        size_t len;
        st = dfl_lines_next(&r, line, sizeof line, &len, err);
        if (st != DFL_OK || len == (size_t)-1) break;
        char *t = trim(line);
        if (*t == '\0') continue;
        int nf = split(t, f, MAXF);
        st = h.ncols == 0 ? read_header(&r, f, nf, dim, want_dir, &h, err)
                          : read_row(&r, f, nf, &h, p, err);
        if (st != DFL_OK) break;
    }
    if (st == DFL_OK && h.ncols == 0)
        st = dfl_err_set(err, DFL_E_INPUT, "%s: empty file (expected a header x,y[,z])", name);
    if (st == DFL_OK && p->n == 0)
        st = dfl_err_set(err, DFL_E_INPUT, "%s: no points after the header", name);
    if (st != DFL_OK) dfl_points_free(p);
    return st;
}

void dfl_points_free(dfl_points *p)
{
    free(p->v);
    *p = (dfl_points){0};
}
