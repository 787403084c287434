/* `dflab help STUDY`: the keys a study reads, from its own getters.  A
 * validation pass over a config of the study records every getter call
 * (io/config.h, read record) with the type and range the getter checks
 * and the default it takes, so the list cannot drift from the code. */
#include <stdio.h>
#include <string.h>

#include "harness/experiment.h"
#include "harness/help.h"
#include "harness/meaning.h"
#include "harness/nonfinite.h"
#include "harness/probe.h"
#include "harness/sweep.h"
#include "io/config.h"
#include "io/table.h"

/* The values of the sweep axis "sec.key" of cfg, in first-seen order,
 * comma-separated into buf ("..." past the buffer): what a swept key
 * takes, not its point-0 value.  False when the key is not swept. */
static bool swept_list(const dfl_cfg *cfg, const char *name, char *buf, size_t size)
{
    size_t a = 0, na = dfl_cfg_sweep_axes(cfg);
    while (a < na && strcmp(dfl_cfg_sweep_axis_name(cfg, a), name) != 0) a++;
    if (a == na) return false;
    size_t len = 0;
    buf[0] = '\0';
    const size_t np = dfl_cfg_sweep_points(cfg);
    for (size_t i = 0; i < np && i < 100000; i++) {
        dfl_cfg *pt;
        if (dfl_cfg_sweep_point(cfg, i, &pt, NULL) != DFL_OK) break;
        const char *v = dfl_cfg_axis_value(pt, a);
        char probe[1100];
        snprintf(probe, sizeof probe, ", %s, ", v);
        char have[1100 + 1024];
        snprintf(have, sizeof have, ", %s, ", buf);
        if (!strstr(have, probe) && len + strlen(v) + 6 < size)
            len += (size_t)snprintf(buf + len, size - len, "%s%s", len ? ", " : "", v);
        else if (!strstr(have, probe) && len + 6 < size)
            len += (size_t)snprintf(buf + len, size - len, ", ...");
        dfl_cfg_free(pt);
    }
    return true;
}

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
        double mem_budget, work_budget; /* every study: the runner's budgets */
        dfl_sweep_budgets(pt, &mem_budget, &work_budget, NULL);
        dfl_study_ctx ctx = {.stage_dir = "/nonexistent/dflab-help", .tag = "", .point = 0,
                             .npoints = 1, .threads = 1};
        dfl_err e2;
        st = study->run(pt, &ctx, t, &e2);
        if (dfl_cfg_validated(pt)) st = DFL_OK;
        else if (st != DFL_OK) *err = e2;
    }
    if (st == DFL_OK) {
        fprintf(out, "%s: %s\n\nKeys it reads (as read from %s; a key written there shows its\n"
                     "value -- a swept key its list --, an absent one the default the study\n"
                     "takes; below each, what it means; `dflab help %s --columns` explains the\n"
                     "table):\n\n",
                study->name, study->summary, config, study->name);
        fprintf(out, "  %-28s %-10s %s\n", "key", "value", "expects");
        const size_t n = dfl_cfg_reads(pt);
        for (size_t i = 0; i < n; i++) {
            dfl_cfg_read r;
            dfl_cfg_read_at(pt, i, &r);
            char k[256], list[1024];
            snprintf(k, sizeof k, "%s.%s", r.sec, r.key);
            const char *m = dfl_key_meaning(study->name, r.sec, r.key);
            const char *v = swept_list(cfg, k, list, sizeof list) ? list : r.value;
            fprintf(out, "  %-28s %-10s %s%s\n", k, v, r.expect, r.is_default ? " (default)" : "");
            fprintf(out, "  %-28s %s\n", "", m[0] ? m : "(no meaning given)");
        }
        fprintf(out, "\nA comma list in any value makes it a sweep axis (`dflab plan`).\n");
    }
    dfl_table_free(t);
    dfl_cfg_free(pt);
    dfl_cfg_free(cfg);
    return st;
}
