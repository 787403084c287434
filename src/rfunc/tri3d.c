#include "rfunc/tri3d.h"

#include <assert.h>
#include <math.h>
#include <string.h>

#include "core/vec.h"
#include "rfunc/trim.h"

DFL_NAMES_DEFINE(dfl_rfunc_tri_trim, DFL_RFUNC_TRI_TRIM_LIST, DFL_RFUNC_TRI_TRIM_COUNT,
                 dfl_rfunc_tri_trim_names, dfl_rfunc_tri_trim_name, dfl_rfunc_tri_trim_parse,
                 "triangle trim")

static double amax3(const double *u)
{
    return fmax(fabs(u[0]), fmax(fabs(u[1]), fabs(u[2])));
}

dfl_rfunc_tri_opts dfl_rfunc_tri_defaults(void)
{
    dfl_rfunc_tri_opts o = {DFL_RFUNC_TRI_CONDITIONAL, 0, 0.2, 2};
    return o;
}

dfl_status dfl_rfunc_tri_init(const double *A, const double *B, const double *C,
                              const dfl_rfunc_tri_opts *o, dfl_rfunc_tri *out, dfl_err *err)
{
    if (o->trim != DFL_RFUNC_TRI_PRISM && o->trim != DFL_RFUNC_TRI_CONDITIONAL)
        return dfl_err_set(err, DFL_E_INPUT, "triangle: unknown trim %d", (int)o->trim);
    if (o->trim == DFL_RFUNC_TRI_CONDITIONAL &&
        (!(o->a > 0.0) || !isfinite(o->a) || o->k < 2 || o->k % 2 != 0))
        return dfl_err_set(err, DFL_E_INPUT,
                           "triangle: conditional trim needs a > 0 and an even k >= 2"
                           " (got a = %g, k = %d)",
                           o->a, o->k);
    dfl_rfunc_tri t;
    memset(&t, 0, sizeof t);
    t.o = *o;
    const double *V[3] = {A, B, C};
    double lmax = 0.0, size = 0.0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            if (!isfinite(V[i][j]))
                return dfl_err_set(err, DFL_E_INPUT, "triangle: non-finite vertex coordinate");
            t.v[i][j] = V[i][j];
        }
    double e[3][3];
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) e[i][j] = t.v[(i + 1) % 3][j] - t.v[i][j];
        lmax = fmax(lmax, sqrt(dfl_vec3_dot(e[i], e[i])));
        size = fmax(size, amax3(t.v[i]));
    }
    double nn[3];
    dfl_vec3_cross(e[0], e[1], nn);
    const double area2 = sqrt(dfl_vec3_dot(nn, nn));
    if (!(area2 > 1e-12 * lmax * lmax))
        return dfl_err_set(err, DFL_E_INPUT,
                           "degenerate triangle: vertices are collinear or coincide");
    for (int j = 0; j < 3; j++) t.n[j] = nn[j] / area2;
    for (int i = 0; i < 3; i++) {
        /* n x e_i points into the triangle for the orientation n defines. */
        double m[3];
        dfl_vec3_cross(t.n, e[i], m);
        const double mn = sqrt(dfl_vec3_dot(m, m));
        for (int j = 0; j < 3; j++) t.m[i][j] = m[j] / mn;
    }
    t.scale = fmax(size, lmax);
    *out = t;
    return DFL_OK;
}

/* Conditional term a f^k (k even) and its derivative in f. */
static double cond_term(const dfl_rfunc_tri *t, double f, double *dcdf)
{
    if (t->o.trim != DFL_RFUNC_TRI_CONDITIONAL) {
        *dcdf = 0.0;
        return 0.0;
    }
    double fk1 = 1.0;
    for (int i = 0; i < t->o.k - 1; i++) fk1 *= f;
    *dcdf = t->o.a * t->o.k * fk1;
    return t->o.a * fk1 * f;
}

static double trim_core(const dfl_rfunc_tri *t, const double *x, double f, double *gt)
{
    double p[3];
    for (int i = 0; i < 3; i++) {
        double w[3] = {x[0] - t->v[i][0], x[1] - t->v[i][1], x[2] - t->v[i][2]};
        p[i] = dfl_vec3_dot(w, t->m[i]);
    }
    double dcdf;
    const double c = cond_term(t, f, &dcdf);
    double ax, ay, ac, bx, by, bc;
    const double t1 = dfl_rfunc_conj0(p[0], p[1], c, &ax, &ay, &ac);
    const double tv = dfl_rfunc_conj0(t1, p[2], c, &bx, &by, &bc);
    if (gt) {
        /* grad c = dc/df n; chain rule through the left fold. */
        const double cn = (bx * ac + bc) * dcdf;
        for (int j = 0; j < 3; j++)
            gt[j] = bx * (ax * t->m[0][j] + ay * t->m[1][j]) + by * t->m[2][j] + cn * t->n[j];
    }
    return tv;
}

double dfl_rfunc_tri_trim_eval(const dfl_rfunc_tri *t, const double *x, double *grad)
{
    double w[3] = {x[0] - t->v[0][0], x[1] - t->v[0][1], x[2] - t->v[0][2]};
    return trim_core(t, x, dfl_vec3_dot(w, t->n), grad);
}

double dfl_rfunc_tri_eval(const dfl_rfunc_tri *t, const double *x, double *grad)
{
    double w[3] = {x[0] - t->v[0][0], x[1] - t->v[0][1], x[2] - t->v[0][2]};
    const double f = dfl_vec3_dot(w, t->n);
    double gt[3], hgF[3] = {f * t->n[0], f * t->n[1], f * t->n[2]};
    const double tv = trim_core(t, x, f, grad ? gt : NULL);
    return dfl_rfunc_compose(3, t->o.smooth, fabs(f), hgF, tv, gt, grad);
}

dfl_status dfl_rfunc_tri_jet(const dfl_rfunc_tri *t, const double *x, const double *dir, int K,
                             dfl_jet *out, dfl_err *err)
{
    assert(K >= 0 && K <= DFL_JET_MAX);
    const double xs = fmax(t->scale, amax3(x));
    const double dn = sqrt(dfl_vec3_dot(dir, dir));
    dfl_jet f, F, p[3], c, t1, tv;
    dfl_status st;
    double w[3] = {x[0] - t->v[0][0], x[1] - t->v[0][1], x[2] - t->v[0][2]};
    dfl_jet_linear(dfl_rfunc_snap(dfl_vec3_dot(w, t->n), xs),
                   dfl_rfunc_snap(dfl_vec3_dot(dir, t->n), dn), K, &f);
    dfl_jet_mul(&f, &f, &F);
    for (int i = 0; i < 3; i++) {
        double wi[3] = {x[0] - t->v[i][0], x[1] - t->v[i][1], x[2] - t->v[i][2]};
        dfl_jet_linear(dfl_rfunc_snap(dfl_vec3_dot(wi, t->m[i]), xs),
                       dfl_rfunc_snap(dfl_vec3_dot(dir, t->m[i]), dn), K, &p[i]);
    }
    const dfl_jet *cp = NULL;
    if (t->o.trim == DFL_RFUNC_TRI_CONDITIONAL) {
        if ((st = dfl_jet_powi(&f, t->o.k, &c, err)) != DFL_OK) return st;
        dfl_jet_scale(&c, t->o.a, &c);
        cp = &c;
    }
    if ((st = dfl_rfunc_conj0_jet(&p[0], &p[1], cp, &t1, err)) != DFL_OK) return st;
    if ((st = dfl_rfunc_conj0_jet(&t1, &p[2], cp, &tv, err)) != DFL_OK) return st;
    return dfl_rfunc_compose_jet(t->o.smooth, &F, &tv, out, err);
}
