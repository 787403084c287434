/* Runs a check once per ISA this CPU runs, each in a child process with
 * DFL_ISA set (core/isa.h: the ISA is chosen once per process), so that a
 * check of behaviour that could differ between the per-ISA kernels (an
 * undefined cast of a NaN to an index) sees every variant, and a crash in
 * one variant fails the test instead of ending the run. */
#ifndef DFL_TESTS_UTIL_PER_ISA_H
#define DFL_TESTS_UTIL_PER_ISA_H

/* check(ctx) returns the number of failures (printed to stderr by the
 * check).  Runs it in a forked child per ISA with dfl_isa_cpu_has; for
 * each, cr_expect that the child exited 0, naming the ISA and whether it
 * exited (1: a check failed, 3: the ISA was not taken) or was killed by a
 * signal.  Returns the number of ISAs run. */
int dfl_test_per_isa(int (*check)(const void *ctx), const void *ctx);

#endif
