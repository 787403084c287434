/* `dflab help STUDY` (help.c).
 *
 *   dfl_study_help   prints the keys study reads, with the value config
 *                    gives (or the default), type and range
 *
 * The list comes from a validation pass of the study over config's first
 * sweep point (io/config.h, read record): the getters' own checks, no
 * second table.  Keys a study reads only in some branches (e.g. those of
 * another shape kind) appear when config takes that branch.  Fails as
 * loading config or the study's checks fail.
 */
#ifndef DFL_EXPERIMENTS_HELP_H
#define DFL_EXPERIMENTS_HELP_H

#include <stdio.h>

#include "harness/experiment.h"

dfl_status dfl_study_help(const dfl_study *study, const char *config, FILE *out, dfl_err *err);

#endif
