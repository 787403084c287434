#include "cfg/list_cfg.h"

#include <stdlib.h>
#include <string.h>


dfl_status dfl_section_names_from_cfg(const dfl_cfg *cfg, const char *sec, const char *key,
                                      int max, char (*names)[DFL_SECTION_NAME_LEN], int *n,
                                      const char *what, dfl_err *err)
{
    const char *list;
    dfl_status st = dfl_cfg_string(cfg, sec, key, &list, err);
    if (st != DFL_OK) return st;
    *n = 0;
    for (const char *s = list; *s;) {
        while (*s == ' ' || *s == '\t') s++;
        if (!*s) break;
        const size_t len = strcspn(s, " \t");
        if (*n == max || len >= DFL_SECTION_NAME_LEN)
            return dfl_cfg_reject(cfg, sec, key, err,
                                  "expected at most %d section names of < %d characters", max,
                                  DFL_SECTION_NAME_LEN);
        memcpy(names[*n], s, len);
        names[*n][len] = '\0';
        (*n)++;
        s += len;
    }
    if (*n == 0)
        return dfl_cfg_reject(cfg, sec, key, err, "expected at least one %s", what);
    return DFL_OK;
}

dfl_status dfl_points_n_from_cfg(const dfl_cfg *cfg, const char *sec, const char *key, int dim,
                                 size_t n, double *out, const char *what, dfl_err *err)
{
    double *pts = NULL;
    size_t got = 0;
    dfl_status st = dfl_cfg_points(cfg, sec, key, dim, n, &pts, &got, err);
    if (st != DFL_OK) return st;
    if (got != n) {
        free(pts);
        return dfl_cfg_reject(cfg, sec, key, err, "expected %s, got %zu", what, got);
    }
    memcpy(out, pts, n * (size_t)dim * sizeof *out);
    free(pts);
    return DFL_OK;
}
