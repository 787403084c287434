#include "compare/compare.h"

const dfl_study *const dfl_compare_studies[] = {
    &dfl_study_compare_methods,
    NULL,
};
