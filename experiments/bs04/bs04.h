/* bs04 (Biswas & Shapiro 2004): the paper's studies.
 *
 * Each study lives in its own file here and defines one `dfl_study`;
 * dfl_bs04_studies lists them in `dflab list` order.  Add a bs04 study:
 * write bs04/bs04_X.c, declare it below and add one row to the list in
 * bs04/bs04.c. */
#ifndef DFL_EXPERIMENTS_BS04_H
#define DFL_EXPERIMENTS_BS04_H

#include "harness/experiment.h"

extern const dfl_study dfl_study_bs04_gradbounds;
extern const dfl_study dfl_study_bs04_corrected;
extern const dfl_study dfl_study_bs04_normalization;
extern const dfl_study dfl_study_bs04_fields;
extern const dfl_study dfl_study_bs04_recursive;
extern const dfl_study dfl_study_bs04_polygonization;
extern const dfl_study dfl_study_bs04_bulging;
extern const dfl_study dfl_study_bs04_scurve;
extern const dfl_study dfl_study_bs04_spacecurves;
extern const dfl_study dfl_study_bs04_triangle;
extern const dfl_study dfl_study_bs04_triedge;
extern const dfl_study dfl_study_bs04_surface;
extern const dfl_study dfl_study_bs04_hetero;

/* NULL-terminated. */
extern const dfl_study *const dfl_bs04_studies[];

#endif
