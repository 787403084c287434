#include "proxy/analytic_inputs.h"

#include <math.h>
#include <string.h>

#include "core/vec.h"

static void unit_or(double v[3], const double *fallback)
{
    double l = dfl_vec3_norm(v);
    if (l > 0)
        for (int j = 0; j < 3; j++) v[j] /= l;
    else
        for (int j = 0; j < 3; j++) v[j] = fallback[j];
}

/* a unit vector orthogonal to a */
static void ortho(const double a[3], double o[3])
{
    double t2[3];
    dfl_vec3_tangent_basis(a, o, t2);
}

static void set_curv(dfl_surfpoint *sp, double k1, const double e1[3], double k2)
{
    dfl_curvature *c = &sp->curv;
    c->k1 = k1;
    c->k2 = k2;
    memcpy(c->e1, e1, sizeof c->e1);
    dfl_vec3_cross(sp->n, e1, c->e2);
    memcpy(c->n, sp->n, sizeof c->n);
    c->K = k1 * k2;
    c->H = 0.5 * (k1 + k2);
}

void ta_answer(const ta_shape *s, const double x[3], dfl_surfpoint *sp)
{
    double w[3];
    for (int j = 0; j < 3; j++) w[j] = x[j] - s->c[j];
    sp->certified = 1;
    if (s->kind == TA_SPHERE) {
        double n[3] = {w[0], w[1], w[2]}, e[3];
        const double l = dfl_vec3_norm(w);
        unit_or(n, (const double[3]){1, 0, 0});
        for (int j = 0; j < 3; j++) sp->n[j] = n[j], sp->p[j] = s->c[j] + s->R * n[j];
        sp->d = l - s->R;
        ortho(n, e);
        set_curv(sp, 1 / s->R, e, 1 / s->R);
    } else if (s->kind == TA_PLANE) {
        sp->d = dfl_vec3_dot(w, s->a);
        for (int j = 0; j < 3; j++) sp->n[j] = s->a[j], sp->p[j] = x[j] - sp->d * s->a[j];
        double e[3];
        ortho(s->a, e);
        set_curv(sp, 0, e, 0);
    } else if (s->kind == TA_CYLINDER) {
        const double z = dfl_vec3_dot(w, s->a);
        double n[3], o[3];
        for (int j = 0; j < 3; j++) n[j] = w[j] - z * s->a[j];
        const double l = dfl_vec3_norm(n);
        ortho(s->a, o);
        unit_or(n, o);
        for (int j = 0; j < 3; j++)
            sp->n[j] = n[j], sp->p[j] = s->c[j] + z * s->a[j] + s->R * n[j];
        sp->d = l - s->R;
        set_curv(sp, 0, s->a, 1 / s->R); /* e2 = n x a, around the axis */
    } else {
        const double z = dfl_vec3_dot(w, s->a);
        double rh[3], o[3], q[3], n[3];
        for (int j = 0; j < 3; j++) rh[j] = w[j] - z * s->a[j];
        ortho(s->a, o);
        unit_or(rh, o);
        for (int j = 0; j < 3; j++) q[j] = s->c[j] + s->R * rh[j];
        for (int j = 0; j < 3; j++) n[j] = x[j] - q[j];
        const double D = dfl_vec3_norm(n);
        unit_or(n, rh);
        for (int j = 0; j < 3; j++) sp->n[j] = n[j], sp->p[j] = q[j] + s->r * n[j];
        sp->d = D - s->r;
        /* parallel circle: kappa = cos(theta) / (R + r cos(theta)), along phi = a x rh */
        const double ct = dfl_vec3_dot(n, rh);
        double ph[3];
        dfl_vec3_cross(s->a, rh, ph);
        set_curv(sp, ct / (s->R + s->r * ct), ph, 1 / s->r);
    }
}

double ta_sdf(const ta_shape *s, const double x[3])
{
    dfl_surfpoint sp;
    ta_answer(s, x, &sp);
    return sp.d;
}

static dfl_status ta_query(const void *ctx, size_t m, const double *x, int need_curv,
                           dfl_surfpoint *out, dfl_err *err)
{
    (void)need_curv;
    (void)err;
    for (size_t i = 0; i < m; i++) ta_answer(ctx, x + 3 * i, &out[i]);
    return DFL_OK;
}

void ta_input(const ta_shape *s, dfl_proxy_input *out)
{
    out->name = "analytic";
    out->query = ta_query;
    out->destroy = NULL;
    out->ctx = (void *)s;
    out->has_inside = 1;
}
