/* compare: every dflab method side by side on the same shapes, measured by
 * one protocol (issue 18's "one protocol, one bench").  Not a paper: the
 * fourth study folder beside bs04, sjp10 and hvb25.
 *
 * Each study lives in its own file here and defines one `dfl_study`;
 * dfl_compare_studies lists them in `dflab list` order.  Add a study:
 * write compare/compare_X.c, declare it below and add one row to the list
 * in compare/compare.c. */
#ifndef DFL_EXPERIMENTS_COMPARE_H
#define DFL_EXPERIMENTS_COMPARE_H

#include "harness/experiment.h"

extern const dfl_study dfl_study_compare_methods;

/* NULL-terminated. */
extern const dfl_study *const dfl_compare_studies[];

#endif
