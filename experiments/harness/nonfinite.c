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

#include "io/table.h"

dfl_status dfl_study_allow_nonfinite(const dfl_cfg *pt, bool *out, dfl_err *err)
{
    return dfl_cfg_bool_opt(pt, "study", "allow_nonfinite", false, out, err);
}

/* The table read back with io/table.h's reader (the one the merge uses),
 * so quoting and empty cells are read as they are written. */
static dfl_status check_file(const char *path, const char *name, const bool *allow, size_t np,
                             dfl_err *err)
{
    dfl_table *t = dfl_table_new();
    if (!t) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    dfl_status st = dfl_table_append_csv(t, path, err);
    const size_t nc = dfl_table_cols(t), nr = dfl_table_rows(t);
    for (size_t i = 0; i < nr && st == DFL_OK; i++) {
        size_t point = 0;
        const char *pc = dfl_table_get(t, i, "point");
        if (pc && *pc) {
            char *end;
            const unsigned long k = strtoul(pc, &end, 10);
            if (end != pc && k < np) point = (size_t)k;
        }
        if (point < np && allow[point]) continue;
        for (size_t j = 0; j < nc; j++) {
            const char *col = dfl_table_col_name(t, j);
            if (!strstr(col, "nonfinite")) continue;
            const char *cell = dfl_table_get(t, i, col);
            char *end;
            const double v = strtod(cell, &end);
            if (end == cell || !(v > 0)) continue;
            st = dfl_err_set(err, DFL_E_NUMERIC,
                             "%s: row %zu (point %zu): %s: %.0f non-finite point%s (error +inf "
                             "in its metrics); the outputs are written; [study] allow_nonfinite "
                             "= true accepts them",
                             name, i + 1, point, col, v, v == 1 ? "" : "s");
            break;
        }
    }
    dfl_table_free(t);
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
