#include "bs04/bs04.h"

const dfl_study *const dfl_bs04_studies[] = {
    &dfl_study_bs04_gradbounds,   &dfl_study_bs04_corrected,  &dfl_study_bs04_normalization,
    &dfl_study_bs04_fields,       &dfl_study_bs04_recursive,  &dfl_study_bs04_polygonization,
    &dfl_study_bs04_bulging,      &dfl_study_bs04_scurve,     &dfl_study_bs04_spacecurves,
    &dfl_study_bs04_triangle,     &dfl_study_bs04_triedge,    &dfl_study_bs04_surface,
    &dfl_study_bs04_hetero,       NULL,
};
