/* The results directory of `dflab run`, checked before the run starts.
 *
 *   dfl_outdir_check(dir, &g, err)   is dir usable? remembers what exists
 *   dfl_outdir_undo(&g)              after a failed run: removes the (empty)
 *                                    directories the run created above dir
 *
 * dir is usable when it is not empty and not "/", passes
 * dfl_dir_check_name (not "." or ".." at its end, no ".." after a missing
 * folder), is a directory if it exists, and its deepest existing ancestor
 * is a directory in which a file can be made (dfl_dir_probe, which leaves
 * nothing behind: this is what tells /proc/x or a read-only mount from a
 * writable place).
 * Each failure is DFL_E_INPUT "--out DIR: ..." (exit status 2): the user
 * chose the place.  The runner creates the missing parents itself; undo
 * removes those that are empty after a failed run, so a failed run leaves
 * no directory behind.
 */
#ifndef DFL_CLI_OUTDIR_H
#define DFL_CLI_OUTDIR_H

#include <stddef.h>

#include "core/status.h"

typedef struct dfl_outdir_guard {
    char dir[4096];      /* the results directory, trailing '/' dropped */
    size_t exist_len;    /* length of its deepest existing ancestor */
} dfl_outdir_guard;

dfl_status dfl_outdir_check(const char *dir, dfl_outdir_guard *g, dfl_err *err);
void dfl_outdir_undo(const dfl_outdir_guard *g);

#endif
