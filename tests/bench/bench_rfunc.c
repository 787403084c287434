/* placeholder until the rfunc benchmark lands */
#include "bench.h"

void bench_rfunc(void) {}
