/* libFuzzer harness: config -> field -> evaluate and jet.  The input is
 * INI text holding [field] (and [shape] or what the field kind reads);
 * the field is built as `dflab probe` builds it and evaluated at a few
 * points inside dflab's domain, with jets along a fixed direction.  A
 * non-finite value at such a point is reported by probe as an error, so
 * here it is only counted, not trapped; crashes, sanitizer reports and
 * hangs (libFuzzer's -timeout) are the findings.  As the runner refuses a
 * point above its budgets, the harness does not build a field whose
 * estimate (cfg/field_cost.h) is above the fuzzer's: 256 MB (-rss_limit_mb
 * is 2048) or 2 s of work (-timeout is 20). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cfg/field_cfg.h"
#include "cfg/field_cost.h"
#include "fuzz_util.h"
#include "io/config.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > 4096) return 0; /* keep constructions small */
    char *text = fuzz_text(data, size);
    if (!text) return 0;
    dfl_cfg *c = NULL;
    dfl_err err;
    if (dfl_cfg_parse_string("/nonexistent-dir/fuzz.ini", text, &c, &err) == DFL_OK &&
        dfl_cfg_sweep_points(c) == 1) {
        dfl_field f = {0};
        dfl_cost cost = {0};
        /* a config the estimate refuses still goes to the factory, whose
         * errors are what is fuzzed; only a valid but large one is skipped */
        const int big = dfl_field_cost_from_cfg(c, "field", &cost, &err) == DFL_OK &&
                        (cost.bytes > 256e6 || dfl_cost_seconds(&cost, 1) > 2);
        if (!big && dfl_field_from_cfg(c, "field", &f, &err) == DFL_OK) {
            static const double pts[][3] = {{0.5, 0.5, 0.5}, {0, 0, 0}, {-3, 7, 1e3},
                                            {1e6, -1e6, 2}, {0.25, 0.75, 0.1}};
            const double dir[3] = {0.6, -0.8, 0.3};
            for (size_t i = 0; i < sizeof pts / sizeof pts[0]; i++) {
                double g[3];
                (void)dfl_field_eval1(&f, pts[i], g);
                if (f.ops->jet) {
                    dfl_jet j;
                    (void)dfl_field_jet(&f, pts[i], dir, 4, &j, &err);
                }
            }
            dfl_field_destroy(&f);
        }
    }
    dfl_cfg_free(c);
    free(text);
    return 0;
}
