/* Config -> curves, surfaces and their distance shapes.  Every message
 * names file:line, [section] and key (dfl_cfg_where), because the library
 * checks (geom/) know the data but not where it came from. */
#include "cfg/curve_cfg.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


dfl_status dfl_curve_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_bspline *out,
                              dfl_err *err)
{
    long order;
    const char *raw;
    bool closed;
    dfl_status st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "order", 4, 2, DFL_BSPLINE_MAX_ORDER, &order, err)))
        return st;
    if ((st = dfl_cfg_bool_opt(cfg, sec, "closed", false, &closed, err))) return st;
    if ((st = dfl_cfg_string(cfg, sec, "control", &raw, err))) return st;
    int dim = dfl_cfg_point_dim(raw);
    if (dim != 2 && dim != 3)
        return dfl_cfg_reject(cfg, sec, "control", err,
                              "expected points of 2 (planar) or 3 (space curve) numbers, the first"
                              " point has %d", dim);
    double *cp = NULL, *knots = NULL;
    size_t ncp = 0, nk = 0;
    if ((st = dfl_cfg_points(cfg, sec, "control", dim, 2, &cp, &ncp, err))) return st;
    if ((st = dfl_bspline_check_control(dim, (int)order, ncp, cp, closed, err))) {
        free(cp);
        return dfl_cfg_err_at(cfg, sec, "control", st, err);
    }
    if (dfl_cfg_has(cfg, sec, "knots")) {
        if ((st = dfl_cfg_doubles(cfg, sec, "knots", 1, &knots, &nk, err))) {
            free(cp);
            return st;
        }
        if ((st = dfl_bspline_check_knots((int)order, ncp, knots, nk, closed, err))) {
            free(cp);
            free(knots);
            return dfl_cfg_err_at(cfg, sec, "knots", st, err);
        }
    }
    dfl_bspline c;
    if (closed) st = dfl_bspline_init_periodic(dim, (int)order, ncp, cp, knots, nk, &c, err);
    else st = dfl_bspline_init(dim, (int)order, ncp, cp, knots, nk, &c, err);
    free(cp);
    free(knots);
    if (st != DFL_OK) return dfl_cfg_err_at(cfg, sec, "control", st, err);
    /* a regular parametrization is needed for normals and footpoints */
    double ext = 0.0;
    for (int j = 0; j < dim; j++) {
        double lo = INFINITY, hi = -INFINITY;
        for (size_t i = 0; i < c.n; i++) {
            lo = fmin(lo, c.cp[i * (size_t)dim + (size_t)j]);
            hi = fmax(hi, c.cp[i * (size_t)dim + (size_t)j]);
        }
        ext = fmax(ext, hi - lo);
    }
    const size_t ns = dfl_bspline_span_count(&c);
    for (size_t s = 0; s < ns; s++) {
        size_t j = dfl_bspline_span_index(&c, s);
        for (int q = 0; q <= 8; q++) {
            double t = c.knots[j] + (c.knots[j + 1] - c.knots[j]) * q / 8.0, D[2 * 3];
            dfl_bspline_eval_side(&c, t, q == 8 ? -1 : 1, 1, D);
            double sp = 0.0;
            for (int k = 0; k < dim; k++) sp += D[dim + k] * D[dim + k];
            double len = (c.knots[j + 1] - c.knots[j]);
            if (!(sqrt(sp) * len > 1e-12 * ext)) {
                dfl_bspline_free(&c);
                return dfl_cfg_reject(cfg, sec, "control", err,
                                      "degenerate control polygon: the curve has zero speed at"
                                      " t = %g (coincident control points?)", t);
            }
        }
    }
    *out = c;
    return DFL_OK;
}

dfl_status dfl_curve_section_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_bspline *out,
                                      dfl_err *err)
{
    const char *kind;
    dfl_status st = dfl_cfg_string(cfg, sec, "kind", &kind, err);
    if (st != DFL_OK) return st;
    if (strcmp(kind, "bspline_curve") != 0)
        return dfl_cfg_reject(cfg, sec, "kind", err, "expected bspline_curve, got '%s'", kind);
    return dfl_curve_from_cfg(cfg, sec, out, err);
}

dfl_status dfl_foot_opts_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_foot_opts *out,
                                  dfl_err *err)
{
    static const char *const backends[] = {"newton", "ceres"};
    dfl_foot_opts o;
    dfl_foot_opts_default(&o);
    int b;
    long samples, cand;
    dfl_status st;
    if ((st = dfl_cfg_enum_opt(cfg, sec, "backend", backends, 2, 0, &b, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "samples", o.samples_per_span, 2, 10000, &samples, err)))
        return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "candidates", o.candidates, 1, DFL_FOOT_MAX_CAND, &cand,
                              err)))
        return st;
    o.backend = b == 1 ? DFL_FOOT_CERES : DFL_FOOT_NEWTON;
    o.samples_per_span = (int)samples;
    o.candidates = (int)cand;
    *out = o;
    return DFL_OK;
}

static void free_patches(dfl_surface *p, size_t n)
{
    for (size_t i = 0; i < n; i++) dfl_surface_free(&p[i]);
    free(p);
}

dfl_status dfl_surface_from_cfg(const dfl_cfg *cfg, const char *sec, const char *kind_name,
                                dfl_surface_set *out, dfl_err *err)
{
    const int bezier = strcmp(kind_name, "bezier_surface") == 0;
    long ku, kv, npatch = 1, nu = 0, nv = 0;
    dfl_status st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "order_u", 4, 2, DFL_BSPLINE_MAX_ORDER, &ku, err)))
        return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "order_v", 4, 2, DFL_BSPLINE_MAX_ORDER, &kv, err)))
        return st;
    if (bezier) {
        if ((st = dfl_cfg_int_opt(cfg, sec, "patches", 1, 1, 100000, &npatch, err))) return st;
        nu = ku;
        nv = kv;
    } else {
        if ((st = dfl_cfg_int(cfg, sec, "nu", ku, 100000, &nu, err))) return st;
        if ((st = dfl_cfg_int(cfg, sec, "nv", kv, 100000, &nv, err))) return st;
    }
    double *cp = NULL, *U = NULL, *V = NULL;
    size_t ncp = 0, nU = 0, nV = 0;
    if ((st = dfl_cfg_points(cfg, sec, "control", 3, 1, &cp, &ncp, err))) return st;
    size_t want = (size_t)npatch * (size_t)nu * (size_t)nv;
    if (ncp != want) {
        free(cp);
        if (bezier)
            return dfl_cfg_reject(cfg, sec, "control", err,
                                  "%zu control points given, expected %zu (patches %ld x order_u"
                                  " %ld x order_v %ld)", ncp, want, npatch, ku, kv);
        return dfl_cfg_reject(cfg, sec, "control", err,
                              "%zu control points given, expected nu x nv = %zu", ncp, want);
    }
    if (!bezier) {
        if (dfl_cfg_has(cfg, sec, "knots_u") &&
            (st = dfl_cfg_doubles(cfg, sec, "knots_u", 1, &U, &nU, err)))
            goto fail;
        if (dfl_cfg_has(cfg, sec, "knots_v") &&
            (st = dfl_cfg_doubles(cfg, sec, "knots_v", 1, &V, &nV, err)))
            goto fail;
        if (U && (st = dfl_bspline_check_knots((int)ku, (size_t)nu, U, nU, 0, err))) {
            dfl_cfg_err_at(cfg, sec, "knots_u", st, err);
            goto fail;
        }
        if (V && (st = dfl_bspline_check_knots((int)kv, (size_t)nv, V, nV, 0, err))) {
            dfl_cfg_err_at(cfg, sec, "knots_v", st, err);
            goto fail;
        }
    }
    dfl_surface *patches = calloc((size_t)npatch, sizeof *patches);
    if (!patches) {
        st = dfl_err_set(err, DFL_E_NOMEM, "out of memory");
        goto fail;
    }
    for (long p = 0; p < npatch; p++) {
        const double *P = cp + (size_t)p * (size_t)(nu * nv) * 3;
        if (bezier) st = dfl_surface_init_bezier((int)ku, (int)kv, P, &patches[p], err);
        else
            st = dfl_surface_init((int)ku, (int)kv, (size_t)nu, (size_t)nv, P, U, nU, V, nV,
                                  &patches[p], err);
        if (st != DFL_OK) {
            free_patches(patches, (size_t)p);
            if (npatch > 1) dfl_err_prefix(err, "patch %ld", p);
            dfl_cfg_err_at(cfg, sec, "control", st, err);
            goto fail;
        }
    }
    dfl_surface_set set;
    if ((st = dfl_surface_set_init((size_t)npatch, patches, &set, err))) {
        free_patches(patches, (size_t)npatch);
        goto fail;
    }
    free(patches);
    if (bezier) {
        static const char *const conts[] = {"any", "C0", "G1"};
        int want_c;
        if ((st = dfl_cfg_enum_opt(cfg, sec, "continuity", conts, 3, 0, &want_c, err))) {
            dfl_surface_set_free(&set);
            goto fail;
        }
        if (want_c > 0 && set.npatch > 1) {
            size_t nshared, iso;
            dfl_join j = dfl_surface_set_joins(&set, 1e-9, 1e-6, &nshared, &iso);
            const size_t np = set.npatch;
            if (iso < np || (int)j < want_c) {
                dfl_surface_set_free(&set);
                if (iso < np)
                    st = dfl_cfg_reject(cfg, sec, "continuity", err,
                                        "continuity %s required, but patch %zu shares no edge with"
                                        " another patch", conts[want_c], iso);
                else
                    st = dfl_cfg_reject(cfg, sec, "continuity", err,
                                        "continuity %s required, but a shared edge is only %s",
                                        conts[want_c], conts[j]);
                goto fail;
            }
        }
    }
    free(cp);
    free(U);
    free(V);
    *out = set;
    return DFL_OK;
fail:
    free(cp);
    free(U);
    free(V);
    return st;
}

dfl_status dfl_param_shape_from_cfg(const dfl_cfg *cfg, const char *sec, const char *kind_name,
                                    dfl_shape *out, dfl_err *err)
{
    dfl_foot_opts o;
    dfl_status st;
    if (strcmp(kind_name, "bspline_curve") == 0) {
        static const char *const modes[] = {"auto", "signed", "unsigned"};
        int mode;
        if ((st = dfl_cfg_enum_opt(cfg, sec, "distance", modes, 3, 0, &mode, err))) return st;
        if ((st = dfl_foot_opts_from_cfg(cfg, sec, &o, err))) return st;
        dfl_bspline c;
        if ((st = dfl_curve_from_cfg(cfg, sec, &c, err))) return st;
        int closed2d = c.dim == 2 && dfl_bspline_is_closed(&c, 1e-12);
        if (mode == 1 && !closed2d) {
            int dim = c.dim;
            dfl_bspline_free(&c);
            return dfl_cfg_reject(cfg, sec, "distance", err,
                                  "signed distance needs a closed planar curve, but this curve is"
                                  " %s (set closed = true, or make the first and last control"
                                  " points equal)", dim != 2 ? "a space curve" : "open");
        }
        int sgn = mode == 1 || (mode == 0 && closed2d);
        dfl_shape sh;
        if ((st = dfl_shape_param_curve(&c, &o, sgn, &sh, err)))
            return dfl_cfg_err_at(cfg, sec, "control", st, err);
        *out = sh;
        return DFL_OK;
    }
    if (strcmp(kind_name, "bspline_surface") == 0 || strcmp(kind_name, "bezier_surface") == 0) {
        if ((st = dfl_foot_opts_from_cfg(cfg, sec, &o, err))) return st;
        dfl_surface_set s;
        if ((st = dfl_surface_from_cfg(cfg, sec, kind_name, &s, err))) return st;
        dfl_shape sh;
        if ((st = dfl_shape_param_surface(&s, &o, &sh, err))) return st;
        *out = sh;
        return DFL_OK;
    }
    return dfl_cfg_reject(cfg, sec, "kind", err, "unknown parametric kind '%s'", kind_name);
}
