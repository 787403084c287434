/* The bad-input table (tests/cli/bad_input_table.py): well over a hundred
 * hostile inputs -- bytes that are not text, endless lines, duplicate
 * sections, out-of-domain numbers, unusable --out values, a full stdout,
 * too little memory -- each run through the real binary and checked for
 * its exit status (2 input, 1 machine), one escaped error line naming
 * file, line and key, an empty stdout and no files left behind.  The table
 * lives in Python because many cases are raw bytes and redirections. */
#include <criterion/criterion.h>
#include <stdlib.h>

#include "util/e2e_util.h"

Test(bad_input, table_through_the_binary, .timeout = 600)
{
    const char *bin = getenv("DFL_DFLAB");
    if (!bin || !*bin) bin = "build/dflab";
    char dir[256];
    e2e_tmpdir(dir, sizeof dir);
    char *out = NULL;
    int rc = e2e_python_run(dir, &out, "tests/cli/bad_input_table.py %s", bin);
    cr_expect_eq(rc, 0, "bad-input table failed:\n%s", out ? out : "");
    free(out);
    e2e_rmtree(dir);
}
