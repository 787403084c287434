/* sjp10 Fig. 2: cells (and degrees of freedom) against the error, per
 * curve, for the adaptive PHT fit at a list of thresholds eps and for the
 * uniform bicubic Hermite grid (every cell at level k: 2^k cells per axis,
 * pht/fit.h's uniform mode) at a list of levels; validation errors on the
 * same cached points for every fit of a case (sjp10_common.h).  A smooth
 * case (a shape whose SDF has no medial axis in the box) shows the
 * slope 1/2 of log cells vs log 1/error that sjp10 quotes for C4 functions
 * on uniform grids.  Slopes are fitted in the report.
 *
 * Keys.  [study]
 *   cases          = <section> ...    shape sections (planar, with derivatives)
 *   fit            = <section>        PHT fit options (pht_cfg.h); its eps is
 *                                     replaced by each entry of eps
 *   eps            = e1 e2 ...        thresholds (> 0)
 *   uniform_levels = k1 k2 ...        uniform grid levels (0..12)
 *   uniform_samples = 1               estimator points per cell of the uniform
 *                                     fits (only its column uses them)
 *   val_n = 301, band = 0.02          validation grid (+ midpoints), medial band
 *   rules = dflab paper               fit rules of the pht rows (sjp10_common.h)
 * Validation: the grid (val_ columns, the same cached points for every fit
 * of a case) and the per-cell protocol (cv_ columns, pht/validate.h);
 * `converged` / `reason` judge eps against the per-cell max.
 * Rows: one per case and method (pht: per rule and eps; uniform: per level,
 * rule "dflab").
 * Signs: dflab's SDF is negative inside (sjp10: positive inside); errors
 * are absolute values and do not depend on it.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cfg/field_cost.h"
#include "cfg/list_cfg.h"
#include "cfg/pht_cfg.h"
#include "pht/pht_field.h"
#include "sjp10/sjp10.h"
#include "sjp10/sjp10_common.h"

typedef struct cells_keys {
    sjp10_case c[SJP10_MAX_CASES];
    int ncases;
    dfl_pht_fit_opts fit;
    double *eps;
    size_t neps;
    double *levels;
    size_t nlevels;
    long uniform_samples, val_n;
    double band;
    int rules[SJP10_RULES], nrules;
} cells_keys;

static void keys_free(void *keys)
{
    cells_keys *k = keys;
    sjp10_cases_free(k->c, k->ncases);
    free(k->eps);
    free(k->levels);
}

static dfl_status read_keys(const dfl_cfg *cfg, void *keys, dfl_err *err)
{
    cells_keys *k = keys;
    dfl_status st = sjp10_cases_from_cfg(cfg, "study", "cases", 1, k->c, &k->ncases, err);
    if (st) return st;
    for (int i = 0; i < k->ncases; i++)
        if (k->c[i].shape.dim != 2)
            return dfl_cfg_reject(cfg, "study", "cases", err, "[%s] is not a planar shape", k->c[i].name);
    if ((st = sjp10_fit_from_cfg(cfg, "fit", 2, &k->fit, err))) return st;
    if ((st = dfl_cfg_doubles(cfg, "study", "eps", 1, &k->eps, &k->neps, err))) return st;
    for (size_t i = 0; i < k->neps; i++)
        if (!(k->eps[i] > 0.0))
            return dfl_cfg_reject(cfg, "study", "eps", err, "expected thresholds > 0, got %g", k->eps[i]);
    if ((st = dfl_cfg_doubles(cfg, "study", "uniform_levels", 0, &k->levels, &k->nlevels, err)))
        return st;
    for (size_t i = 0; i < k->nlevels; i++)
        if (!(k->levels[i] >= 0 && k->levels[i] <= 12 && k->levels[i] == floor(k->levels[i])))
            return dfl_cfg_reject(cfg, "study", "uniform_levels", err,
                                  "expected integer levels in 0..12, got %g", k->levels[i]);
    if ((st = dfl_cfg_int_opt(cfg, "study", "uniform_samples", 1, 1, 4096, &k->uniform_samples, err)))
        return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "val_n", 301, 2, 4001, &k->val_n, err))) return st;
    if ((st = sjp10_rules_from_cfg(cfg, k->rules, &k->nrules, err))) return st;
    return dfl_cfg_double_opt(cfg, "study", "band", 0.02, 0.0, 1e300, &k->band, err);
}

static dfl_status put_row(dfl_table *t, const sjp10_case *c, const char *method, int rule,
                          double eps, long level, const dfl_pht_fit_opts *o, const dfl_pht_fit *fit,
                          const dfl_pht_val *v, const dfl_pht_cellval *cv, double band,
                          dfl_err *err)
{
    dfl_status st = dfl_table_row(t, err);
    if (!st) st = dfl_table_set_string(t, "case", c->name, err);
    if (!st) st = dfl_table_set_string(t, "kind", c->shape.ops->kind, err);
    if (!st) st = dfl_table_set_string(t, "method", method, err);
    if (!st) st = dfl_table_set_string(t, "rule", sjp10_rule_name(rule), err);
    if (!st) st = dfl_table_set_double(t, "eps", eps, err);
    if (!st) st = dfl_table_set_int(t, "uniform_level", level, err);
    if (!st) st = dfl_table_set_int(t, "max_level", o->max_level, err);
    if (!st) st = dfl_table_set_int(t, "samples", o->samples, err);
    if (!st) st = dfl_table_set_string(t, "split", dfl_pht_split_name(o->split), err);
    if (!st) st = dfl_table_set_int(t, "grade", o->grade, err);
    if (!st) st = dfl_table_set_int(t, "peaks", o->peaks, err);
    if (!st) st = sjp10_put_fit(t, fit, cv, eps, err);
    if (!st) st = dfl_table_set_double(t, "band", band, err);
    if (!st) st = sjp10_put_val(t, "val_", v, err);
    if (!st) st = sjp10_put_cellval(t, cv, eps, err);
    return st;
}

/* What the rows of one case share (sjp10_each_fit's arg). */
typedef struct case_run {
    const cells_keys *k;
    const sjp10_case *c;
    const sjp10_ref *ref;
    const dfl_study_ctx *ctx;
    dfl_table *t;
} case_run;

/* Fit (adaptive when level < 0, else uniform at level), validate, one row. */
static dfl_status one_fit(void *arg, int rule, double eps, long level, size_t i, dfl_err *err)
{
    const case_run *a = arg;
    const cells_keys *k = a->k;
    dfl_pht_fit_opts o = k->fit;
    dfl_pht_fit fit;
    dfl_field f = {0};
    dfl_pht_val v;
    dfl_pht_cellval cv;
    (void)i;
    sjp10_rule_apply(rule, &o);
    dfl_status st = sjp10_fit_at(a->c->src, a->c->name, &o, eps, level, k->uniform_samples, &fit,
                                 err);
    if (st) return st;
    st = sjp10_cellval(fit.spline, &a->c->shape, k->band, level < 0 ? eps : NAN, &cv, err);
    if (!st) st = dfl_pht_field_new(&fit.spline, &f, err);
    if (!st) st = sjp10_ref_errors(&f, a->ref, a->ctx->threads, &v, err);
    if (!st)
        st = put_row(a->t, a->c, level < 0 ? "pht" : "uniform", rule, level < 0 ? eps : NAN, level,
                     &o, &fit, &v, &cv, k->band, err);
    dfl_field_destroy(&f);
    dfl_pht_fit_free(&fit);
    return st;
}

static dfl_status run_case(const cells_keys *k, const sjp10_case *c, const dfl_study_ctx *ctx,
                           dfl_table *t, dfl_err *err)
{
    sjp10_ref ref;
    dfl_status st = sjp10_ref_grid(&c->shape, k->fit.lo, k->fit.hi, (int)k->val_n, 1, k->band,
                                   ctx->threads, &ref, err);
    case_run a = {k, c, &ref, ctx, t};
    if (!st)
        st = sjp10_each_fit(k->rules, k->nrules, k->eps, k->neps, k->levels, k->nlevels, one_fit,
                            &a, err);
    sjp10_ref_free(&ref);
    return st;
}

static dfl_status run_cases(void *keys, const dfl_study_ctx *ctx, dfl_table *t, dfl_err *err)
{
    const cells_keys *k = keys;
    dfl_status st = DFL_OK;
    for (int i = 0; i < k->ncases && !st; i++) st = run_case(k, &k->c[i], ctx, t, err);
    return st;
}

static const sjp10_study CELLS = {sizeof(cells_keys), read_keys, run_cases, keys_free};

static dfl_status cells_run(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_table *table,
                            dfl_err *err)
{
    cells_keys k;
    return sjp10_run(&CELLS, &k, cfg, ctx, table, err);
}

/* Peak memory: the cases run one after another, each holding its
 * validation points (sjp10_ref_cost: val_n^2 nodes and midpoints) while its
 * fits run one at a time: the largest of the adaptive fits (bounded by the
 * mesh at [fit] max_level) and the uniform ones (4^level cells), each with
 * the per-cell protocol (sjp10_fit_cost).  Work: every fit and the
 * validation points, at the case's shape class; the keys are read without
 * building the shapes or their Hermite sources (read_keys does). */
static dfl_status cells_estimate(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_cost *c,
                                 dfl_err *err)
{
    (void)ctx;
    char names[SJP10_MAX_CASES][DFL_SECTION_NAME_LEN];
    int n = 0, rules[SJP10_RULES], nrules = 0;
    cells_keys k;
    memset(&k, 0, sizeof k);
    dfl_status st = dfl_section_names_from_cfg(cfg, "study", "cases", SJP10_MAX_CASES, names, &n,
                                               "case section", err);
    if (!st) st = sjp10_fit_from_cfg(cfg, "fit", 2, &k.fit, err);
    if (!st) st = dfl_cfg_doubles(cfg, "study", "eps", 1, &k.eps, &k.neps, err);
    if (!st) st = dfl_cfg_doubles(cfg, "study", "uniform_levels", 0, &k.levels, &k.nlevels, err);
    if (!st) st = dfl_cfg_int_opt(cfg, "study", "uniform_samples", 1, 1, 4096, &k.uniform_samples, err);
    if (!st) st = dfl_cfg_int_opt(cfg, "study", "val_n", 301, 2, 4001, &k.val_n, err);
    if (!st) st = sjp10_rules_from_cfg(cfg, rules, &nrules, err);
    const char *fsec = "study";
    if (!st) dfl_cfg_string(cfg, "study", "fit", &fsec, NULL);
    fsec = dfl_cfg_section_name(cfg, fsec);
    for (int i = 0; i < n && !st; i++) {
        if (!dfl_cfg_has_section(cfg, names[i])) continue; /* the run names it */
        const dfl_cost_class cls = dfl_shape_cost_class(cfg, names[i]);
        dfl_cost one, fits;
        memset(&one, 0, sizeof one);
        memset(&fits, 0, sizeof fits);
        sjp10_ref_cost(2, k.val_n, 1, cls, "study", "val_n", &one);
        for (size_t e = 0; e < (size_t)nrules * k.neps; e++) {
            dfl_cost f;
            memset(&f, 0, sizeof f);
            sjp10_fit_cost(&k.fit, 2, -1, cls, 1, fsec, "max_level", &f);
            dfl_cost_add_step(&fits, &f);
        }
        for (size_t l = 0; l < k.nlevels; l++) {
            if (!(k.levels[l] >= 0 && k.levels[l] <= 12)) continue; /* the run refuses it */
            dfl_pht_fit_opts u = k.fit;
            u.samples = (int)k.uniform_samples;
            dfl_cost f;
            memset(&f, 0, sizeof f);
            sjp10_fit_cost(&u, 2, (int)k.levels[l], cls, 1, "study", "uniform_levels", &f);
            dfl_cost_add_step(&fits, &f);
        }
        dfl_cost_add_cost(&one, &fits);
        dfl_cost_add_step(c, &one);
    }
    free(k.eps);
    free(k.levels);
    return st;
}

DFL_STUDY_DEFINE_ESTIMATED(sjp10_cells, cells_run, cells_estimate,
                 "sjp10 Fig. 2: cells and dofs vs validation error, adaptive PHT vs uniform Hermite grid");
