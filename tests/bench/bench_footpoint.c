/* placeholder until the footpoint benchmark lands */
#include "bench.h"

void bench_footpoint(void) {}
