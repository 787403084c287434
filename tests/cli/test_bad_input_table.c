/* The bad-input table (tests/cli/bad_input_table.py): well over a hundred
 * hostile inputs -- bytes that are not text, endless lines, duplicate
 * sections, out-of-domain numbers, unusable --out values, a full stdout,
 * too little memory -- each run through the real binary and checked for
 * its exit status (2 input, 1 machine), one escaped error line naming
 * file, line and key, an empty stdout and no files left behind.  The table
 * lives in Python because many cases are raw bytes and redirections. */
#include <criterion/criterion.h>

#include "util/e2e_util.h"

Test(bad_input, table_through_the_binary, .timeout = 1800)
{
    e2e_expect_binary_script("tests/cli/bad_input_table.py", NULL, "bad-input table failed");
}
