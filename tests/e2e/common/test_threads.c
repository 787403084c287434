/* Thread-count determinism, fast subset: scripts/check_threads.py --quick
 * runs the small paper configs and the smoke configs at --threads 1,
 * --threads 2 and OMP_NUM_THREADS=1 and compares every output byte for
 * byte (manifest wall times aside).  `make check-threads` runs all
 * configs. */
#include <criterion/criterion.h>
#include <stdlib.h>

#include "util/e2e_util.h"

Test(e2e_threads, quick_configs_same_bytes_at_1_and_2_threads, .timeout = 600)
{
    const char *bin = getenv("DFL_DFLAB");
    if (!bin || !*bin) bin = "build/dflab";
    char dir[256];
    e2e_tmpdir(dir, sizeof dir);
    char *out = NULL;
    int rc = e2e_python_run(dir, &out, "scripts/check_threads.py %s --quick", bin);
    cr_expect_eq(rc, 0, "thread-count determinism:\n%s", out ? out : "");
    free(out);
    e2e_rmtree(dir);
}
