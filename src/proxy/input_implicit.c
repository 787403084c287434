/* Implicit proxy inputs: the paper's gradient-start Newton and our
 * certified search (see proxy/input_implicit.h). */
#include "proxy/input_implicit.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/vec.h"
#include "proxy/input_implicit_fast.h"

#define PAPER_STARTS 4

DFL_NAMES_DEFINE(dfl_implicit_foot_method, DFL_IMPLICIT_FOOT_LIST, DFL_IMPLICIT_FOOT_COUNT,
                 dfl_implicit_foot_names, dfl_implicit_foot_name, dfl_implicit_foot_parse,
                 "footpoint method")

typedef struct imp_ctx {
    dfl_implicit *s;
    dfl_implicit_foot_method method;
    double scale;
    dfl_imp_index *ix;   /* robust only: the fast path's samples */
} imp_ctx;

int dfl_proxy_implicit_certify(const dfl_implicit *s, const double x[3], const double p[3],
                               double d)
{
    const double scale = dfl_implicit_scale(s);
    double G[3], H[9];
    double g = dfl_implicit_g(s, p, G, H);
    double gn = dfl_vec3_norm(G);
    if (!(gn > 0) || !isfinite(g)) return 0;
    double u[3] = {x[0] - p[0], x[1] - p[1], x[2] - p[2]}, c[3];
    dfl_vec3_cross(G, u, c);
    if (!(fabs(g) / gn <= 1e-10 * scale)) return 0;
    if (!(dfl_vec3_norm(c) / gn <= 1e-8 * (scale + dfl_vec3_norm(u)))) return 0;
    if (!(fabs(dfl_vec3_dot(u, G) / gn - d) <= 1e-8 * (scale + fabs(d)))) return 0;
    dfl_curvature k;
    if (dfl_curvature_implicit(G, H, &k, NULL) != DFL_OK) return 0;
    if (!(1 + k.k1 * d > 0) || !(1 + k.k2 * d > 0)) return 0;
    double gx = dfl_implicit_g(s, x, NULL, NULL);
    if (fabs(d) > 1e-12 * scale && (gx > 0) != (d > 0)) return 0;
    return 1;
}

/* The paper's Newton on the square system from p0 (input_implicit_fast.h). */
static int paper_newton(const imp_ctx *c, const double x[3], const double p0[3], double p[3])
{
    memcpy(p, p0, 3 * sizeof *p);
    return dfl_imp_square_newton(c->s, x, p, c->scale);
}

static void fill(const imp_ctx *c, const double x[3], const double p[3], int need_curv,
                 dfl_surfpoint *o)
{
    double G[3], H[9];
    dfl_implicit_g(c->s, p, G, H);
    double gn = dfl_vec3_norm(G);
    memcpy(o->p, p, 3 * sizeof *p);
    for (int j = 0; j < 3; j++) o->n[j] = G[j] / gn;
    o->d = (x[0] - p[0]) * o->n[0] + (x[1] - p[1]) * o->n[1] + (x[2] - p[2]) * o->n[2];
    if (!need_curv || dfl_curvature_implicit(G, H, &o->curv, NULL) != DFL_OK)
        dfl_curvature_set_nan(&o->curv);
}

/* The k-th start of the paper's methods (k = 1..PAPER_STARTS) into p0, from
 * the previous start prev (x for k = 1); 0 when there is none (grad g
 * vanishes: a walk ends there). */
static int paper_start(const imp_ctx *c, dfl_implicit_foot_method m, const double x[3], int k,
                       const double prev[3], double p0[3])
{
    double G[3];
    if (m == DFL_IMPLICIT_FOOT_WALK) {
        const double g = dfl_implicit_g(c->s, prev, G, NULL), gg = dfl_vec3_dot(G, G);
        if (!(gg > 0)) return 0;
        for (int j = 0; j < 3; j++) p0[j] = prev[j] - g * G[j] / gg;
        return 1;
    }
    double g = dfl_implicit_g(c->s, x, G, NULL);
    const double gg = dfl_vec3_dot(G, G), fr = (double)k / PAPER_STARTS;
    if (!(gg > 0)) return 0;
    if (m == DFL_IMPLICIT_FOOT_AGAINST) g = fabs(g);
    for (int j = 0; j < 3; j++) p0[j] = x[j] - fr * g * G[j] / gg;
    return 1;
}

static void paper_point(const imp_ctx *c, const double x[3], int need_curv, dfl_surfpoint *o)
{
    double best[3] = {NAN, NAN, NAN}, bd2 = HUGE_VAL, last[3] = {NAN, NAN, NAN};
    int ok = 0;
    double prev[3] = {x[0], x[1], x[2]};
    for (int k = 1; k <= PAPER_STARTS; k++) {
        double p0[3], p[3];
        if (!paper_start(c, c->method, x, k, prev, p0)) break;
        memcpy(prev, p0, sizeof prev);
        int conv = paper_newton(c, x, p0, p);
        if (!conv) {
            if (!ok && isfinite(p[0] + p[1] + p[2])) memcpy(last, p, sizeof last);
            continue;
        }
        double u[3] = {x[0] - p[0], x[1] - p[1], x[2] - p[2]}, d2 = dfl_vec3_dot(u, u);
        if (!ok || d2 < bd2) {
            memcpy(best, p, sizeof best);
            bd2 = d2;
        }
        ok = 1;
    }
    if (!ok) memcpy(best, last, sizeof best);
    o->certified = ok;
    if (isfinite(best[0] + best[1] + best[2])) {
        fill(c, x, best, need_curv, o);
    } else {
        for (int j = 0; j < 3; j++) o->p[j] = o->n[j] = NAN;
        o->d = NAN;
        dfl_curvature_set_nan(&o->curv);
    }
}

static void robust_point(const imp_ctx *c, const double x[3], int need_curv, dfl_surfpoint *o)
{
    double fp[3], fd;
    if (c->ix && dfl_imp_fast_foot(c->ix, x, fp, &fd)) {
        o->certified = 1;
        fill(c, x, fp, need_curv, o);
        o->d = fd;
        return;
    }
    dfl_footpoint f;
    int ok = dfl_implicit_footpoint_with(c->s, DFL_FOOT_NEWTON, x, &f, NULL) == DFL_OK;
    int cert = ok && dfl_proxy_implicit_certify(c->s, x, f.p, f.d);
    if (!cert) {
        /* the hard cases: Ceres LM from the same starts */
        dfl_footpoint h;
        if (dfl_implicit_footpoint_with(c->s, DFL_FOOT_CERES, x, &h, NULL) == DFL_OK) {
            int hc = dfl_proxy_implicit_certify(c->s, x, h.p, h.d);
            if (hc || !ok || fabs(h.d) < fabs(f.d)) {
                f = h;
                ok = 1;
                cert = hc;
            }
        }
    }
    o->certified = cert;
    if (!ok) {
        for (int j = 0; j < 3; j++) o->p[j] = o->n[j] = NAN;
        o->d = NAN;
        dfl_curvature_set_nan(&o->curv);
        return;
    }
    fill(c, x, f.p, need_curv, o);
    o->d = f.d;
}

static dfl_status imp_query(const void *vctx, size_t m, const double *x, int need_curv,
                            dfl_surfpoint *out, dfl_err *err)
{
    (void)err;
    const imp_ctx *c = vctx;
    for (size_t i = 0; i < m; i++) {
        if (c->method == DFL_IMPLICIT_FOOT_ROBUST) robust_point(c, x + 3 * i, need_curv, out + i);
        else paper_point(c, x + 3 * i, need_curv, out + i);
    }
    return DFL_OK;
}

static void imp_destroy(void *vctx)
{
    imp_ctx *c = vctx;
    dfl_imp_index_free(c->ix);
    dfl_implicit_free(c->s);
    free(c);
}

dfl_status dfl_proxy_input_implicit(dfl_implicit **imp, dfl_implicit_foot_method method,
                                    dfl_proxy_input *out, dfl_err *err)
{
    if (!imp || !*imp) return dfl_err_set(err, DFL_E_INPUT, "implicit input: no surface");
    if ((unsigned)method >= DFL_IMPLICIT_FOOT_COUNT) {
        dfl_implicit_free(*imp);
        *imp = NULL;
        return dfl_err_set(err, DFL_E_INPUT, "implicit input: unknown footpoint method %d",
                           (int)method);
    }
    imp_ctx *c = calloc(1, sizeof *c);
    if (!c) {
        dfl_implicit_free(*imp);
        *imp = NULL;
        return dfl_err_set(err, DFL_E_NOMEM, "implicit input: out of memory");
    }
    c->s = *imp;
    *imp = NULL;
    c->method = method;
    c->scale = dfl_implicit_scale(c->s);
    if (method == DFL_IMPLICIT_FOOT_ROBUST && !(c->ix = dfl_imp_index_new(c->s))) {
        imp_destroy(c);
        return dfl_err_set(err, DFL_E_NOMEM, "implicit input: out of memory");
    }
    out->name = "implicit";
    out->query = imp_query;
    out->destroy = imp_destroy;
    out->ctx = c;
    out->has_inside = 1;
    return DFL_OK;
}
