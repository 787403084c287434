/* sjp10 (Song, Juettler & Poteaux 2010): PHT-spline fits of the signed distance: the paper's studies.
 *
 * Each study lives in its own file here and defines one `dfl_study`;
 * dfl_sjp10_studies lists them in `dflab list` order.  Add a sjp10 study:
 * write sjp10/sjp10_X.c, declare it below and add one row to the list in
 * sjp10/sjp10.c. */
#ifndef DFL_EXPERIMENTS_SJP10_H
#define DFL_EXPERIMENTS_SJP10_H

#include "harness/experiment.h"

extern const dfl_study dfl_study_sjp10_fig1;
extern const dfl_study dfl_study_sjp10_cells;
extern const dfl_study dfl_study_sjp10_3d;
extern const dfl_study dfl_study_sjp10_offsets;

/* NULL-terminated. */
extern const dfl_study *const dfl_sjp10_studies[];

#endif
