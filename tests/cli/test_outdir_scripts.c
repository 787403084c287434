/* Output folders and emitted scripts, end to end through the real binary:
 *   tests/cli/outdir_cases.sh  every output-folder case (foreign folders,
 *       '.'/'..' names, old-format folders, a cut-off replacement, a kill
 *       at the swap) under a watched parent whose listing is diffed;
 *   tests/cli/emit_hostile.sh  the parallel, Slurm and --commands scripts
 *       run with hostile names against stub launchers.
 * Each script prints "ok" when every check held. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/e2e_util.h"

static void run_script(const char *script)
{
    char dir[256], cmd[2048], log[512];
    e2e_tmpdir(dir, sizeof dir);
    const char *dflab = getenv("DFL_DFLAB") ? getenv("DFL_DFLAB") : "build/dflab";
    snprintf(log, sizeof log, "%s/case.log", dir);
    snprintf(cmd, sizeof cmd, "mkdir '%s/w' && DFL_PYTHON=%s bash %s '%s' '%s/w' > '%s' 2>&1", dir,
             e2e_python(), script, dflab, dir, log);
    const int rc = system(cmd);
    char *out = e2e_slurp(log);
    cr_expect_eq(rc, 0, "%s failed:\n%s", script, out ? out : "(no output)");
    cr_expect(out && strstr(out, "ok\n") != NULL, "%s: %s", script, out ? out : "");
    free(out);
    cr_expect_eq(e2e_rmtree(dir), 0);
}

/* ~35 dflab processes: sized for the sanitizer build (~3.7 s each there) */
Test(outdir_cases, nothing_outside_the_output_folder_is_written_or_deleted, .timeout = 300)
{
    run_script("tests/cli/outdir_cases.sh");
}

Test(emit_hostile, emitted_scripts_run_no_command_hidden_in_a_name, .timeout = 200)
{
    run_script("tests/cli/emit_hostile.sh");
}
