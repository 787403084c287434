#include "sjp10/sjp10.h"

const dfl_study *const dfl_sjp10_studies[] = {
    NULL,
};
