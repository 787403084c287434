#include "sjp10/sjp10.h"

const dfl_study *const dfl_sjp10_studies[] = {
    &dfl_study_sjp10_fig1,
    &dfl_study_sjp10_cells,
    &dfl_study_sjp10_offsets,
    &dfl_study_sjp10_3d,
    NULL,
};
