/* The tables are scanned as written (the merged CSV files), so the rule
 * holds for whatever a study writes: the metric columns of field/metrics
 * and any study's own count, and for rows of points that a rerun did not
 * recompute. */
#include "harness/nonfinite.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "io/dirs.h"

dfl_status dfl_study_allow_nonfinite(const dfl_cfg *pt, bool *out, dfl_err *err)
{
    return dfl_cfg_bool_opt(pt, "study", "allow_nonfinite", false, out, err);
}

/* The next cell of a CSV record at *p (RFC 4180 quotes), copied into buf
 * (truncated to size - 1); *eol is set when the record ends after it. */
static void next_cell(const char **p, char *buf, size_t size, int *eol)
{
    const char *s = *p;
    size_t n = 0;
    int q = 0;
    for (; *s; s++) {
        if (q) {
            if (*s == '"' && s[1] == '"') s++;
            else if (*s == '"') {
                q = 0;
                continue;
            }
        } else if (*s == '"') {
            q = 1;
            continue;
        } else if (*s == ',' || *s == '\n') {
            break;
        }
        if (n + 1 < size && *s != '\r') buf[n++] = *s;
    }
    buf[n] = '\0';
    *eol = *s != ',';
    *p = *s ? s + 1 : s;
}

enum { MAX_COLS = 4096, CELL = 256 };

static dfl_status check_file(const char *path, const char *name, const bool *allow, size_t np,
                             dfl_err *err)
{
    char *text = dfl_file_read_all(path, NULL);
    if (!text) return dfl_err_set(err, DFL_E_IO, "%s: cannot read", path);
    char (*cols)[CELL] = malloc(MAX_COLS * sizeof *cols);
    char *cell = malloc(CELL);
    if (!cols || !cell) {
        free(text), free(cols), free(cell);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    }
    const char *p = text;
    size_t nc = 0;
    int eol = 0;
    long pcol = -1;
    while (*p && !eol && nc < MAX_COLS) {
        next_cell(&p, cols[nc], CELL, &eol);
        if (strcmp(cols[nc], "point") == 0) pcol = (long)nc;
        nc++;
    }
    dfl_status st = DFL_OK;
    char hit_col[CELL] = "";
    double hit = 0;
    for (long row = 1; *p && st == DFL_OK; row++) {
        size_t point = 0;
        hit = 0;
        for (size_t j = 0;; j++) {
            next_cell(&p, cell, CELL, &eol);
            if (j < nc && (long)j == pcol) {
                char *end;
                const unsigned long k = strtoul(cell, &end, 10);
                if (end != cell && k < np) point = (size_t)k;
            }
            if (j < nc && hit == 0 && strstr(cols[j], "nonfinite")) {
                char *end;
                const double v = strtod(cell, &end);
                if (end != cell && v > 0) {
                    hit = v;
                    snprintf(hit_col, sizeof hit_col, "%s", cols[j]);
                }
            }
            if (eol) break;
        }
        if (hit > 0 && !(point < np && allow[point]))
            st = dfl_err_set(err, DFL_E_NUMERIC,
                             "%s: row %ld (point %zu): %s: %.0f non-finite point%s (error +inf "
                             "in its metrics); the outputs are written; [study] allow_nonfinite "
                             "= true accepts them",
                             name, row, point, hit_col, hit, hit == 1 ? "" : "s");
    }
    free(text), free(cols), free(cell);
    return st;
}

static int by_name(const struct dirent **a, const struct dirent **b)
{
    return strcmp((*a)->d_name, (*b)->d_name);
}

static int is_csv(const struct dirent *de)
{
    const size_t n = strlen(de->d_name);
    return n > 4 && strcmp(de->d_name + n - 4, ".csv") == 0 && !strstr(de->d_name, ".tmp.");
}

dfl_status dfl_nonfinite_check(const char *dir, const bool *allow, size_t np, dfl_err *err)
{
    struct dirent **list = NULL;
    const int n = scandir(dir, &list, is_csv, by_name);
    if (n < 0) return dfl_err_set(err, DFL_E_IO, "%s: cannot list", dir);
    dfl_status st = DFL_OK;
    for (int i = 0; i < n; i++) {
        char path[8192];
        struct stat sb;
        snprintf(path, sizeof path, "%s/%s", dir, list[i]->d_name);
        if (st == DFL_OK && stat(path, &sb) == 0 && S_ISREG(sb.st_mode))
            st = check_file(path, list[i]->d_name, allow, np, err);
        free(list[i]);
    }
    free(list);
    return st;
}
