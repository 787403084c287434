/* sjp10 in 3D: tricubic PHT fits (8 data per base vertex) of implicit
 * surfaces and a sphere at a list of thresholds, beside the uniform
 * tricubic Hermite grid, validated on a node grid of the box (the 217^3
 * protocol of the peers' Discregrid figures) against a reference SDF
 * (an analytic SDF of the same surface where one exists: the implicit
 * torus is checked against the analytic torus).
 *
 * Keys.  [study]
 *   cases           = <section> ...  case sections (below)
 *   fit             = <section>      PHT fit options (pht_cfg.h, dim 3); eps
 *                                    replaced by each entry of eps, lo/hi by the case's
 *   eps             = e1 e2 ...      thresholds (> 0)
 *   uniform_levels  = k1 ...         uniform grid levels (0..7)
 *   uniform_samples = 1              estimator points per uniform cell
 *   rules           = dflab paper    fit rules of the pht rows (sjp10_common.h)
 * A case section:
 *   shape     = <section>   the surface fitted (its SDF needs derivatives)
 *   ref       = <section>   the validation reference (default: shape)
 *   lo, hi    = x y z       the box
 *   val_n     = 217         validation nodes per axis
 *   midpoints = false       add the (n-1)^3 cell midpoints
 *   band      = 0           medial band width (0: every point counts)
 *   cache     = false       true: exact values computed once and kept
 *                           (slow references, small grids); false: per chunk
 *   eps, uniform_levels     the case's own lists (default: the study's)
 *   samples                 the case's estimator points per cell (default: the fit's)
 *   cell_val  = true        also the per-cell protocol (cv_ columns, pht/validate.h)
 *                           against ref; false for references too slow for it
 *                           (cv_ columns NaN, converged judged by the estimator)
 * [output] vti = true, vti_n (harness/field_out.h; default the case's
 *   val_n, at most 33): per fit volume_<case>_pht_<rule>_<i>.vti (i: the
 *   place of eps in the list) or volume_<case>_uniform_<level>.vti over the
 *   case's box: value, gradient, reference, error = value - reference, and
 *   cell data "level" (the T-mesh level of the leaf holding the cell's
 *   centre); per case and rule a collection volume_<case>_pht_<rule>.pvd
 *   over eps (and volume_<case>_uniform.pvd over the levels).
 * Rows: one per case and fit (pht rows per rule and eps), vti naming its volume.  Signs: negative inside (sjp10: positive).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <omp.h>

#include "cfg/field_cost.h"
#include "cfg/pht_cfg.h"
#include "cfg/shape_cfg.h"
#include "cfg/list_cfg.h"
#include "field/exact.h"
#include "harness/field_out.h"
#include "io/vtk.h"
#include "pht/pht_field.h"
#include "sjp10/sjp10.h"
#include "sjp10/sjp10_common.h"

/* The default [output] vti_n: the case's val_n, at most this. */
#define VOLUME_MAX_N 33

typedef struct case3 {
    char name[DFL_SECTION_NAME_LEN];
    dfl_shape shape, ref;
    int have_shape, have_ref;
    dfl_pht_source *src;
    double lo[3], hi[3];
    long val_n;
    bool midpoints, cache, cell_val;
    double band;
    double *eps, *levels;   /* the case's own lists (NULL: the study's) */
    size_t neps, nlevels;
    int own_eps, own_levels; /* the case gives its own list */
    long samples;           /* the case's estimator points per cell (0: the fit's) */
} case3;

typedef struct keys3 {
    case3 c[SJP10_MAX_CASES];
    int ncases;
    dfl_pht_fit_opts fit;
    double *eps, *levels;
    size_t neps, nlevels;
    long uniform_samples;
    int rules[SJP10_RULES], nrules;
    dfl_volume_opts vol;     /* [output] vti, vti_n (per case: min(val_n, 33) by default) */
    int vol_n_given;
} keys3;

static void keys_free(void *keys)
{
    keys3 *k = keys;
    for (int i = 0; i < k->ncases; i++) {
        dfl_pht_source_free(k->c[i].src);
        if (k->c[i].have_shape) dfl_shape_free(&k->c[i].shape);
        if (k->c[i].have_ref) dfl_shape_free(&k->c[i].ref);
        free(k->c[i].eps);
        free(k->c[i].levels);
    }
    free(k->eps);
    free(k->levels);
}

/* [sec] eps (thresholds > 0) or uniform_levels (integers 0..7), whichever key is given. */
static dfl_status read_lists(const dfl_cfg *cfg, const char *sec, const char *eps_key,
                             const char *lev_key, double **out, size_t *n, dfl_err *err)
{
    const char *key = eps_key ? eps_key : lev_key;
    dfl_status st = dfl_cfg_doubles(cfg, sec, key, eps_key ? 1 : 0, out, n, err);
    if (st) return st;
    for (size_t i = 0; i < *n; i++) {
        const double v = (*out)[i];
        if (eps_key && !(v > 0.0))
            return dfl_cfg_reject(cfg, sec, key, err, "expected thresholds > 0, got %g", v);
        if (!eps_key && !(v >= 0 && v <= 7 && v == floor(v)))
            return dfl_cfg_reject(cfg, sec, key, err, "expected integer levels in 0..7, got %g", v);
    }
    return DFL_OK;
}

static dfl_status read_case(const dfl_cfg *cfg, case3 *c, dfl_err *err)
{
    const char *sec = c->name, *ssec, *rsec;
    dfl_status st;
    if (!dfl_cfg_has_section(cfg, sec))
        return dfl_cfg_reject(cfg, "study", "cases", err, "no section [%s]", sec);
    if ((st = dfl_cfg_string(cfg, sec, "shape", &ssec, err))) return st;
    if (!dfl_cfg_has_section(cfg, ssec))
        return dfl_cfg_reject(cfg, sec, "shape", err, "no section [%s]", ssec);
    if ((st = dfl_cfg_string_opt(cfg, sec, "ref", ssec, &rsec, err))) return st;
    if (!dfl_cfg_has_section(cfg, rsec))
        return dfl_cfg_reject(cfg, sec, "ref", err, "no section [%s]", rsec);
    if ((st = dfl_shape_from_cfg(cfg, ssec, &c->shape, err))) return st;
    c->have_shape = 1;
    if (c->shape.dim != 3) return dfl_cfg_reject(cfg, sec, "shape", err, "expected a 3D shape");
    if ((st = sjp10_source_new(cfg, ssec, &c->shape, &c->src, err))) return st;
    if ((st = dfl_shape_from_cfg(cfg, rsec, &c->ref, err))) return st;
    c->have_ref = 1;
    if (c->ref.dim != 3) return dfl_cfg_reject(cfg, sec, "ref", err, "expected a 3D shape");
    if ((st = dfl_cfg_vec(cfg, sec, "lo", 3, c->lo, err))) return st;
    if ((st = dfl_cfg_vec(cfg, sec, "hi", 3, c->hi, err))) return st;
    for (int j = 0; j < 3; j++)
        if (!(c->lo[j] < c->hi[j])) return dfl_cfg_reject(cfg, sec, "hi", err, "expected hi > lo");
    if ((st = dfl_cfg_int_opt(cfg, sec, "val_n", 217, 2, 1001, &c->val_n, err))) return st;
    if ((st = dfl_cfg_bool_opt(cfg, sec, "midpoints", false, &c->midpoints, err))) return st;
    if ((st = dfl_cfg_bool_opt(cfg, sec, "cache", false, &c->cache, err))) return st;
    if ((st = dfl_cfg_bool_opt(cfg, sec, "cell_val", true, &c->cell_val, err))) return st;
    if ((st = dfl_cfg_double_opt(cfg, sec, "band", 0.0, 0.0, 1e300, &c->band, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "samples", 0, 0, 4096, &c->samples, err))) return st;
    c->own_eps = dfl_cfg_has(cfg, sec, "eps");
    if (c->own_eps && (st = read_lists(cfg, sec, "eps", NULL, &c->eps, &c->neps, err))) return st;
    c->own_levels = dfl_cfg_has(cfg, sec, "uniform_levels");
    if (c->own_levels &&
        (st = read_lists(cfg, sec, NULL, "uniform_levels", &c->levels, &c->nlevels, err)))
        return st;
    return DFL_OK;
}

static dfl_status read_keys(const dfl_cfg *cfg, void *keys, dfl_err *err)
{
    keys3 *k = keys;
    char names[SJP10_MAX_CASES][DFL_SECTION_NAME_LEN];
    dfl_status st = dfl_section_names_from_cfg(cfg, "study", "cases", SJP10_MAX_CASES, names,
                                               &k->ncases, "case section", err);
    if (st) return st;
    for (int i = 0; i < k->ncases; i++) memcpy(k->c[i].name, names[i], DFL_SECTION_NAME_LEN);
    for (int i = 0; i < k->ncases; i++)
        if ((st = read_case(cfg, &k->c[i], err))) return st;
    if ((st = sjp10_fit_from_cfg(cfg, "fit", 3, &k->fit, err))) return st;
    if ((st = read_lists(cfg, "study", "eps", NULL, &k->eps, &k->neps, err))) return st;
    if ((st = read_lists(cfg, "study", NULL, "uniform_levels", &k->levels, &k->nlevels, err))) return st;
    if ((st = sjp10_rules_from_cfg(cfg, k->rules, &k->nrules, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "uniform_samples", 1, 1, 4096, &k->uniform_samples,
                              err)))
        return st;
    k->vol_n_given = dfl_cfg_has(cfg, "output", "vti_n");
    return dfl_volume_opts_from_cfg(cfg, VOLUME_MAX_N, &k->vol, err);
}

/* The volume's nodes per axis for case c: [output] vti_n, else the case's
 * val_n up to VOLUME_MAX_N. */
static long volume_n(const keys3 *k, const case3 *c)
{
    if (k->vol_n_given) return k->vol.n;
    return c->val_n < VOLUME_MAX_N ? c->val_n : VOLUME_MAX_N;
}

/* The volume's stem of one fit: volume_<case>_pht_<rule>_<i> (i: the
 * threshold's place in the case's eps list) or volume_<case>_uniform_<level>;
 * the case's collection over its thresholds (or levels) drops the last part. */
static void volume_stem(const case3 *c, int rule, long level, size_t i, int with_index,
                        char *buf, size_t size)
{
    if (level < 0)
        snprintf(buf, size, "volume_%s_pht_%s", c->name, sjp10_rule_name(rule));
    else
        snprintf(buf, size, "volume_%s_uniform", c->name);
    const size_t l = strlen(buf);
    if (with_index) snprintf(buf + l, size - l, "_%zu", level < 0 ? i : (size_t)level);
}

/* Samples the fit's spline and the case's reference on the case's box and
 * writes the volume with the T-mesh level of the leaf holding each
 * volume cell's centre as cell data "level". */
static dfl_status write_volume(const keys3 *k, const case3 *c, const dfl_pht_fit *fit,
                               const dfl_field *f, const char *stem, const dfl_study_ctx *ctx,
                               dfl_err *err)
{
    dfl_grid g;
    dfl_volume_grid(c->lo, c->hi, volume_n(k, c), &g);
    int dims[3];
    double org[3], sp[3];
    dfl_grid_frame(&g, dims, org, sp);
    const size_t nc = dfl_vti_ncells(dims), cn = (size_t)dims[0] - 1;
    double *lev = malloc(nc * sizeof *lev);
    if (!lev) return dfl_err_set(err, DFL_E_NOMEM, "out of memory for the levels of %s", stem);
    for (size_t q = 0; q < nc; q++) {
        const size_t ijk[3] = {q % cn, q / cn % cn, q / cn / cn};
        double x[3];
        for (int a = 0; a < 3; a++) x[a] = org[a] + ((double)ijk[a] + 0.5) * sp[a];
        dfl_tmesh_cell cell;
        dfl_tmesh_cell_get(fit->mesh, dfl_tmesh_locate(fit->mesh, x, NULL), &cell);
        lev[q] = cell.level;
    }
    dfl_field ref;
    dfl_field_exact_view(&c->ref, &ref);
    const dfl_vtk_array cells[1] = {{"level", 1, lev}};
    dfl_status st = dfl_volume_write(ctx, stem, f, &ref, false, &g, cells, 1, k->vol.compress, err);
    free(lev);
    return st;
}

/* The case's collection of volumes over its n thresholds (or levels lev),
 * time = the place in the list (ParaView's time slider steps through the
 * list in the config's order). */
static dfl_status write_collection(const case3 *c, int rule, const double *lev, size_t n,
                                   const dfl_study_ctx *ctx, dfl_err *err)
{
    dfl_pvd_entry e[64];
    char names[64][DFL_SECTION_NAME_LEN + 64], stem[DFL_SECTION_NAME_LEN + 64], path[4400];
    if (n > 64) n = 64;
    for (size_t i = 0; i < n; i++) {
        volume_stem(c, rule, lev ? (long)lev[i] : -1, i, 1, stem, sizeof stem);
        if (snprintf(names[i], sizeof names[i], "%s%s.vti", stem, ctx->tag) >=
            (int)sizeof names[i])
            return dfl_err_set(err, DFL_E_INTERNAL, "volume name %s%s too long", stem, ctx->tag);
        e[i] = (dfl_pvd_entry){names[i], (double)i};
    }
    volume_stem(c, rule, lev ? 0 : -1, 0, 0, stem, sizeof stem);
    return dfl_pvd_write(dfl_study_path(ctx, stem, "pvd", path, sizeof path), e, n, err);
}

static dfl_status put_row(dfl_table *t, const case3 *c, const char *method, int rule, double eps,
                          long level, const dfl_pht_fit_opts *o, const dfl_pht_fit *fit,
                          const dfl_pht_val *v, const dfl_pht_cellval *cv, double t_val,
                          dfl_err *err)
{
    dfl_status st = dfl_table_row(t, err);
    if (!st) st = dfl_table_set_string(t, "case", c->name, err);
    if (!st) st = dfl_table_set_string(t, "method", method, err);
    if (!st) st = dfl_table_set_string(t, "rule", sjp10_rule_name(rule), err);
    if (!st) st = dfl_table_set_double(t, "eps", eps, err);
    if (!st) st = dfl_table_set_int(t, "uniform_level", level, err);
    if (!st) st = dfl_table_set_int(t, "max_level", o->max_level, err);
    if (!st) st = dfl_table_set_int(t, "samples", o->samples, err);
    if (!st) st = dfl_table_set_int(t, "grade", o->grade, err);
    if (!st) st = dfl_table_set_int(t, "peaks", o->peaks, err);
    if (!st) st = sjp10_put_fit(t, fit, cv, eps, err);
    if (!st) st = dfl_table_set_int(t, "val_n", c->val_n, err);
    if (!st) st = dfl_table_set_int(t, "midpoints", c->midpoints, err);
    if (!st) st = dfl_table_set_double(t, "band", c->band, err);
    if (!st) st = sjp10_put_val(t, "val_", v, err);
    if (!st) st = dfl_table_set_double(t, "t_val", t_val, err);
    if (!st) st = sjp10_put_cellval(t, cv, eps, err);
    return st;
}

/* What the rows of one case share (sjp10_each_fit's arg); ref NULL: the
 * errors are streamed (cache = false). */
typedef struct case_run {
    const keys3 *k;
    const case3 *c;
    const sjp10_ref *ref;
    const dfl_study_ctx *ctx;
    dfl_table *t;
} case_run;

static dfl_status one_fit(void *arg, int rule, double eps, long level, size_t idx, dfl_err *err)
{
    const case_run *a = arg;
    const keys3 *k = a->k;
    const case3 *c = a->c;
    const dfl_study_ctx *ctx = a->ctx;
    dfl_pht_fit_opts o = k->fit;
    sjp10_rule_apply(rule, &o);
    dfl_pht_cellval cv;
    memcpy(o.lo, c->lo, sizeof o.lo);
    memcpy(o.hi, c->hi, sizeof o.hi);
    if (c->samples > 0) o.samples = (int)c->samples;
    dfl_pht_fit fit;
    dfl_field f = {0};
    dfl_pht_val v;
    dfl_status st = sjp10_fit_at(c->src, c->name, &o, eps, level, k->uniform_samples, &fit, err);
    if (st) return st;
    if (c->cell_val)
        st = sjp10_cellval(fit.spline, &c->ref, c->band, level < 0 ? eps : NAN, &cv, err);
    if (!st) st = dfl_pht_field_new(&fit.spline, &f, err);
    const double t0 = omp_get_wtime();
    if (!st)
        st = a->ref ? sjp10_ref_errors(&f, a->ref, ctx->threads, &v, err)
                    : sjp10_stream_errors(&f, &c->ref, c->lo, c->hi, (int)c->val_n, c->midpoints,
                                          c->band, ctx->threads, &v, err);
    const double t_val = omp_get_wtime() - t0;
    if (!st)
        st = put_row(a->t, c, level < 0 ? "pht" : "uniform", rule, level < 0 ? eps : NAN, level,
                     &o, &fit, &v, c->cell_val ? &cv : NULL, t_val, err);
    char stem[DFL_SECTION_NAME_LEN + 64];
    volume_stem(c, rule, level, idx, 1, stem, sizeof stem);
    if (!st) st = dfl_study_put_file(a->t, "vti", ctx, stem, "vti", k->vol.vti, err);
    if (!st && k->vol.vti) st = write_volume(k, c, &fit, &f, stem, ctx, err);
    dfl_field_destroy(&f);
    dfl_pht_fit_free(&fit);
    return st;
}

static dfl_status run_case(const keys3 *k, const case3 *c, const dfl_study_ctx *ctx, dfl_table *t,
                           dfl_err *err)
{
    sjp10_ref ref = {0};
    dfl_status st = DFL_OK;
    if (c->cache)
        st = sjp10_ref_grid(&c->ref, c->lo, c->hi, (int)c->val_n, c->midpoints, c->band,
                            ctx->threads, &ref, err);
    const double *eps = c->own_eps ? c->eps : k->eps, *lev = c->own_levels ? c->levels : k->levels;
    const size_t neps = c->own_eps ? c->neps : k->neps, nlev = c->own_levels ? c->nlevels : k->nlevels;
    case_run a = {k, c, c->cache ? &ref : NULL, ctx, t};
    if (!st) st = sjp10_each_fit(k->rules, k->nrules, eps, neps, lev, nlev, one_fit, &a, err);
    for (int r = 0; r < k->nrules && !st && k->vol.vti && neps > 1; r++)
        st = write_collection(c, k->rules[r], NULL, neps, ctx, err);
    if (!st && k->vol.vti && nlev > 1) st = write_collection(c, 0, lev, nlev, ctx, err);
    sjp10_ref_free(&ref);
    return st;
}

static dfl_status run_cases(void *keys, const dfl_study_ctx *ctx, dfl_table *t, dfl_err *err)
{
    const keys3 *k = keys;
    dfl_status st = DFL_OK;
    for (int i = 0; i < k->ncases && !st; i++) st = run_case(k, &k->c[i], ctx, t, err);
    return st;
}

static const sjp10_study STUDY3 = {sizeof(keys3), read_keys, run_cases, keys_free};

static dfl_status run3d(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_table *table,
                        dfl_err *err)
{
    keys3 k;
    return sjp10_run(&STUDY3, &k, cfg, ctx, table, err);
}

/* Peak memory: a case with cache = true keeps its validation points
 * (val_n^3 nodes, plus (val_n - 1)^3 midpoints) with exact d, grad d and a
 * band flag: 57 bytes each, counted as 64; the cases run one after another,
 * so the largest counts.  Work: each case's points once at its reference
 * shape's cost class (a lower bound: without the cache every fit computes
 * them again).  The fits themselves are not estimated yet. */
/* The config's own copy of section name sec (one of its keys was read), so
 * that a dfl_cost may keep it; "study" if none. */
static const char *cfg_sec(const dfl_cfg *cfg, const char *sec)
{
    for (size_t k = 0; k < dfl_cfg_reads(cfg); k++) {
        dfl_cfg_read r;
        if (dfl_cfg_read_at(cfg, k, &r) && strcmp(r.sec, sec) == 0) return r.sec;
    }
    return "study";
}

static dfl_status estimate3d(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_cost *c,
                             dfl_err *err)
{
    (void)ctx;
    char names[SJP10_MAX_CASES][DFL_SECTION_NAME_LEN];
    int n = 0;
    dfl_status st = dfl_section_names_from_cfg(cfg, "study", "cases", SJP10_MAX_CASES, names, &n,
                                               "case section", err);
    double big = 0;
    const char *big_sec = NULL;
    long big_n = 0;
    for (int i = 0; !st && i < n; i++) {
        const char *sec = names[i], *ssec = "shape", *rsec;
        long vn;
        bool mid, cache;
        if (!dfl_cfg_has_section(cfg, sec)) continue; /* run3d names it */
        if ((st = dfl_cfg_string(cfg, sec, "shape", &ssec, err))) break;
        if ((st = dfl_cfg_string_opt(cfg, sec, "ref", ssec, &rsec, err))) break;
        if ((st = dfl_cfg_int_opt(cfg, sec, "val_n", 217, 2, 1001, &vn, err))) break;
        if ((st = dfl_cfg_bool_opt(cfg, sec, "midpoints", false, &mid, err))) break;
        if ((st = dfl_cfg_bool_opt(cfg, sec, "cache", false, &cache, err))) break;
        const double m = (double)vn * vn * vn + (mid ? (double)(vn - 1) * (vn - 1) * (vn - 1) : 0);
        if (cache && 64 * m > big) big = 64 * m, big_sec = sec, big_n = vn;
        dfl_cost_add_work(c, cfg_sec(cfg, sec), "val_n", dfl_shape_cost_class(cfg, rsec), m,
                          "%.3g validation points of [%s]", m, sec);
    }
    dfl_volume_opts vo;
    if (!st) st = dfl_volume_opts_from_cfg(cfg, VOLUME_MAX_N, &vo, err);
    if (!st && vo.vti)
        dfl_cost_add_bytes(c, "output", "vti_n", dfl_volume_bytes(vo.n, 1),
                           "a volume of %ld^3 nodes", vo.n);
    if (!st && big_sec) {
        const char *ks = cfg_sec(cfg, big_sec);
        dfl_cost_add_bytes(c, ks, strcmp(ks, "study") ? "val_n" : "cases", big,
                           "a validation cache of %ld^3 nodes in [%s]", big_n, big_sec);
    }
    return st;
}

DFL_STUDY_DEFINE_ESTIMATED(sjp10_3d, run3d, estimate3d,
                 "sjp10 3D: tricubic PHT fits of implicit surfaces and a sphere vs uniform grid and peers");
