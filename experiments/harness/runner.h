/* `dflab run`: one study config, its sweep, its results directory.
 *
 * Outputs are written into a staging directory beside the results
 * directory and moved into place (file by file, by rename) only after every
 * sweep point succeeded; on failure the staging directory is removed, so a
 * bad config never leaves files behind.
 */
#ifndef DFL_EXPERIMENTS_RUNNER_H
#define DFL_EXPERIMENTS_RUNNER_H

#include "core/status.h"

typedef struct dfl_run_opts {
    const char *config;        /* path of the .ini */
    const char *const *sets;   /* "section.key=value" overrides */
    int nsets;
    const char *outdir;        /* NULL: results/<config stem>/ */
    int threads;               /* <= 0: OpenMP default */
    int quiet;                 /* no progress lines on stderr */
} dfl_run_opts;

dfl_status dfl_run(const dfl_run_opts *opts, dfl_err *err);

#endif
