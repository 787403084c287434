#include "bench.h"

#include <stdio.h>
#include <stdlib.h>

#include "io/manifest.h"

double bench_best(int reps, void (*fn)(void *arg), void *arg)
{
    double best = 1e300;
    for (int r = 0; r < reps; r++) {
        double t0 = dfl_wall_seconds();
        fn(arg);
        double t = dfl_wall_seconds() - t0;
        if (t < best) best = t;
    }
    return best;
}

void bench_report(const char *name, double value, const char *unit)
{
    printf("%s: %.4g %s\n", name, value, unit);
    fflush(stdout);
}

void bench_pair(const char *name, double rate, double naive_rate, const char *unit)
{
    char buf[256];
    bench_report(name, rate, unit);
    snprintf(buf, sizeof buf, "%s.naive", name);
    bench_report(buf, naive_rate, unit);
    snprintf(buf, sizeof buf, "%s.ratio", name);
    bench_report(buf, rate / naive_rate, "x");
}

int main(void)
{
    bench_field();
    bench_footpoint();
    bench_rfunc();
    bench_proxy();
    bench_trace();
    bench_proxy_input();
    bench_pht();
    return 0;
}
