#include "bench.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "core/isa.h"
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

double bench_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
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

const char *bench_cpu_model(char *buf, size_t size)
{
    snprintf(buf, size, "unknown");
    FILE *fp = fopen("/proc/cpuinfo", "r");
    char line[512];
    while (fp && fgets(line, sizeof line, fp)) {
        const char *col = strchr(line, ':');
        if (strncmp(line, "model name", 10) == 0 && col) {
            snprintf(buf, size, "%s", col + 2);
            buf[strcspn(buf, "\n")] = '\0';
            break;
        }
    }
    if (fp) fclose(fp);
    return buf;
}

int bench_active_level(void)
{
    switch (dfl_isa_active()) {
    case DFL_ISA_AVX512: return BENCH_AVX512;
    case DFL_ISA_AVX2: return BENCH_AVX2;
    default: return BENCH_SSE2;
    }
}

double bench_kernel_floor(const bench_ctx *c, const char *name, double rate1, const bench_ops *op)
{
    char buf[192], unit[160];
    const char *bound = "?";
    const int lv = bench_active_level();
    const double ff = bench_floor_fraction(&c->floor, lv, rate1, op, &bound);
    const double fp = bench_fma_fraction(&c->floor, rate1, op);
    snprintf(buf, sizeof buf, "%s.ops", name);
    snprintf(unit, sizeof unit, "ops/eval (%g mul, %g add, %g div, %g sqrt)",
             op->mul, op->add, op->div, op->sqrt);
    bench_report(buf, op->mul + op->add + op->div + op->sqrt, unit);
    snprintf(buf, sizeof buf, "%s.floor_fraction", name);
    snprintf(unit, sizeof unit, "of the %s floor (one thread; bound: %s)", bench_level_name(lv),
             bound);
    bench_report(buf, ff, unit);
    snprintf(buf, sizeof buf, "%s.fma_peak_fraction", name);
    bench_report(buf, fp, "of the machine's FMA peak (one thread)");
    return ff;
}

void bench_summary_add(bench_ctx *c, const char *measure, double dflab, const char *peer,
                       double peer_value, double ratio, double floor_fraction)
{
    if (c->nrows == BENCH_ROWS) abort(); /* the table is sized for the measures */
    /* the CSV is written without quoting: a comma or quote in a name, or
     * a name cut to its field, is the bench's own bug */
    if (strpbrk(measure, ",\"\n") || (peer && strpbrk(peer, ",\"\n")) ||
        strlen(measure) >= sizeof c->rows[0].measure ||
        (peer && strlen(peer) >= sizeof c->rows[0].peer))
        abort();
    bench_row *r = &c->rows[c->nrows++];
    snprintf(r->measure, sizeof r->measure, "%s", measure);
    snprintf(r->peer, sizeof r->peer, "%s", peer ? peer : "");
    r->dflab = dflab;
    r->peer_value = peer_value;
    r->ratio = ratio;
    r->floor_fraction = floor_fraction;
}

void bench_summary_peer(bench_ctx *c, const char *measure, const char *peer, double peer_value)
{
    if (strpbrk(peer, ",\"\n") || strlen(peer) >= sizeof c->rows[0].peer) abort();
    for (int i = 0; i < c->nrows; i++) {
        bench_row *r = &c->rows[i];
        if (strcmp(r->measure, measure) != 0) continue;
        snprintf(r->peer, sizeof r->peer, "%s", peer);
        r->peer_value = peer_value;
        r->ratio = r->dflab / peer_value;
    }
}

static void put_num(FILE *fp, double v)
{
    if (isfinite(v)) fprintf(fp, "%.6g", v);
}

/* The summary CSV; 0 or an error line and 1. */
static int write_summary(const bench_ctx *c, const char *path)
{
    FILE *fp = fopen(path, "w");
    if (!fp) {
        fprintf(stderr, "dflab-bench: cannot write %s\n", path);
        return 1;
    }
    fprintf(fp, "measure,dflab,peer,peer_value,ratio,floor_fraction\n");
    for (int i = 0; i < c->nrows; i++) {
        const bench_row *r = &c->rows[i];
        fprintf(fp, "%s,", r->measure);
        put_num(fp, r->dflab);
        fprintf(fp, ",%s,", r->peer);
        put_num(fp, r->peer_value);
        fputc(',', fp);
        put_num(fp, r->ratio);
        fputc(',', fp);
        put_num(fp, r->floor_fraction);
        fputc('\n', fp);
    }
    if (fclose(fp) != 0) {
        fprintf(stderr, "dflab-bench: cannot write %s\n", path);
        return 1;
    }
    printf("# summary: %s (%d measures)\n", path, c->nrows);
    return 0;
}

/* The load average (1, 5, 15 min) and the core count: the machine is
 * shared, so every run says how busy it was. */
static void print_load(const char *when)
{
    double l1 = NAN, l5 = NAN, l15 = NAN;
    FILE *fp = fopen("/proc/loadavg", "r");
    if (fp) {
        if (fscanf(fp, "%lf %lf %lf", &l1, &l5, &l15) != 3) l1 = l5 = l15 = NAN;
        fclose(fp);
    }
    printf("# machine load %s: %.2f %.2f %.2f (1, 5, 15 min) on %ld cores\n", when, l1, l5, l15,
           sysconf(_SC_NPROCESSORS_ONLN));
}

/* dflab-bench [--summary FILE] [GROUP...]: every group, or only those
 * named (field, footpoint, rfunc, proxy, trace, proxy_input, pht, vdb, mesh). */
int main(int argc, char **argv)
{
    static const struct {
        const char *name;
        void (*run)(bench_ctx *c);
    } groups[] = {{"field", bench_field}, {"footpoint", bench_footpoint}, {"rfunc", bench_rfunc},
                  {"proxy", bench_proxy}, {"trace", bench_trace},
                  {"proxy_input", bench_proxy_input}, {"pht", bench_pht},
                  {"vdb", bench_vdb}, {"mesh", bench_mesh}};
    const size_t ng = sizeof groups / sizeof groups[0];
    const char *summary = NULL;
    dfl_isa isa;
    dfl_err err;
    if (dfl_isa_from_env(&isa, &err) != DFL_OK) {
        fprintf(stderr, "dflab-bench: error: %s\n", err.msg);
        return 2;
    }
    int named = 0;
    for (int a = 1; a < argc; a++) {
        if (strcmp(argv[a], "--summary") == 0) {
            if (a + 1 == argc) {
                fprintf(stderr, "dflab-bench: --summary needs a file name\n");
                return 2;
            }
            summary = argv[++a];
            continue;
        }
        named++;
        size_t g = 0;
        while (g < ng && strcmp(argv[a], groups[g].name) != 0) g++;
        if (g == ng) {
            fprintf(stderr, "dflab-bench: no group '%s' (field footpoint rfunc proxy trace "
                            "proxy_input pht vdb mesh)\n", argv[a]);
            return 2;
        }
    }
    static bench_ctx ctx;
    print_load("at start");
    printf("# kernels' ISA: %s (DFL_ISA=sse2|avx2|avx512 forces one)\n", dfl_isa_name(isa));
    bench_floor_measure(&ctx.floor);
    for (size_t g = 0; g < ng; g++) {
        int on = !named;
        for (int a = 1; a < argc; a++)
            on |= strcmp(argv[a], groups[g].name) == 0 && strcmp(argv[a - 1], "--summary") != 0;
        if (on) groups[g].run(&ctx);
    }
    print_load("at end");
    return summary ? write_summary(&ctx, summary) : 0;
}
