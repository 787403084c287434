#include "rfunc/tri3d.h"

#include <assert.h>
#include <math.h>
#include <string.h>

#include "core/names.h"
#include "rfunc/trim.h"

#define NAME_(code, name) [code] = name,
const char *const dfl_rfunc_tri_trim_names[DFL_RFUNC_TRI_TRIM_COUNT] = {
    DFL_RFUNC_TRI_TRIM_LIST(NAME_)};
#undef NAME_

const char *dfl_rfunc_tri_trim_name(dfl_rfunc_tri_trim trim)
{
    if ((int)trim < 0 || (int)trim >= DFL_RFUNC_TRI_TRIM_COUNT) return "?";
    return dfl_rfunc_tri_trim_names[trim];
}

dfl_status dfl_rfunc_tri_trim_parse(const char *name, dfl_rfunc_tri_trim *out, dfl_err *err)
{
    int i;
    dfl_status st = dfl_names_parse("triangle trim", dfl_rfunc_tri_trim_names,
                                    DFL_RFUNC_TRI_TRIM_COUNT, name, &i, err);
    if (st == DFL_OK) *out = (dfl_rfunc_tri_trim)i;
    return st;
}

static double dot3(const double *u, const double *v)
{
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

static void cross3(const double *u, const double *v, double *w)
{
    double r[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                   u[0] * v[1] - u[1] * v[0]};
    w[0] = r[0];
    w[1] = r[1];
    w[2] = r[2];
}

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
        lmax = fmax(lmax, sqrt(dot3(e[i], e[i])));
        size = fmax(size, amax3(t.v[i]));
    }
    double nn[3];
    cross3(e[0], e[1], nn);
    const double area2 = sqrt(dot3(nn, nn));
    if (!(area2 > 1e-12 * lmax * lmax))
        return dfl_err_set(err, DFL_E_INPUT,
                           "degenerate triangle: vertices are collinear or coincide");
    for (int j = 0; j < 3; j++) t.n[j] = nn[j] / area2;
    for (int i = 0; i < 3; i++) {
        /* n x e_i points into the triangle for the orientation n defines. */
        double m[3];
        cross3(t.n, e[i], m);
        const double mn = sqrt(dot3(m, m));
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
        p[i] = dot3(w, t->m[i]);
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
    return trim_core(t, x, dot3(w, t->n), grad);
}

double dfl_rfunc_tri_eval(const dfl_rfunc_tri *t, const double *x, double *grad)
{
    double w[3] = {x[0] - t->v[0][0], x[1] - t->v[0][1], x[2] - t->v[0][2]};
    const double f = dot3(w, t->n);
    double gt[3], hgF[3] = {f * t->n[0], f * t->n[1], f * t->n[2]};
    const double tv = trim_core(t, x, f, grad ? gt : NULL);
    return dfl_rfunc_compose(3, t->o.smooth, fabs(f), hgF, tv, gt, grad);
}

dfl_status dfl_rfunc_tri_jet(const dfl_rfunc_tri *t, const double *x, const double *dir, int K,
                             dfl_jet *out, dfl_err *err)
{
    assert(K >= 0 && K <= DFL_JET_MAX);
    const double xs = fmax(t->scale, amax3(x));
    const double dn = sqrt(dot3(dir, dir));
    dfl_jet f, F, p[3], c, t1, tv;
    dfl_status st;
    double w[3] = {x[0] - t->v[0][0], x[1] - t->v[0][1], x[2] - t->v[0][2]};
    dfl_jet_linear(dfl_rfunc_snap(dot3(w, t->n), xs), dfl_rfunc_snap(dot3(dir, t->n), dn), K, &f);
    dfl_jet_mul(&f, &f, &F);
    for (int i = 0; i < 3; i++) {
        double wi[3] = {x[0] - t->v[i][0], x[1] - t->v[i][1], x[2] - t->v[i][2]};
        dfl_jet_linear(dfl_rfunc_snap(dot3(wi, t->m[i]), xs),
                       dfl_rfunc_snap(dot3(dir, t->m[i]), dn), K, &p[i]);
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
