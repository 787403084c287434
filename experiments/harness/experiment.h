/* The study interface.
 *
 * A study is one kind of experiment (smoke, bs04 normalization table, ...).
 * A config names it in `[study] name = ...`.  The runner expands sweeps and
 * calls run() once per sweep point with a single-valued configuration.
 * run() must read and validate every key it uses *before* it writes any
 * file (call dfl_cfg_check_used after reading), append its rows to the
 * table, and write its files only through dfl_study_path() names, which
 * live in the point's stage folder; the runner commits the point when it
 * completes and merges the points (harness/runner.h).  Each point is first
 * run as a validation pass, which dfl_cfg_check_used ends (io/config.h):
 * nothing may be computed or written before it (dfl_field_from_cfg may be:
 * in the pass it builds no field, only a placeholder, field/field.h).
 */
#ifndef DFL_EXPERIMENTS_EXPERIMENT_H
#define DFL_EXPERIMENTS_EXPERIMENT_H

#include <stdbool.h>
#include <stddef.h>

#include "core/budget.h"
#include "core/status.h"
#include "io/config.h"
#include "io/table.h"

typedef struct dfl_study_ctx {
    const char *stage_dir;   /* where files are written during the run */
    const char *tag;         /* unique per sweep point: "" without sweep, else "_pt003" etc. */
    size_t point;            /* sweep point index */
    size_t npoints;          /* number of sweep points */
    int threads;             /* OpenMP threads to use (>= 1) */
} dfl_study_ctx;

typedef struct dfl_study {
    const char *name;        /* value of [study] name */
    const char *summary;     /* one line for `dflab list` */
    dfl_status (*run)(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_table *table,
                      dfl_err *err);
    /* Optional (NULL: dfl_study_estimate_default).  Reads the keys that set
     * the point's size (getters, so bad values fail as in run()) and adds
     * to *cost (zeroed by the caller) the bytes the point holds at its peak
     * and its evaluations by cost class (core/budget.h).  It must not build,
     * fit or allocate anything in proportion to the estimate; it runs before
     * run()'s validation pass, and the runner refuses a point above
     * [study] memory_budget or work_budget before anything computes. */
    dfl_status (*estimate)(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_cost *cost,
                           dfl_err *err);
} dfl_study;

/* The estimate of a study without its own: the [field] section's field
 * (experiments/cfg/field_cost.h), if there is one; [grid] has its own guard
 * (cfg/grid_cfg.h). */
dfl_status dfl_study_estimate_default(const dfl_cfg *cfg, const dfl_study_ctx *ctx,
                                      dfl_cost *cost, dfl_err *err);

/* Defines `const dfl_study dfl_study_<id>` named "<id>" (the config's
 * [study] name), so the symbol and the name cannot drift apart:
 *   DFL_STUDY_DEFINE(bs04_fields, fields_run, "bs04 Fig. 1, 3b: ...");
 * Declare it in the paper's header and list it there (bs04/bs04.h). */
#define DFL_STUDY_DEFINE(id, run_fn, summary_text) \
    const dfl_study dfl_study_##id = {.name = #id, .summary = summary_text, .run = run_fn}
/* The same with an estimate function (see dfl_study.estimate). */
#define DFL_STUDY_DEFINE_ESTIMATED(id, run_fn, estimate_fn, summary_text)                    \
    const dfl_study dfl_study_##id = {.name = #id, .summary = summary_text, .run = run_fn, \
                                      .estimate = estimate_fn}

/* "<stage_dir>/<stem><tag>.<ext>" into buf; returns buf. */
const char *dfl_study_path(const dfl_study_ctx *ctx, const char *stem, const char *ext, char *buf,
                           size_t size);
/* The same name as sweep point `point` would give it: for files written
 * once per run (e.g. a reference image shared by all sweep points). */
const char *dfl_study_path_at(const dfl_study_ctx *ctx, size_t point, const char *stem,
                              const char *ext, char *buf, size_t size);
/* Sets column col of t's current row to the name of this point's file
 * <stem><tag>.<ext> as dfl_study_path gives it, without the directory, or
 * to "" when written is false (the point does not write that file): how a
 * table names its files.  Fails as the table setters do (io/table.h). */
dfl_status dfl_study_put_file(dfl_table *t, const char *col, const dfl_study_ctx *ctx,
                              const char *stem, const char *ext, bool written, dfl_err *err);

/* The file-name tag of sweep point `point` of `npoints`: "" when the run
 * has one point, else "_ptNNN".  The runner and dfl_study_path_at use it. */
const char *dfl_study_tag(size_t point, size_t npoints, char *buf, size_t size);

/* All studies of all papers (registry.c): their number, the i-th in
 * `dflab list` order (NULL when i >= dfl_study_count()), lookup by name
 * (NULL if unknown). */
size_t dfl_study_count(void);
const dfl_study *dfl_study_at(size_t i);
const dfl_study *dfl_study_find(const char *name);

/* One study folder experiments/<folder>/ and its NULL-terminated list;
 * every study's name begins with the folder's name. */
typedef struct dfl_study_group {
    const char *folder;
    const dfl_study *const *studies;
} dfl_study_group;
/* The folders in `dflab list` order (*count of them). */
const dfl_study_group *dfl_study_groups(size_t *count);

#endif
