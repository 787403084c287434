/* hvb25 (Horvath, Valasek & Ban 2025): distance fields from geometric proxies: the paper's studies.
 *
 * Each study lives in its own file here and defines one `dfl_study`;
 * dfl_hvb25_studies lists them in `dflab list` order.  Add a hvb25 study:
 * write hvb25/hvb25_X.c, declare it below and add one row to the list in
 * hvb25/hvb25.c. */
#ifndef DFL_EXPERIMENTS_HVB25_H
#define DFL_EXPERIMENTS_HVB25_H

#include "harness/experiment.h"

extern const dfl_study dfl_study_hvb25_accuracy;
extern const dfl_study dfl_study_hvb25_render;

/* NULL-terminated. */
extern const dfl_study *const dfl_hvb25_studies[];

#endif
