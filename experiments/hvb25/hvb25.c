#include "hvb25/hvb25.h"

const dfl_study *const dfl_hvb25_studies[] = {
    NULL,
};
