/* Helpers for the end-to-end tests of the bs04 space studies (header-only,
 * static): run a study config with overrides into a fresh directory and
 * name its CSV; run an inline config that must fail. */
#ifndef DFL_TESTS_BS04_SPACE_E2E_H
#define DFL_TESTS_BS04_SPACE_E2E_H

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/e2e_util.h"

/* Runs `dflab run cfg --out <tmp>/res --quiet <sets>`; asserts success and
 * writes the results directory into out and the CSV path into csv. */
static inline void bs_run(const char *cfg, const char *sets, const char *study, char *out,
                          size_t nout, char *csv, size_t ncsv)
{
    e2e_run_ok(cfg, sets, out, nout);
    snprintf(csv, ncsv, "%s/%s.csv", out, study);
}

/* Runs a config given as text that must fail; expects no results directory
 * left behind and returns the exit status and the message. */
static inline int bs_run_fail(const char *ini_text, char *msg, size_t nmsg)
{
    char dir[256], cfg[600], out[600];
    e2e_tmpdir(dir, sizeof dir);
    e2e_write(dir, "bad.ini", ini_text, cfg, sizeof cfg);
    const int rc = e2e_run_cfg(dir, cfg, NULL, out, sizeof out);
    char *m = e2e_err_text(dir);
    snprintf(msg, nmsg, "%s", m ? m : "");
    free(m);
    cr_expect_eq(e2e_count_entries(out), -1, "a failed run left %s behind", out);
    return rc;
}

#endif
