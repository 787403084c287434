/* Thread-count determinism, fast subset: scripts/check_threads.py --quick
 * runs the small paper configs and the smoke configs at --threads 1,
 * --threads 2 and OMP_NUM_THREADS=1 and compares every output byte for
 * byte (manifest wall times aside).  `make check-threads` runs all
 * configs. */
#include <criterion/criterion.h>

#include "util/e2e_util.h"

Test(e2e_threads, quick_configs_same_bytes_at_1_and_2_threads, .timeout = 600)
{
    e2e_expect_binary_script("scripts/check_threads.py", "--quick", "thread-count determinism");
}
