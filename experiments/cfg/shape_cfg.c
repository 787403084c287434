#include "cfg/shape_cfg.h"

#include "cfg/curve_cfg.h"
#include "geom/implicit.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* The getters name file:line and key for syntax and range errors; values
 * that parse but describe degenerate geometry (radius 0, zero axis) get a
 * message built with dfl_cfg_where so they name the key just the same. */

static dfl_status bad_value(const dfl_cfg *cfg, const char *sec, const char *key, const char *why,
                            dfl_err *err)
{
    char w[512];
    dfl_cfg_where(cfg, sec, key, w, sizeof w);
    return dfl_err_set(err, DFL_E_INPUT, "%s: %s", w, why);
}

static dfl_status get_pos(const dfl_cfg *cfg, const char *sec, const char *key, double *out,
                          dfl_err *err)
{
    dfl_status st = dfl_cfg_double(cfg, sec, key, -HUGE_VAL, HUGE_VAL, out, err);
    if (st != DFL_OK) return st;
    if (!(*out > 0.0)) {
        char why[96];
        snprintf(why, sizeof why, "expected a number > 0, got %g", *out);
        return bad_value(cfg, sec, key, why, err);
    }
    return DFL_OK;
}

static dfl_status get_nonzero_vec(const dfl_cfg *cfg, const char *sec, const char *key, int dim,
                                  double *out, dfl_err *err)
{
    dfl_status st = dfl_cfg_vec(cfg, sec, key, dim, out, err);
    if (st != DFL_OK) return st;
    double n2 = 0.0;
    for (int j = 0; j < dim; j++) n2 += out[j] * out[j];
    if (!(n2 > 0.0)) return bad_value(cfg, sec, key, "expected a non-zero vector", err);
    return DFL_OK;
}

/* Turns a constructor's message into one that names the section. */
static dfl_status ctor_fail(const dfl_cfg *cfg, const char *sec, dfl_status st, dfl_err *err)
{
    char w[512];
    dfl_cfg_where(cfg, sec, "kind", w, sizeof w);
    dfl_err_prefix(err, "%s", w);
    return st;
}

enum kind {
    K_CIRCLE, K_SPHERE, K_TORUS, K_CYLINDER, K_PLANE, K_CONE, K_BOX, K_SEGMENT,
    K_BSPLINE_CURVE, K_BSPLINE_SURFACE, K_BEZIER_SURFACE, K_IMPLICIT, K_CSG, K_COUNT
};
static const char *const kind_names[] = {
    "circle", "sphere", "torus", "cylinder", "plane", "cone", "box", "segment",
    "bspline_curve", "bspline_surface", "bezier_surface", "implicit", "csg"};

/* CSG sections name other sections; a cycle would recurse forever, and no
 * sensible model nests deeper than this. */
#define MAX_CSG_DEPTH 32

static dfl_status from_cfg(const dfl_cfg *cfg, const char *sec, int depth, dfl_shape *out,
                           dfl_err *err);

static dfl_status csg_from_cfg(const dfl_cfg *cfg, const char *sec, int depth, dfl_shape *out,
                               dfl_err *err)
{
    static const char *const ops[] = {"union", "intersection", "difference", "smooth_union",
                                      "smooth_intersection", "smooth_difference"};
    int op;
    dfl_status st = dfl_cfg_enum(cfg, sec, "op", ops, 6, &op, err);
    if (st != DFL_OK) return st;
    double k = 0.0;
    if (op >= DFL_CSG_SMOOTH_UNION && (st = get_pos(cfg, sec, "k", &k, err)) != DFL_OK) return st;
    const char *na, *nb;
    if ((st = dfl_cfg_string(cfg, sec, "a", &na, err)) != DFL_OK) return st;
    if ((st = dfl_cfg_string(cfg, sec, "b", &nb, err)) != DFL_OK) return st;
    if (depth >= MAX_CSG_DEPTH)
        return bad_value(cfg, sec, "a", "csg nesting too deep (a cycle of sections?)", err);
    if (!dfl_cfg_has_section(cfg, na)) return bad_value(cfg, sec, "a", "no such section", err);
    if (!dfl_cfg_has_section(cfg, nb)) return bad_value(cfg, sec, "b", "no such section", err);
    dfl_shape a = {0}, b = {0};
    if ((st = from_cfg(cfg, na, depth + 1, &a, err)) != DFL_OK) return st;
    if ((st = from_cfg(cfg, nb, depth + 1, &b, err)) != DFL_OK) {
        dfl_shape_free(&a);
        return st;
    }
    if ((st = dfl_shape_csg((dfl_csg_op)op, k, &a, &b, out, err)) != DFL_OK)
        return ctor_fail(cfg, sec, st, err);
    return DFL_OK;
}

/* [shape] kind = implicit: surface = torus | goursat | genus2,
 * solver = newton | ceres (default newton), resolution = sample grid nodes
 * along the longest side (default 64);
 * torus: center, axis, major, minor;
 * goursat: center (default 0 0 0), a (default 0), b (default -5),
 *          c (default 11.8; the tangle cube);
 * genus2: center (default 0 0 0), eps in (0, 0.25) (default 0.1). */
static dfl_status implicit_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_shape *out,
                                    dfl_err *err)
{
    static const char *const surfaces[] = {"torus", "goursat", "genus2"};
    static const char *const solvers[] = {"newton", "ceres"};
    int surf, solver;
    dfl_status st = dfl_cfg_enum(cfg, sec, "surface", surfaces, 3, &surf, err);
    if (st != DFL_OK) return st;
    if ((st = dfl_cfg_enum_opt(cfg, sec, "solver", solvers, 2, 0, &solver, err)) != DFL_OK)
        return st;
    dfl_implicit_options opt;
    dfl_implicit_options_default(&opt);
    opt.backend = solver == 1 ? DFL_FOOT_CERES : DFL_FOOT_NEWTON;
    long res;
    if ((st = dfl_cfg_int_opt(cfg, sec, "resolution", opt.resolution, 8, 1024, &res, err)) !=
        DFL_OK)
        return st;
    opt.resolution = (int)res;
    static const double zero[3] = {0, 0, 0};
    double c[3], ax[3], R, r, a, b, cc, eps;
    dfl_implicit *imp = NULL;
    switch (surf) {
    case 0:
        if ((st = dfl_cfg_vec(cfg, sec, "center", 3, c, err)) != DFL_OK) return st;
        if ((st = get_nonzero_vec(cfg, sec, "axis", 3, ax, err)) != DFL_OK) return st;
        if ((st = get_pos(cfg, sec, "major", &R, err)) != DFL_OK) return st;
        if ((st = get_pos(cfg, sec, "minor", &r, err)) != DFL_OK) return st;
        if (!(r < R)) return bad_value(cfg, sec, "minor", "expected minor < major", err);
        st = dfl_implicit_torus(c, ax, R, r, &opt, &imp, err);
        break;
    case 1:
        if ((st = dfl_cfg_vec_opt(cfg, sec, "center", 3, zero, c, err)) != DFL_OK) return st;
        if ((st = dfl_cfg_double_opt(cfg, sec, "a", 0.0, -HUGE_VAL, HUGE_VAL, &a, err)) != DFL_OK)
            return st;
        if (!(a > -1.0 / 3.0)) return bad_value(cfg, sec, "a", "expected a > -1/3", err);
        if ((st = dfl_cfg_double_opt(cfg, sec, "b", -5.0, -HUGE_VAL, HUGE_VAL, &b, err)) != DFL_OK)
            return st;
        if ((st = dfl_cfg_double_opt(cfg, sec, "c", 11.8, -HUGE_VAL, HUGE_VAL, &cc, err)) !=
            DFL_OK)
            return st;
        st = dfl_implicit_goursat(c, a, b, cc, &opt, &imp, err);
        break;
    default:
        if ((st = dfl_cfg_vec_opt(cfg, sec, "center", 3, zero, c, err)) != DFL_OK) return st;
        if ((st = dfl_cfg_double_opt(cfg, sec, "eps", 0.1, -HUGE_VAL, HUGE_VAL, &eps, err)) !=
            DFL_OK)
            return st;
        if (!(eps > 0.0 && eps < 0.25))
            return bad_value(cfg, sec, "eps", "expected 0 < eps < 0.25", err);
        st = dfl_implicit_genus2(c, eps, &opt, &imp, err);
        break;
    }
    if (st == DFL_OK) st = dfl_implicit_shape(&imp, out, err);
    if (st != DFL_OK) return ctor_fail(cfg, sec, st, err);
    return DFL_OK;
}

static dfl_status get_dim(const dfl_cfg *cfg, const char *sec, long def, int *dim, dfl_err *err)
{
    long d;
    dfl_status st = dfl_cfg_int_opt(cfg, sec, "dim", def, 2, 3, &d, err);
    *dim = (int)d;
    return st;
}

static dfl_status from_cfg(const dfl_cfg *cfg, const char *sec, int depth, dfl_shape *out,
                           dfl_err *err)
{
    int kind;
    dfl_status st = dfl_cfg_enum(cfg, sec, "kind", kind_names, K_COUNT, &kind, err);
    if (st != DFL_OK) return st;
    double c[3], c2[3], ax[3], r, R;
    int dim;
    switch (kind) {
    case K_CIRCLE:
    case K_SPHERE:
        dim = kind == K_CIRCLE ? 2 : 3;
        if ((st = dfl_cfg_vec(cfg, sec, "center", dim, c, err)) != DFL_OK) return st;
        if ((st = get_pos(cfg, sec, "radius", &r, err)) != DFL_OK) return st;
        st = dim == 2 ? dfl_shape_circle(c, r, out, err) : dfl_shape_sphere(c, r, out, err);
        break;
    case K_TORUS:
        if ((st = dfl_cfg_vec(cfg, sec, "center", 3, c, err)) != DFL_OK) return st;
        if ((st = get_nonzero_vec(cfg, sec, "axis", 3, ax, err)) != DFL_OK) return st;
        if ((st = get_pos(cfg, sec, "major", &R, err)) != DFL_OK) return st;
        if ((st = get_pos(cfg, sec, "minor", &r, err)) != DFL_OK) return st;
        if (!(r < R)) return bad_value(cfg, sec, "minor", "expected minor < major", err);
        st = dfl_shape_torus(c, ax, R, r, out, err);
        break;
    case K_CYLINDER:
        if ((st = dfl_cfg_vec(cfg, sec, "center", 3, c, err)) != DFL_OK) return st;
        if ((st = get_nonzero_vec(cfg, sec, "axis", 3, ax, err)) != DFL_OK) return st;
        if ((st = get_pos(cfg, sec, "radius", &r, err)) != DFL_OK) return st;
        st = dfl_shape_cylinder(c, ax, r, out, err);
        break;
    case K_PLANE:
        if ((st = get_dim(cfg, sec, 3, &dim, err)) != DFL_OK) return st;
        if ((st = dfl_cfg_vec(cfg, sec, "point", dim, c, err)) != DFL_OK) return st;
        if ((st = get_nonzero_vec(cfg, sec, "normal", dim, ax, err)) != DFL_OK) return st;
        st = dfl_shape_plane(dim, c, ax, out, err);
        break;
    case K_CONE:
        if ((st = dfl_cfg_vec(cfg, sec, "a", 3, c, err)) != DFL_OK) return st;
        if ((st = dfl_cfg_vec(cfg, sec, "b", 3, c2, err)) != DFL_OK) return st;
        if ((st = dfl_cfg_double(cfg, sec, "ra", 0.0, HUGE_VAL, &R, err)) != DFL_OK) return st;
        if ((st = dfl_cfg_double(cfg, sec, "rb", 0.0, HUGE_VAL, &r, err)) != DFL_OK) return st;
        if (!(R + r > 0.0)) return bad_value(cfg, sec, "rb", "ra and rb are both 0", err);
        if (c[0] == c2[0] && c[1] == c2[1] && c[2] == c2[2])
            return bad_value(cfg, sec, "b", "a and b coincide", err);
        st = dfl_shape_cone(c, c2, R, r, out, err);
        break;
    case K_BOX:
        if ((st = get_dim(cfg, sec, 3, &dim, err)) != DFL_OK) return st;
        if ((st = dfl_cfg_vec(cfg, sec, "center", dim, c, err)) != DFL_OK) return st;
        if ((st = dfl_cfg_vec(cfg, sec, "half", dim, c2, err)) != DFL_OK) return st;
        for (int j = 0; j < dim; j++)
            if (!(c2[j] > 0.0)) return bad_value(cfg, sec, "half", "expected all > 0", err);
        st = dfl_shape_box(dim, c, c2, out, err);
        break;
    case K_SEGMENT:
        if ((st = get_dim(cfg, sec, 2, &dim, err)) != DFL_OK) return st;
        if ((st = dfl_cfg_vec(cfg, sec, "a", dim, c, err)) != DFL_OK) return st;
        if ((st = dfl_cfg_vec(cfg, sec, "b", dim, c2, err)) != DFL_OK) return st;
        st = dfl_shape_segment(dim, c, c2, out, err);
        break;
    case K_BSPLINE_CURVE:
    case K_BSPLINE_SURFACE:
    case K_BEZIER_SURFACE:
        /* the curves module reports its own keys */
        return dfl_param_shape_from_cfg(cfg, sec, kind_names[kind], out, err);
    case K_IMPLICIT:
        return implicit_from_cfg(cfg, sec, out, err);
    case K_CSG:
        return csg_from_cfg(cfg, sec, depth, out, err);
    default:
        return dfl_err_set(err, DFL_E_INTERNAL, "shape kind %d not handled", kind);
    }
    if (st != DFL_OK) return ctor_fail(cfg, sec, st, err);
    return DFL_OK;
}

dfl_status dfl_shape_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_shape *out, dfl_err *err)
{
    return from_cfg(cfg, sec, 0, out, err);
}
