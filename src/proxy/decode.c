/* The derivation is in decode.h; this file keeps the order of operations
 * that makes each formula finite at zero curvature (no 1/kappa anywhere). */
#include "proxy/decode.h"

#include <math.h>

#include "core/vec.h"

int dfl_proxy_encode(int order, const double xc[3], const dfl_surfpoint *sp,
                     const double *offset, double delta, double *s, int *side)
{
    double p[3], d[3];
    for (int j = 0; j < 3; j++) p[j] = sp->p[j] + (offset ? offset[j] : 0.0);
    for (int j = 0; j < 3; j++) d[j] = p[j] - xc[j];
    int moved = 0;
    if (dfl_vec3_norm(d) < delta) {
        for (int j = 0; j < 3; j++) p[j] = xc[j] - delta * sp->n[j];
        for (int j = 0; j < 3; j++) d[j] = p[j] - xc[j];
        moved = 1;
    }
    *side = sp->d >= 0 ? 1 : -1;
    for (int j = 0; j < 3; j++) s[j] = p[j];
    if (order == 1) return moved;

    /* n = sgn (p - xc)/|p - xc| must be the input's normal (side of it). */
    const double sgn = dfl_vec3_dot(sp->n, d) >= 0 ? 1.0 : -1.0;
    const dfl_curvature *c = &sp->curv;
    const int first = fabs(c->k1) >= fabs(c->k2);
    const double *e = first ? c->e1 : c->e2;
    s[3] = first ? c->k1 : c->k2;
    s[4] = first ? c->k2 : c->k1;
    const double len = sgn > 0 ? 1.0 : 2.0;
    for (int j = 0; j < 3; j++) s[5 + j] = len * e[j];
    return moved;
}

void dfl_proxy_decode(int order, dfl_proxy_position pos, const double xc[3], const double *s,
                      int side, dfl_proxy_geom *g)
{
    double d[3];
    for (int j = 0; j < 3; j++) {
        if (pos == DFL_PROXY_DISPLACEMENT) {
            d[j] = s[j];
            g->p[j] = xc[j] + s[j];
        } else {
            g->p[j] = s[j];
            d[j] = s[j] - xc[j];
        }
    }
    const double dl = dfl_vec3_norm(d);
    if (order == 1) {
        /* n points from the footpoint to xc, flipped inside. */
        const double f = -(double)side / dl;
        for (int j = 0; j < 3; j++) g->n[j] = f * d[j];
        g->kr = g->kR = 0.0;
        for (int j = 0; j < 3; j++) g->t[j] = g->b[j] = 0.0;
        return;
    }
    const double *lt = s + 5;
    const double l2 = dfl_vec3_dot(lt, lt);
    const double sgn = l2 > 2.25 ? -1.0 : 1.0;
    for (int j = 0; j < 3; j++) g->n[j] = sgn * d[j] / dl;
    /* t is orthogonal to n up to the storage's rounding; project it back
     * so that (n, t, b) is orthonormal. */
    const double tn = dfl_vec3_dot(lt, g->n);
    double t[3];
    for (int j = 0; j < 3; j++) t[j] = lt[j] - tn * g->n[j];
    const double tl = dfl_vec3_norm(t);
    for (int j = 0; j < 3; j++) g->t[j] = t[j] / tl;
    dfl_vec3_cross(g->n, g->t, g->b);
    g->kr = s[3];
    g->kR = s[4];
}

double dfl_proxy_geom_eval(const dfl_proxy_geom *g, int order, const double x[3], double *grad)
{
    const double v[3] = {x[0] - g->p[0], x[1] - g->p[1], x[2] - g->p[2]};
    const double vn = dfl_vec3_dot(v, g->n);
    if (order == 1) {
        if (grad)
            for (int j = 0; j < 3; j++) grad[j] = g->n[j];
        return vn;
    }
    const double vt = dfl_vec3_dot(v, g->t), vb = dfl_vec3_dot(v, g->b);
    const double kR = g->kR, kr = g->kr;
    /* radial offset in p's meridian half-plane: the equator circle */
    const double uR = 1.0 + kR * vn, wR = kR * vb;
    const double SR = sqrt(uR * uR + wR * wR);
    const double a = (kR * (vn * vn + vb * vb) + 2.0 * vn) / (1.0 + SR);
    /* distance to the tube circle */
    const double ur = 1.0 + kr * a, wr = kr * vt;
    const double Sr = sqrt(ur * ur + wr * wr);
    const double phi = (kr * (a * a + vt * vt) + 2.0 * a) / (1.0 + Sr);
    if (grad) {
        double ga[3];
        if (SR > 0)
            for (int j = 0; j < 3; j++) ga[j] = (uR * g->n[j] + wR * g->b[j]) / SR;
        else
            for (int j = 0; j < 3; j++) ga[j] = g->n[j];
        if (Sr > 0)
            for (int j = 0; j < 3; j++) grad[j] = (ur * ga[j] + wr * g->t[j]) / Sr;
        else
            for (int j = 0; j < 3; j++) grad[j] = ga[j];
    }
    return phi;
}
