/* Field costs from keys (field_cost.h).  Kept apart from the factories so
 * that estimating never builds: the runner calls this before any field
 * exists. */
#include "cfg/field_cost.h"

#include <math.h>
#include <string.h>

#include "cfg/field_cfg.h"
#include "cfg/curve_cfg.h"
#include "cfg/pht_cfg.h"
#include "cfg/proxy_cfg.h"
#include "cfg/vdb_cfg.h"
#include "field/gridpeer.h"
#include "geom/polygonize.h"
#include "proxy/decode.h"
#include "proxy/store.h"

static const char *kind_of(const dfl_cfg *cfg, const char *sec)
{
    const char *k = NULL;
    if (!dfl_cfg_has(cfg, sec, "kind") || dfl_cfg_string(cfg, sec, "kind", &k, NULL)) return "";
    return k;
}

/* depth bounds CSG nesting (and ends a cycle, which the shape reader
 * reports): beyond it a shape counts as the dearest class */
static dfl_cost_class shape_class(const dfl_cfg *cfg, const char *sec, int depth)
{
    for (; depth < 8 && sec && dfl_cfg_has_section(cfg, sec); depth++) {
        const char *k = kind_of(cfg, sec);
        if (!strcmp(k, "implicit") || !strcmp(k, "bezier_surface") ||
            !strcmp(k, "bspline_surface") || !strcmp(k, "bspline_curve"))
            return DFL_COST_FOOTPOINT;
        if (!strcmp(k, "mesh")) return DFL_COST_EXACT;
        if (strcmp(k, "csg") != 0) return *k ? DFL_COST_CHEAP : DFL_COST_EXACT;
        /* csg: the dearer of its operands, bounded by the depth */
        const char *a = NULL, *b = NULL;
        if (dfl_cfg_string(cfg, sec, "a", &a, NULL) || dfl_cfg_string(cfg, sec, "b", &b, NULL))
            return DFL_COST_EXACT;
        if (shape_class(cfg, b, depth + 1) == DFL_COST_FOOTPOINT) return DFL_COST_FOOTPOINT;
        sec = a;
    }
    return depth >= 8 ? DFL_COST_FOOTPOINT : DFL_COST_EXACT;
}

dfl_cost_class dfl_shape_cost_class(const dfl_cfg *cfg, const char *sec)
{
    return shape_class(cfg, sec, 0);
}

int dfl_shape_dim_guess(const dfl_cfg *cfg, const char *sec)
{
    for (int depth = 0; depth < 8 && sec && dfl_cfg_has_section(cfg, sec); depth++) {
        const char *k = kind_of(cfg, sec);
        if (!strcmp(k, "circle") || !strcmp(k, "ellipse")) return 2;
        if (!strcmp(k, "bspline_curve")) {
            const char *raw;
            if (dfl_cfg_has(cfg, sec, "control") && !dfl_cfg_string(cfg, sec, "control", &raw, NULL))
                return dfl_cfg_point_dim(raw) == 3 ? 3 : 2;
            return 2;
        }
        if (!strcmp(k, "plane") || !strcmp(k, "box") || !strcmp(k, "segment")) {
            long d = !strcmp(k, "segment") ? 2 : 3;
            if (dfl_cfg_has(cfg, sec, "dim") && dfl_cfg_int(cfg, sec, "dim", 2, 3, &d, NULL))
                d = 3;
            return (int)d;
        }
        if (strcmp(k, "csg") != 0 || dfl_cfg_string(cfg, sec, "a", &sec, NULL)) return 3;
    }
    return 3;
}

static dfl_status proxy_cost(const dfl_cfg *cfg, const char *sec, dfl_cost *c, dfl_err *err)
{
    dfl_proxy_cfg p;
    dfl_status st = dfl_proxy_cfg_read(cfg, sec, &p, err);
    if (st) return st;
    const double r = p.build.res, cells = r * r * r;
    const int ns = DFL_PROXY_NSCALAR(p.build.order);
    dfl_cost_add_bytes(c, sec, "res", cells * (ns * (double)dfl_proxy_storage_size(p.build.storage) + 1),
                       "a proxy grid of %.0f^3 cells, order %d, %s", r, p.build.order,
                       dfl_proxy_storage_name(p.build.storage));
    const char *input = "sdf", *shape = "shape";
    if (dfl_cfg_has(cfg, sec, "input")) dfl_cfg_string(cfg, sec, "input", &input, NULL);
    if (dfl_cfg_has(cfg, sec, "shape")) dfl_cfg_string(cfg, sec, "shape", &shape, NULL);
    const dfl_cost_class cls =
        strcmp(input, "sdf") ? DFL_COST_FOOTPOINT : dfl_shape_cost_class(cfg, shape);
    dfl_cost_add_work(c, sec, "res", cls, cells * (p.build.order == 2 ? 2 : 1),
                      "%.3g %s footpoints", cells, input);
    return DFL_OK;
}

static dfl_status gridpeer_cost(const dfl_cfg *cfg, const char *sec, dfl_cost *c, dfl_err *err)
{
    int kind = DFL_GRIDPEER_TAYLOR1, storage = DFL_GRIDPEER_FLOAT64;
    long n = 16;
    const char *shape = "shape";
    dfl_status st = dfl_cfg_enum_opt(cfg, sec, "method", dfl_gridpeer_kind_names,
                                     DFL_GRIDPEER_KIND_COUNT, kind, &kind, err);
    if (!st) st = dfl_cfg_enum_opt(cfg, sec, "storage", dfl_gridpeer_storage_names,
                                   DFL_GRIDPEER_STORAGE_COUNT, storage, &storage, err);
    if (!st) st = dfl_cfg_int_opt(cfg, sec, "res", 16, 1, 1024, &n, err);
    if (!st) st = dfl_cfg_string_opt(cfg, sec, "shape", "shape", &shape, err);
    if (st) return st;
    if (kind == DFL_GRIDPEER_TRICUBIC && n < 4)
        return dfl_cfg_reject(cfg, sec, "res", err, "expected res >= 4 for tricubic, got %ld", n);
    const double scalars = (double)dfl_gridpeer_scalars((dfl_gridpeer_kind)kind, (int)n);
    /* the build keeps float64 values before a float16 grid is packed;
     * tricubic keeps its coefficients as doubles (either storage: the
     * halves' values) and their (n + 2)^3 extension with the ghosts, plus
     * a prefilter line of 3n doubles per thread (negligible) */
    double bytes = scalars * (storage == DFL_GRIDPEER_FLOAT64 ? 8 : 10);
    if (kind == DFL_GRIDPEER_TRICUBIC) bytes = scalars * 8 + 8.0 * pow((double)n + 2, 3);
    dfl_cost_add_bytes(c, sec, "res", bytes, "a grid peer of %ld^3 cells (%.3g scalars)", n,
                       scalars);
    const double nodes = (double)(n + 1) * (n + 1) * (n + 1);
    dfl_cost_add_work(c, sec, "res", dfl_shape_cost_class(cfg, shape), nodes,
                      "%.3g distances", nodes);
    return DFL_OK;
}

double dfl_pht_fit_bytes_bound(const dfl_pht_fit_opts *o, int dim, double *leaves)
{
    const double n = ldexp(1.0, o->split == DFL_PHT_SPLIT_BINARY ? o->max_level
                                                                 : dim * o->max_level);
    const double fan = ldexp(1.0, o->split == DFL_PHT_SPLIT_BINARY ? 1 : dim);
    if (leaves) *leaves = n;
    return n * fan / (fan - 1) * DFL_PHT_CELL_BYTES(dim);
}

static dfl_status pht_cost(const dfl_cfg *cfg, const char *sec, dfl_cost *c, dfl_err *err)
{
    const char *shape = "shape";
    dfl_status st = dfl_cfg_string_opt(cfg, sec, "shape", "shape", &shape, err);
    if (st) return st;
    const int dim = dfl_shape_dim_guess(cfg, shape);
    dfl_pht_fit_opts o;
    if ((st = dfl_pht_opts_from_cfg(cfg, sec, dim, &o, err))) return st;
    double leaves;
    const double bytes = dfl_pht_fit_bytes_bound(&o, dim, &leaves);
    dfl_cost_add_bytes(c, sec, "max_level", bytes,
                       "a PHT mesh of up to %.3g cells (max_level = %d in %dD)", leaves,
                       o.max_level, dim);
    dfl_cost_add_work(c, sec, "max_level", dfl_shape_cost_class(cfg, shape),
                      leaves * (o.samples + 1), "%.3g estimator points and footpoints",
                      leaves * (o.samples + 1));
    return DFL_OK;
}

static dfl_status vdb_cost(const dfl_cfg *cfg, const char *sec, dfl_cost *c, dfl_err *err)
{
    dfl_vdb_cfg v;
    dfl_status st = dfl_vdb_cfg_read(cfg, sec, &v, err);
    if (st) return st;
    double leaves;
    const double grid = dfl_vdb_bytes_bound(&v.opts, &leaves);
    dfl_cost_add_bytes(c, sec, "voxel", grid,
                       "an OpenVDB grid of up to %.3g leaves of 8^3 voxels (voxel %g)", leaves,
                       v.opts.voxel);
    const dfl_cost_class cls = dfl_shape_cost_class(cfg, v.shape);
    if (v.build == DFL_VDB_DIRECT) {
        const double evals = leaves * (512 + 1) + leaves / 4096 + 1;
        dfl_cost_add_work(c, sec, "voxel", cls, evals, "%.3g distances of the band search", evals);
        return DFL_OK;
    }
    /* mesh: the voxel lattice of the box sampled, marched, refined */
    double nodes = 1;
    for (int a = 0; a < 3; a++) nodes *= floor((v.opts.hi[a] - v.opts.lo[a]) / v.opts.voxel) + 3;
    dfl_cost_add_bytes(c, sec, "voxel", 24 * nodes,
                       "the marching-cubes lattice of %.3g nodes and its mesh", nodes);
    dfl_cost_add_work(c, sec, "voxel", cls, nodes * (1 + 30 * 7),
                      "%.3g distances of the marching-cubes mesh", nodes * (1 + 30 * 7));
    return DFL_OK;
}

/* Entries of a point list "x y; x y; ..." (blank entries, e.g. after a
 * trailing ';', do not count); the factory parses and checks them. */
static double count_points(const char *raw)
{
    double n = 0;
    int in = 0;
    for (const char *p = raw; *p; p++) {
        if (*p == ';') in = 0;
        else if (*p != ' ' && *p != '\t' && !in) in = 1, n++;
    }
    return n;
}

dfl_status dfl_rfunc_parts_bound(const dfl_cfg *cfg, const char *sec, double *parts,
                                 const char **key, dfl_err *err)
{
    double n = 0, big = -1;
    const char *raw;
    dfl_status st = DFL_OK;
    *key = "vertices";
#define PART(k, count)                       \
    do {                                     \
        const double c_ = (count);           \
        n += c_;                             \
        if (c_ > big) big = c_, *key = (k);  \
    } while (0)
    if (dfl_cfg_has(cfg, sec, "vertices") && !dfl_cfg_string(cfg, sec, "vertices", &raw, NULL))
        PART("vertices", count_points(raw)); /* n - 1 segments, n when closed */
    /* vertices and curve together: the factory refuses the pair, naming it */
    if (dfl_cfg_has(cfg, sec, "curve") && !dfl_cfg_has(cfg, sec, "vertices")) {
        const char *csec;
        double eps;
        dfl_bspline c;
        if ((st = dfl_cfg_string(cfg, sec, "curve", &csec, err))) return st;
        if ((st = dfl_cfg_double(cfg, sec, "eps", 1e-12, 1e300, &eps, err))) return st;
        /* a missing or wrong section: the factory names it */
        if (dfl_cfg_has_section(cfg, csec) && dfl_cfg_has(cfg, csec, "kind") &&
            !dfl_cfg_string(cfg, csec, "kind", &raw, NULL) && !strcmp(raw, "bspline_curve")) {
            if ((st = dfl_curve_from_cfg(cfg, csec, &c, err))) return st;
            PART("eps", dfl_polygonize_curve_segments_bound(&c, eps) + 1);
            dfl_bspline_free(&c);
        }
    }
    if (dfl_cfg_has(cfg, sec, "triangles") && !dfl_cfg_string(cfg, sec, "triangles", &raw, NULL))
        PART("triangles", count_points(raw) / 3);
    if (dfl_cfg_has(cfg, sec, "surface")) {
        long max_tris;
        if ((st = dfl_cfg_int_opt(cfg, sec, "max_tris", 200000, 1, 10000000, &max_tris, err)))
            return st;
        PART("max_tris", (double)max_tris);
    }
    if (dfl_cfg_has(cfg, sec, "points") && !dfl_cfg_string(cfg, sec, "points", &raw, NULL))
        PART("points", count_points(raw));
    if (dfl_cfg_has(cfg, sec, "region")) PART("region", 1);
#undef PART
    *parts = n;
    return DFL_OK;
}

static dfl_status rfunc_cost(const dfl_cfg *cfg, const char *sec, dfl_cost *c, dfl_err *err)
{
    double parts;
    const char *key;
    dfl_status st = dfl_rfunc_parts_bound(cfg, sec, &parts, &key, err);
    if (st) return st;
    dfl_cost_add_bytes(c, sec, key, parts * DFL_RFUNC_PART_BYTES,
                       "an R-function field of up to %.3g parts", parts);
    dfl_cost_add_work(c, sec, key, DFL_COST_CHEAP, parts, "%.3g parts set up", parts);
    return DFL_OK;
}

int dfl_field_dim_guess(const dfl_cfg *cfg, const char *sec)
{
    const char *k = kind_of(cfg, sec), *raw, *shape = "shape";
    if (!strcmp(k, "normalized")) return 2;
    if (!strcmp(k, "rfunc")) {
        static const char *const keys[] = {"vertices", "triangles", "points", "region"};
        if (dfl_cfg_has(cfg, sec, "surface")) return 3;
        for (int i = 0; i < 4; i++)
            if (dfl_cfg_has(cfg, sec, keys[i]) && !dfl_cfg_string(cfg, sec, keys[i], &raw, NULL))
                return dfl_cfg_point_dim(raw) == 3 ? 3 : 2;
        if (dfl_cfg_has(cfg, sec, "curve") && !dfl_cfg_string(cfg, sec, "curve", &raw, NULL))
            return dfl_shape_dim_guess(cfg, raw); /* its control points' */
        return 2;
    }
    if (dfl_cfg_has(cfg, sec, "shape")) dfl_cfg_string(cfg, sec, "shape", &shape, NULL);
    return dfl_shape_dim_guess(cfg, shape);
}

dfl_status dfl_field_eval_cost(const dfl_cfg *cfg, const char *sec, dfl_cost_class *cls,
                               double *units, dfl_err *err)
{
    const dfl_field_kind *kind;
    dfl_status st = dfl_field_kind_from_cfg(cfg, sec, &kind, err);
    if (st) return st;
    *cls = DFL_COST_DECODE;
    *units = 1;
    if (!strcmp(kind->name, "exact")) {
        const char *shape = "shape";
        if ((st = dfl_cfg_string_opt(cfg, sec, "shape", "shape", &shape, err))) return st;
        /* an unknown kind is named here, before a caller sizes anything by
         * the dimension dfl_shape_dim_guess can only guess for it */
        int k;
        if (dfl_cfg_has_section(cfg, shape) &&
            (st = dfl_cfg_enum(cfg, shape, "kind", dfl_shape_kind_names, DFL_SHAPE_KIND_COUNT, &k,
                               err)))
            return st;
        *cls = dfl_shape_cost_class(cfg, shape);
    } else if (!strcmp(kind->name, "rfunc")) {
        const char *key;
        *cls = DFL_COST_CHEAP;
        st = dfl_rfunc_parts_bound(cfg, sec, units, &key, err);
        *units += DFL_RFUNC_EVAL_UNITS;
    } else if (!strcmp(kind->name, "normalized")) {
        long m = 1;
        if (dfl_cfg_has(cfg, sec, "m") && (st = dfl_cfg_int(cfg, sec, "m", 1, 6, &m, err)))
            return st;
        *cls = DFL_COST_CHEAP;
        *units = pow(m * (m + 1) / 2.0 + 2, 4);
    }
    return st;
}

dfl_status dfl_field_cost_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_cost *cost,
                                   dfl_err *err)
{
    const dfl_field_kind *kind;
    dfl_status st = dfl_field_kind_from_cfg(cfg, sec, &kind, err);
    if (st) return st;
    if (!strcmp(kind->name, "proxy")) return proxy_cost(cfg, sec, cost, err);
    if (!strcmp(kind->name, "gridpeer")) return gridpeer_cost(cfg, sec, cost, err);
    if (!strcmp(kind->name, "pht")) return pht_cost(cfg, sec, cost, err);
    if (!strcmp(kind->name, "openvdb")) return vdb_cost(cfg, sec, cost, err);
    if (!strcmp(kind->name, "rfunc")) return rfunc_cost(cfg, sec, cost, err);
    return DFL_OK;
}
