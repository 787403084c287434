/* `dflab help STUDY` lists what the study's getters read, with the ranges
 * they check; `dflab list` works from any folder. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "util/e2e_util.h"

static char *run_in(const char *dir, const char *args, int *rc)
{
    const char *bin = getenv("DFL_DFLAB");
    char abs[4096], cwd[2048], cmd[8192], path[512];
    if (!bin || !*bin) bin = "build/dflab";
    if (bin[0] == '/' || !getcwd(cwd, sizeof cwd)) snprintf(abs, sizeof abs, "%s", bin);
    else snprintf(abs, sizeof abs, "%s/%s", cwd, bin);
    snprintf(cmd, sizeof cmd, "cd '%s' && '%s' %s > out.txt 2> err.txt", dir, abs, args);
    *rc = system(cmd);
    snprintf(path, sizeof path, "%s/out.txt", dir);
    return e2e_slurp(path);
}

Test(help_list, help_study_lists_keys_ranges_and_defaults)
{
    char dir[256];
    e2e_tmpdir(dir, sizeof dir);
    int rc;
    char *out = run_in(dir, "help bs04_gradbounds", &rc);
    cr_assert_eq(rc, 0, "%s", out ? out : "");
    /* the getters' own expectations (experiments/bs04/bs04_gradbounds.c) */
    cr_expect(strstr(out, "study.p ") && strstr(out, "an integer in [1, 64]"), "%s", out);
    cr_expect(strstr(out, "study.samples") && strstr(out, "an integer in [8, 10000000]"), "%s", out);
    cr_expect(strstr(out, "one of requiv|rconj") != NULL, "%s", out);
    free(out);
    out = run_in(dir, "help smoke", &rc);
    cr_assert_eq(rc, 0, "%s", out ? out : "");
    /* [output] keys are absent from the smoke config: defaults */
    cr_expect(strstr(out, "output.half") && strstr(out, "false") && strstr(out, "(default)"), "%s",
              out);
    free(out);
    cr_expect_eq(e2e_rmtree(dir), 0);
}

Test(help_list, list_from_another_folder)
{
    char dir[256];
    e2e_tmpdir(dir, sizeof dir);
    int rc;
    char *out = run_in(dir, "list", &rc);
    cr_assert_eq(rc, 0);
    cr_expect(strstr(out, "bs04_gradbounds ") != NULL, "%s", out);
    cr_expect(strstr(out, "configs/paper/bs04/bs04_gradbounds.ini\n") != NULL,
              "no configs listed from %s: %s", dir, out);
    free(out);
    cr_expect_eq(e2e_rmtree(dir), 0);
}
