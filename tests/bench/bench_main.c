#include "bench.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

/* dflab-bench [GROUP...]: every group, or only those named (field,
 * footpoint, rfunc, proxy, trace, proxy_input, pht, vdb, mesh). */
int main(int argc, char **argv)
{
    static const struct {
        const char *name;
        void (*run)(void);
    } groups[] = {{"field", bench_field}, {"footpoint", bench_footpoint}, {"rfunc", bench_rfunc},
                  {"proxy", bench_proxy}, {"trace", bench_trace},
                  {"proxy_input", bench_proxy_input}, {"pht", bench_pht},
                  {"vdb", bench_vdb}, {"mesh", bench_mesh}};
    const size_t ng = sizeof groups / sizeof groups[0];
    for (int a = 1; a < argc; a++) {
        size_t g = 0;
        while (g < ng && strcmp(argv[a], groups[g].name) != 0) g++;
        if (g == ng) {
            fprintf(stderr, "dflab-bench: no group '%s' (field footpoint rfunc proxy trace "
                            "proxy_input pht vdb mesh)\n", argv[a]);
            return 2;
        }
    }
    for (size_t g = 0; g < ng; g++) {
        int on = argc == 1;
        for (int a = 1; a < argc; a++) on |= strcmp(argv[a], groups[g].name) == 0;
        if (on) groups[g].run();
    }
    return 0;
}
