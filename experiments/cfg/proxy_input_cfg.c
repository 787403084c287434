/* Config glue of the proxy inputs: one table row per shape kind says which
 * representations it offers; a builder per representation. */
#include "cfg/proxy_input_cfg.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "cfg/curve_cfg.h"
#include "cfg/shape_cfg.h"
#include "geom/shape.h"
#include "geom/surface_random.h"
#include "proxy/input_implicit.h"
#include "proxy/input_param.h"
#include "proxy/input_sdf.h"
#include "proxy/truth.h"

enum { IN_PARAMETRIC, IN_SDF, IN_IMPLICIT, IN_COUNT };
static const char *const input_names[IN_COUNT] = {"parametric", "sdf", "implicit"};

typedef struct input_keys {
    int input;
    dfl_proxy_curv_method curv;
    dfl_implicit_foot_method footpoint;
    dfl_curvfit_opts fit;
    int param_grid;
    int implicit_resolution;
    int param_starts;
} input_keys;

static dfl_status read_keys(const dfl_cfg *cfg, const char *sec, input_keys *k, dfl_err *err)
{
    static const char *const curvs[] = {"analytic", "fit"};
    int cv, fp;
    long g, pg;
    dfl_status st;
    if ((st = dfl_cfg_enum_opt(cfg, sec, "input", input_names, IN_COUNT, IN_SDF, &k->input,
                               err)) != DFL_OK)
        return st;
    if ((st = dfl_cfg_enum_opt(cfg, sec, "curvature", curvs, 2, 0, &cv, err)) != DFL_OK) return st;
    static const char *const fallbacks[] = {"none", "plane"};
    int fb;
    if ((st = dfl_cfg_enum_opt(cfg, sec, "curvature_fallback", fallbacks, 2, 0, &fb, err)) !=
        DFL_OK)
        return st;
    k->fit.plane_fallback = fb;
    static const char *const clamps[] = {"none", "focal"};
    int fc;
    if ((st = dfl_cfg_enum_opt(cfg, sec, "curvature_clamp", clamps, 2, 0, &fc, err)) != DFL_OK)
        return st;
    k->fit.focal_clamp = fc;
    if ((st = dfl_cfg_enum_opt(cfg, sec, "footpoint", dfl_implicit_foot_names,
                               DFL_IMPLICIT_FOOT_COUNT, DFL_IMPLICIT_FOOT_ROBUST, &fp, err)) !=
        DFL_OK)
        return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "fit_grid", 5, 3, 15, &g, err)) != DFL_OK) return st;
    /* [1e-6, 1e4]: the range of h in which the fit's (unscaled) normal
     * equations stay regular for every fit_grid 3..15; outside it the
     * design is singular, which is the input's fault */
    if ((st = dfl_cfg_double_opt(cfg, sec, "fit_spacing", 0.01, 1e-6, 1e4, &k->fit.spacing,
                                 err)) != DFL_OK)
        return st;
    if (!(k->fit.spacing > 0.0))
        return dfl_cfg_reject(cfg, sec, "fit_spacing", err, "expected a number > 0");
    if ((st = dfl_cfg_int_opt(cfg, sec, "param_grid", 16, 4, 512, &pg, err)) != DFL_OK) return st;
    long ir;
    if ((st = dfl_cfg_int_opt(cfg, sec, "implicit_resolution", 64, 8, 1024, &ir, err)) != DFL_OK)
        return st;
    k->implicit_resolution = (int)ir;
    long ps;
    if ((st = dfl_cfg_int_opt(cfg, sec, "param_starts", 3, 1, 3, &ps, err)) != DFL_OK) return st;
    k->param_starts = (int)ps;
    k->curv = cv ? DFL_PROXY_CURV_FIT : DFL_PROXY_CURV_ANALYTIC;
    k->footpoint = (dfl_implicit_foot_method)fp;
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

/* A constructor's failure, named at the shape's kind key. */
static dfl_status at_kind(const build_req *rq, dfl_status st, dfl_err *err)
{
    return st == DFL_OK ? DFL_OK : dfl_cfg_err_at(rq->cfg, rq->shape_sec, "kind", st, err);
}

static void param_opts(const build_req *rq, dfl_param_input_opts *o)
{
    dfl_param_input_opts_default(o);
    o->grid = rq->k->param_grid;
    o->starts = rq->k->param_starts;
}

/* cone: a, b, ra, rb of the shape section (ranges checked by the
 * constructors) */
static dfl_status cone_keys(const build_req *rq, double a[3], double b[3], double *ra,
                            double *rb, dfl_err *err)
{
    const dfl_cfg *cfg = rq->cfg;
    const char *sec = rq->shape_sec;
    dfl_status st;
    if ((st = dfl_cfg_vec(cfg, sec, "a", 3, a, err)) != DFL_OK) return st;
    if ((st = dfl_cfg_vec(cfg, sec, "b", 3, b, err)) != DFL_OK) return st;
    if ((st = dfl_cfg_double(cfg, sec, "ra", 0.0, HUGE_VAL, ra, err)) != DFL_OK) return st;
    return dfl_cfg_double(cfg, sec, "rb", 0.0, HUGE_VAL, rb, err);
}

/* sphere: center, radius; torus: center, axis, major, minor; cone: a, b,
 * ra, rb (the keys of experiments/cfg/shape_cfg.h; the constructors check
 * the ranges) */
static dfl_status build_param_analytic(const build_req *rq, dfl_proxy_input *out, dfl_err *err)
{
    const dfl_cfg *cfg = rq->cfg;
    const char *sec = rq->shape_sec;
    dfl_param_input_opts o;
    param_opts(rq, &o);
    double c[3], ax[3], R, r;
    dfl_status st;
    if (rq->kind == DFL_SHAPE_CONE) {
        double a[3], b[3], ra, rb;
        if ((st = cone_keys(rq, a, b, &ra, &rb, err)) != DFL_OK) return st;
        return at_kind(rq, dfl_proxy_input_param_cone(a, b, ra, rb, &o, out, err), err);
    }
    if ((st = dfl_cfg_vec(cfg, sec, "center", 3, c, err)) != DFL_OK) return st;
    if (rq->kind == DFL_SHAPE_SPHERE) {
        if ((st = dfl_cfg_double(cfg, sec, "radius", 0.0, HUGE_VAL, &r, err)) != DFL_OK) return st;
        return at_kind(rq, dfl_proxy_input_param_sphere(c, r, &o, out, err), err);
    }
    if ((st = dfl_cfg_vec(cfg, sec, "axis", 3, ax, err)) != DFL_OK) return st;
    if ((st = dfl_cfg_double(cfg, sec, "major", 0.0, HUGE_VAL, &R, err)) != DFL_OK) return st;
    if ((st = dfl_cfg_double(cfg, sec, "minor", 0.0, HUGE_VAL, &r, err)) != DFL_OK) return st;
    return at_kind(rq, dfl_proxy_input_param_torus(c, ax, R, r, &o, out, err), err);
}

/* bezier_surface / bspline_surface: the patches of experiments/cfg/
 * curve_cfg.h, or with random_seed = s (bezier_surface only) the random
 * patch of geom/surface_random.h with random_order (4), random_half (0.8),
 * random_amp (0.4). */
static dfl_status patches_from_cfg(const build_req *rq, dfl_surface_set *out, dfl_err *err)
{
    const dfl_cfg *cfg = rq->cfg;
    const char *sec = rq->shape_sec;
    dfl_surface_set set = {0};
    dfl_status st;
    if (rq->kind == DFL_SHAPE_BEZIER_SURFACE && dfl_cfg_has(cfg, sec, "random_seed")) {
        long seed, k;
        double half, amp;
        if ((st = dfl_cfg_int(cfg, sec, "random_seed", 0, 2147483647L, &seed, err)) != DFL_OK)
            return st;
        if ((st = dfl_cfg_int_opt(cfg, sec, "random_order", 4, 2, 16, &k, err)) != DFL_OK)
            return st;
        if ((st = dfl_cfg_double_opt(cfg, sec, "random_half", 0.8, 1e-300, HUGE_VAL, &half,
                                     err)) != DFL_OK)
            return st;
        if ((st = dfl_cfg_double_opt(cfg, sec, "random_amp", 0.4, 0.0, HUGE_VAL, &amp, err)) !=
            DFL_OK)
            return st;
        st = dfl_surface_random_bezier((uint64_t)seed, (int)k, half, amp, &set, err);
        if (st != DFL_OK) return dfl_cfg_err_at(cfg, sec, "random_seed", st, err);
    } else {
        st = dfl_surface_from_cfg(cfg, sec, dfl_shape_kind_name((dfl_shape_kind)rq->kind), &set,
                                  err);
        if (st != DFL_OK) return st;
    }
    *out = set;
    return DFL_OK;
}

static dfl_status build_param_patches(const build_req *rq, dfl_proxy_input *out, dfl_err *err)
{
    dfl_param_input_opts o;
    param_opts(rq, &o);
    dfl_surface_set set;
    dfl_status st = patches_from_cfg(rq, &set, err);
    if (st != DFL_OK) return st;
    return at_kind(rq, dfl_proxy_input_param_surfaces(&set, &o, out, err), err);
}

/* sphere: |q|^2 - r^2; torus: the quartic; implicit: its own surface
 * (experiments/cfg/shape_cfg.h) */
static dfl_status build_implicit(const build_req *rq, dfl_proxy_input *out, dfl_err *err)
{
    const dfl_cfg *cfg = rq->cfg;
    const char *sec = rq->shape_sec;
    dfl_implicit *imp = NULL;
    double c[3], ax[3], R, r;
    dfl_status st;
    dfl_implicit_options io;
    dfl_implicit_options_default(&io);
    io.resolution = rq->k->implicit_resolution;
    if (rq->kind == DFL_SHAPE_IMPLICIT) {
        if ((st = dfl_implicit_from_cfg(cfg, sec, &imp, err)) != DFL_OK) return st;
    } else {
        if ((st = dfl_cfg_vec(cfg, sec, "center", 3, c, err)) != DFL_OK) return st;
        if (rq->kind == DFL_SHAPE_SPHERE) {
            if ((st = dfl_cfg_double(cfg, sec, "radius", 0.0, HUGE_VAL, &r, err)) != DFL_OK)
                return st;
            st = dfl_implicit_sphere(c, r, &io, &imp, err);
        } else {
            if ((st = dfl_cfg_vec(cfg, sec, "axis", 3, ax, err)) != DFL_OK) return st;
            if ((st = dfl_cfg_double(cfg, sec, "major", 0.0, HUGE_VAL, &R, err)) != DFL_OK)
                return st;
            if ((st = dfl_cfg_double(cfg, sec, "minor", 0.0, HUGE_VAL, &r, err)) != DFL_OK)
                return st;
            st = dfl_implicit_torus(c, ax, R, r, &io, &imp, err);
        }
        if (st != DFL_OK) return at_kind(rq, st, err);
    }
    return at_kind(rq, dfl_proxy_input_implicit(&imp, rq->k->footpoint, out, err), err);
}

/* The representations of each kind ([kind][input]); NULL: not offered. */
typedef struct kind_row {
    int kind;
    input_builder b[IN_COUNT];
} kind_row;

static const kind_row rows[] = {
    {DFL_SHAPE_SPHERE, {build_param_analytic, build_sdf, build_implicit}},
    {DFL_SHAPE_TORUS, {build_param_analytic, build_sdf, build_implicit}},
    {DFL_SHAPE_IMPLICIT, {NULL, NULL, build_implicit}},
    {DFL_SHAPE_CONE, {build_param_analytic, build_sdf, NULL}},
    {DFL_SHAPE_BEZIER_SURFACE, {build_param_patches, NULL, NULL}},
    {DFL_SHAPE_BSPLINE_SURFACE, {build_param_patches, NULL, NULL}},
    {DFL_SHAPE_CYLINDER, {NULL, build_sdf, NULL}},
    {DFL_SHAPE_PLANE, {NULL, build_sdf, NULL}},
    {DFL_SHAPE_BOX, {NULL, build_sdf, NULL}},
    {DFL_SHAPE_CSG, {NULL, build_sdf, NULL}},
    {DFL_SHAPE_MESH, {NULL, build_sdf, NULL}},
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

dfl_status dfl_proxy_truth_from_cfg(const dfl_cfg *cfg, const char *field_sec,
                                    const char *shape_sec, dfl_field *out, dfl_err *err)
{
    input_keys k;
    dfl_status st = read_keys(cfg, field_sec, &k, err);
    if (st != DFL_OK) return st;
    int kind;
    if ((st = dfl_cfg_enum(cfg, shape_sec, "kind", dfl_shape_kind_names, DFL_SHAPE_KIND_COUNT,
                           &kind, err)) != DFL_OK)
        return st;
    const build_req rq = {cfg, field_sec, shape_sec, kind, &k};
    if (kind == DFL_SHAPE_BEZIER_SURFACE || kind == DFL_SHAPE_BSPLINE_SURFACE) {
        dfl_surface_set set;
        if ((st = patches_from_cfg(&rq, &set, err)) != DFL_OK) return st;
        return at_kind(&rq, dfl_proxy_truth_param(&set, 0, out, err), err);
    }
    if (kind == DFL_SHAPE_IMPLICIT) {
        dfl_implicit *imp = NULL;
        if ((st = dfl_implicit_from_cfg(cfg, shape_sec, &imp, err)) != DFL_OK) return st;
        return at_kind(&rq, dfl_proxy_truth_implicit(&imp, out, err), err);
    }
    if (kind == DFL_SHAPE_CONE && k.input == IN_PARAMETRIC) {
        double a[3], b[3], ra, rb;
        if ((st = cone_keys(&rq, a, b, &ra, &rb, err)) != DFL_OK) return st;
        return at_kind(&rq, dfl_proxy_truth_cone_lateral(a, b, ra, rb, 0, out, err), err);
    }
    dfl_shape s = {0};
    if ((st = dfl_shape_from_cfg(cfg, shape_sec, &s, err)) != DFL_OK) return st;
    st = dfl_proxy_truth_exact(&s, out, err);
    dfl_shape_free(&s);
    return at_kind(&rq, st, err);
}
