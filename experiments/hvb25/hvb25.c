#include "hvb25/hvb25.h"

const dfl_study *const dfl_hvb25_studies[] = {
    &dfl_study_hvb25_accuracy,
    &dfl_study_hvb25_render,
    NULL,
};
