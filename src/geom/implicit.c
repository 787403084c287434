/* The implicit surface object: construction, evaluation of g in world
 * coordinates, and the surface samples that seed every footpoint search. */
#include "geom/implicit_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void dfl_implicit_options_default(dfl_implicit_options *opt)
{
    opt->backend = DFL_FOOT_NEWTON;
    opt->resolution = 64;
    opt->max_iterations = 100;
    opt->ceres_max_iterations = 1000;
}

double dfl_implicit_g(const dfl_implicit *s, const double x[3], double grad[3], double hess[9])
{
    double q[3], G[3], H[9];
    to_local(s, x, q);
    double g = dfl_poly3_eval(&s->g, q, hess ? 2 : (grad ? 1 : 0), G, H, NULL);
    if (grad) vec_to_world(s, G, grad);
    if (hess) {
        /* H_w = Q^T H_l Q */
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                double v = 0.0;
                for (int a = 0; a < 3; a++)
                    for (int b = 0; b < 3; b++) v += s->Q[3 * a + i] * H[3 * a + b] * s->Q[3 * b + j];
                hess[3 * i + j] = v;
            }
    }
    return g;
}

void dfl_implicit_g3(const dfl_implicit *s, const double x[3], double d3[27])
{
    double q[3], G[3], H[9], T[27];
    to_local(s, x, q);
    dfl_poly3_eval(&s->g, q, 3, G, H, T);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++) {
                double v = 0.0;
                for (int a = 0; a < 3; a++)
                    for (int b = 0; b < 3; b++)
                        for (int c = 0; c < 3; c++)
                            v += s->Q[3 * a + i] * s->Q[3 * b + j] * s->Q[3 * c + k] *
                                 T[9 * a + 3 * b + c];
                d3[9 * i + 3 * j + k] = v;
            }
}

double dfl_implicit_spacing(const dfl_implicit *s) { return s->h; }
double dfl_implicit_scale(const dfl_implicit *s) { return s->scale; }

const double *dfl_implicit_samples(const dfl_implicit *s, size_t *n)
{
    /* the first 3*ns doubles are the local copies the solver uses */
    *n = s->ns;
    return s->samp + 3 * s->ns;
}

/* ---- surface samples and their buckets ----------------------------------- */

static dfl_status make_samples(dfl_implicit *s, dfl_err *err)
{
    int res = s->opt.resolution;
    double ext[3], emax = 0.0;
    for (int a = 0; a < 3; a++) {
        ext[a] = s->hi[a] - s->lo[a];
        emax = fmax(emax, ext[a]);
    }
    double h = emax / (res - 1);
    s->h = h;
    s->scale = sqrt(dfl_vec3_dot(ext, ext));
    int n[3];
    for (int a = 0; a < 3; a++) n[a] = (int)ceil(ext[a] / h) + 1;
    size_t cap = 1024, ns = 0;
    double *buf = malloc(cap * 3 * sizeof *buf);
    if (!buf) return dfl_err_set(err, DFL_E_NOMEM, "implicit: out of memory");
    for (int k = 0; k < n[2]; k++)
        for (int j = 0; j < n[1]; j++)
            for (int i = 0; i < n[0]; i++) {
                double node[3] = {s->lo[0] + i * h, s->lo[1] + j * h, s->lo[2] + k * h};
                double G[3];
                double g = g_local(s, node, G, NULL);
                double gn = sqrt(dfl_vec3_dot(G, G));
                if (!(gn > 0.0) || fabs(g) > 1.5 * h * gn) continue;
                double q[3] = {node[0], node[1], node[2]};
                if (!project(s, q)) continue;
                double dq[3] = {q[0] - node[0], q[1] - node[1], q[2] - node[2]};
                if (dfl_vec3_dot(dq, dq) > 9.0 * h * h) continue;
                if (ns == cap) {
                    cap *= 2;
                    double *nb = realloc(buf, cap * 3 * sizeof *nb);
                    if (!nb) {
                        free(buf);
                        return dfl_err_set(err, DFL_E_NOMEM, "implicit: out of memory");
                    }
                    buf = nb;
                }
                memcpy(buf + 3 * ns, q, sizeof q);
                ns++;
            }
    if (ns == 0) {
        free(buf);
        return dfl_err_set(err, DFL_E_INPUT,
                           "implicit: no point of g = 0 found in the bounding box (empty surface?)");
    }
    /* buckets of side 2h over the box grown by 2h */
    s->bcell = 2.0 * h;
    size_t nbt = 1;
    for (int a = 0; a < 3; a++) {
        s->blo[a] = s->lo[a] - 2.0 * h;
        s->nb[a] = (int)ceil((ext[a] + 4.0 * h) / s->bcell);
        if (s->nb[a] < 1) s->nb[a] = 1;
        nbt *= (size_t)s->nb[a];
    }
    s->bstart = calloc(nbt + 1, sizeof *s->bstart);
    /* local copies sorted by bucket, then world copies behind them */
    s->samp = malloc(ns * 6 * sizeof *s->samp);
    size_t *cell = malloc(ns * sizeof *cell);
    if (!s->bstart || !s->samp || !cell) {
        free(buf);
        free(cell);
        return dfl_err_set(err, DFL_E_NOMEM, "implicit: out of memory");
    }
    for (size_t i = 0; i < ns; i++) {
        int c[3];
        bucket_of(s, buf + 3 * i, c);
        cell[i] = bucket_index(s, c[0], c[1], c[2]);
        s->bstart[cell[i] + 1]++;
    }
    for (size_t b = 0; b < nbt; b++) s->bstart[b + 1] += s->bstart[b];
    size_t *fill = calloc(nbt, sizeof *fill);
    if (!fill) {
        free(buf);
        free(cell);
        return dfl_err_set(err, DFL_E_NOMEM, "implicit: out of memory");
    }
    for (size_t i = 0; i < ns; i++) {
        size_t at = s->bstart[cell[i]] + fill[cell[i]]++;
        memcpy(s->samp + 3 * at, buf + 3 * i, 3 * sizeof *buf);
    }
    for (size_t i = 0; i < ns; i++) to_world(s, s->samp + 3 * i, s->samp + 3 * (ns + i));
    s->ns = ns;
    free(fill);
    free(cell);
    free(buf);
    return DFL_OK;
}

/* ---- construction --------------------------------------------------------- */

void dfl_implicit_free(dfl_implicit *s)
{
    if (!s) return;
    dfl_lsq_ctx_free(s->lsq);
    free(s->samp);
    free(s->bstart);
    free(s);
}

dfl_status dfl_implicit_new(int nterms, const dfl_monomial *terms, const double *o,
                            const double Q[9], const double lo[3], const double hi[3],
                            const dfl_implicit_options *opt, dfl_implicit **out, dfl_err *err)
{
    if (nterms < 1 || nterms > DFL_IMPLICIT_MAX_TERMS)
        return dfl_err_set(err, DFL_E_INPUT, "implicit: %d terms (1..%d)", nterms,
                           DFL_IMPLICIT_MAX_TERMS);
    dfl_implicit_options o2;
    if (opt) o2 = *opt; else dfl_implicit_options_default(&o2);
    if (o2.resolution < 8 || o2.resolution > 1024)
        return dfl_err_set(err, DFL_E_INPUT, "implicit: resolution %d outside [8, 1024]",
                           o2.resolution);
    if (o2.max_iterations < 1 || o2.ceres_max_iterations < 1)
        return dfl_err_set(err, DFL_E_INPUT, "implicit: iteration limits must be >= 1");
    for (int a = 0; a < 3; a++)
        if (!(lo[a] < hi[a]) || !isfinite(lo[a]) || !isfinite(hi[a]))
            return dfl_err_set(err, DFL_E_INPUT, "implicit: empty bounding box on axis %d", a);
    dfl_implicit *s = calloc(1, sizeof *s);
    if (!s) return dfl_err_set(err, DFL_E_NOMEM, "implicit: out of memory");
    for (int k = 0; k < nterms; k++) {
        const dfl_monomial *m = &terms[k];
        int deg = m->e[0] + m->e[1] + m->e[2];
        if (m->e[0] < 0 || m->e[1] < 0 || m->e[2] < 0 || deg > DFL_IMPLICIT_MAX_DEGREE ||
            !isfinite(m->c)) {
            free(s);
            return dfl_err_set(err, DFL_E_INPUT,
                               "implicit: term %d has bad exponents or coefficient", k);
        }
        dfl_poly3_term(&s->g, m->c, m->e[0], m->e[1], m->e[2]);
    }
    for (int a = 0; a < 3; a++) dfl_poly3_deriv(&s->g, a, &s->gd[a]);
    for (int a = 0; a < 3; a++) s->o[a] = o ? o[a] : 0.0;
    for (int i = 0; i < 9; i++) s->Q[i] = Q ? Q[i] : (i % 4 == 0 ? 1.0 : 0.0);
    if (Q) {
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                double v = dfl_vec3_dot(Q + 3 * i, Q + 3 * j) - (i == j);
                if (fabs(v) > 1e-12) {
                    free(s);
                    return dfl_err_set(err, DFL_E_INPUT, "implicit: frame is not orthonormal");
                }
            }
    }
    memcpy(s->lo, lo, sizeof s->lo);
    memcpy(s->hi, hi, sizeof s->hi);
    s->opt = o2;
    dfl_status st = make_samples(s, err);
    if (st == DFL_OK) st = dfl_lsq_ctx_new(&s->lsq, err);
    if (st != DFL_OK) {
        dfl_implicit_free(s);
        return st;
    }
    *out = s;
    return DFL_OK;
}
