/* Distance shapes of parametric curves and surfaces (param_shape.h). */
#include "geom/foot_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/vec.h"

#include "geom/param_shape.h"

typedef struct curve_shape {
    dfl_bspline c;
    dfl_curve_locator *L;
    dfl_curve_sdf *S;
} curve_shape;

static void unit_perp(int dim, const double *t, double *n)
{
    /* deterministic unit normal: 2D right normal; 3D e_k minus its tangent
     * part, e_k the axis least aligned with t */
    double len = sqrt(dfl_vecn_dot(dim, t, t));
    if (dim == 2) {
        n[0] = len > 0 ? t[1] / len : 1.0;
        n[1] = len > 0 ? -t[0] / len : 0.0;
        return;
    }
    int k = 0;
    for (int j = 1; j < 3; j++)
        if (fabs(t[j]) < fabs(t[k])) k = j;
    double e[3] = {0, 0, 0};
    e[k] = 1.0;
    double s = len > 0 ? dfl_vecn_dot(3, e, t) / (len * len) : 0.0;
    for (int j = 0; j < 3; j++) n[j] = e[j] - s * t[j];
    double m = sqrt(dfl_vecn_dot(3, n, n));
    for (int j = 0; j < 3; j++) n[j] /= m;
}

static void curve_shape_eval(const void *impl, size_t m, const double *pts, double *val,
                             double *grad)
{
    const curve_shape *cs = impl;
    const int dim = cs->c.dim;
    for (size_t i = 0; i < m; i++) {
        const double *x = pts + i * (size_t)dim;
        double *g = grad ? grad + i * (size_t)dim : NULL;
        if (cs->S) {
            dfl_curve_sdf_val v;
            if (dfl_curve_sdf_eval(cs->S, x, 1, &v, NULL) != DFL_OK) {
                val[i] = NAN;
                if (g) g[0] = g[1] = NAN;
                continue;
            }
            val[i] = v.d;
            if (g) {
                g[0] = v.g[0];
                g[1] = v.g[1];
            }
            continue;
        }
        dfl_curve_foot f;
        if (dfl_curve_footpoint(cs->L, x, &f, NULL) != DFL_OK) {
            val[i] = NAN;
            if (g)
                for (int j = 0; j < dim; j++) g[j] = NAN;
            continue;
        }
        val[i] = f.dist;
        if (!g) continue;
        if (f.dist > 0.0) {
            for (int j = 0; j < dim; j++) g[j] = (x[j] - f.p[j]) / f.dist;
        } else {
            double D[2 * 3];
            dfl_bspline_eval(&cs->c, f.t, 1, D);
            unit_perp(dim, D + dim, g);
        }
    }
}

static dfl_status curve_shape_jet(const void *impl, const double *x, const double *dir, int K,
                                  dfl_jet *out, dfl_err *err)
{
    const curve_shape *cs = impl;
    return dfl_curve_dist_jet(cs->L, cs->S, x, dir, K, out, err);
}

static void curve_shape_free(void *impl)
{
    curve_shape *cs = impl;
    if (!cs) return;
    /* with a signed distance, L is borrowed from S */
    if (cs->S) dfl_curve_sdf_free(cs->S);
    else dfl_curve_locator_free(cs->L);
    dfl_bspline_free(&cs->c);
    free(cs);
}

static const dfl_shape_ops curve_ops = {"bspline_curve", curve_shape_eval, curve_shape_jet,
                                        curve_shape_free, NULL};

dfl_status dfl_shape_param_curve(dfl_bspline *c, const dfl_foot_opts *opt, int signed_dist,
                                 dfl_shape *out, dfl_err *err)
{
    dfl_status st;
    if (c->dim != 2 && c->dim != 3) {
        dfl_bspline_free(c);
        return dfl_err_set(err, DFL_E_INPUT, "curve shapes need dimension 2 or 3, got %d",
                           c->dim);
    }
    curve_shape *cs = calloc(1, sizeof *cs);
    if (!cs) {
        dfl_bspline_free(c);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory for a curve shape");
    }
    cs->c = *c;
    memset(c, 0, sizeof *c);
    if (signed_dist) st = dfl_curve_sdf_new(&cs->c, opt, &cs->S, err);
    else st = dfl_curve_locator_new(&cs->c, opt, &cs->L, err);
    if (st != DFL_OK) {
        curve_shape_free(cs);
        return st;
    }
    if (cs->S) cs->L = cs->S->L; /* borrowed: the SDF owns its locator */
    out->dim = cs->c.dim;
    out->ops = &curve_ops;
    out->impl = cs;
    return DFL_OK;
}

typedef struct surface_shape {
    dfl_surface_set s;
    dfl_surface_locator *L;
} surface_shape;

static void surface_shape_eval(const void *impl, size_t m, const double *pts, double *val,
                               double *grad)
{
    const surface_shape *ss = impl;
    for (size_t i = 0; i < m; i++) {
        const double *x = pts + 3 * i;
        dfl_surface_foot f;
        if (dfl_surface_footpoint(ss->L, x, &f, NULL) != DFL_OK) {
            val[i] = NAN;
            if (grad) grad[3 * i] = grad[3 * i + 1] = grad[3 * i + 2] = NAN;
            continue;
        }
        val[i] = f.dist;
        if (!grad) continue;
        double *g = grad + 3 * i;
        if (f.dist > 0.0) {
            for (int j = 0; j < 3; j++) g[j] = (x[j] - f.p[j]) / f.dist;
        } else if (dfl_surface_normal(&ss->s.patch[f.patch], f.u, f.v, g) == 0.0) {
            g[0] = 1.0;
            g[1] = g[2] = 0.0;
        }
    }
}

static void surface_shape_free(void *impl)
{
    surface_shape *ss = impl;
    if (!ss) return;
    dfl_surface_locator_free(ss->L);
    dfl_surface_set_free(&ss->s);
    free(ss);
}

static const dfl_shape_ops surface_ops = {"bspline_surface", surface_shape_eval, NULL,
                                          surface_shape_free, NULL};

dfl_status dfl_shape_param_surface(dfl_surface_set *s, const dfl_foot_opts *opt, dfl_shape *out,
                                   dfl_err *err)
{
    surface_shape *ss = calloc(1, sizeof *ss);
    if (!ss) {
        dfl_surface_set_free(s);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory for a surface shape");
    }
    ss->s = *s;
    memset(s, 0, sizeof *s);
    dfl_status st = dfl_surface_locator_new(&ss->s, opt, &ss->L, err);
    if (st != DFL_OK) {
        surface_shape_free(ss);
        return st;
    }
    out->dim = 3;
    out->ops = &surface_ops;
    out->impl = ss;
    return DFL_OK;
}
