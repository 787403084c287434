/* Resource budgets: how much memory a run may hold and how long it may
 * take, and the cost of a piece of work in those terms.
 *
 * Function index
 *   dfl_budget_paths_default     the machine's files (/proc, /sys/fs/cgroup)
 *   dfl_budget_cgroup_limit      tightest memory limit of the process's cgroups
 *   dfl_budget_meminfo           a /proc/meminfo field in bytes
 *   dfl_budget_memory_default_at the default memory budget from given files
 *   dfl_budget_memory_default    the same from the machine's files
 *   dfl_cost_add_bytes / _work   accumulate a study's estimate (dfl_cost)
 *   dfl_cost_add_cost / _step    combine estimates: held together, one after another
 *   dfl_cost_seconds             the estimate's time on `threads` cores
 *
 * Memory.  The default budget is half the smallest of: physical memory
 * (MemTotal), the memory limit of every cgroup the process is in (v2
 * `memory.max`, v1 `memory.limit_in_bytes`, the process's own group and
 * all its ancestors up to the mount root, since a parent's limit binds its
 * children) -- and at most MemAvailable.  A limit that cannot be read
 * counts as no limit; when nothing can be read the default is 4 GB.
 *
 * Work.  A study counts evaluations per cost class (DFL_COST_CLASSES); each
 * class has a time per evaluation on one core, chosen on the slow side of
 * what this code measures (a 2020s x86 core) so that an estimate errs
 * long, not short: these are conservative constants, not a measurement of
 * the running machine (a certified implicit footpoint measured about 4e-5 s,
 * one on a cubic B-spline space curve 3.3e-5 s).  Work is spread over
 * `threads` cores.
 */
#ifndef DFL_CORE_BUDGET_H
#define DFL_CORE_BUDGET_H

#include <stddef.h>

/* code, name, seconds per evaluation on one core */
#define DFL_COST_CLASSES(X)                                                           \
    X(CHEAP, "cheap", 2e-8)         /* an analytic SDF, a grid lookup */              \
    X(DECODE, "decode", 1e-6)       /* a proxy decode (hermite: 0.8 us measured) */   \
    X(EXACT, "exact", 1e-6)         /* an exact distance to a curve, mesh or CSG */   \
    X(FOOTPOINT, "footpoint", 1e-4) /* a footpoint on an implicit surface or a curve */

typedef enum dfl_cost_class {
#define X(code, name, sec) DFL_COST_##code,
    DFL_COST_CLASSES(X)
#undef X
    DFL_COST_NCLASSES
} dfl_cost_class;

typedef struct dfl_budget_paths {
    const char *proc_cgroup; /* /proc/self/cgroup */
    const char *cgroup_root; /* /sys/fs/cgroup: v2 unified, or v1 with memory/ below */
    const char *meminfo;     /* /proc/meminfo */
} dfl_budget_paths;

void dfl_budget_paths_default(dfl_budget_paths *p);

/* Bytes; INFINITY when no cgroup limits the process's memory (or none can
 * be read).  v2: the "0::PATH" line of proc_cgroup, files
 * cgroup_root/PATH/memory.max and each ancestor's ("max" = no limit).  v1:
 * the line whose controllers include "memory", files
 * cgroup_root/memory/PATH/memory.limit_in_bytes and each ancestor's
 * (values >= 2^60 = no limit).  The smallest limit found wins. */
double dfl_budget_cgroup_limit(const dfl_budget_paths *p);

/* The value of `field` (e.g. "MemTotal", "MemAvailable") in bytes; NAN when
 * the file or field is missing. */
double dfl_budget_meminfo(const dfl_budget_paths *p, const char *field);

/* Bytes, > 0 (the rule above). */
double dfl_budget_memory_default_at(const dfl_budget_paths *p);
double dfl_budget_memory_default(void);

/* A study's estimate of one sweep point.  The largest contributor of each
 * kind is remembered as the config key to name in a refusal. */
typedef struct dfl_cost {
    double bytes;                    /* peak bytes held at once (sum of adds) */
    double evals[DFL_COST_NCLASSES]; /* evaluations by class */
    double big_bytes, big_seconds;   /* the largest single add of each */
    const char *mem_sec, *mem_key;   /* its config key (NULL: none yet) */
    const char *work_sec, *work_key;
    char mem_what[160], work_what[160]; /* what it is, e.g. "8.6e+09 proxies" */
} dfl_cost;

/* Adds bytes (>= 0; +inf allowed) held at the same time as everything else
 * added, caused by [sec] key; `what` (printf-style) says what they are. */
void dfl_cost_add_bytes(dfl_cost *c, const char *sec, const char *key, double bytes,
                        const char *what, ...) __attribute__((format(printf, 5, 6)));
/* Adds n evaluations of class cls caused by [sec] key. */
void dfl_cost_add_work(dfl_cost *c, const char *sec, const char *key, dfl_cost_class cls,
                       double n, const char *what, ...) __attribute__((format(printf, 6, 7)));
/* Combining estimates.  add_cost: b is held at the same time as c (bytes
 * and work add up).  add_step: step runs after c's other steps, each freeing
 * its memory before the next starts (a study's cases or fits one after
 * another): c's bytes become the larger of the two (with its key), the work
 * adds up.  Start a sequence from a zeroed dfl_cost, then add_cost it to
 * what is held throughout.  The largest single contribution of either kind
 * keeps naming the key. */
void dfl_cost_add_cost(dfl_cost *c, const dfl_cost *b);
void dfl_cost_add_step(dfl_cost *c, const dfl_cost *step);
/* Seconds of c's work on threads (>= 1) cores. */
double dfl_cost_seconds(const dfl_cost *c, int threads);
/* Seconds per evaluation of class cls on one core (the table above). */
double dfl_cost_class_seconds(dfl_cost_class cls);

#endif
