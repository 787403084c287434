/* sjp10 Fig. 1: per curve the adaptive PHT fit of its signed distance, the
 * T-mesh (cells coloured by level), the fitted SDF as a graph surface and a
 * sampled image; the row gives the fit's size, time and validation errors.
 *
 * Keys.  [study]
 *   cases      = <section> ...   shape sections (closed curves, circle, ...)
 *   fit        = <section>       PHT fit options (experiments/cfg/pht_cfg.h:
 *                                eps, max_level, samples, split, estimator,
 *                                seed, lo, hi)
 *   val_n      = 301             validation grid nodes per axis (+ midpoints)
 *   band       = 0.02            medial band width (pht/validate.h)
 *   image_n    = 201             nodes per axis of the .vti/.exr sample
 *   graph_n    = 101             nodes per axis of the graph surface
 *   rules      = dflab paper     fit rules (sjp10_common.h): dflab's (the fit
 *                                section's grade, peaks) and/or sjp10's alone
 * [output] vti, exr, compress, half (harness/field_out.h).
 * Validation: the grid (val_ columns) and the per-cell protocol (cv_
 * columns, pht/validate.h); `converged` / `reason` judge eps against the
 * per-cell max (sjp10_common.h).
 * Rows: one per rule and case (rule column).  Files per case (stem
 * <case>, <case>_paper for the paper rule): <case>_mesh.vtp/.csv (leaf cells,
 * point data "level"), <case>_graph.vtp (z = f, point data value, error =
 * f - d), <case>.vti/.exr (value, gradient, reference = exact SDF, error).
 * Signs: dflab's f and d are negative inside (sjp10: positive inside).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cfg/field_cost.h"
#include "cfg/list_cfg.h"
#include "cfg/pht_cfg.h"
#include "field/sample.h"
#include "harness/field_out.h"
#include "io/path.h"
#include "pht/pht_field.h"
#include "sjp10/sjp10.h"
#include "sjp10/sjp10_common.h"

typedef struct fig1_keys {
    sjp10_case c[SJP10_MAX_CASES];
    int ncases;
    dfl_pht_fit_opts fit;
    long val_n, image_n, graph_n;
    double band;
    dfl_field_write_opts out;
    int rules[SJP10_RULES], nrules;
} fig1_keys;

static dfl_status read_keys(const dfl_cfg *cfg, void *keys, dfl_err *err)
{
    fig1_keys *k = keys;
    dfl_status st = sjp10_cases_from_cfg(cfg, "study", "cases", 1, k->c, &k->ncases, err);
    if (st) return st;
    for (int i = 0; i < k->ncases; i++)
        if (k->c[i].shape.dim != 2)
            return dfl_cfg_reject(cfg, "study", "cases", err, "[%s] is not a planar shape", k->c[i].name);
    if ((st = sjp10_fit_from_cfg(cfg, "fit", 2, &k->fit, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "val_n", 301, 2, 4001, &k->val_n, err))) return st;
    if ((st = dfl_cfg_double_opt(cfg, "study", "band", 0.02, 0.0, 1e300, &k->band, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "image_n", 201, 2, 4001, &k->image_n, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "graph_n", 101, 2, 2001, &k->graph_n, err))) return st;
    if ((st = sjp10_rules_from_cfg(cfg, k->rules, &k->nrules, err))) return st;
    return dfl_field_out_from_cfg(cfg, &k->out, err);
}

static dfl_status write_image(const dfl_study_ctx *ctx, const char *stem, const dfl_field *f,
                              const dfl_shape *shape, const fig1_keys *k, dfl_err *err)
{
    dfl_grid g = {2, {(int)k->image_n, (int)k->image_n, 1},
                  {k->fit.lo[0], k->fit.lo[1], 0}, {k->fit.hi[0], k->fit.hi[1], 0}};
    const size_t m = dfl_grid_size(&g);
    dfl_field_bufs b = {0};
    double *xy = malloc(2 * m * sizeof *xy), *dg = malloc(2 * m * sizeof *dg);
    dfl_status st = DFL_OK;
    if (!xy || !dg || !dfl_field_bufs_alloc(&b, m, 2, true))
        st = dfl_err_set(err, DFL_E_NOMEM, "sjp10_fig1: out of memory (image)");
    if (!st) st = dfl_field_sample(f, &g, ctx->threads, b.u, b.gu, err);
    if (!st) {
        for (size_t i = 0; i < m; i++) dfl_grid_node(&g, i, xy + 2 * i);
        sjp10_shape_eval(shape, m, xy, b.ref, dg, ctx->threads);
        st = dfl_field_out_write(ctx, stem, &g, b.u, b.gu, b.ref, &k->out, err);
    }
    free(xy), free(dg);
    dfl_field_bufs_free(&b);
    return st;
}

static dfl_status put_row(dfl_table *t, const sjp10_case *c, const char *base, int rule,
                          const fig1_keys *k, const dfl_pht_fit *fit, const dfl_pht_val *v,
                          const dfl_pht_cellval *cv, const dfl_study_ctx *ctx, dfl_err *err)
{
    char stem[160];
    dfl_status st = dfl_table_row(t, err);
    if (!st) st = dfl_table_set_string(t, "case", c->name, err);
    if (!st) st = dfl_table_set_string(t, "rule", sjp10_rule_name(rule), err);
    if (!st) st = dfl_table_set_string(t, "kind", c->shape.ops->kind, err);
    if (!st) st = dfl_table_set_double(t, "eps", k->fit.eps, err);
    if (!st) st = dfl_table_set_int(t, "max_level", k->fit.max_level, err);
    if (!st) st = dfl_table_set_int(t, "samples", k->fit.samples, err);
    if (!st) st = dfl_table_set_string(t, "split", dfl_pht_split_name(k->fit.split), err);
    if (!st) st = dfl_table_set_string(t, "estimator", dfl_pht_estimator_name(k->fit.estimator), err);
    if (!st) st = dfl_table_set_int(t, "grade", k->fit.grade && rule == 0, err);
    if (!st) st = dfl_table_set_int(t, "peaks", k->fit.peaks && rule == 0, err);
    if (!st) st = sjp10_put_fit(t, fit, cv, k->fit.eps, err);
    if (!st) st = dfl_table_set_double(t, "band", k->band, err);
    if (!st) st = sjp10_put_val(t, "val_", v, err);
    if (!st) st = sjp10_put_cellval(t, cv, k->fit.eps, err);
    snprintf(stem, sizeof stem, "%s_mesh", base);
    if (!st) st = dfl_study_put_file(t, "mesh_vtp", ctx, stem, "vtp", true, err);
    if (!st) st = dfl_study_put_file(t, "mesh_csv", ctx, stem, "csv", true, err);
    snprintf(stem, sizeof stem, "%s_graph", base);
    if (!st) st = dfl_study_put_file(t, "graph_vtp", ctx, stem, "vtp", true, err);
    if (!st) st = dfl_study_put_file(t, "image_vti", ctx, base, "vti", k->out.vti, err);
    return st;
}

static dfl_status run_case(const fig1_keys *k, sjp10_case *c, int rule, const dfl_study_ctx *ctx,
                           dfl_table *t, dfl_err *err)
{
    dfl_pht_fit fit;
    dfl_field f = {0};
    sjp10_ref ref = {0};
    dfl_pht_val v;
    dfl_pht_cellval cv;
    char stem[160], base[96];
    dfl_pht_fit_opts o = k->fit;
    sjp10_rule_apply(rule, &o);
    snprintf(base, sizeof base, "%s%s", c->name, rule ? "_paper" : "");
    dfl_status st = dfl_pht_fit_run(c->src, &o, &fit, err);
    if (st) return dfl_err_prefix(err, "[%s]", c->name);
    if (!st) st = sjp10_cellval(fit.spline, &c->shape, k->band, k->fit.eps, &cv, err);
    if (!st) st = dfl_pht_field_new(&fit.spline, &f, err);
    if (!st) st = sjp10_ref_grid(&c->shape, k->fit.lo, k->fit.hi, (int)k->val_n, 1, k->band,
                                 ctx->threads, &ref, err);
    if (!st) st = sjp10_ref_errors(&f, &ref, ctx->threads, &v, err);
    snprintf(stem, sizeof stem, "%s_mesh", base);
    if (!st) st = sjp10_write_mesh(ctx, stem, dfl_pht_field_spline(&f), err);
    snprintf(stem, sizeof stem, "%s_graph", base);
    if (!st) st = sjp10_write_graph(ctx, stem, &f, &c->shape, k->fit.lo, k->fit.hi,
                                    (int)k->graph_n, ctx->threads, err);
    if (!st) st = write_image(ctx, base, &f, &c->shape, k, err);
    if (!st) st = put_row(t, c, base, rule, k, &fit, &v, &cv, ctx, err);
    sjp10_ref_free(&ref);
    dfl_field_destroy(&f);
    dfl_pht_fit_free(&fit);
    return st;
}

static dfl_status run_cases(void *keys, const dfl_study_ctx *ctx, dfl_table *t, dfl_err *err)
{
    fig1_keys *k = keys;
    dfl_status st = DFL_OK;
    for (int r = 0; r < k->nrules && !st; r++)
        for (int i = 0; i < k->ncases && !st; i++)
            st = run_case(k, &k->c[i], k->rules[r], ctx, t, err);
    return st;
}

static void keys_free(void *keys)
{
    fig1_keys *k = keys;
    sjp10_cases_free(k->c, k->ncases);
}

static const sjp10_study FIG1 = {sizeof(fig1_keys), read_keys, run_cases, keys_free};

static dfl_status fig1_run(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_table *table,
                           dfl_err *err)
{
    fig1_keys k;
    return sjp10_run(&FIG1, &k, cfg, ctx, table, err);
}

/* Peak memory: the fits run one after another (per rule and case); each
 * holds its mesh (bounded by [fit] max_level) with the per-cell protocol
 * (sjp10_fit_cost), its validation points (sjp10_ref_cost), and then one
 * of the files: the mesh's .vtp (cells x 4 corners with a level, quads and
 * outlines: 224 bytes a leaf, twice for the writer's copies), the graph
 * (graph_n^2 nodes: points, values, errors and triangles, 160 bytes a node,
 * twice) or the image (image_n^2 nodes: 56 bytes a node and the field
 * files' buffers).  Work: the fit, the validation points, graph and image
 * (a spline evaluation, DECODE, and an exact distance per node) and the
 * files, at the case's shape class; the shapes are not built. */
static dfl_status fig1_estimate(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_cost *c,
                                dfl_err *err)
{
    (void)ctx;
    char names[SJP10_MAX_CASES][DFL_SECTION_NAME_LEN];
    int n = 0;
    fig1_keys k;
    memset(&k, 0, sizeof k);
    dfl_status st = dfl_section_names_from_cfg(cfg, "study", "cases", SJP10_MAX_CASES, names, &n,
                                               "case section", err);
    if (!st) st = sjp10_fit_from_cfg(cfg, "fit", 2, &k.fit, err);
    if (!st) st = dfl_cfg_int_opt(cfg, "study", "val_n", 301, 2, 4001, &k.val_n, err);
    if (!st) st = dfl_cfg_int_opt(cfg, "study", "image_n", 201, 2, 4001, &k.image_n, err);
    if (!st) st = dfl_cfg_int_opt(cfg, "study", "graph_n", 101, 2, 2001, &k.graph_n, err);
    if (!st) st = sjp10_rules_from_cfg(cfg, k.rules, &k.nrules, err);
    if (!st) st = dfl_field_out_from_cfg(cfg, &k.out, err);
    const char *fsec = "study";
    if (!st) dfl_cfg_string(cfg, "study", "fit", &fsec, NULL);
    fsec = dfl_cfg_section_name(cfg, fsec);
    for (int i = 0; i < n && !st; i++) {
        if (!dfl_cfg_has_section(cfg, names[i])) continue; /* the run names it */
        const dfl_cost_class cls = dfl_shape_cost_class(cfg, names[i]);
        for (int r = 0; r < k.nrules; r++) {
            dfl_cost one, files;
            double leaves;
            memset(&one, 0, sizeof one);
            memset(&files, 0, sizeof files);
            sjp10_fit_cost(&k.fit, 2, -1, cls, 1, fsec, "max_level", &one);
            sjp10_ref_cost(2, k.val_n, 1, cls, "study", "val_n", &one);
            dfl_pht_fit_bytes_bound(&k.fit, 2, &leaves);
            const double gn = (double)k.graph_n * k.graph_n, im = (double)k.image_n * k.image_n;
            dfl_cost step;
            memset(&step, 0, sizeof step);
            dfl_cost_add_bytes(&step, fsec, "max_level", 2 * 224 * leaves, "the mesh file");
            dfl_cost_add_step(&files, &step);
            memset(&step, 0, sizeof step);
            dfl_cost_add_bytes(&step, "study", "graph_n", 2 * 160 * gn, "the graph of %ld^2 nodes",
                               k.graph_n);
            dfl_cost_add_work(&step, "study", "graph_n", DFL_COST_DECODE, gn, "the graph");
            dfl_cost_add_work(&step, "study", "graph_n", cls, gn, "the graph's errors");
            dfl_cost_add_step(&files, &step);
            memset(&step, 0, sizeof step);
            dfl_cost_add_bytes(&step, "study", "image_n", 56 * im + dfl_field_out_bytes(&k.out, im),
                               "the image of %ld^2 nodes", k.image_n);
            dfl_cost_add_work(&step, "study", "image_n", DFL_COST_DECODE, im, "the image");
            dfl_cost_add_work(&step, "study", "image_n", cls, im, "the image's reference");
            dfl_cost_add_work(&step, "study", "image_n", DFL_COST_CHEAP,
                              dfl_field_out_units(&k.out, im), "the image's files");
            dfl_cost_add_step(&files, &step);
            dfl_cost_add_cost(&one, &files);
            dfl_cost_add_step(c, &one);
        }
    }
    return st;
}

DFL_STUDY_DEFINE_ESTIMATED(sjp10_fig1, fig1_run, fig1_estimate,
                 "sjp10 Fig. 1: adaptive PHT fits of closed curves' SDFs (T-mesh, graph, image)");
