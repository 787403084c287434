/* Private to the implicit-surface files (implicit.c, implicit_foot.c,
 * implicit_sdf.c, implicit_surfaces.c): the object's layout and the small
 * frame and evaluation helpers they share.  Not an API: include
 * geom/implicit.h instead. */
#ifndef DFL_GEOM_IMPLICIT_IMPL_H
#define DFL_GEOM_IMPLICIT_IMPL_H

#include <math.h>

#include "core/vec.h"
#include "geom/implicit.h"
#include "geom/poly3.h"
#include "solve/lsq.h"

struct dfl_implicit {
    dfl_poly3 g, gd[3];         /* g and its three partials, local coordinates */
    double o[3], Q[9];          /* local = Q (world - o) */
    double lo[3], hi[3];        /* local box holding the zero set */
    dfl_implicit_options opt;
    double h, scale;
    size_t ns;
    double *samp;               /* ns * 3, local, sorted by bucket */
    double blo[3], bcell;
    int nb[3];
    size_t *bstart;             /* nb0*nb1*nb2 + 1 */
    dfl_lsq_ctx *lsq;
};

static inline void to_local(const dfl_implicit *s, const double x[3], double q[3])
{
    double d[3] = {x[0] - s->o[0], x[1] - s->o[1], x[2] - s->o[2]};
    for (int i = 0; i < 3; i++) q[i] = dfl_vec3_dot(s->Q + 3 * i, d);
}

static inline void vec_to_local(const dfl_implicit *s, const double v[3], double q[3])
{
    for (int i = 0; i < 3; i++) q[i] = dfl_vec3_dot(s->Q + 3 * i, v);
}

static inline void vec_to_world(const dfl_implicit *s, const double q[3], double v[3])
{
    for (int j = 0; j < 3; j++) v[j] = s->Q[j] * q[0] + s->Q[3 + j] * q[1] + s->Q[6 + j] * q[2];
}

static inline void to_world(const dfl_implicit *s, const double q[3], double x[3])
{
    vec_to_world(s, q, x);
    for (int j = 0; j < 3; j++) x[j] += s->o[j];
}

static inline double g_local(const dfl_implicit *s, const double q[3], double G[3], double H[9])
{
    if (H) return dfl_poly3_eval(&s->g, q, 2, G, H, NULL);
    if (G) return dfl_poly3_eval(&s->g, q, 1, G, NULL, NULL);
    return dfl_poly3_eval(&s->g, q, 0, NULL, NULL, NULL);
}

static inline double dist2_to(const double *a, const double *b)
{
    double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return dfl_vec3_dot(d, d);
}

/* Samples are bucketed in cubes of side bcell from blo: the cell of q,
 * clamped to the grid. */
static inline void bucket_of(const dfl_implicit *s, const double q[3], int c[3])
{
    for (int a = 0; a < 3; a++) {
        double f = floor((q[a] - s->blo[a]) / s->bcell);
        /* NaN too to 0: casting it to int is undefined */
        int i = !(f >= 0.0) ? 0 : (f >= s->nb[a] ? s->nb[a] - 1 : (int)f);
        c[a] = i;
    }
}

static inline size_t bucket_index(const dfl_implicit *s, int i, int j, int k)
{
    return ((size_t)k * (size_t)s->nb[1] + (size_t)j) * (size_t)s->nb[0] + (size_t)i;
}

/* Projects q onto g = 0 along the gradient (Newton on g restricted to the
 * gradient line); 1 if it converged. */
static inline int project(const dfl_implicit *s, double q[3])
{
    for (int it = 0; it < 40; it++) {
        double G[3];
        double g = g_local(s, q, G, NULL);
        double gg = dfl_vec3_dot(G, G);
        if (!(gg > 0.0)) return 0;
        double step = g / gg;
        for (int a = 0; a < 3; a++) q[a] -= step * G[a];
        if (fabs(step) * sqrt(gg) <= 1e-14 * s->scale) return 1;
    }
    return 0;
}

#endif
