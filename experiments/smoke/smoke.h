/* Smoke studies: the harness end to end on an exact field (no paper). */
#ifndef DFL_EXPERIMENTS_SMOKE_H
#define DFL_EXPERIMENTS_SMOKE_H

#include "harness/experiment.h"

extern const dfl_study dfl_study_smoke;

/* NULL-terminated. */
extern const dfl_study *const dfl_smoke_studies[];

#endif
