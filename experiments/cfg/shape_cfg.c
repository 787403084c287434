#include "cfg/shape_cfg.h"

#include "cfg/curve_cfg.h"
#include "geom/ellipse.h"
#include "field/isomesh.h"
#include "geom/implicit.h"
#include "geom/mesh.h"
#include "geom/trimesh.h"

#include <math.h>
#include <stdbool.h>

#include "core/domain.h"
#include <stdio.h>
#include <string.h>

/* The getters name file:line and key for syntax and range errors; values
 * that parse but describe degenerate geometry (radius 0, zero axis) are
 * rejected with dfl_cfg_reject, so they name the key just the same. */

static dfl_status get_pos(const dfl_cfg *cfg, const char *sec, const char *key, double *out,
                          dfl_err *err)
{
    dfl_status st = dfl_cfg_double(cfg, sec, key, -DFL_COORD_MAX, DFL_COORD_MAX, out, err);
    if (st != DFL_OK) return st;
    if (!(*out > 0.0))
        return dfl_cfg_reject(cfg, sec, key, err, "expected a number > 0, got %g", *out);
    return DFL_OK;
}

static dfl_status get_nonzero_vec(const dfl_cfg *cfg, const char *sec, const char *key, int dim,
                                  double *out, dfl_err *err)
{
    dfl_status st = dfl_cfg_vec(cfg, sec, key, dim, out, err);
    if (st != DFL_OK) return st;
    double n2 = 0.0;
    for (int j = 0; j < dim; j++) n2 += out[j] * out[j];
    if (!(n2 > 0.0)) return dfl_cfg_reject(cfg, sec, key, err, "expected a non-zero vector");
    return DFL_OK;
}

/* A constructor's status, its message naming the section (its kind key)
 * on failure. */
static dfl_status ctor_result(const dfl_cfg *cfg, const char *sec, dfl_status st, dfl_err *err)
{
    return st == DFL_OK ? DFL_OK : dfl_cfg_err_at(cfg, sec, "kind", st, err);
}

static dfl_status get_dim(const dfl_cfg *cfg, const char *sec, long def, int *dim, dfl_err *err)
{
    long d;
    dfl_status st = dfl_cfg_int_opt(cfg, sec, "dim", def, 2, 3, &d, err);
    *dim = (int)d;
    return st;
}

/* ---- one parser per kind ------------------------------------------------ */

/* What a kind's parser is asked to build: section sec of cfg, of the given
 * kind, at CSG nesting depth (0 at the top). */
typedef struct shape_req {
    const dfl_cfg *cfg;
    const char *sec;
    dfl_shape_kind kind;
    int depth;
} shape_req;

/* CSG sections name other sections; a cycle would recurse forever, and no
 * sensible model nests deeper than this. */
#define MAX_CSG_DEPTH 32

static dfl_status from_cfg(const dfl_cfg *cfg, const char *sec, int depth, dfl_shape *out,
                           dfl_err *err);

static dfl_status csg_from_cfg(const shape_req *rq, dfl_shape *out, dfl_err *err)
{
    const dfl_cfg *cfg = rq->cfg;
    const char *sec = rq->sec;
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
    if (rq->depth >= MAX_CSG_DEPTH)
        return dfl_cfg_reject(cfg, sec, "a", err, "csg nesting too deep (a cycle of sections?)");
    if (!dfl_cfg_has_section(cfg, na)) return dfl_cfg_reject(cfg, sec, "a", err, "no such section");
    if (!dfl_cfg_has_section(cfg, nb)) return dfl_cfg_reject(cfg, sec, "b", err, "no such section");
    dfl_shape a = {0}, b = {0};
    if ((st = from_cfg(cfg, na, rq->depth + 1, &a, err)) != DFL_OK) return st;
    if ((st = from_cfg(cfg, nb, rq->depth + 1, &b, err)) != DFL_OK) {
        dfl_shape_free(&a);
        return st;
    }
    return ctor_result(cfg, sec, dfl_shape_csg((dfl_csg_op)op, k, &a, &b, out, err), err);
}

/* The torus keys shared by kind = torus and the implicit torus: center,
 * axis (non-zero), major > 0, minor in (0, major). */
static dfl_status torus_keys(const dfl_cfg *cfg, const char *sec, double c[3], double ax[3],
                             double *R, double *r, dfl_err *err)
{
    dfl_status st;
    if ((st = dfl_cfg_vec(cfg, sec, "center", 3, c, err)) != DFL_OK) return st;
    if ((st = get_nonzero_vec(cfg, sec, "axis", 3, ax, err)) != DFL_OK) return st;
    if ((st = get_pos(cfg, sec, "major", R, err)) != DFL_OK) return st;
    if ((st = get_pos(cfg, sec, "minor", r, err)) != DFL_OK) return st;
    if (!(*r < *R)) return dfl_cfg_reject(cfg, sec, "minor", err, "expected minor < major");
    return DFL_OK;
}

/* [shape] kind = implicit: surface = torus | goursat | genus2 | sphere | ellipsoid,
 * solver = newton | ceres (default newton), resolution = sample grid nodes
 * along the longest side (default 64);
 * torus: center, axis, major, minor;
 * goursat: center (default 0 0 0), a (default 0), b (default -5),
 *          c (default 11.8; the tangle cube);
 * genus2: center (default 0 0 0), eps in (0, 0.25) (default 0.1);
 * sphere: center, radius (the polynomial |q|^2 - r^2);
 * ellipsoid: center (default 0 0 0), semi = a b c (> 0), scramble = k >= 0
 *          (default 4; geom/implicit.h's positive factor). */
dfl_status dfl_implicit_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_implicit **out,
                                 dfl_err *err)
{
    static const char *const surfaces[] = {"torus", "goursat", "genus2", "sphere", "ellipsoid"};
    static const char *const solvers[] = {"newton", "ceres"};
    int surf, solver;
    dfl_status st = dfl_cfg_enum(cfg, sec, "surface", surfaces, 5, &surf, err);
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
        if ((st = torus_keys(cfg, sec, c, ax, &R, &r, err)) != DFL_OK) return st;
        st = dfl_implicit_torus(c, ax, R, r, &opt, &imp, err);
        break;
    case 1:
        if ((st = dfl_cfg_vec_opt(cfg, sec, "center", 3, zero, c, err)) != DFL_OK) return st;
        if ((st = dfl_cfg_double_opt(cfg, sec, "a", 0.0, -DFL_COORD_MAX, DFL_COORD_MAX, &a, err)) != DFL_OK)
            return st;
        if (!(a > -1.0 / 3.0)) return dfl_cfg_reject(cfg, sec, "a", err, "expected a > -1/3");
        if ((st = dfl_cfg_double_opt(cfg, sec, "b", -5.0, -DFL_COORD_MAX, DFL_COORD_MAX, &b, err)) != DFL_OK)
            return st;
        if ((st = dfl_cfg_double_opt(cfg, sec, "c", 11.8, -DFL_COORD_MAX, DFL_COORD_MAX, &cc, err)) !=
            DFL_OK)
            return st;
        st = dfl_implicit_goursat(c, a, b, cc, &opt, &imp, err);
        break;
    case 3:
        if ((st = dfl_cfg_vec(cfg, sec, "center", 3, c, err)) != DFL_OK) return st;
        if ((st = get_pos(cfg, sec, "radius", &r, err)) != DFL_OK) return st;
        st = dfl_implicit_sphere(c, r, &opt, &imp, err);
        break;
    case 4: {
        double semi[3], k;
        if ((st = dfl_cfg_vec_opt(cfg, sec, "center", 3, zero, c, err)) != DFL_OK) return st;
        if ((st = dfl_cfg_vec(cfg, sec, "semi", 3, semi, err)) != DFL_OK) return st;
        for (int j = 0; j < 3; j++)
            if (!(semi[j] > 0.0)) return dfl_cfg_reject(cfg, sec, "semi", err, "expected all > 0");
        if ((st = dfl_cfg_double_opt(cfg, sec, "scramble", 4.0, 0.0, HUGE_VAL, &k, err)) != DFL_OK)
            return st;
        st = dfl_implicit_ellipsoid(c, semi, k, &opt, &imp, err);
        break;
    }
    default:
        if ((st = dfl_cfg_vec_opt(cfg, sec, "center", 3, zero, c, err)) != DFL_OK) return st;
        if ((st = dfl_cfg_double_opt(cfg, sec, "eps", 0.1, -DFL_COORD_MAX, DFL_COORD_MAX, &eps, err)) !=
            DFL_OK)
            return st;
        if (!(eps > 0.0 && eps < 0.25))
            return dfl_cfg_reject(cfg, sec, "eps", err, "expected 0 < eps < 0.25");
        st = dfl_implicit_genus2(c, eps, &opt, &imp, err);
        break;
    }
    if (st == DFL_OK) *out = imp;
    return ctor_result(cfg, sec, st, err);
}

static dfl_status implicit_from_cfg(const shape_req *rq, dfl_shape *out, dfl_err *err)
{
    dfl_implicit *imp = NULL;
    dfl_status st = dfl_implicit_from_cfg(rq->cfg, rq->sec, &imp, err);
    if (st == DFL_OK) st = ctor_result(rq->cfg, rq->sec, dfl_implicit_shape(&imp, out, err), err);
    return st;
}

/* circle, sphere: center, radius */
static dfl_status ball_from_cfg(const shape_req *rq, dfl_shape *out, dfl_err *err)
{
    const dfl_cfg *cfg = rq->cfg;
    const char *sec = rq->sec;
    const int dim = rq->kind == DFL_SHAPE_CIRCLE ? 2 : 3;
    double c[3], r;
    dfl_status st;
    if ((st = dfl_cfg_vec(cfg, sec, "center", dim, c, err)) != DFL_OK) return st;
    if ((st = get_pos(cfg, sec, "radius", &r, err)) != DFL_OK) return st;
    st = dim == 2 ? dfl_shape_circle(c, r, out, err) : dfl_shape_sphere(c, r, out, err);
    return ctor_result(cfg, sec, st, err);
}

static dfl_status torus_from_cfg(const shape_req *rq, dfl_shape *out, dfl_err *err)
{
    const dfl_cfg *cfg = rq->cfg;
    const char *sec = rq->sec;
    double c[3], ax[3], R, r;
    dfl_status st = torus_keys(cfg, sec, c, ax, &R, &r, err);
    if (st != DFL_OK) return st;
    return ctor_result(cfg, sec, dfl_shape_torus(c, ax, R, r, out, err), err);
}

static dfl_status cylinder_from_cfg(const shape_req *rq, dfl_shape *out, dfl_err *err)
{
    const dfl_cfg *cfg = rq->cfg;
    const char *sec = rq->sec;
    double c[3], ax[3], r;
    dfl_status st;
    if ((st = dfl_cfg_vec(cfg, sec, "center", 3, c, err)) != DFL_OK) return st;
    if ((st = get_nonzero_vec(cfg, sec, "axis", 3, ax, err)) != DFL_OK) return st;
    if ((st = get_pos(cfg, sec, "radius", &r, err)) != DFL_OK) return st;
    return ctor_result(cfg, sec, dfl_shape_cylinder(c, ax, r, out, err), err);
}

static dfl_status plane_from_cfg(const shape_req *rq, dfl_shape *out, dfl_err *err)
{
    const dfl_cfg *cfg = rq->cfg;
    const char *sec = rq->sec;
    double c[3], n[3];
    int dim;
    dfl_status st;
    if ((st = get_dim(cfg, sec, 3, &dim, err)) != DFL_OK) return st;
    if ((st = dfl_cfg_vec(cfg, sec, "point", dim, c, err)) != DFL_OK) return st;
    if ((st = get_nonzero_vec(cfg, sec, "normal", dim, n, err)) != DFL_OK) return st;
    return ctor_result(cfg, sec, dfl_shape_plane(dim, c, n, out, err), err);
}

static dfl_status cone_from_cfg(const shape_req *rq, dfl_shape *out, dfl_err *err)
{
    const dfl_cfg *cfg = rq->cfg;
    const char *sec = rq->sec;
    double a[3], b[3], ra, rb;
    dfl_status st;
    if ((st = dfl_cfg_vec(cfg, sec, "a", 3, a, err)) != DFL_OK) return st;
    if ((st = dfl_cfg_vec(cfg, sec, "b", 3, b, err)) != DFL_OK) return st;
    if ((st = dfl_cfg_double(cfg, sec, "ra", 0.0, DFL_COORD_MAX, &ra, err)) != DFL_OK) return st;
    if ((st = dfl_cfg_double(cfg, sec, "rb", 0.0, DFL_COORD_MAX, &rb, err)) != DFL_OK) return st;
    if (!(ra + rb > 0.0)) return dfl_cfg_reject(cfg, sec, "rb", err, "ra and rb are both 0");
    if (a[0] == b[0] && a[1] == b[1] && a[2] == b[2])
        return dfl_cfg_reject(cfg, sec, "b", err, "a and b coincide");
    return ctor_result(cfg, sec, dfl_shape_cone(a, b, ra, rb, out, err), err);
}

static dfl_status box_from_cfg(const shape_req *rq, dfl_shape *out, dfl_err *err)
{
    const dfl_cfg *cfg = rq->cfg;
    const char *sec = rq->sec;
    double c[3], h[3];
    int dim;
    dfl_status st;
    if ((st = get_dim(cfg, sec, 3, &dim, err)) != DFL_OK) return st;
    if ((st = dfl_cfg_vec(cfg, sec, "center", dim, c, err)) != DFL_OK) return st;
    if ((st = dfl_cfg_vec(cfg, sec, "half", dim, h, err)) != DFL_OK) return st;
    for (int j = 0; j < dim; j++)
        if (!(h[j] > 0.0)) return dfl_cfg_reject(cfg, sec, "half", err, "expected all > 0");
    return ctor_result(cfg, sec, dfl_shape_box(dim, c, h, out, err), err);
}

static dfl_status segment_from_cfg(const shape_req *rq, dfl_shape *out, dfl_err *err)
{
    const dfl_cfg *cfg = rq->cfg;
    const char *sec = rq->sec;
    double a[3], b[3];
    int dim;
    dfl_status st;
    if ((st = get_dim(cfg, sec, 2, &dim, err)) != DFL_OK) return st;
    if ((st = dfl_cfg_vec(cfg, sec, "a", dim, a, err)) != DFL_OK) return st;
    if ((st = dfl_cfg_vec(cfg, sec, "b", dim, b, err)) != DFL_OK) return st;
    return ctor_result(cfg, sec, dfl_shape_segment(dim, a, b, out, err), err);
}

/* ellipse: center = x y, a = semi-axis along x > 0, b = along y > 0 */
static dfl_status ellipse_from_cfg(const shape_req *rq, dfl_shape *out, dfl_err *err)
{
    const dfl_cfg *cfg = rq->cfg;
    const char *sec = rq->sec;
    double c[2], a, b;
    dfl_status st;
    if ((st = dfl_cfg_vec(cfg, sec, "center", 2, c, err)) != DFL_OK) return st;
    if ((st = get_pos(cfg, sec, "a", &a, err)) != DFL_OK) return st;
    if ((st = get_pos(cfg, sec, "b", &b, err)) != DFL_OK) return st;
    return ctor_result(cfg, sec, dfl_shape_ellipse(c, a, b, out, err), err);
}

/* bspline_curve, bspline_surface, bezier_surface: the curves module reads
 * (and reports) its own keys */
static dfl_status param_from_cfg(const shape_req *rq, dfl_shape *out, dfl_err *err)
{
    const dfl_cfg *cfg = rq->cfg;
    const char *sec = rq->sec;
    return dfl_param_shape_from_cfg(cfg, sec, dfl_shape_kind_name(rq->kind), out, err);
}

/* mesh: file = PATH | polygonize = SECTION (+ resolution, box, refine),
 * fit = none | box (+ center, size), distance = signed | unsigned (see
 * shape_cfg.h) */
static dfl_status mesh_source(const shape_req *rq, dfl_trimesh *m, dfl_err *err)
{
    const dfl_cfg *cfg = rq->cfg;
    const char *sec = rq->sec;
    const bool has_file = dfl_cfg_has(cfg, sec, "file"), has_poly = dfl_cfg_has(cfg, sec, "polygonize");
    dfl_status st;
    if (has_file == has_poly)
        return dfl_cfg_reject(cfg, sec, "kind", err,
                              "a mesh needs exactly one of file = PATH or polygonize = SECTION");
    if (has_file) {
        char path[4096];
        if ((st = dfl_cfg_path_value(cfg, sec, "file", path, sizeof path, err)) != DFL_OK)
            return st;
        if ((st = dfl_trimesh_read(path, m, err)) != DFL_OK)
            return dfl_cfg_err_at(cfg, sec, "file", st, err);
        return DFL_OK;
    }
    const char *src;
    if ((st = dfl_cfg_string(cfg, sec, "polygonize", &src, err)) != DFL_OK) return st;
    if (rq->depth >= MAX_CSG_DEPTH)
        return dfl_cfg_reject(cfg, sec, "polygonize", err, "nesting too deep (a cycle of sections?)");
    if (!dfl_cfg_has_section(cfg, src))
        return dfl_cfg_reject(cfg, sec, "polygonize", err, "no such section");
    long n, refine;
    double lo[3], hi[3];
    static const double mone[3] = {-1, -1, -1}, one[3] = {1, 1, 1};
    if ((st = dfl_cfg_int_opt(cfg, sec, "resolution", 96, 8, 1024, &n, err)) != DFL_OK) return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "refine", 8, 0, 100, &refine, err)) != DFL_OK) return st;
    if ((st = dfl_cfg_vec_opt(cfg, sec, "lo", 3, mone, lo, err)) != DFL_OK) return st;
    if ((st = dfl_cfg_vec_opt(cfg, sec, "hi", 3, one, hi, err)) != DFL_OK) return st;
    double ext = 0.0;
    for (int j = 0; j < 3; j++) {
        if (!(hi[j] > lo[j])) return dfl_cfg_reject(cfg, sec, "hi", err, "expected hi > lo on every axis");
        ext = fmax(ext, hi[j] - lo[j]);
    }
    /* equal spacing on every axis: n nodes along the longest side */
    dfl_grid g = {3, {0, 0, 0}, {lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}};
    for (int j = 0; j < 3; j++)
        g.n[j] = (int)fmax(2.0, ceil((hi[j] - lo[j]) / ext * (double)(n - 1)) + 1.0);
    dfl_shape inner = {0};
    if ((st = from_cfg(cfg, src, rq->depth + 1, &inner, err)) != DFL_OK) return st;
    if (inner.dim != 3) {
        dfl_shape_free(&inner);
        return dfl_cfg_reject(cfg, sec, "polygonize", err, "[%s] is not a 3D shape", src);
    }
    st = dfl_shape_isomesh(&inner, &g, (int)refine, 0, m, NULL, err);
    dfl_shape_free(&inner);
    return st == DFL_OK ? DFL_OK : dfl_cfg_err_at(cfg, sec, "polygonize", st, err);
}

static dfl_status mesh_from_cfg(const shape_req *rq, dfl_shape *out, dfl_err *err)
{
    const dfl_cfg *cfg = rq->cfg;
    const char *sec = rq->sec;
    static const char *const fits[] = {"none", "box"};
    static const char *const dists[] = {"signed", "unsigned"};
    int fit, dist;
    double center[3], size;
    static const double zero[3] = {0, 0, 0};
    dfl_status st;
    if ((st = dfl_cfg_enum_opt(cfg, sec, "distance", dists, 2, 0, &dist, err)) != DFL_OK) return st;
    if ((st = dfl_cfg_enum_opt(cfg, sec, "fit", fits, 2, 0, &fit, err)) != DFL_OK) return st;
    if (fit == 1) {
        if ((st = dfl_cfg_vec_opt(cfg, sec, "center", 3, zero, center, err)) != DFL_OK) return st;
        if ((st = dfl_cfg_double_opt(cfg, sec, "size", 1.6, 0.0, DFL_COORD_MAX, &size, err)) !=
            DFL_OK)
            return st;
        if (!(size > 0.0)) return dfl_cfg_reject(cfg, sec, "size", err, "expected a number > 0");
    } else if (dfl_cfg_has(cfg, sec, "center") || dfl_cfg_has(cfg, sec, "size")) {
        const char *k = dfl_cfg_has(cfg, sec, "center") ? "center" : "size";
        return dfl_cfg_reject(cfg, sec, k, err, "only read with fit = box");
    }
    dfl_trimesh m;
    if ((st = mesh_source(rq, &m, err)) != DFL_OK) return st;
    if (fit == 1) dfl_trimesh_fit(&m, center, size);
    st = dfl_shape_mesh(&m, dist == 0 ? DFL_MESH_SIGNED : DFL_MESH_UNSIGNED, out, err);
    if (st != DFL_OK) {
        dfl_trimesh_free(&m);
        return dfl_cfg_err_at(cfg, sec, dfl_cfg_has(cfg, sec, "file") ? "file" : "polygonize", st,
                              err);
    }
    return DFL_OK;
}

/* ---- the table: one parser per kind of geom/shape.h's DFL_SHAPE_KIND_LIST ---- */

typedef dfl_status (*shape_parser)(const shape_req *rq, dfl_shape *out, dfl_err *err);

static const shape_parser parsers[DFL_SHAPE_KIND_COUNT] = {
    [DFL_SHAPE_CIRCLE] = ball_from_cfg,
    [DFL_SHAPE_SPHERE] = ball_from_cfg,
    [DFL_SHAPE_TORUS] = torus_from_cfg,
    [DFL_SHAPE_CYLINDER] = cylinder_from_cfg,
    [DFL_SHAPE_PLANE] = plane_from_cfg,
    [DFL_SHAPE_CONE] = cone_from_cfg,
    [DFL_SHAPE_BOX] = box_from_cfg,
    [DFL_SHAPE_SEGMENT] = segment_from_cfg,
    [DFL_SHAPE_ELLIPSE] = ellipse_from_cfg,
    [DFL_SHAPE_BSPLINE_CURVE] = param_from_cfg,
    [DFL_SHAPE_BSPLINE_SURFACE] = param_from_cfg,
    [DFL_SHAPE_BEZIER_SURFACE] = param_from_cfg,
    [DFL_SHAPE_IMPLICIT] = implicit_from_cfg,
    [DFL_SHAPE_CSG] = csg_from_cfg,
    [DFL_SHAPE_MESH] = mesh_from_cfg,
};

static dfl_status from_cfg(const dfl_cfg *cfg, const char *sec, int depth, dfl_shape *out,
                           dfl_err *err)
{
    int kind;
    dfl_status st = dfl_cfg_enum(cfg, sec, "kind", dfl_shape_kind_names, DFL_SHAPE_KIND_COUNT,
                                 &kind, err);
    if (st != DFL_OK) return st;
    if (!parsers[kind])
        return dfl_err_set(err, DFL_E_INTERNAL, "shape kind '%s' has no config parser",
                           dfl_shape_kind_name((dfl_shape_kind)kind));
    const shape_req rq = {cfg, sec, (dfl_shape_kind)kind, depth};
    return parsers[kind](&rq, out, err);
}

dfl_status dfl_shape_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_shape *out, dfl_err *err)
{
    return from_cfg(cfg, sec, 0, out, err);
}
