/* The encoder of proxy/decode.h, dfl_proxy_encode (named for what it holds;
 * the decoding is inline in decode.h, where its derivation is). */
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
    if (dfl_vec3_dot(d, d) < delta * delta) {
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
