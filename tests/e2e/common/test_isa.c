/* ISA determinism, fast subset: scripts/check_isa.py --quick runs the
 * small paper configs, cut-down PHT and proxy paper configs and the smoke
 * configs once per instruction set this CPU runs (DFL_ISA=sse2|avx2|avx512,
 * core/isa.h) and compares every output with the sse2 run byte for byte
 * (wall times aside); it also checks that an unknown DFL_ISA is exit 2 with
 * one line.  `make check-isa` runs all configs. */
#include <criterion/criterion.h>

#include "util/e2e_util.h"

Test(e2e_isa, quick_configs_same_bytes_on_every_isa, .timeout = 900)
{
    e2e_expect_binary_script("scripts/check_isa.py", "--quick", "ISA determinism");
}
