/* Footpoints and the closed-curve SDF (formulas and conventions in
 * footpoint.h).  Queries keep everything on the stack so that a shape's
 * batch eval can run in parallel without allocation; only the ceres
 * backend allocates, inside Ceres. */
#include "geom/footpoint.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/polygonize.h"
#include "solve/lsq.h"

#define KMAX DFL_BSPLINE_MAX_ORDER

void dfl_foot_opts_default(dfl_foot_opts *o)
{
    o->backend = DFL_FOOT_NEWTON;
    o->samples_per_span = 16;
    o->candidates = 4;
    o->max_iter = 100;
    o->tie_rel = 1e-9;
}

dfl_status dfl_foot_opts_check(const dfl_foot_opts *o, dfl_err *err)
{
    if (o->backend != DFL_FOOT_NEWTON && o->backend != DFL_FOOT_CERES)
        return dfl_err_set(err, DFL_E_INPUT, "backend: expected newton or ceres");
    if (o->samples_per_span < 2 || o->samples_per_span > 10000)
        return dfl_err_set(err, DFL_E_INPUT, "samples_per_span = %d: expected 2..10000",
                           o->samples_per_span);
    if (o->candidates < 1 || o->candidates > DFL_FOOT_MAX_CAND)
        return dfl_err_set(err, DFL_E_INPUT, "candidates = %d: expected 1..%d", o->candidates,
                           DFL_FOOT_MAX_CAND);
    if (o->max_iter < 1 || o->max_iter > 100000)
        return dfl_err_set(err, DFL_E_INPUT, "max_iter = %d: expected 1..100000", o->max_iter);
    if (!(o->tie_rel >= 0.0 && o->tie_rel < 1.0))
        return dfl_err_set(err, DFL_E_INPUT, "tie_rel = %g: expected [0, 1)", o->tie_rel);
    return DFL_OK;
}

static double dot3(int n, const double *a, const double *b)
{
    double s = 0.0;
    for (int j = 0; j < n; j++) s += a[j] * b[j];
    return s;
}

static double d2(int n, const double *a, const double *b)
{
    double s = 0.0;
    for (int j = 0; j < n; j++) s += (a[j] - b[j]) * (a[j] - b[j]);
    return s;
}

/* Rounding of g = |P - x|^2 / 2 at the point P (n coordinates): |r| times
 * the rounding of P and x, plus g's own.  The Newton step controls of
 * curves and surfaces accept a step that stays within it. */
static double g_noise(int n, const double *P, const double *x, double g)
{
    return 4e-15 * (g + sqrt(2.0 * g) * (sqrt(dot3(n, P, P)) + sqrt(dot3(n, x, x)))) + 1e-300;
}

static double cp_extent(int dim, size_t n, const double *cp)
{
    double ext = 0.0;
    for (int j = 0; j < dim; j++) {
        double lo = INFINITY, hi = -INFINITY;
        for (size_t i = 0; i < n; i++) {
            lo = fmin(lo, cp[i * (size_t)dim + (size_t)j]);
            hi = fmax(hi, cp[i * (size_t)dim + (size_t)j]);
        }
        ext = fmax(ext, hi - lo);
    }
    return ext;
}

/* top-k list of (value, index) kept sorted ascending */
typedef struct topk {
    int n, k;
    double g[DFL_FOOT_MAX_CAND];
    size_t i[DFL_FOOT_MAX_CAND];
    size_t j[DFL_FOOT_MAX_CAND];
    size_t p[DFL_FOOT_MAX_CAND];
} topk;

static void topk_insert(topk *t, double g, size_t p, size_t i, size_t j)
{
    if (t->n == t->k && g >= t->g[t->n - 1]) return;
    int pos = t->n < t->k ? t->n++ : t->n - 1;
    while (pos > 0 && t->g[pos - 1] > g) {
        t->g[pos] = t->g[pos - 1];
        t->i[pos] = t->i[pos - 1];
        t->j[pos] = t->j[pos - 1];
        t->p[pos] = t->p[pos - 1];
        pos--;
    }
    t->g[pos] = g;
    t->i[pos] = i;
    t->j[pos] = j;
    t->p[pos] = p;
}

/* ======================================================== curves ===== */

struct dfl_curve_locator {
    const dfl_bspline *c;
    dfl_foot_opts o;
    size_t ns;
    double *ts, *ps;
    double size;
    dfl_lsq_ctx *lsq;
};

dfl_status dfl_curve_locator_new(const dfl_bspline *c, const dfl_foot_opts *opt,
                                 dfl_curve_locator **out, dfl_err *err)
{
    dfl_foot_opts o;
    if (opt) o = *opt;
    else dfl_foot_opts_default(&o);
    dfl_status st = dfl_foot_opts_check(&o, err);
    if (st != DFL_OK) return st;
    dfl_curve_locator *L = calloc(1, sizeof *L);
    if (!L) return dfl_err_set(err, DFL_E_NOMEM, "out of memory for a curve locator");
    L->c = c;
    L->o = o;
    size_t nsp = dfl_bspline_span_count(c), S = (size_t)o.samples_per_span;
    L->ns = nsp * S + (c->closed ? 0 : 1);
    L->ts = malloc(L->ns * sizeof(double));
    L->ps = malloc(L->ns * (size_t)c->dim * sizeof(double));
    if (!L->ts || !L->ps) {
        dfl_curve_locator_free(L);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory for a curve locator");
    }
    size_t k = 0;
    for (size_t s = 0; s < nsp; s++) {
        size_t j = dfl_bspline_span_index(c, s);
        double a = c->knots[j], b = c->knots[j + 1];
        for (size_t q = 0; q < S; q++) L->ts[k++] = a + (b - a) * (double)q / (double)S;
    }
    if (!c->closed) L->ts[k++] = c->t1;
    assert(k == L->ns);
    for (size_t i = 0; i < L->ns; i++) dfl_bspline_eval(c, L->ts[i], 0, L->ps + i * (size_t)c->dim);
    L->size = cp_extent(c->dim, c->n, c->cp);
    if (o.backend == DFL_FOOT_CERES && (st = dfl_lsq_ctx_new(&L->lsq, err)) != DFL_OK) {
        dfl_curve_locator_free(L);
        return st;
    }
    *out = L;
    return DFL_OK;
}

void dfl_curve_locator_free(dfl_curve_locator *L)
{
    if (!L) return;
    free(L->ts);
    free(L->ps);
    if (L->lsq) dfl_lsq_ctx_free(L->lsq);
    free(L);
}

/* Damped Newton on g(t) = |C(t) - x|^2 / 2. */
static void curve_newton(const dfl_bspline *c, const double *x, double t, int maxit,
                         dfl_curve_foot *f)
{
    const int dim = c->dim;
    const double T = c->t1 - c->t0;
    double D[3 * 3], Dn[3 * 3], r[3];
    t = dfl_bspline_wrap(c, t);
    dfl_bspline_eval(c, t, 2, D);
    double g = 0.5 * d2(dim, D, x);
    int it = 0;
    for (; it < maxit; it++) {
        for (int j = 0; j < dim; j++) r[j] = D[j] - x[j];
        double v2 = dot3(dim, D + dim, D + dim);
        double g1 = dot3(dim, D + dim, r);
        double g2 = v2 + dot3(dim, D + 2 * dim, r);
        if (!(v2 > 0.0)) break; /* singular point of the parametrization */
        double step = g2 > 0.0 ? -g1 / g2 : -g1 / v2;
        if (fabs(step) > 0.25 * T) step = copysign(0.25 * T, step);
        /* step control: g must not increase; near the solution g cannot
         * resolve the decrease (it is second order in the step), so a step
         * that keeps g within rounding and reduces |g'| is accepted too */
        int ok = 0;
        double tn = t, gn = g;
        const double noise = g_noise(dim, D, x, g);
        for (int h = 0; h < 60; h++) {
            tn = c->closed ? dfl_bspline_wrap(c, t + step) : fmin(c->t1, fmax(c->t0, t + step));
            dfl_bspline_eval(c, tn, 2, Dn);
            gn = 0.5 * d2(dim, Dn, x);
            double rn[3];
            for (int j = 0; j < dim; j++) rn[j] = Dn[j] - x[j];
            double g1n = dot3(dim, Dn + dim, rn);
            int at_bound = !c->closed && (tn == c->t0 || tn == c->t1);
            if (gn < g || (gn <= g + noise && (fabs(g1n) < fabs(g1) || at_bound))) {
                ok = 1;
                break;
            }
            step *= 0.5;
        }
        if (!ok) break;
        double moved = fabs(tn - t);
        if (c->closed && moved > 0.5 * T) moved = T - moved;
        t = tn;
        g = gn;
        memcpy(D, Dn, sizeof D);
        if (moved <= 1e-15 * (fabs(t) + T)) break;
    }
    f->t = t;
    memcpy(f->p, D, (size_t)dim * sizeof(double));
    f->dist = sqrt(d2(dim, D, x));
    f->iterations = it;
    f->flags = 0;
}

/* Ceres, phase 1: LM on the residual C(t) - x.  LM is Gauss-Newton at
 * heart; with a non-zero residual it converges only linearly, at the rate
 * kappa d, and stops on its relative cost tolerance while the parameter is
 * still off by ~sqrt(eps) (far worse near a centre of curvature, where
 * kappa d -> 1).  Phase 2 therefore runs LM on the footpoint condition
 * g'(t) = C'(t).(C(t) - x) = 0, a zero-residual problem whose Jacobian is
 * g'' (Newton-like, quadratic convergence; linear at a focal point, but
 * with a cost that keeps falling fast, so the tolerances do not stop it
 * early).  The polished point is kept only if it is not farther (phase 2
 * alone could run to a maximum of the distance). */
typedef struct ceres_curve_user {
    const dfl_bspline *c;
    const double *x;
    int stationarity;
} ceres_curve_user;

static int ceres_curve_res(void *user, const double *p, double *r, double *J)
{
    const ceres_curve_user *u = user;
    const int dim = u->c->dim;
    double D[3 * 3];
    if (!isfinite(p[0])) return 1;
    dfl_bspline_eval(u->c, p[0], 2, D);
    if (u->stationarity) {
        double rr[3];
        for (int j = 0; j < dim; j++) rr[j] = D[j] - u->x[j];
        r[0] = dot3(dim, D + dim, rr);
        if (J) J[0] = dot3(dim, D + dim, D + dim) + dot3(dim, D + 2 * dim, rr);
        return 0;
    }
    for (int j = 0; j < dim; j++) {
        r[j] = D[j] - u->x[j];
        if (J) J[j] = D[dim + j];
    }
    return 0;
}

static dfl_status curve_ceres(const dfl_curve_locator *L, const double *x, double t,
                              dfl_curve_foot *f, dfl_err *err)
{
    const dfl_bspline *c = L->c;
    ceres_curve_user u = {c, x, 0};
    double lo = c->t0, hi = c->t1, p = t;
    const double *plo = c->closed ? NULL : &lo, *phi = c->closed ? NULL : &hi;
    dfl_lsq_options opt;
    dfl_lsq_options_default(&opt);
    opt.max_iterations = L->o.max_iter;
    dfl_lsq_result res;
    dfl_status st = dfl_lsq_solve(L->lsq, 1, c->dim, ceres_curve_res, &u, plo, phi, &opt, &p, &res, err);
    if (st != DFL_OK) return st;
    int iters = res.iterations;
    p = dfl_bspline_wrap(c, p);
    double P[3];
    dfl_bspline_eval(c, p, 0, P);
    double dist = sqrt(d2(c->dim, P, x));
    if (c->closed || (p > c->t0 && p < c->t1)) {
        u.stationarity = 1;
        double q = p;
        st = dfl_lsq_solve(L->lsq, 1, 1, ceres_curve_res, &u, plo, phi, &opt, &q, &res, err);
        if (st != DFL_OK) return st;
        iters += res.iterations;
        q = dfl_bspline_wrap(c, q);
        double Q[3];
        dfl_bspline_eval(c, q, 0, Q);
        double dq = sqrt(d2(c->dim, Q, x));
        if (dq <= dist + 1e-14 * (1.0 + dist)) {
            p = q;
            dist = dq;
            memcpy(P, Q, sizeof P);
        }
    }
    f->t = p;
    memcpy(f->p, P, (size_t)c->dim * sizeof(double));
    f->dist = dist;
    f->iterations = iters;
    f->flags = 0;
    return DFL_OK;
}

static void curve_flags(const dfl_bspline *c, const double *x, dfl_curve_foot *f)
{
    const int dim = c->dim;
    if (!c->closed && (f->t <= c->t0 || f->t >= c->t1)) f->flags |= DFL_FOOT_END;
    double D[3 * 3];
    dfl_bspline_eval(c, f->t, 2, D);
    double v2 = dot3(dim, D + dim, D + dim), r[3];
    for (int j = 0; j < dim; j++) r[j] = D[j] - x[j];
    /* g'' = |C'|^2 (1 - kappa d): vanishes at a centre of curvature */
    double g2 = v2 + dot3(dim, D + 2 * dim, r);
    if (!(f->flags & DFL_FOOT_END) && fabs(g2) <= 1e-6 * v2) f->flags |= DFL_FOOT_FOCAL;
}

/* 1 if the distance stays within tol of max(a, b) along the shorter
 * parameter arc from a to b (sampled at 32 points). */
static int curve_same_basin(const dfl_bspline *c, const double *x, const dfl_curve_foot *a,
                            const dfl_curve_foot *b, double tol)
{
    double ta = a->t, tb = b->t;
    if (c->closed) {
        double T = c->t1 - c->t0;
        if (tb - ta > 0.5 * T) tb -= T;
        else if (ta - tb > 0.5 * T) tb += T;
    }
    const double lim = fmax(a->dist, b->dist) + tol;
    for (int k = 1; k < 32; k++) {
        double p[3];
        dfl_bspline_eval(c, ta + (tb - ta) * k / 32.0, 0, p);
        if (sqrt(d2(c->dim, p, x)) > lim) return 0;
    }
    return 1;
}

/* Shared by the single and all-minima queries: refines the candidates into
 * res[], sorted, de-duplicated; ties flagged and ordered by parameter. */
static int curve_search(const dfl_curve_locator *L, const double *x, dfl_curve_foot *res,
                        dfl_status *st, dfl_err *err)
{
    const dfl_bspline *c = L->c;
    const int dim = c->dim;
    const size_t ns = L->ns;
    topk tk = {0, L->o.candidates, {0}, {0}, {0}, {0}};
    for (size_t i = 0; i < ns; i++) {
        double g = d2(dim, L->ps + i * (size_t)dim, x);
        double gp = i > 0 ? d2(dim, L->ps + (i - 1) * (size_t)dim, x)
                          : (c->closed ? d2(dim, L->ps + (ns - 1) * (size_t)dim, x) : INFINITY);
        double gn = i + 1 < ns ? d2(dim, L->ps + (i + 1) * (size_t)dim, x)
                               : (c->closed ? d2(dim, L->ps, x) : INFINITY);
        if (g <= gp && g <= gn) topk_insert(&tk, g, 0, i, 0);
    }
    *st = DFL_OK;
    int n = 0;
    for (int q = 0; q < tk.n; q++) {
        dfl_curve_foot f;
        double t0 = L->ts[tk.i[q]];
        if (L->o.backend == DFL_FOOT_CERES) {
            *st = curve_ceres(L, x, t0, &f, err);
            if (*st != DFL_OK) return 0;
        } else {
            curve_newton(c, x, t0, L->o.max_iter, &f);
        }
        curve_flags(c, x, &f);
        res[n++] = f;
    }
    /* sort by distance (insertion sort, n <= 16) */
    for (int a = 1; a < n; a++) {
        dfl_curve_foot f = res[a];
        int b = a;
        while (b > 0 && res[b - 1].dist > f.dist) {
            res[b] = res[b - 1];
            b--;
        }
        res[b] = f;
    }
    /* drop duplicates of earlier (closer) footpoints: the same point, or
     * the same basin (no barrier of the distance between them, as at a
     * degenerate minimum where a centre of curvature meets the medial axis) */
    const double same = 1e-7 * L->size;
    const double tol = L->o.tie_rel * res[0].dist + 1e-14 * L->size;
    int m = 0;
    for (int a = 0; a < n; a++) {
        int dup = 0;
        for (int b = 0; b < m && !dup; b++)
            if (sqrt(d2(dim, res[a].p, res[b].p)) <= same ||
                curve_same_basin(c, x, &res[b], &res[a], tol))
                dup = 1;
        if (!dup) res[m++] = res[a];
    }
    /* ties with the best: medial axis; order the tied ones by parameter */
    int nt = 1;
    while (nt < m && res[nt].dist - res[0].dist <= tol) nt++;
    if (nt > 1) {
        for (int a = 0; a < nt; a++) res[a].flags |= DFL_FOOT_MEDIAL;
        for (int a = 1; a < nt; a++) {
            dfl_curve_foot f = res[a];
            int b = a;
            while (b > 0 && res[b - 1].t > f.t) {
                res[b] = res[b - 1];
                b--;
            }
            res[b] = f;
        }
    }
    return m;
}

dfl_status dfl_curve_footpoint(const dfl_curve_locator *L, const double *x, dfl_curve_foot *out,
                               dfl_err *err)
{
    dfl_curve_foot res[DFL_FOOT_MAX_CAND];
    dfl_status st;
    int n = curve_search(L, x, res, &st, err);
    if (st != DFL_OK) return st;
    assert(n >= 1);
    *out = res[0];
    return DFL_OK;
}

int dfl_curve_footpoints(const dfl_curve_locator *L, const double *x, dfl_curve_foot *out,
                         int max, dfl_err *err)
{
    dfl_curve_foot res[DFL_FOOT_MAX_CAND];
    dfl_status st;
    int n = curve_search(L, x, res, &st, err);
    if (st != DFL_OK) return 0;
    if (n > max) n = max;
    memcpy(out, res, (size_t)n * sizeof *out);
    return n;
}

/* ====================================================== surfaces ===== */

struct dfl_surface_locator {
    const dfl_surface_set *s;
    dfl_foot_opts o;
    size_t *nsu, *nsv;   /* grid sizes per patch */
    size_t *off;         /* first sample of each patch */
    double **us, **vs;   /* sample parameters per patch */
    double *ps;          /* all sample points */
    double size;
    dfl_lsq_ctx *lsq;
};

static double *patch_samples(const dfl_surface *s, int dir, size_t S, size_t *n)
{
    size_t nsp = dfl_surface_span_count(s, dir);
    const double *U = dir == 0 ? s->knots_u : s->knots_v;
    double *x = malloc((nsp * S + 1) * sizeof(double));
    if (!x) return NULL;
    size_t k = 0;
    for (size_t q = 0; q < nsp; q++) {
        size_t j = dfl_surface_span_index(s, dir, q);
        for (size_t i = 0; i < S; i++) x[k++] = U[j] + (U[j + 1] - U[j]) * (double)i / (double)S;
    }
    x[k++] = dir == 0 ? s->u1 : s->v1;
    *n = k;
    return x;
}

dfl_status dfl_surface_locator_new(const dfl_surface_set *s, const dfl_foot_opts *opt,
                                   dfl_surface_locator **out, dfl_err *err)
{
    dfl_foot_opts o;
    if (opt) o = *opt;
    else dfl_foot_opts_default(&o);
    dfl_status st = dfl_foot_opts_check(&o, err);
    if (st != DFL_OK) return st;
    dfl_surface_locator *L = calloc(1, sizeof *L);
    if (!L) return dfl_err_set(err, DFL_E_NOMEM, "out of memory for a surface locator");
    L->s = s;
    L->o = o;
    const size_t np = s->npatch;
    L->nsu = calloc(np, sizeof(size_t));
    L->nsv = calloc(np, sizeof(size_t));
    L->off = calloc(np + 1, sizeof(size_t));
    L->us = calloc(np, sizeof(double *));
    L->vs = calloc(np, sizeof(double *));
    if (!L->nsu || !L->nsv || !L->off || !L->us || !L->vs) goto nomem;
    for (size_t p = 0; p < np; p++) {
        L->us[p] = patch_samples(&s->patch[p], 0, (size_t)o.samples_per_span, &L->nsu[p]);
        L->vs[p] = patch_samples(&s->patch[p], 1, (size_t)o.samples_per_span, &L->nsv[p]);
        if (!L->us[p] || !L->vs[p]) goto nomem;
        L->off[p + 1] = L->off[p] + L->nsu[p] * L->nsv[p];
    }
    L->ps = malloc(L->off[np] * 3 * sizeof(double));
    if (!L->ps) goto nomem;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t p = 0; p < np; p++) {
        const dfl_surface *sp = &s->patch[p];
        for (size_t j = 0; j < L->nsv[p]; j++)
            for (size_t i = 0; i < L->nsu[p]; i++)
                dfl_surface_eval(sp, L->us[p][i], L->vs[p][j], 0,
                                 L->ps + (L->off[p] + i + L->nsu[p] * j) * 3);
        for (size_t i = 0; i < sp->nu * sp->nv; i++)
            for (int c = 0; c < 3; c++) {
                lo[c] = fmin(lo[c], sp->cp[3 * i + (size_t)c]);
                hi[c] = fmax(hi[c], sp->cp[3 * i + (size_t)c]);
            }
    }
    L->size = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    if (o.backend == DFL_FOOT_CERES && (st = dfl_lsq_ctx_new(&L->lsq, err)) != DFL_OK) {
        dfl_surface_locator_free(L);
        return st;
    }
    *out = L;
    return DFL_OK;
nomem:
    dfl_surface_locator_free(L);
    return dfl_err_set(err, DFL_E_NOMEM, "out of memory for a surface locator");
}

void dfl_surface_locator_free(dfl_surface_locator *L)
{
    if (!L) return;
    for (size_t p = 0; L->s && p < L->s->npatch; p++) {
        if (L->us) free(L->us[p]);
        if (L->vs) free(L->vs[p]);
    }
    free(L->us);
    free(L->vs);
    free(L->nsu);
    free(L->nsv);
    free(L->off);
    free(L->ps);
    if (L->lsq) dfl_lsq_ctx_free(L->lsq);
    free(L);
}

static double clampd(double a, double lo, double hi) { return a < lo ? lo : (a > hi ? hi : a); }

/* Projected damped Newton on g(u, v) = |S(u, v) - x|^2 / 2 with an active
 * set for the domain bounds the gradient pushes against. */
static void surface_newton(const dfl_surface *s, const double *x, double u, double v, int maxit,
                           dfl_surface_foot *f)
{
    double D[6 * 3], Dn[6 * 3], r[3];
    const double su = s->u1 - s->u0, sv = s->v1 - s->v0;
    dfl_surface_eval(s, u, v, 2, D);
    double g = 0.5 * d2(3, D, x);
    int it = 0;
    for (; it < maxit; it++) {
        for (int j = 0; j < 3; j++) r[j] = D[j] - x[j];
        const double *Su = D + 3, *Sv = D + 6, *Suu = D + 9, *Suv = D + 12, *Svv = D + 15;
        double gu = dot3(3, Su, r), gv = dot3(3, Sv, r);
        double E = dot3(3, Su, Su), F = dot3(3, Su, Sv), G = dot3(3, Sv, Sv);
        double Huu = E + dot3(3, Suu, r), Huv = F + dot3(3, Suv, r), Hvv = G + dot3(3, Svv, r);
        int fu = !((u <= s->u0 && gu > 0.0) || (u >= s->u1 && gu < 0.0));
        int fv = !((v <= s->v0 && gv > 0.0) || (v >= s->v1 && gv < 0.0));
        if (!fu && !fv) break;
        double du = 0.0, dv = 0.0;
        if (fu && fv) {
            double det = Huu * Hvv - Huv * Huv, detG = E * G - F * F;
            if (Huu > 0.0 && det > 0.0) {
                du = -(Hvv * gu - Huv * gv) / det;
                dv = -(-Huv * gu + Huu * gv) / det;
            } else if (detG > 0.0) {
                du = -(G * gu - F * gv) / detG;
                dv = -(-F * gu + E * gv) / detG;
            } else {
                double tr = E + G > 0.0 ? E + G : 1.0;
                du = -gu / tr;
                dv = -gv / tr;
            }
        } else if (fu) {
            du = Huu > 0.0 ? -gu / Huu : -gu / (E > 0.0 ? E : 1.0);
        } else {
            dv = Hvv > 0.0 ? -gv / Hvv : -gv / (G > 0.0 ? G : 1.0);
        }
        if (!isfinite(du) || !isfinite(dv)) break;
        double big = fmax(fabs(du) / su, fabs(dv) / sv);
        if (big > 0.5) {
            du *= 0.5 / big;
            dv *= 0.5 / big;
        }
        /* step control as for curves: decrease g, or stay within rounding
         * of g while reducing the free part of the gradient */
        int ok = 0;
        double un = u, vn = v, gn = g;
        const double noise = g_noise(3, D, x, g);
        const double pg = (fu ? gu * gu : 0.0) + (fv ? gv * gv : 0.0);
        for (int h = 0; h < 60; h++) {
            un = clampd(u + du, s->u0, s->u1);
            vn = clampd(v + dv, s->v0, s->v1);
            dfl_surface_eval(s, un, vn, 2, Dn);
            gn = 0.5 * d2(3, Dn, x);
            double rn[3];
            for (int j = 0; j < 3; j++) rn[j] = Dn[j] - x[j];
            double gun = dot3(3, Dn + 3, rn), gvn = dot3(3, Dn + 6, rn);
            double pgn = (fu ? gun * gun : 0.0) + (fv ? gvn * gvn : 0.0);
            if (gn < g || (gn <= g + noise && pgn < pg)) {
                ok = 1;
                break;
            }
            du *= 0.5;
            dv *= 0.5;
        }
        if (!ok) break;
        double moved = fabs(un - u) / su + fabs(vn - v) / sv;
        u = un;
        v = vn;
        g = gn;
        memcpy(D, Dn, sizeof D);
        if (moved <= 1e-15 * (1.0 + fabs(u) / su + fabs(v) / sv)) break;
    }
    f->u = u;
    f->v = v;
    memcpy(f->p, D, 3 * sizeof(double));
    f->dist = sqrt(d2(3, D, x));
    f->iterations = it;
    f->flags = 0;
}

/* Ceres residuals over both parameters (fix < 0) or over one, the other
 * held at fixval (fix = 0: u held, fix = 1: v held): phase 1 the distance
 * residual S - x, phase 2 (stationarity) the gradient of |S - x|^2 / 2 in
 * the free parameters, Jacobian = Hessian (see curve_ceres for why). */
typedef struct ceres_surf_user {
    const dfl_surface *s;
    const double *x;
    int fix;
    double fixval;
    int stationarity;
} ceres_surf_user;

static int ceres_surf_res(void *user, const double *p, double *r, double *J)
{
    const ceres_surf_user *cu = user;
    double D[6 * 3], rr[3];
    double u = cu->fix == 0 ? cu->fixval : p[0];
    double v = cu->fix == 1 ? cu->fixval : (cu->fix == 0 ? p[0] : p[1]);
    if (!isfinite(u) || !isfinite(v)) return 1;
    dfl_surface_eval(cu->s, u, v, 2, D);
    for (int j = 0; j < 3; j++) rr[j] = D[j] - cu->x[j];
    const double *Su = D + 3, *Sv = D + 6;
    if (cu->stationarity) {
        double gu = dot3(3, Su, rr), gv = dot3(3, Sv, rr);
        double Huu = dot3(3, Su, Su) + dot3(3, D + 9, rr);
        double Huv = dot3(3, Su, Sv) + dot3(3, D + 12, rr);
        double Hvv = dot3(3, Sv, Sv) + dot3(3, D + 15, rr);
        if (cu->fix < 0) {
            r[0] = gu;
            r[1] = gv;
            if (J) {
                J[0] = Huu;
                J[1] = Huv;
                J[2] = Huv;
                J[3] = Hvv;
            }
        } else if (cu->fix == 0) {
            r[0] = gv;
            if (J) J[0] = Hvv;
        } else {
            r[0] = gu;
            if (J) J[0] = Huu;
        }
        return 0;
    }
    for (int j = 0; j < 3; j++) {
        r[j] = rr[j];
        if (!J) continue;
        if (cu->fix < 0) {
            J[2 * j] = Su[j];
            J[2 * j + 1] = Sv[j];
        } else {
            J[j] = cu->fix == 0 ? Sv[j] : Su[j];
        }
    }
    return 0;
}

/* One Ceres solve in the free parameters of cu; prm holds (u, v). */
static dfl_status surf_solve(const dfl_surface_locator *L, const dfl_surface *sp,
                             ceres_surf_user *cu, double *prm, int *iters, dfl_err *err)
{
    dfl_lsq_options opt;
    dfl_lsq_options_default(&opt);
    opt.max_iterations = L->o.max_iter;
    dfl_lsq_result lr;
    double lo[2] = {sp->u0, sp->v0}, hi[2] = {sp->u1, sp->v1};
    const int m = cu->stationarity ? (cu->fix < 0 ? 2 : 1) : 3;
    dfl_status st;
    if (cu->fix < 0) {
        st = dfl_lsq_solve(L->lsq, 2, m, ceres_surf_res, cu, lo, hi, &opt, prm, &lr, err);
    } else {
        int k = cu->fix == 0 ? 1 : 0; /* the free parameter */
        st = dfl_lsq_solve(L->lsq, 1, m, ceres_surf_res, cu, &lo[k], &hi[k], &opt, &prm[k], &lr,
                           err);
    }
    if (st != DFL_OK) return st;
    *iters += lr.iterations;
    prm[0] = clampd(prm[0], sp->u0, sp->u1);
    prm[1] = clampd(prm[1], sp->v0, sp->v1);
    return DFL_OK;
}

/* Ceres' projected LM stalls on an active bound (the projected step of the
 * coupled 2x2 system is poor and the trust region collapses), so bounds the
 * gradient pushes against are made explicit: that parameter is held and LM
 * runs on the other one (an active-set loop around Ceres); then the free
 * parameters are polished on the stationarity residual. */
static dfl_status surface_ceres(const dfl_surface_locator *L, const dfl_surface *sp,
                                const double *x, double u, double v, dfl_surface_foot *f,
                                dfl_err *err)
{
    int iters = 0;
    ceres_surf_user cu = {sp, x, -1, 0.0, 0};
    double prm[2] = {u, v};
    dfl_status st = surf_solve(L, sp, &cu, prm, &iters, err);
    if (st != DFL_OK) return st;
    int fix = -1;
    for (int round = 0; round < 4; round++) {
        double D[3 * 3], r[3];
        dfl_surface_eval(sp, prm[0], prm[1], 1, D);
        for (int j = 0; j < 3; j++) r[j] = D[j] - x[j];
        double gu = dot3(3, D + 3, r), gv = dot3(3, D + 6, r);
        int hu = (prm[0] <= sp->u0 && gu > 0.0) || (prm[0] >= sp->u1 && gu < 0.0);
        int hv = (prm[1] <= sp->v0 && gv > 0.0) || (prm[1] >= sp->v1 && gv < 0.0);
        int nfix = hu && hv ? 2 : hu ? 0 : hv ? 1 : -1;
        if (nfix == fix || nfix == 2) {
            fix = nfix;
            break;
        }
        fix = nfix;
        if (fix < 0) break;
        cu.fix = fix;
        cu.fixval = prm[fix];
        if ((st = surf_solve(L, sp, &cu, prm, &iters, err)) != DFL_OK) return st;
    }
    double P[3];
    dfl_surface_eval(sp, prm[0], prm[1], 0, P);
    double dist = sqrt(d2(3, P, x));
    if (fix != 2) {
        double q[2] = {prm[0], prm[1]}, Q[3];
        cu.fix = fix;
        cu.fixval = fix >= 0 ? prm[fix] : 0.0;
        cu.stationarity = 1;
        if ((st = surf_solve(L, sp, &cu, q, &iters, err)) != DFL_OK) return st;
        dfl_surface_eval(sp, q[0], q[1], 0, Q);
        double dq = sqrt(d2(3, Q, x));
        if (dq <= dist + 1e-14 * (1.0 + dist)) {
            prm[0] = q[0];
            prm[1] = q[1];
            dist = dq;
            memcpy(P, Q, sizeof P);
        }
    }
    f->u = prm[0];
    f->v = prm[1];
    memcpy(f->p, P, sizeof P);
    f->dist = dist;
    f->iterations = iters;
    f->flags = 0;
    return DFL_OK;
}

static void surface_flags(const dfl_surface *s, const double *x, dfl_surface_foot *f)
{
    if (f->u <= s->u0 || f->u >= s->u1 || f->v <= s->v0 || f->v >= s->v1)
        f->flags |= DFL_FOOT_END;
    double D[6 * 3], r[3];
    dfl_surface_eval(s, f->u, f->v, 2, D);
    for (int j = 0; j < 3; j++) r[j] = D[j] - x[j];
    double E = dot3(3, D + 3, D + 3), F = dot3(3, D + 3, D + 6), G = dot3(3, D + 6, D + 6);
    double Huu = E + dot3(3, D + 9, r), Huv = F + dot3(3, D + 12, r), Hvv = G + dot3(3, D + 15, r);
    /* det H = det I * (1 - k1 d)(1 - k2 d): vanishes at a focal point */
    if (!(f->flags & DFL_FOOT_END) && fabs(Huu * Hvv - Huv * Huv) <= 1e-6 * (E * G - F * F))
        f->flags |= DFL_FOOT_FOCAL;
}

/* 1 if the distance stays within tol of max(a, b) on the parameter
 * segment from a to b of one patch (sampled at 32 points). */
static int surface_same_basin(const dfl_surface *s, const double *x, const dfl_surface_foot *a,
                              const dfl_surface_foot *b, double tol)
{
    const double lim = fmax(a->dist, b->dist) + tol;
    for (int k = 1; k < 32; k++) {
        double p[3], w = k / 32.0;
        dfl_surface_eval(s, a->u + w * (b->u - a->u), a->v + w * (b->v - a->v), 0, p);
        if (sqrt(d2(3, p, x)) > lim) return 0;
    }
    return 1;
}

dfl_status dfl_surface_footpoint(const dfl_surface_locator *L, const double x[3],
                                 dfl_surface_foot *out, dfl_err *err)
{
    const dfl_surface_set *s = L->s;
    topk tk = {0, L->o.candidates, {0}, {0}, {0}, {0}};
    for (size_t p = 0; p < s->npatch; p++) {
        const size_t nu = L->nsu[p], nv = L->nsv[p];
        const double *P = L->ps + L->off[p] * 3;
        for (size_t j = 0; j < nv; j++)
            for (size_t i = 0; i < nu; i++) {
                double g = d2(3, P + (i + nu * j) * 3, x);
                if ((i > 0 && d2(3, P + (i - 1 + nu * j) * 3, x) < g) ||
                    (i + 1 < nu && d2(3, P + (i + 1 + nu * j) * 3, x) < g) ||
                    (j > 0 && d2(3, P + (i + nu * (j - 1)) * 3, x) < g) ||
                    (j + 1 < nv && d2(3, P + (i + nu * (j + 1)) * 3, x) < g))
                    continue;
                topk_insert(&tk, g, p, i, j);
            }
    }
    dfl_surface_foot res[DFL_FOOT_MAX_CAND];
    int n = 0;
    for (int q = 0; q < tk.n; q++) {
        const size_t p = tk.p[q];
        const dfl_surface *sp = &s->patch[p];
        double u = L->us[p][tk.i[q]], v = L->vs[p][tk.j[q]];
        dfl_surface_foot f;
        if (L->o.backend == DFL_FOOT_CERES) {
            dfl_status st = surface_ceres(L, sp, x, u, v, &f, err);
            if (st != DFL_OK) return st;
        } else {
            surface_newton(sp, x, u, v, L->o.max_iter, &f);
        }
        f.patch = p;
        surface_flags(sp, x, &f);
        res[n++] = f;
    }
    assert(n >= 1);
    for (int a = 1; a < n; a++) {
        dfl_surface_foot f = res[a];
        int b = a;
        while (b > 0 && res[b - 1].dist > f.dist) {
            res[b] = res[b - 1];
            b--;
        }
        res[b] = f;
    }
    const double same = 1e-7 * L->size;
    const double tol = L->o.tie_rel * res[0].dist + 1e-14 * L->size;
    int m = 0;
    for (int a = 0; a < n; a++) {
        int dup = 0;
        for (int b = 0; b < m && !dup; b++)
            if (sqrt(d2(3, res[a].p, res[b].p)) <= same ||
                (res[a].patch == res[b].patch &&
                 surface_same_basin(&s->patch[res[a].patch], x, &res[b], &res[a], tol)))
                dup = 1;
        if (!dup) res[m++] = res[a];
    }
    int best = 0, nt = 1;
    while (nt < m && res[nt].dist - res[0].dist <= tol) nt++;
    if (nt > 1) {
        for (int a = 1; a < nt; a++) {
            const dfl_surface_foot *A = &res[a], *B = &res[best];
            if (A->patch < B->patch || (A->patch == B->patch && (A->u < B->u ||
                                                                 (A->u == B->u && A->v < B->v))))
                best = a;
        }
        res[best].flags |= DFL_FOOT_MEDIAL;
    }
    *out = res[best];
    return DFL_OK;
}

/* ============================================ closed curve SDF ===== */

struct dfl_curve_sdf {
    const dfl_bspline *c;
    dfl_curve_locator *L;
    dfl_polyline poly;
    int orient; /* +1 counter-clockwise */
};

dfl_status dfl_curve_sdf_new(const dfl_bspline *c, const dfl_foot_opts *opt, dfl_curve_sdf **out,
                             dfl_err *err)
{
    if (c->dim != 2)
        return dfl_err_set(err, DFL_E_INPUT,
                           "signed distance needs a planar curve, got dimension %d", c->dim);
    if (!dfl_bspline_is_closed(c, 1e-12))
        return dfl_err_set(err, DFL_E_INPUT,
                           "a closed curve is required for a signed distance (periodic, or with "
                           "first and last points equal)");
    dfl_curve_sdf *S = calloc(1, sizeof *S);
    if (!S) return dfl_err_set(err, DFL_E_NOMEM, "out of memory for a curve SDF");
    S->c = c;
    dfl_status st = dfl_curve_locator_new(c, opt, &S->L, err);
    if (st != DFL_OK) {
        free(S);
        return st;
    }
    double size = cp_extent(2, c->n, c->cp);
    if ((st = dfl_polygonize_curve(c, 1e-4 * size, 0, &S->poly, err)) != DFL_OK) {
        dfl_curve_sdf_free(S);
        return st;
    }
    /* close the polygon exactly (clamped curves meet within 1e-12) */
    memcpy(S->poly.pts + 2 * (S->poly.n - 1), S->poly.pts, 2 * sizeof(double));
    double area = 0.0;
    for (size_t i = 0; i + 1 < S->poly.n; i++) {
        const double *a = S->poly.pts + 2 * i, *b = a + 2;
        area += a[0] * b[1] - a[1] * b[0];
    }
    if (!(fabs(area) > 1e-10 * size * size)) {
        dfl_curve_sdf_free(S);
        return dfl_err_set(err, DFL_E_INPUT,
                           "degenerate closed curve: it encloses no area (signed area %g)",
                           0.5 * area);
    }
    S->orient = area > 0.0 ? 1 : -1;
    *out = S;
    return DFL_OK;
}

void dfl_curve_sdf_free(dfl_curve_sdf *S)
{
    if (!S) return;
    dfl_curve_locator_free(S->L);
    dfl_polyline_free(&S->poly);
    free(S);
}

int dfl_curve_sdf_orientation(const dfl_curve_sdf *S) { return S->orient; }

/* Winding number of the closed polygon around x (Sunday's crossing rule). */
static int winding(const dfl_polyline *p, const double *x)
{
    int wn = 0;
    for (size_t i = 0; i + 1 < p->n; i++) {
        const double *a = p->pts + 2 * i, *b = a + 2;
        double isl = (b[0] - a[0]) * (x[1] - a[1]) - (x[0] - a[0]) * (b[1] - a[1]);
        if (a[1] <= x[1]) {
            if (b[1] > x[1] && isl > 0.0) wn++;
        } else if (b[1] <= x[1] && isl < 0.0) {
            wn--;
        }
    }
    return wn;
}

static void sdf_from_foot(const dfl_curve_sdf *S, const double *x, const dfl_curve_foot *f,
                          int order, dfl_curve_sdf_val *o)
{
    const dfl_bspline *c = S->c;
    double D[4 * 2];
    dfl_bspline_eval(c, f->t, 3, D);
    const double *C1 = D + 2, *C2 = D + 4, *C3 = D + 6;
    double v = sqrt(C1[0] * C1[0] + C1[1] * C1[1]);
    double T[2] = {C1[0] / v, C1[1] / v};
    double N[2] = {S->orient * T[1], -S->orient * T[0]};
    double w[2] = {x[0] - f->p[0], x[1] - f->p[1]};
    int sign;
    if (f->dist > S->poly.bound) {
        o->winding = winding(&S->poly, x);
        sign = o->winding != 0 ? -1 : 1;
    } else {
        sign = N[0] * w[0] + N[1] * w[1] < 0.0 ? -1 : 1;
        o->winding = sign < 0 ? S->orient : 0;
    }
    memset(o->h, 0, sizeof o->h);
    memset(o->t3, 0, sizeof o->t3);
    o->d = sign * f->dist;
    o->t = f->t;
    o->foot[0] = f->p[0];
    o->foot[1] = f->p[1];
    o->flags = f->flags & (DFL_FOOT_MEDIAL | DFL_FOOT_FOCAL);
    double cr12 = C1[0] * C2[1] - C1[1] * C2[0], cr13 = C1[0] * C3[1] - C1[1] * C3[0];
    double dot12 = C1[0] * C2[0] + C1[1] * C2[1];
    o->kappa = -S->orient * cr12 / (v * v * v);
    o->kappa_s = -S->orient * (cr13 / (v * v * v) - 3.0 * cr12 * dot12 / pow(v, 5)) / v;
    if ((f->flags & DFL_FOOT_END) && f->dist > 0.0) {
        /* footpoint at the joint of a clamped closed curve (a corner): there
         * d = sign |x - P| locally, whose derivatives are those of the
         * distance to the point P */
        double r = f->dist, u[2] = {w[0] / r, w[1] / r};
        o->g[0] = sign * u[0];
        o->g[1] = sign * u[1];
        if (order >= 2) {
            o->h[0] = sign * (1.0 - u[0] * u[0]) / r;
            o->h[1] = sign * (-u[0] * u[1]) / r;
            o->h[2] = sign * (1.0 - u[1] * u[1]) / r;
        }
        if (order >= 3) {
            /* d_ijk of |x - P|: (3 u_i u_j u_k - d_ij u_k - d_ik u_j - d_jk u_i) / r^2 */
            static const int I[4][3] = {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {1, 1, 1}};
            for (int q = 0; q < 4; q++) {
                int i = I[q][0], j = I[q][1], k = I[q][2];
                double val = 3.0 * u[i] * u[j] * u[k] - (i == j) * u[k] - (i == k) * u[j] -
                             (j == k) * u[i];
                o->t3[q] = sign * val / (r * r);
            }
        }
        return;
    }
    o->g[0] = N[0];
    o->g[1] = N[1];
    double g = 1.0 - o->kappa * o->d;
    if (fabs(g) < 1e-6) o->flags |= DFL_FOOT_FOCAL;
    if (order >= 2) {
        double a = -o->kappa / g;
        o->h[0] = a * T[0] * T[0];
        o->h[1] = a * T[0] * T[1];
        o->h[2] = a * T[1] * T[1];
    }
    if (order >= 3) {
        double A = -o->kappa_s / (g * g * g), B = -o->kappa * o->kappa / (g * g);
        static const int I[4][3] = {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {1, 1, 1}};
        for (int q = 0; q < 4; q++) {
            int i = I[q][0], j = I[q][1], k = I[q][2];
            o->t3[q] = A * T[i] * T[j] * T[k] +
                       B * (T[i] * T[j] * N[k] + T[i] * N[j] * T[k] + N[i] * T[j] * T[k]);
        }
    }
}

dfl_status dfl_curve_sdf_eval(const dfl_curve_sdf *S, const double x[2], int order,
                              dfl_curve_sdf_val *out, dfl_err *err)
{
    if (order < 0 || order > 3)
        return dfl_err_set(err, DFL_E_INPUT, "derivative order %d: expected 0..3", order);
    dfl_curve_foot f;
    dfl_status st = dfl_curve_footpoint(S->L, x, &f, err);
    if (st != DFL_OK) return st;
    sdf_from_foot(S, x, &f, order, out);
    return DFL_OK;
}

/* ---- jets through the footpoint ---- */

/* sum_m a[m] delta^m / m!  for m = 0..M (Horner). */
static void taylor_compose(const double *a, int stride, int M, const dfl_jet *delta, int K,
                           dfl_jet *out)
{
    double fact[KMAX + 2];
    fact[0] = 1.0;
    for (int m = 1; m <= M; m++) fact[m] = fact[m - 1] * m;
    dfl_jet acc;
    dfl_jet_const(a[M * stride] / fact[M], K, &acc);
    for (int m = M - 1; m >= 0; m--) {
        dfl_jet_mul(&acc, delta, &acc);
        dfl_jet_add_const(&acc, a[m * stride] / fact[m], &acc);
    }
    *out = acc;
}

/* Jet of the footpoint branch through foot f: writes the residual jets
 * r_j(s) = C_j(t(s)) - x_j - s dir_j and C'_j(t(s)).  side: piece used. */
static dfl_status follow_foot(const dfl_bspline *c, const double *x, const double *dir, int K,
                              double t, int side, int fixed, dfl_jet *r, dfl_jet *c1,
                              dfl_jet *delta_out, dfl_err *err)
{
    const int dim = c->dim, p = c->order - 1;
    double D[(KMAX + 3) * 3];
    dfl_bspline_eval_side(c, t, side, p + 2, D);
    dfl_jet delta, X[3];
    dfl_jet_zero(&delta);
    for (int j = 0; j < dim; j++) dfl_jet_linear(x[j], dir[j], K, &X[j]);
    int iters = 0;
    while ((1 << iters) <= K + 1) iters++;
    iters += 1;
    if (fixed) iters = 0;
    dfl_jet C[3], C1[3], C2[3], R[3];
    for (int it = 0; it <= iters; it++) {
        for (int j = 0; j < dim; j++) {
            taylor_compose(D + j, dim, p, &delta, K, &C[j]);
            taylor_compose(D + dim + j, dim, p, &delta, K, &C1[j]);
            taylor_compose(D + 2 * dim + j, dim, p, &delta, K, &C2[j]);
            dfl_jet_sub(&C[j], &X[j], &R[j]);
        }
        if (it == iters) break;
        /* Newton on F = C'.(C - x): delta -= F / F' */
        dfl_jet F, Fp, tmp;
        dfl_jet_zero(&F);
        dfl_jet_zero(&Fp);
        for (int j = 0; j < dim; j++) {
            dfl_jet_mul(&C1[j], &R[j], &tmp);
            dfl_jet_add(&F, &tmp, &F);
            dfl_jet_mul(&C2[j], &R[j], &tmp);
            dfl_jet_add(&Fp, &tmp, &Fp);
            dfl_jet_mul(&C1[j], &C1[j], &tmp);
            dfl_jet_add(&Fp, &tmp, &Fp);
        }
        dfl_status st = dfl_jet_div(&F, &Fp, &tmp, err);
        if (st != DFL_OK) return st;
        dfl_jet_sub(&delta, &tmp, &delta);
        /* t* is the root: delta(0) = 0 exactly (drops rounding residue) */
        double a[DFL_JET_MAX + 1];
        a[0] = 0.0;
        for (int k = 1; k <= K; k++) {
            double v = dfl_jet_coeff(&delta, k);
            a[k] = isfinite(v) ? v : 0.0;
        }
        dfl_jet_poly(a, K + 1, K, &delta);
    }
    for (int j = 0; j < dim; j++) {
        r[j] = R[j];
        c1[j] = C1[j];
    }
    if (delta_out) *delta_out = delta;
    return DFL_OK;
}

static int is_knot(const dfl_bspline *c, double t)
{
    for (size_t i = 0; i < c->n + (size_t)c->order; i++)
        if (c->knots[i] == t) return 1;
    return 0;
}

/* sign of the first non-zero coefficient of delta (0 if none) */
static int lead_sign(const dfl_jet *d, int K)
{
    for (int k = 1; k <= K; k++) {
        double v = dfl_jet_coeff(d, k);
        if (isfinite(v) && fabs(v) > 0.0) return v > 0 ? 1 : -1;
    }
    return 0;
}

/* mode 0: unsigned |x - C|; mode 1: signed N.(x - C) with orientation o */
static dfl_status branch_jet(const dfl_bspline *c, const double *x, const double *dir, int K,
                             const dfl_curve_foot *f, int mode, int orient, int sign,
                             dfl_jet *out, dfl_err *err)
{
    const int dim = c->dim;
    dfl_jet r[3], c1[3], delta, acc, tmp;
    int fixed = (f->flags & DFL_FOOT_END) != 0;
    if (fixed && !c->closed) {
        /* the footpoint stays at the end while g'(t_end) pushes outward */
        double D[2 * 3];
        dfl_bspline_eval(c, f->t, 1, D);
        double g1 = 0.0;
        for (int j = 0; j < dim; j++) g1 += D[dim + j] * (D[j] - x[j]);
        /* first-order change of g' along dir: -C'.dir; stays if the sign holds */
        double dg = 0.0;
        for (int j = 0; j < dim; j++) dg -= D[dim + j] * dir[j];
        int at_start = f->t <= c->t0;
        double gs = g1 != 0.0 ? g1 : dg;
        fixed = at_start ? gs >= 0.0 : gs <= 0.0;
    }
    int side = 1;
    dfl_status st = follow_foot(c, x, dir, K, f->t, side, fixed, r, c1, &delta, err);
    if (st != DFL_OK) return st;
    if (!fixed && (is_knot(c, f->t) || (c->closed && f->t == c->t0)) && lead_sign(&delta, K) < 0) {
        side = -1;
        if ((st = follow_foot(c, x, dir, K, f->t, side, fixed, r, c1, &delta, err)) != DFL_OK)
            return st;
    }
    if (mode == 0 || fixed) {
        dfl_jet_zero(&acc);
        for (int j = 0; j < dim; j++) {
            dfl_jet_mul(&r[j], &r[j], &tmp);
            dfl_jet_add(&acc, &tmp, &acc);
        }
        if ((st = dfl_jet_sqrt(&acc, out, err)) != DFL_OK) return st;
        if (mode == 1 && sign < 0) dfl_jet_neg(out, out);
        return DFL_OK;
    }
    /* d = N.(x - C) = -N.r, N = orient (C'_y, -C'_x) / |C'| */
    dfl_jet v2, v, num;
    dfl_jet_mul(&c1[0], &c1[0], &v2);
    dfl_jet_mul(&c1[1], &c1[1], &tmp);
    dfl_jet_add(&v2, &tmp, &v2);
    if ((st = dfl_jet_sqrt(&v2, &v, err)) != DFL_OK) return st;
    dfl_jet_mul(&c1[1], &r[0], &num);
    dfl_jet_mul(&c1[0], &r[1], &tmp);
    dfl_jet_sub(&num, &tmp, &num);
    dfl_jet_scale(&num, -(double)orient, &num);
    return dfl_jet_div(&num, &v, out, err);
}

/* lexicographic comparison of jets (value first) with a small tolerance */
static int jet_cmp(const dfl_jet *a, const dfl_jet *b, int K)
{
    for (int k = 0; k <= K; k++) {
        double x = dfl_jet_coeff(a, k), y = dfl_jet_coeff(b, k);
        if (!isfinite(x) || !isfinite(y)) return 0;
        double tol = 1e-9 * (fabs(x) + fabs(y)) + 1e-13;
        if (x < y - tol) return -1;
        if (x > y + tol) return 1;
    }
    return 0;
}

static dfl_status curve_jet(const dfl_curve_locator *L, const dfl_curve_sdf *S, const double *x,
                            const double *dir, int K, dfl_jet *out, dfl_err *err)
{
    if (K < 0 || K > DFL_JET_MAX)
        return dfl_err_set(err, DFL_E_INPUT, "jet order %d: expected 0..%d", K, DFL_JET_MAX);
    dfl_curve_foot fs[DFL_FOOT_MAX_CAND];
    dfl_err e2;
    int n = dfl_curve_footpoints(L, x, fs, DFL_FOOT_MAX_CAND, &e2);
    if (n < 1) return dfl_err_set(err, DFL_E_NUMERIC, "footpoint search failed: %s", e2.msg);
    int sign = 1, orient = 1, mode = S ? 1 : 0;
    if (S) {
        dfl_curve_sdf_val v;
        sdf_from_foot(S, x, &fs[0], 0, &v);
        sign = v.d < 0.0 ? -1 : 1;
        orient = S->orient;
    }
    int nt = (fs[0].flags & DFL_FOOT_MEDIAL) ? n : 1;
    dfl_jet best;
    int have = 0;
    for (int q = 0; q < nt; q++) {
        if (q > 0 && !(fs[q].flags & DFL_FOOT_MEDIAL)) break;
        dfl_jet j;
        dfl_status st = branch_jet(L->c, x, dir, K, &fs[q], mode, orient, sign, &j, err);
        if (st != DFL_OK) return st;
        /* d for s > 0 is the nearest branch: min of |.|, i.e. the smallest
         * jet outside and the largest (least negative) inside */
        if (!have || (sign > 0 ? jet_cmp(&j, &best, K) < 0 : jet_cmp(&j, &best, K) > 0)) best = j;
        have = 1;
    }
    *out = best;
    return DFL_OK;
}

dfl_status dfl_curve_sdf_jet(const dfl_curve_sdf *S, const double x[2], const double dir[2], int K,
                             dfl_jet *out, dfl_err *err)
{
    return curve_jet(S->L, S, x, dir, K, out, err);
}

/* ======================================================== shapes ===== */

typedef struct curve_shape {
    dfl_bspline c;
    dfl_curve_locator *L;
    dfl_curve_sdf *S;
} curve_shape;

static void unit_perp(int dim, const double *t, double *n)
{
    /* deterministic unit normal: 2D right normal; 3D e_k minus its tangent
     * part, e_k the axis least aligned with t */
    double len = sqrt(dot3(dim, t, t));
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
    double s = len > 0 ? dot3(3, e, t) / (len * len) : 0.0;
    for (int j = 0; j < 3; j++) n[j] = e[j] - s * t[j];
    double m = sqrt(dot3(3, n, n));
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
    return curve_jet(cs->L, cs->S, x, dir, K, out, err);
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
                                        curve_shape_free};

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
                                          surface_shape_free};

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
