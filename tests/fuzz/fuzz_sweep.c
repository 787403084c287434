/* libFuzzer harness: the sweep expander.  The input is INI text, then
 * optionally a line "--" followed by --set assignments, one per line.
 * Every sweep point (up to 64) is made and its axis values read. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_util.h"
#include "io/config.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = fuzz_text(data, size);
    if (!text) return 0;
    char *sets = strstr(text, "\n--\n");
    if (sets) *sets = '\0', sets += 4;
    dfl_cfg *c = NULL;
    dfl_err err;
    if (dfl_cfg_parse_string("/nonexistent-dir/fuzz.ini", text, &c, &err) == DFL_OK) {
        dfl_status st = DFL_OK;
        for (char *s = sets; s && *s && st == DFL_OK;) {
            char *nl = strchr(s, '\n');
            if (nl) *nl = '\0';
            st = dfl_cfg_set(c, s, &err);
            s = nl ? nl + 1 : NULL;
        }
        if (st == DFL_OK) {
            size_t np = dfl_cfg_sweep_points(c), na = dfl_cfg_sweep_axes(c);
            size_t step = np > 64 ? np / 64 : 1;
            for (size_t i = 0; i < np; i += step) {
                dfl_cfg *p = NULL;
                if (dfl_cfg_sweep_point(c, i, &p, &err) != DFL_OK) __builtin_trap();
                for (size_t a = 0; a < na; a++) {
                    const char *v = dfl_cfg_axis_value(p, a);
                    if (strchr(v, ',')) __builtin_trap(); /* one item per point */
                    (void)dfl_cfg_sweep_axis_name(c, a);
                }
                if (dfl_cfg_sweep_points(p) != 1) __builtin_trap();
                dfl_cfg_free(p);
            }
        }
        dfl_cfg_free(c);
    }
    free(text);
    return 0;
}
