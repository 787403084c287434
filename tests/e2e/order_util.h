/* Helpers of the bs04 fields / normalization / recursive end-to-end tests
 * (header-only, static). */
#ifndef DFL_TESTS_E2E_ORDER_UTIL_H
#define DFL_TESTS_E2E_ORDER_UTIL_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "e2e_util.h"

/* Text of column col in data row `row` of a CSV without quoted commas
 * (malloc'ed; NULL when absent). */
static inline char *ou_cell(const char *path, long row, const char *col)
{
    char *all = e2e_slurp(path);
    if (!all) return NULL;
    char *save = NULL, *line = strtok_r(all, "\n", &save);
    int ci = -1, k = 0;
    for (char *p = line, *q; p; p = q ? q + 1 : NULL, k++) {
        q = strchr(p, ',');
        size_t len = q ? (size_t)(q - p) : strlen(p);
        if (strlen(col) == len && strncmp(p, col, len) == 0) ci = k;
    }
    char *out = NULL;
    for (long r = 0; ci >= 0 && (line = strtok_r(NULL, "\n", &save)); r++) {
        if (r != row) continue;
        char *p = line;
        for (int j = 0; j < ci && p; j++) {
            p = strchr(p, ',');
            if (p) p++;
        }
        if (p) {
            size_t len = strcspn(p, ",");
            out = malloc(len + 1);
            memcpy(out, p, len);
            out[len] = '\0';
        }
        break;
    }
    free(all);
    return out;
}

/* Runs `dflab run <cfg> --out <dir>/res --quiet <extra>`; returns the
 * exit status and leaves stderr in <dir>/err.txt; out receives <dir>/res. */
static inline int ou_run(const char *dir, const char *cfg, const char *extra, char *out,
                         size_t size)
{
    char args[4096];
    snprintf(out, size, "%s/res", dir);
    snprintf(args, sizeof args, "run %s --out %s --quiet %s", cfg, out, extra ? extra : "");
    return e2e_dflab(dir, args);
}

#endif
