/* Private to the harness (runner.c, point.c, merge.c, plan.c): a loaded,
 * validated sweep and the names of its folders.
 *
 *   dfl_sweep_open     load, override, find the study, validate every point
 *   dfl_sweep_close    free
 *   dfl_sweep_label    "sec.key=value ..." of a point
 *   dfl_sweep_outdir   the default output folder of a config and overrides
 *   dfl_point_run      compute one point into OUT.points/ptNNN (point.c)
 *   dfl_point_check    whether OUT.points/ptNNN is up to date (point.c)
 *   dfl_point_parse, _load, _verify, _rec_free   a committed point's record
 *                      (point.json) and its files (point.c)
 *   dfl_merge_into     assemble OUT from its points (merge.c)
 *   dfl_sweep_clean_stale  remove dead runs' stage folders of OUT (merge.c)
 *   dfl_sweep_budgets      [study] memory_budget (GB) and work_budget (hours)
 *   dfl_sweep_check_budget a point's estimate against them (budget_check.c)
 *   dfl_sweep_estimate     a point's estimated peak bytes and seconds (for launchers)
 */
#ifndef DFL_EXPERIMENTS_SWEEP_H
#define DFL_EXPERIMENTS_SWEEP_H

#include <stdbool.h>
#include <stddef.h>

#include "harness/experiment.h"
#include "harness/runner.h"
#include "io/config.h"

typedef struct dfl_sweep {
    const dfl_run_opts *o;
    dfl_cfg *cfg;
    const dfl_study *study;
    size_t np, na;
    char outdir[4096];
    char points[4200];      /* OUT.points */
    char sweep_sha[65];     /* dfl_cfg_sweep_hash of the whole sweep */
    char config_stamp[4096]; /* o->config as provenance names it (dfl_path_stamp) */
    char binary_sha[65];    /* sha256 of the running dflab */
    int threads;            /* what the study gets (>= 1) */
} dfl_sweep;

dfl_status dfl_sweep_open(const dfl_run_opts *o, dfl_sweep *s, dfl_err *err);
void dfl_sweep_close(dfl_sweep *s);
const char *dfl_sweep_label(const dfl_sweep *s, const dfl_cfg *pt, char *buf, size_t size);
void dfl_sweep_outdir(const dfl_run_opts *o, char *buf, size_t size);
/* OUT.points/ptNNN into buf. */
const char *dfl_point_dir(const dfl_sweep *s, size_t k, char *buf, size_t size);

dfl_status dfl_point_run(const dfl_sweep *s, size_t k, double *seconds, dfl_err *err);

/* *current: OUT.points/ptNNN exists and is point k of this very sweep and
 * binary, with every file its point.json lists unchanged (size and
 * sha256).  A point of another sweep, or one whose files changed (a note
 * on stderr names the file unless quiet), is not current: it is
 * recomputed.  DFL_E_INPUT (exit 2) for what dflab never writes there: a
 * malformed point.json (file and byte named), a non-regular entry (FIFO,
 * folder, device, link), a file that point.json does not list. */
dfl_status dfl_point_check(const dfl_sweep *s, size_t k, int quiet, bool *current, dfl_err *err);

/* A committed point's record. */
typedef struct dfl_point_rec {
    char *json;      /* the whole point.json, checked strict JSON; malloc'ed */
    long index, np;  /* 0 <= index < np <= DFL_POINT_NP_MAX */
    long threads;    /* -1 when not recorded */
    double wall;     /* wall_seconds, 0 when not recorded */
    char study[256], sweep[80], binary[80], config[4096];
} dfl_point_rec;

#define DFL_POINT_NP_MAX 100000000L

/* Parses text (len bytes, NUL-terminated; ownership passes to r->json on
 * success, text is freed on failure) as the point.json at name.
 * DFL_E_INPUT "NAME: byte N: key: expected ..." for anything but strict
 * JSON with index, npoints, study, sweep_sha256, binary_sha256 (and
 * config, threads, wall_seconds when present) of the right types and
 * ranges, and a "files" array of {"name", "bytes", "sha256"}. */
dfl_status dfl_point_parse(char *text, size_t len, const char *name, dfl_point_rec *r,
                           dfl_err *err);
/* Reads dir/point.json (a regular file of at most 16 MiB) and parses it. */
dfl_status dfl_point_load(const char *dir, dfl_point_rec *r, dfl_err *err);
/* Checks dir against its record r: every entry is a regular file listed
 * in r's "files" (or point.json itself), every listed file exists with the
 * recorded bytes and sha256.  DFL_E_INPUT naming the first entry that
 * fails; *changed (may be NULL) is set when the failure is a missing or
 * changed listed file (what a resume recomputes), cleared otherwise. */
dfl_status dfl_point_verify(const char *dir, const dfl_point_rec *r, bool *changed,
                            dfl_err *err);
void dfl_point_rec_free(dfl_point_rec *r);

dfl_status dfl_merge_into(const char *dir, const dfl_sweep *expect, int quiet,
                          const char *cmdline, dfl_err *err);
void dfl_sweep_clean_stale(const char *outdir);

/* [study] memory_budget = <GB> (1e-3 .. 1e6; default core/budget.h's
 * dfl_budget_memory_default) and work_budget = <hours> (1e-6 .. 1e6;
 * default 24) of point pt, in bytes and seconds (marks both used). */
dfl_status dfl_sweep_budgets(const dfl_cfg *pt, double *mem_bytes, double *work_seconds,
                             dfl_err *err);
/* The study's estimate of point pt (its hook or dfl_study_estimate_default)
 * against the budgets: DFL_E_INPUT naming the key that dominates, the
 * estimate and the budget, when the point's peak memory or its time on
 * ctx->threads cores is above them.  Builds nothing. */
dfl_status dfl_sweep_check_budget(const dfl_sweep *s, const dfl_cfg *pt, const dfl_study_ctx *ctx,
                                  dfl_err *err);

/* Point k's estimate (its study's estimate hook or the [field] cost): peak
 * bytes and seconds on `threads` cores (core/budget.h: conservative, errs
 * long).  Fails as the estimate's getters do. */
dfl_status dfl_sweep_estimate(const dfl_sweep *s, size_t k, int threads, double *bytes,
                              double *seconds, dfl_err *err);

#endif
