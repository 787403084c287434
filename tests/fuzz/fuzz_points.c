/* libFuzzer harness: the points CSV reader (io/points.h) on bytes read
 * through a FILE in memory; the first byte picks dim and --jet. */
#include <stdint.h>
#include <stdio.h>
#include <math.h>

#include "io/points.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1) return 0;
    const int dim = (data[0] & 1) ? 3 : 2, want_dir = (data[0] & 2) != 0;
    FILE *fp = size > 1 ? fmemopen((void *)(data + 1), size - 1, "rb") : fopen("/dev/null", "rb");
    if (!fp) return 0;
    dfl_points p;
    dfl_err err;
    if (dfl_points_read(fp, "fuzz.csv", dim, want_dir, &p, &err) == DFL_OK) {
        if (p.n == 0) __builtin_trap();
        for (size_t i = 0; i < 6 * p.n; i++)
            if (!isfinite(p.v[i])) __builtin_trap(); /* only finite numbers get through */
        dfl_points_free(&p);
    }
    fclose(fp);
    return 0;
}
