#include "cfg/proxy_cfg.h"

#include "core/domain.h"

#include <math.h>
#include <string.h>

#include "cfg/proxy_input_cfg.h"
#include "proxy/proxy_field.h"

/* lo / hi: one number for every axis, or three. */
static dfl_status read_box_end(const dfl_cfg *cfg, const char *sec, const char *key, double def,
                               double out[3], dfl_err *err)
{
    const char *s;
    dfl_status st = dfl_cfg_string_opt(cfg, sec, key, NULL, &s, err);
    if (st) return st;
    if (!s) {
        out[0] = out[1] = out[2] = def;
        return DFL_OK;
    }
    if (dfl_cfg_point_dim(s) == 1) {
        /* a coordinate: |v| <= DFL_COORD_MAX, as the vector form */
        st = dfl_cfg_double(cfg, sec, key, -DFL_COORD_MAX, DFL_COORD_MAX, &out[0], err);
        out[1] = out[2] = out[0];
        return st;
    }
    return dfl_cfg_vec(cfg, sec, key, 3, out, err);
}

dfl_status dfl_proxy_cfg_read(const dfl_cfg *cfg, const char *sec, dfl_proxy_cfg *out,
                              dfl_err *err)
{
    dfl_proxy_cfg c;
    memset(&c, 0, sizeof c);
    dfl_proxy_build_opts_default(&c.build);
    long order, res, seed;
    int filt, sto, pos;
    bool sg;
    dfl_status st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "order", 1, 1, 2, &order, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "res", 16, 1, 2048, &res, err))) return st;
    if ((st = read_box_end(cfg, sec, "lo", -1.0, c.build.lo, err))) return st;
    if ((st = read_box_end(cfg, sec, "hi", 1.0, c.build.hi, err))) return st;
    for (int j = 0; j < 3; j++)
        if (!(c.build.lo[j] < c.build.hi[j]))
            return dfl_cfg_reject(cfg, sec, dfl_cfg_has(cfg, sec, "hi") ? "hi" : "lo", err,
                                  "expected lo < hi on every axis (axis %d: %g >= %g)", j,
                                  c.build.lo[j], c.build.hi[j]);
    if ((st = dfl_cfg_enum_opt(cfg, sec, "filter", dfl_proxy_filter_names,
                               DFL_PROXY_FILTER_COUNT, DFL_PROXY_NEAREST, &filt, err)))
        return st;
    if ((st = dfl_cfg_enum_opt(cfg, sec, "storage", dfl_proxy_storage_names,
                               DFL_PROXY_STORAGE_COUNT, DFL_PROXY_DOUBLE, &sto, err)))
        return st;
    if ((st = dfl_cfg_enum_opt(cfg, sec, "position", dfl_proxy_position_names,
                               DFL_PROXY_POSITION_COUNT, DFL_PROXY_DISPLACEMENT, &pos, err)))
        return st;
    int ck;
    if ((st = dfl_cfg_enum_opt(cfg, sec, "clip", dfl_proxy_clip_names, DFL_PROXY_CLIP_COUNT,
                               DFL_PROXY_CLIP_BOUND, &ck, err)))
        return st;
    c.clip_kind = (dfl_proxy_clip)ck;
    if (c.clip_kind == DFL_PROXY_CLIP_OFF && dfl_cfg_has(cfg, sec, "clip_radius"))
        return dfl_cfg_reject(cfg, sec, "clip_radius", err,
                              "clip = off takes no radius (remove clip_radius or choose "
                              "clip = bound|paper)");
    if (dfl_cfg_has(cfg, sec, "clip_radius")) {
        if ((st = dfl_cfg_double(cfg, sec, "clip_radius", -1e300, 1e300, &c.clip_cells, err)))
            return st;
        if (!(c.clip_cells > 0))
            return dfl_cfg_reject(cfg, sec, "clip_radius", err,
                                  "expected a radius > 0 (in cell sizes), got %g", c.clip_cells);
    }
    if ((st = dfl_cfg_bool_opt(cfg, sec, "signed", false, &sg, err))) return st;
    if ((st = dfl_cfg_double_opt(cfg, sec, "noise", 0.0, 0.0, 1e300, &c.build.noise, err)))
        return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "seed", 1, 0, 0x7fffffffL, &seed, err))) return st;
    if (dfl_cfg_has(cfg, sec, "noise_at")) {
        double at[3];
        if ((st = dfl_cfg_vec(cfg, sec, "noise_at", 3, at, err))) return st;
        long idx = 0, mul = 1;
        for (int j = 0; j < 3; j++) {
            /* the cell of a point on a face between two cells: the upper one */
            const double t = (at[j] - c.build.lo[j]) / (c.build.hi[j] - c.build.lo[j]) * res;
            if (!(t >= 0 && t < res))
                return dfl_cfg_reject(cfg, sec, "noise_at", err,
                                      "expected a point inside the box (axis %d: %g)", j, at[j]);
            idx += (long)floor(t) * mul;
            mul *= res;
        }
        c.build.noise_cell = idx;
    }
    c.build.order = (int)order;
    c.build.res = (int)res;
    c.build.storage = (dfl_proxy_storage)sto;
    c.build.position = (dfl_proxy_position)pos;
    c.build.seed = (uint64_t)seed;
    c.filter = (dfl_proxy_filter)filt;
    c.is_signed = sg;
    *out = c;
    return DFL_OK;
}

dfl_status dfl_proxy_grid_from_cfg(const dfl_cfg *cfg, const char *sec, const char *shape_sec,
                                   dfl_proxy_grid *grid, dfl_proxy_filter_opts *fo,
                                   dfl_err *err)
{
    memset(grid, 0, sizeof *grid);
    dfl_proxy_cfg c;
    dfl_status st = dfl_proxy_cfg_read(cfg, sec, &c, err);
    if (st) return st;
    /* a triangle mesh's SDF has no curvature at an edge or vertex footpoint:
     * its Hessian there is 1 / (the rounding of |x - p|), of either sign,
     * and an order-2 proxy built from it is a needle cylinder or sphere that
     * flips the sign of whole cells (measured: errors of 2 |d| at 10 % of a
     * marching-cubes genus-2 mesh's 17^3 probe nodes) */
    const char *kind = "", *input = "sdf", *curv = "analytic";
    if (c.build.order == 2 && dfl_cfg_string(cfg, shape_sec, "kind", &kind, NULL) == DFL_OK &&
        strcmp(kind, "mesh") == 0 &&
        dfl_cfg_string_opt(cfg, sec, "input", "sdf", &input, NULL) == DFL_OK &&
        dfl_cfg_string_opt(cfg, sec, "curvature", "analytic", &curv, NULL) == DFL_OK &&
        strcmp(input, "sdf") == 0 && strcmp(curv, "analytic") == 0)
        return dfl_cfg_reject(cfg, sec, "curvature", err,
                              "[%s] is a triangle mesh, whose SDF has no curvature at edges and "
                              "vertices: order 2 needs curvature = fit (or use order = 1)",
                              shape_sec);
    dfl_proxy_input in;
    if ((st = dfl_proxy_input_from_cfg(cfg, sec, shape_sec, &in, err))) return st;
    if (c.is_signed && !in.has_inside) {
        /* the name before the free, which zeroes in */
        const char *name = in.name ? in.name : "chosen";
        dfl_proxy_input_free(&in);
        return dfl_cfg_reject(cfg, sec, "signed", err,
                              "the %s input of this shape has no inside (use signed = false)",
                              name);
    }
    /* a validation pass builds no proxy: the grid's shape and options are
     * what the studies read before they compute (io/config.h) */
    if (dfl_cfg_validating(cfg))
        st = dfl_proxy_grid_alloc(&c.build, in.has_inside, c.build.order == 1 && in.has_inside,
                                  grid, err);
    else
        st = dfl_proxy_grid_build(&in, &c.build, grid, err);
    dfl_proxy_input_free(&in);
    if (st) return st;
    dfl_proxy_filter_opts_default(c.filter, grid, fo);
    if (c.clip_cells > 0) fo->clip = c.clip_cells * dfl_proxy_cell_size(grid);
    fo->clip_kind = c.clip_kind;
    fo->is_signed = c.is_signed;
    return DFL_OK;
}

dfl_status dfl_proxy_field_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out,
                                    dfl_err *err)
{
    dfl_proxy_grid g;
    dfl_proxy_filter_opts fo;
    const char *shape = "shape";
    dfl_status st = dfl_cfg_string_opt(cfg, sec, "shape", "shape", &shape, err);
    if (st) return st;
    if (!dfl_cfg_has_section(cfg, shape))
        return dfl_cfg_reject(cfg, sec, "shape", err, "no section [%s]", shape);
    st = dfl_proxy_grid_from_cfg(cfg, sec, shape, &g, &fo, err);
    if (st) return st;
    st = dfl_proxy_field_new(&g, &fo, out, err);
    if (st) dfl_proxy_grid_free(&g);
    return st;
}
