/* `dflab help STUDY`: the keys a study reads, from its own getters.  A
 * validation pass over a config of the study records every getter call
 * (io/config.h, read record) with the type and range the getter checks
 * and the default it takes, so the list cannot drift from the code. */
#include <stdio.h>
#include <string.h>

#include "harness/experiment.h"
#include "harness/help.h"
#include "harness/nonfinite.h"
#include "harness/probe.h"
#include "io/config.h"
#include "io/table.h"

dfl_status dfl_study_help(const dfl_study *study, const char *config, FILE *out, dfl_err *err)
{
    dfl_cfg *cfg = NULL, *pt = NULL;
    dfl_status st = dfl_cfg_load(config, &cfg, err);
    if (st == DFL_OK) st = dfl_cfg_sweep_point(cfg, 0, &pt, err);
    dfl_table *t = dfl_table_new();
    if (st == DFL_OK && !t) st = dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    if (st == DFL_OK) {
        dfl_cfg_validate_only(pt);
        dfl_probe_sections_defer(pt); /* the probe's, not the study's keys */
        const char *dummy;
        dfl_cfg_string(pt, "study", "name", &dummy, NULL);
        bool allow; /* every study: the runner's non-finite rule */
        dfl_study_allow_nonfinite(pt, &allow, NULL);
        dfl_study_ctx ctx = {.stage_dir = "/nonexistent/dflab-help", .tag = "", .point = 0,
                             .npoints = 1, .threads = 1};
        dfl_err e2;
        st = study->run(pt, &ctx, t, &e2);
        if (dfl_cfg_validated(pt)) st = DFL_OK;
        else if (st != DFL_OK) *err = e2;
    }
    if (st == DFL_OK) {
        fprintf(out, "%s: %s\n\nKeys it reads (as read from %s; a key written there shows its\n"
                     "value, an absent one the default the study takes):\n\n",
                study->name, study->summary, config);
        fprintf(out, "  %-28s %-10s %s\n", "key", "value", "expects");
        const size_t n = dfl_cfg_reads(pt);
        for (size_t i = 0; i < n; i++) {
            dfl_cfg_read r;
            dfl_cfg_read_at(pt, i, &r);
            char k[256];
            snprintf(k, sizeof k, "%s.%s", r.sec, r.key);
            fprintf(out, "  %-28s %-10s %s%s\n", k, r.value, r.expect,
                    r.is_default ? " (default)" : "");
        }
        fprintf(out, "\nA comma list in any value makes it a sweep axis (`dflab plan`).\n");
    }
    dfl_table_free(t);
    dfl_cfg_free(pt);
    dfl_cfg_free(cfg);
    return st;
}
