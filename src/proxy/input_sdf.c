/* SDF proxy input: the paper's footpoint x - f grad f and curvature from the
 * SDF's Hessian (Goldman) or from the cubic fit (proxy/curvfit.h). */
#include "proxy/input_sdf.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/vec.h"
#include "proxy/curvfit.h"

#define CHUNK 64

typedef struct sdf_ctx {
    dfl_shape shape;
    dfl_proxy_curv_method curv;
    dfl_curvfit *fit;   /* curv == FIT only */
    int plane_fallback, focal_clamp; /* dfl_curvfit_opts' */
} sdf_ctx;

static void point_curvature(const sdf_ctx *c, dfl_surfpoint *o)
{
    if (c->curv == DFL_PROXY_CURV_FIT) {
        if (dfl_curvfit_sdf(c->fit, &c->shape, o->p, o->n, &o->curv) != DFL_OK) {
            dfl_curvature_set_nan(&o->curv);
            o->certified = 0;
            if (c->plane_fallback) {
                /* the tangent plane: both curvatures 0, any orthonormal
                 * tangent pair with e1 x e2 = n (the fit's own frame) */
                dfl_curvature *k = &o->curv;
                dfl_vec3_tangent_basis(o->n, k->e1, k->e2);
                for (int j = 0; j < 3; j++) k->n[j] = o->n[j];
                k->k1 = k->k2 = k->K = k->H = 0.0;
            }
        } else if (c->focal_clamp) {
            /* 1 + k d >= 0 for both: the cut keeps k1 <= k2 (both are
             * raised to the same -1/d when d > 0, lowered to it when d < 0) */
            dfl_curvature *k = &o->curv;
            const double d = o->d;
            if (1.0 + k->k1 * d < 0.0) k->k1 = -1.0 / d;
            if (1.0 + k->k2 * d < 0.0) k->k2 = -1.0 / d;
            k->K = k->k1 * k->k2;
            k->H = 0.5 * (k->k1 + k->k2);
        }
        return;
    }
    double H[9];
    if (dfl_shape_hessian(&c->shape, o->p, H, NULL) != DFL_OK ||
        dfl_curvature_implicit(o->n, H, &o->curv, NULL) != DFL_OK) {
        dfl_curvature_set_nan(&o->curv);
        o->certified = 0;
    }
}

static dfl_status sdf_query(const void *vctx, size_t m, const double *x, int need_curv,
                            dfl_surfpoint *out, dfl_err *err)
{
    (void)err;
    const sdf_ctx *c = vctx;
    double val[CHUNK], grad[3 * CHUNK];
    for (size_t i0 = 0; i0 < m; i0 += CHUNK) {
        size_t nb = m - i0 < CHUNK ? m - i0 : CHUNK;
        c->shape.ops->eval(c->shape.impl, nb, x + 3 * i0, val, grad);
        for (size_t k = 0; k < nb; k++) {
            const double *xi = x + 3 * (i0 + k), *g = grad + 3 * k;
            dfl_surfpoint *o = out + i0 + k;
            double f = val[k], gn = sqrt(dfl_vec3_dot(g, g));
            for (int j = 0; j < 3; j++) {
                o->p[j] = xi[j] - f * g[j];
                o->n[j] = g[j] / gn;
            }
            o->d = f;
            o->certified = isfinite(f) && isfinite(gn) && fabs(gn - 1.0) <= 1e-6;
            if (need_curv) point_curvature(c, o);
            else dfl_curvature_set_nan(&o->curv);
        }
    }
    return DFL_OK;
}

static void sdf_destroy(void *vctx)
{
    sdf_ctx *c = vctx;
    dfl_shape_free(&c->shape);
    free(c->fit);
    free(c);
}

dfl_status dfl_proxy_input_sdf(dfl_shape *shape, dfl_proxy_curv_method curv,
                               const dfl_curvfit_opts *fit, dfl_proxy_input *out, dfl_err *err)
{
    dfl_status st = DFL_OK;
    sdf_ctx *c = NULL;
    if (!shape || !shape->ops || shape->dim != 3) {
        st = dfl_err_set(err, DFL_E_INPUT, "sdf input: need a 3D shape");
        goto fail;
    }
    if (curv == DFL_PROXY_CURV_FIT && !fit) {
        st = dfl_err_set(err, DFL_E_INPUT, "sdf input: curvature = fit needs fit options");
        goto fail;
    }
    if (!(c = calloc(1, sizeof *c))) {
        st = dfl_err_set(err, DFL_E_NOMEM, "sdf input: out of memory");
        goto fail;
    }
    c->curv = curv;
    if (curv == DFL_PROXY_CURV_FIT) {
        if (!(c->fit = malloc(sizeof *c->fit))) {
            st = dfl_err_set(err, DFL_E_NOMEM, "sdf input: out of memory");
            goto fail;
        }
        if ((st = dfl_curvfit_init(fit->g, fit->spacing, c->fit, err)) != DFL_OK) goto fail;
        c->plane_fallback = fit->plane_fallback != 0;
        c->focal_clamp = fit->focal_clamp != 0;
    }
    c->shape = *shape;
    memset(shape, 0, sizeof *shape);
    out->name = "sdf";
    out->query = sdf_query;
    out->destroy = sdf_destroy;
    out->ctx = c;
    out->has_inside = 1;
    return DFL_OK;
fail:
    if (c) free(c->fit);
    free(c);
    dfl_shape_free(shape);
    return st;
}
