/* Sweeps as units of work: `dflab run`, `dflab run --point K`, `dflab merge`,
 * `dflab plan`.
 *
 * Function index
 *   dfl_run     a config's sweep points (all of them, or one), then the merge
 *   dfl_merge   a folder's committed points -> what a one-process run writes
 *   dfl_plan    the points, their commands, a Slurm array or GNU parallel job
 *
 * Layout of an output folder OUT (default results/<config stem>/, or
 * results/runs/<stem>/<overrides>/ when --set is given) and its points:
 *   OUT/<study>.csv, config.ini, manifest.json, the study's files
 *   OUT.points/ptNNN/   one committed sweep point: its rows (<study>.csv),
 *                       its files (same names as in OUT), config.ini and
 *                       point.json (resolved config with defaults, hashes,
 *                       wall time, host, threads)
 * Every point is validated (all getters and dfl_cfg_check_used) before any
 * computes.  A point is computed in OUT.points/ptNNN.stage.<host>.<pid>/
 * and renamed into place when complete, so a kill loses only the running
 * point; a rerun skips points whose config (the whole sweep's keys and
 * values) and dflab binary (sha256) match, unless force.  The merge builds
 * OUT.stage.<host>.<pid>/ from the points (hard links) and replaces OUT as a
 * whole: no file of an earlier run survives; points of an earlier sweep
 * in OUT.points go too.  Leftover stage folders of dead runs
 * (this host, process gone) are removed by the next run of the same OUT.
 */
#ifndef DFL_EXPERIMENTS_RUNNER_H
#define DFL_EXPERIMENTS_RUNNER_H

#include <stdio.h>

#include "core/status.h"

typedef struct dfl_run_opts {
    const char *config;        /* path of the .ini */
    const char *const *sets;   /* "section.key=value" overrides */
    int nsets;
    const char *outdir;        /* NULL: see above */
    int threads;               /* <= 0: OpenMP default */
    int quiet;                 /* no progress lines on stderr */
    long point;                /* with has_point: run only points point..point_last, no merge */
    long point_last;           /* >= point (== point: one point) */
    int has_point;
    int force;                 /* recompute points that are up to date */
    const char *cmdline;       /* for the manifest (NULL: "") */
} dfl_run_opts;

dfl_status dfl_run(const dfl_run_opts *opts, dfl_err *err);

/* Assembles dir.points/ into dir, replacing its other contents.  DFL_E_INPUT
 * naming the folder when a point is missing, claimed twice, or comes from
 * another config, study, sweep size or dflab binary than the others.  Then
 * the run's non-finite rule (harness/nonfinite.h) over the merged folder,
 * each point's allow_nonfinite from its config.ini: DFL_E_NUMERIC (exit 1,
 * the folder written) as the run would have ended. */
dfl_status dfl_merge(const char *dir, int quiet, const char *cmdline, dfl_err *err);

typedef struct dfl_plan_opts {
    dfl_run_opts run;   /* config, sets, outdir, threads as `run` takes them */
    int commands;       /* one `dflab run ... --point K` line per point */
    const char *emit;   /* NULL, "slurm" or "parallel" */
    long max_parallel;  /* Slurm %M / parallel -j (<= 0: 4) */
    const char *exe;    /* the dflab to call (absolute path) */
    long per_task;      /* points per job (<= 0: 1): job i runs --point iK-(i+1)K-1 */
    const char *time;   /* Slurm --time (NULL: from the estimate) */
    const char *mem;    /* Slurm --mem (NULL: from the estimate) */
    int cores;          /* this machine's cores (<= 0: 1), for the default threads */
} dfl_plan_opts;

/* Prints the plan on out.  Validates every point first (as dfl_run).
 * Emitted jobs: each runs a batch of per_task points (`--point A-B`, one
 * process) with --threads T (run.threads, default max(1, cores / jobs at
 * once)).  Slurm: --cpus-per-task = T; --mem (default: the largest point
 * estimate x 1.5 + 512 MB, in MB) and --time (default: the slowest batch's
 * estimate on T cores x 2 + 10 minutes) unless given; the merge job runs
 * afterany (after the array ends, whatever its tasks did), and the merge
 * refuses with one line naming the missing points when a task failed or
 * was cancelled. */
dfl_status dfl_plan(const dfl_plan_opts *opts, FILE *out, dfl_err *err);

#endif
