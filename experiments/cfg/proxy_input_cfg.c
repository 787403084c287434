/* Config glue of the proxy inputs: one table row per shape kind says which
 * representations it offers; a builder per representation. */
#include "cfg/proxy_input_cfg.h"

#include <stdio.h>
#include <string.h>

#include "cfg/shape_cfg.h"
#include "geom/shape.h"
#include "proxy/input_sdf.h"

enum { IN_PARAMETRIC, IN_SDF, IN_IMPLICIT, IN_COUNT };
static const char *const input_names[IN_COUNT] = {"parametric", "sdf", "implicit"};

typedef struct input_keys {
    int input;
    dfl_proxy_curv_method curv;
    int footpoint_robust;
    dfl_curvfit_opts fit;
    int param_grid;
} input_keys;

static dfl_status read_keys(const dfl_cfg *cfg, const char *sec, input_keys *k, dfl_err *err)
{
    static const char *const curvs[] = {"analytic", "fit"};
    static const char *const foots[] = {"paper", "robust"};
    int cv, fp;
    long g, pg;
    dfl_status st;
    if ((st = dfl_cfg_enum_opt(cfg, sec, "input", input_names, IN_COUNT, IN_SDF, &k->input,
                               err)) != DFL_OK)
        return st;
    if ((st = dfl_cfg_enum_opt(cfg, sec, "curvature", curvs, 2, 0, &cv, err)) != DFL_OK) return st;
    if ((st = dfl_cfg_enum_opt(cfg, sec, "footpoint", foots, 2, 1, &fp, err)) != DFL_OK) return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "fit_grid", 5, 3, 15, &g, err)) != DFL_OK) return st;
    if ((st = dfl_cfg_double_opt(cfg, sec, "fit_spacing", 0.01, 0.0, 1e300, &k->fit.spacing,
                                 err)) != DFL_OK)
        return st;
    if (!(k->fit.spacing > 0.0))
        return dfl_cfg_reject(cfg, sec, "fit_spacing", err, "expected a number > 0");
    if ((st = dfl_cfg_int_opt(cfg, sec, "param_grid", 16, 4, 512, &pg, err)) != DFL_OK) return st;
    k->curv = cv ? DFL_PROXY_CURV_FIT : DFL_PROXY_CURV_ANALYTIC;
    k->footpoint_robust = fp;
    k->fit.g = (int)g;
    k->param_grid = (int)pg;
    return DFL_OK;
}

/* What the builders are handed. */
typedef struct build_req {
    const dfl_cfg *cfg;
    const char *field_sec, *shape_sec;
    int kind;
    const input_keys *k;
} build_req;

typedef dfl_status (*input_builder)(const build_req *rq, dfl_proxy_input *out, dfl_err *err);

static dfl_status build_sdf(const build_req *rq, dfl_proxy_input *out, dfl_err *err)
{
    dfl_shape s = {0};
    dfl_status st = dfl_shape_from_cfg(rq->cfg, rq->shape_sec, &s, err);
    if (st != DFL_OK) return st;
    st = dfl_proxy_input_sdf(&s, rq->k->curv, &rq->k->fit, out, err);
    return st == DFL_OK ? DFL_OK : dfl_cfg_err_at(rq->cfg, rq->field_sec, "input", st, err);
}

/* The representations of each kind ([kind][input]); NULL: not offered. */
typedef struct kind_row {
    int kind;
    input_builder b[IN_COUNT];
} kind_row;

static const kind_row rows[] = {
    {DFL_SHAPE_SPHERE, {NULL, build_sdf, NULL}},
    {DFL_SHAPE_TORUS, {NULL, build_sdf, NULL}},
    {DFL_SHAPE_CONE, {NULL, build_sdf, NULL}},
    {DFL_SHAPE_CYLINDER, {NULL, build_sdf, NULL}},
    {DFL_SHAPE_PLANE, {NULL, build_sdf, NULL}},
    {DFL_SHAPE_BOX, {NULL, build_sdf, NULL}},
    {DFL_SHAPE_CSG, {NULL, build_sdf, NULL}},
};

static const kind_row *row_of(int kind)
{
    for (size_t r = 0; r < sizeof rows / sizeof *rows; r++)
        if (rows[r].kind == kind) return &rows[r];
    return NULL;
}

dfl_status dfl_proxy_input_from_cfg(const dfl_cfg *cfg, const char *field_sec,
                                    const char *shape_sec, dfl_proxy_input *out, dfl_err *err)
{
    input_keys k;
    dfl_status st = read_keys(cfg, field_sec, &k, err);
    if (st != DFL_OK) return st;
    int kind;
    if ((st = dfl_cfg_enum(cfg, shape_sec, "kind", dfl_shape_kind_names, DFL_SHAPE_KIND_COUNT,
                           &kind, err)) != DFL_OK)
        return st;
    const kind_row *row = row_of(kind);
    if (!row || !row->b[k.input]) {
        char offers[64] = "";
        for (int i = 0; row && i < IN_COUNT; i++)
            if (row->b[i]) {
                if (offers[0]) strcat(offers, ", ");
                strcat(offers, input_names[i]);
            }
        return dfl_cfg_reject(cfg, field_sec, "input", err,
                              "[%s] kind = %s has no %s representation (it offers: %s)",
                              shape_sec, dfl_shape_kind_name((dfl_shape_kind)kind),
                              input_names[k.input], offers[0] ? offers : "none");
    }
    const build_req rq = {cfg, field_sec, shape_sec, kind, &k};
    return row->b[k.input](&rq, out, err);
}
