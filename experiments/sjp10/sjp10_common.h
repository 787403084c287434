/* Glue shared by the sjp10 studies: validation point sets whose exact
 * distances are computed once and reused by every fit of a case, the table
 * columns of a fit and of its validation, and the T-mesh / graph files.
 *
 * Why a cached reference: pht/validate.h's dfl_pht_validate_points
 * evaluates the exact SDF (and the medial band's second SDF) at every call;
 * a curve's footpoints cost ~10 us, and the cells-vs-error study validates
 * a dozen fits per curve on the same points.  The band criterion is the
 * library's (dfl_pht_medial_band) and the statistics are those of
 * dfl_pht_val, so the numbers equal dfl_pht_validate_points' on the same
 * points.
 *
 *   sjp10_ref_grid     points of the grid protocol (nodes [+ midpoints]), exact d, grad d, band
 *   sjp10_ref_errors   errors of a field against a reference (deterministic, parallel)
 *   sjp10_ref_free
 *   sjp10_stream_errors  the same without a cache (points and exact values per chunk)
 *   sjp10_put_fit      cells, base vertices, dofs, levels, times, converged + reason of a fit
 *   sjp10_put_val      validation columns <prefix>max, mean, rms, gmax, off_max, ...
 *   sjp10_cellval      the per-cell protocol (pht/validate.h) with the studies' options
 *   sjp10_put_cellval  its columns cv_points, cv_max, cv_band_max, cv_off_max, ...
 *   sjp10_rules_from_cfg / sjp10_rule_apply   [study] rules = dflab paper
 *   sjp10_eval         batched field evaluation in fixed parallel chunks
 *   sjp10_write_mesh   the leaf cells of a spline: .vtp (cells as quads coloured by level) + .csv
 *   sjp10_write_graph  the graph surface z = f(x, y) of a 2D field as a .vtp
 *   sjp10_shape_eval   batched exact SDF in fixed parallel chunks
 *   sjp10_cases_from_cfg / _free   the shape sections a study lists, with Hermite sources
 *   sjp10_fit_from_cfg the fit options of the section [study] <key> names
 *   sjp10_source_new   a Hermite source on a config's shape (open curves rejected)
 *   sjp10_run          a study's run: read its keys, check them, run its cases, free
 *   sjp10_fit_at       one row's fit: adaptive at eps or uniform at a level
 *   sjp10_each_fit     a case's rows in the tables' order (rules x eps, then levels)
 */
#ifndef DFL_EXPERIMENTS_SJP10_COMMON_H
#define DFL_EXPERIMENTS_SJP10_COMMON_H

#include <stddef.h>

#include "field/field.h"
#include "geom/shape.h"
#include "harness/experiment.h"
#include "pht/fit.h"
#include "pht/validate.h"

typedef struct sjp10_ref {
    int dim;
    size_t m;
    double *pts;          /* m * dim */
    double *d, *g;        /* exact SDF and gradient (m, m * dim) */
    unsigned char *near;  /* medial band flags (m) */
    double band;
} sjp10_ref;

/* n^dim nodes of [lo, hi] and, when midpoints != 0, the (n-1)^dim cell
 * midpoints; exact values by the shape (parallel chunks), band of width
 * band >= 0.  DFL_E_INPUT for n < 2, DFL_E_NOMEM. */
dfl_status sjp10_ref_grid(const dfl_shape *shape, const double *lo, const double *hi, int n,
                          int midpoints, double band, int threads, sjp10_ref *out, dfl_err *err);
void sjp10_ref_free(sjp10_ref *r);

/* Errors of f at r's points (points with a non-finite exact value are
 * skipped).  DFL_E_NOMEM. */
dfl_status sjp10_ref_errors(const dfl_field *f, const sjp10_ref *r, int threads, dfl_pht_val *out,
                            dfl_err *err);

/* The exact SDF (and gradient, m * dim) at m points, fixed parallel chunks. */
void sjp10_shape_eval(const dfl_shape *s, size_t m, const double *pts, double *val, double *grad,
                      int threads);

#define SJP10_MAX_CASES 8
/* One case: a shape section and (when asked for) its Hermite source. */
typedef struct sjp10_case {
    char name[64];
    dfl_shape shape;
    int have_shape;
    dfl_pht_source *src;
} sjp10_case;
/* The blank-separated shape sections of [sec] key (at most SJP10_MAX_CASES)
 * into c[0..*n-1]; with want_src a Hermite source for each (a shape without
 * derivatives or an open curve: DFL_E_INPUT naming the section's kind).
 * Everything built is freed on failure. */
dfl_status sjp10_cases_from_cfg(const dfl_cfg *cfg, const char *sec, const char *key, int want_src,
                                sjp10_case *c, int *n, dfl_err *err);
void sjp10_cases_free(sjp10_case *c, int n);

/* The fit options of the section [study] key names (pht_cfg.h), for dim;
 * DFL_E_INPUT naming the key when the section is missing. */
dfl_status sjp10_fit_from_cfg(const dfl_cfg *cfg, const char *key, int dim, dfl_pht_fit_opts *o,
                              dfl_err *err);

/* A Hermite source on the shape of section sec: DFL_E_INPUT naming
 * [sec] closed for an open B-spline curve (unsigned distance) and [sec]
 * kind for a shape without SDF derivatives. */
dfl_status sjp10_source_new(const dfl_cfg *cfg, const char *sec, const dfl_shape *shape,
                            dfl_pht_source **src, dfl_err *err);

/* The same statistics on the grid protocol without caching: points are
 * made, and the exact SDF evaluated, chunk by chunk (for grids too large
 * to hold, e.g. the 217^3 protocol of fast analytic references).
 * DFL_E_INPUT for n < 2, DFL_E_NOMEM. */
dfl_status sjp10_stream_errors(const dfl_field *f, const dfl_shape *shape, const double *lo,
                               const double *hi, int n, int midpoints, double band, int threads,
                               dfl_pht_val *out, dfl_err *err);

/* f at m points in chunks of fixed size, OpenMP over chunks. */
void sjp10_eval(const dfl_field *f, size_t m, const double *pts, double *val, double *grad,
                int threads);

/* Columns of a fit.  converged = 1 iff the fit's estimator met eps in
 * every cell (f->converged) and, when cv is given, the per-cell validation
 * max is <= eps; reason = "none" (converged), "level_cap" (cells above eps
 * at max_level stopped the fit; capped_cells counts them), "estimator" (the
 * estimator met eps but the validation max is above it).  eps NaN (uniform
 * grids, no target): converged = f->converged and reason "no_target". */
dfl_status sjp10_put_fit(dfl_table *t, const dfl_pht_fit *f, const dfl_pht_cellval *cv, double eps,
                         dfl_err *err);

/* The per-cell protocol on f's spline against shape, band width band,
 * share above eps (pht/validate.h's default density).  DFL_E_NOMEM. */
dfl_status sjp10_cellval(const dfl_pht_spline *s, const dfl_shape *shape, double band, double eps,
                         dfl_pht_cellval *out, dfl_err *err);
/* cv_points, cv_max, cv_band_max, cv_off_max, cv_medial_max, cv_medial_points,
 * cv_medial_cells, cv_above_eps (share of points above eps, NaN without eps),
 * cv_gmax; cv NULL (not run): NaN maxima and share, zero counts. */
dfl_status sjp10_put_cellval(dfl_table *t, const dfl_pht_cellval *cv, double eps, dfl_err *err);

/* Fit rules: "dflab" (the fit section's grade and peaks) and "paper"
 * (sjp10's rule alone: grade = peaks = 0).  [study] rules = one or both
 * (default "dflab"), in the order given, no repeats; DFL_E_INPUT naming the
 * key.  rules[i] is 0 (dflab) or 1 (paper). */
#define SJP10_RULES 2
dfl_status sjp10_rules_from_cfg(const dfl_cfg *cfg, int *rules, int *n, dfl_err *err);
const char *sjp10_rule_name(int rule);
/* o with the rule applied. */
void sjp10_rule_apply(int rule, dfl_pht_fit_opts *o);
dfl_status sjp10_put_val(dfl_table *t, const char *prefix, const dfl_pht_val *v, dfl_err *err);

/* <stem><tag>.vtp: every leaf cell as a quad (2D; 3D: its 6 faces) with
 * its own corner points carrying point data "level", plus its outline as
 * a closed polyline; and <stem><tag>.csv with lo_*, hi_*, level per cell. */
dfl_status sjp10_write_mesh(const dfl_study_ctx *ctx, const char *stem,
                            const dfl_pht_spline *s, dfl_err *err);

/* <stem><tag>.vtp: the graph (x, y, f(x, y)) of a 2D field on an n x n grid
 * of [lo, hi], triangulated, with point data "value" and, when ref is
 * given (a shape), "error" = f - d. */
dfl_status sjp10_write_graph(const dfl_study_ctx *ctx, const char *stem, const dfl_field *f,
                             const dfl_shape *ref, const double lo[2], const double hi[2], int n,
                             int threads, dfl_err *err);

/* ---- the frame of a run ------------------------------------------------ */
/* What a study's run does around its cases, the same in every sjp10 study:
 * its keys (size bytes, zeroed first) filled by read; every key of the
 * config used (dfl_cfg_check_used ends the validation pass, so nothing
 * computes before it); then cases; free on every path, since read may stop
 * half-way and free takes whatever it built. */
typedef struct sjp10_study {
    size_t size;
    dfl_status (*read)(const dfl_cfg *cfg, void *keys, dfl_err *err);
    dfl_status (*cases)(void *keys, const dfl_study_ctx *ctx, dfl_table *t, dfl_err *err);
    void (*free)(void *keys);
} sjp10_study;
/* keys: s->size bytes of the study's own key struct. */
dfl_status sjp10_run(const sjp10_study *s, void *keys, const dfl_cfg *cfg, const dfl_study_ctx *ctx,
                     dfl_table *t, dfl_err *err);

/* The fit of one row: adaptive at eps (o->eps = eps) when level < 0, else
 * uniform at level with uniform_samples estimator points per cell
 * (o->samples is set, so the row reports what the fit used).  A failure's
 * message is prefixed with [name], the case. */
dfl_status sjp10_fit_at(const dfl_pht_source *src, const char *name, dfl_pht_fit_opts *o,
                        double eps, long level, long uniform_samples, dfl_pht_fit *fit,
                        dfl_err *err);

/* One row of a case: rule, eps (NaN for a uniform fit), level (< 0: the
 * adaptive fit) and i, the place of eps (or of level) in its list. */
typedef dfl_status (*sjp10_fit_fn)(void *arg, int rule, double eps, long level, size_t i,
                                   dfl_err *err);
/* The rows of a case in the tables' order, shared by the studies that fit
 * lists of thresholds and levels: per rule (rules[0..nrules-1]) the
 * adaptive fits at eps[0..neps-1], then the uniform fits at
 * lev[0..nlev-1] under rule dflab (rules do not change a uniform fit).
 * Stops at the first failure. */
dfl_status sjp10_each_fit(const int *rules, int nrules, const double *eps, size_t neps,
                          const double *lev, size_t nlev, sjp10_fit_fn fn, void *arg,
                          dfl_err *err);

/* ---- estimates (core/budget.h), from keys alone ------------------------ */
/* The reference of sjp10_ref_grid (n nodes per axis, midpoints or not) and
 * of sjp10_ref_errors beside it: bytes, per point the point, d, grad d and
 * the band flag, and the errors' value and gradient ((3 dim + 2) doubles
 * and a byte); work, per point the exact SDF and the medial band's second
 * one, 2 of class cls.  Named [sec] key (sec: the config's own string). */
void sjp10_ref_cost(int dim, long n, int midpoints, dfl_cost_class cls, const char *sec,
                    const char *key, dfl_cost *c);
/* One fit with options o in dim (uniform >= 0: the uniform fit at that
 * level; < 0: the adaptive fit, bounded by the mesh at max_level,
 * dfl_pht_fit_bytes_bound) of a shape of class cls, and with cellval the
 * per-cell protocol on it.  Bytes: the fit's mesh, and the protocol's
 * partial results (96 bytes a leaf).  Work per leaf: the estimator's
 * samples, the peaks' 1 + 2 dim points and the Hermite footpoint (samples +
 * 2 dim + 2 of class cls), with cellval the protocol's 27 corner, edge and
 * centre points and 4 random ones (31 of cls).  The dense sub-grid and the
 * near-medial offsets of medial cells (dense^dim + dense (1 + 4 scales),
 * 190 points in 2D) are not counted: medial cells are those the medial
 * band meets, a share of the leaves no key bounds, and counting every leaf
 * would put sjp10's own configs at days.  Named [sec] key. */
void sjp10_fit_cost(const dfl_pht_fit_opts *o, int dim, int uniform, dfl_cost_class cls,
                    int cellval, const char *sec, const char *key, dfl_cost *c);

#endif
