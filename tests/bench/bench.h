/* make bench: throughput figures, each beside a naive baseline run in the
 * same process on the same inputs.
 *
 * Output lines are `name: value unit`, one per measurement, e.g.
 *   field.sample.circle: 1.2e+08 points/s
 *   field.sample.circle.naive: 3.4e+07 points/s
 *   field.sample.circle.ratio: 3.5 x
 * so that scripts can grep them.  Timings take the best of several
 * repetitions (the machine is shared).
 *
 * The floor (bench_floor.c) is measured at the start of the run, and
 * kernels with an operation count print their fraction of it.  The
 * measures of issue 19 go to a summary CSV (bench_summary_add; written by
 * bench_main.c with --summary FILE), columns
 *   measure,dflab,peer,peer_value,ratio,floor_fraction
 * (empty where a value does not exist). */
#ifndef DFL_BENCH_H
#define DFL_BENCH_H

#include <stddef.h>

/* Vector levels of the floor: one double (sd forms), then core/isa.h's. */
enum { BENCH_SCALAR, BENCH_SSE2, BENCH_AVX2, BENCH_AVX512, BENCH_LEVELS };

/* Measured throughput per level (one thread; NAN where the CPU lacks it):
 * fma in flop/s (2 per FMA lane), muladd, div, sqrt in double ops/s. */
typedef struct bench_floor {
    int has[BENCH_LEVELS];
    int has_fma;
    double fma[BENCH_LEVELS], muladd[BENCH_LEVELS], div[BENCH_LEVELS], sqrt[BENCH_LEVELS];
    /* divsqrt: a mix of 2 divisions to 1 root (as the strip trims), ops/s;
     * one_divider: the mix runs no faster than divisions and roots queued
     * on one unit (its time >= 0.8 x the sum of their separate times), so
     * a kernel's division and root times add up in its floor. */
    double divsqrt[BENCH_LEVELS];
    int one_divider[BENCH_LEVELS];
    double fma_peak;    /* max of fma[] (muladd's when no FMA): the machine's flop/s per core */
    double muladd_peak; /* max of muladd[] */
} bench_floor;

/* A kernel's double operations per evaluation (|.|, compares and selects
 * are not counted). */
typedef struct bench_ops {
    double mul, add, div, sqrt;
} bench_ops;

#define BENCH_ROWS 64
typedef struct bench_row {
    char measure[48], peer[64];
    double dflab, peer_value, ratio, floor_fraction; /* NAN: empty */
} bench_row;

/* What the groups share: the floor and the summary rows. */
typedef struct bench_ctx {
    bench_floor floor;
    bench_row rows[BENCH_ROWS];
    int nrows;
} bench_ctx;

/* Measures the floor into f and prints it (floor.* lines). */
void bench_floor_measure(bench_floor *f);
/* Fraction of the floor at level that `rate` evaluations per second (one
 * thread) of a kernel of op reach: rate x max((mul + add) / muladd, div /
 * div, sqrt / sqrt); *bound names the largest term.  NAN for a level the
 * CPU lacks. */
double bench_floor_fraction(const bench_floor *f, int level, double rate, const bench_ops *op,
                            const char **bound);
/* Fraction of the machine's FMA peak: rate x (all ops) / fma_peak. */
double bench_fma_fraction(const bench_floor *f, double rate, const bench_ops *op);
/* "scalar", "sse2", "avx2", "avx512". */
const char *bench_level_name(int level);
/* The level of the kernels' ISA in this process (core/isa.h). */
int bench_active_level(void);
/* Prints name.floor_fraction (of the active level's floor, with its
 * bound) and name.fma_peak_fraction for a one-thread rate of op; returns
 * the floor fraction, which the summary's floor_fraction column holds
 * (the FMA-peak fraction would understate a kernel bound by adds,
 * divisions or roots). */
double bench_kernel_floor(const bench_ctx *c, const char *name, double rate1,
                          const bench_ops *op);
/* Appends a summary row (NULL peer: none; NAN values: empty). */
void bench_summary_add(bench_ctx *c, const char *measure, double dflab, const char *peer,
                       double peer_value, double ratio, double floor_fraction);
/* Sets the peer, its value and the ratio dflab / peer_value of the summary
 * row named measure, added earlier by another group (the proxy builds' rows
 * get the OpenVDB fill); nothing if no such row (that group did not run). */
void bench_summary_peer(bench_ctx *c, const char *measure, const char *peer, double peer_value);
/* Wall seconds (monotonic). */
double bench_now(void);
/* The CPU's model name from /proc/cpuinfo into buf ("unknown" if none). */
const char *bench_cpu_model(char *buf, size_t size);

/* Best-of-`reps` wall time in seconds of fn(arg). */
double bench_best(int reps, void (*fn)(void *arg), void *arg);
/* Prints `name: value unit`. */
void bench_report(const char *name, double value, const char *unit);
/* Prints name (rate), name.naive (rate) and name.ratio. */
void bench_pair(const char *name, double rate, double naive_rate, const char *unit);

/* Each bench file defines one entry point; bench_main.c calls them all. */
void bench_field(bench_ctx *c);
void bench_footpoint(bench_ctx *c);
void bench_rfunc(bench_ctx *c);
void bench_proxy(bench_ctx *c);
void bench_trace(bench_ctx *c);
void bench_proxy_input(bench_ctx *c);
void bench_pht(bench_ctx *c);
void bench_vdb(bench_ctx *c);
void bench_mesh(bench_ctx *c);

#endif
