/* Helpers for the end-to-end tests of the bs04 space studies (header-only,
 * static): run a study config with overrides into a fresh directory, read
 * string cells, compare config sections with the shipped shape configs. */
#ifndef DFL_TESTS_BS04_SPACE_E2E_H
#define DFL_TESTS_BS04_SPACE_E2E_H

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "e2e_util.h"
#include "io/config.h"

/* Runs `dflab run cfg <sets> --out <tmp>/res --quiet`; asserts success and
 * writes the results directory into out and the CSV path into csv. */
static inline void bs_run(const char *cfg, const char *sets, const char *study, char *out,
                          size_t nout, char *csv, size_t ncsv)
{
    char dir[256], args[2048], path[600];
    e2e_tmpdir(dir, sizeof dir);
    cr_assert(dir[0], "no temporary directory");
    snprintf(out, nout, "%s/res", dir);
    snprintf(args, sizeof args, "run %s %s --out %s --quiet", cfg, sets, out);
    const int rc = e2e_dflab(dir, args);
    snprintf(path, sizeof path, "%s/err.txt", dir);
    char *msg = e2e_slurp(path);
    cr_assert_eq(rc, 0, "dflab %s failed (%d): %s", args, rc, msg ? msg : "");
    free(msg);
    snprintf(csv, ncsv, "%s/%s.csv", out, study);
}

/* Runs a config that must fail; returns the exit status and the message. */
static inline int bs_run_fail(const char *ini_text, char *msg, size_t nmsg)
{
    char dir[256], args[1024], path[600], cfg[600];
    e2e_tmpdir(dir, sizeof dir);
    e2e_write(dir, "bad.ini", ini_text, cfg, sizeof cfg);
    snprintf(args, sizeof args, "run %s --out %s/res --quiet", cfg, dir);
    const int rc = e2e_dflab(dir, args);
    snprintf(path, sizeof path, "%s/err.txt", dir);
    char *m = e2e_slurp(path);
    snprintf(msg, nmsg, "%s", m ? m : "");
    free(m);
    snprintf(path, sizeof path, "%s/res", dir);
    cr_expect_eq(e2e_count_entries(path), -1, "a failed run left %s behind", path);
    return rc;
}

/* String cell (malloc'ed, NULL when absent) of a CSV without quoting. */
static inline char *bs_cell(const char *path, long row, const char *col)
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
    for (long r = 0; (line = strtok_r(NULL, "\n", &save)); r++) {
        if (r != row) continue;
        char *p = line;
        for (int j = 0; j < ci && p; j++) {
            p = strchr(p, ',');
            if (p) p++;
        }
        if (p && ci >= 0) {
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

/* Every key of [shape] in shape_file has the same value in [sec] of cfg. */
static inline void bs_same_section(const char *cfg, const char *sec, const char *shape_file,
                                   const char *const *keys, int nkeys)
{
    dfl_cfg *a, *b;
    dfl_err err;
    cr_assert_eq(dfl_cfg_load(cfg, &a, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_cfg_load(shape_file, &b, &err), DFL_OK, "%s", err.msg);
    for (int k = 0; k < nkeys; k++) {
        const bool ha = dfl_cfg_has(a, sec, keys[k]), hb = dfl_cfg_has(b, "shape", keys[k]);
        cr_expect_eq(ha, hb, "[%s] %s present in one of %s, %s only", sec, keys[k], cfg,
                     shape_file);
        if (!ha || !hb) continue;
        const char *va, *vb;
        cr_assert_eq(dfl_cfg_string(a, sec, keys[k], &va, &err), DFL_OK, "%s", err.msg);
        cr_assert_eq(dfl_cfg_string(b, "shape", keys[k], &vb, &err), DFL_OK, "%s", err.msg);
        cr_expect_str_eq(va, vb, "[%s] %s of %s differs from %s", sec, keys[k], cfg, shape_file);
    }
    dfl_cfg_free(a);
    dfl_cfg_free(b);
}

#endif
