/* make bench: throughput figures, each beside a naive baseline run in the
 * same process on the same inputs.
 *
 * Output lines are `name: value unit`, one per measurement, e.g.
 *   field.sample.circle: 1.2e+08 points/s
 *   field.sample.circle.naive: 3.4e+07 points/s
 *   field.sample.circle.ratio: 3.5 x
 * so that scripts can grep them.  Timings take the best of several
 * repetitions (the machine is shared). */
#ifndef DFL_BENCH_H
#define DFL_BENCH_H

#include <stddef.h>

/* Best-of-`reps` wall time in seconds of fn(arg). */
double bench_best(int reps, void (*fn)(void *arg), void *arg);
/* Prints `name: value unit`. */
void bench_report(const char *name, double value, const char *unit);
/* Prints name (rate), name.naive (rate) and name.ratio. */
void bench_pair(const char *name, double rate, double naive_rate, const char *unit);

/* Each bench file defines one entry point; bench_main.c calls them all. */
void bench_field(void);
void bench_footpoint(void);
void bench_rfunc(void);
void bench_proxy(void);
void bench_trace(void);
void bench_proxy_input(void);
void bench_pht(void);
void bench_vdb(void);
void bench_mesh(void);

#endif
