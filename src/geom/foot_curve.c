/* Footpoints on parametric curves: Newton and Ceres refinement of the
 * sampled minima (footpoint.h).  Queries keep everything on the stack so
 * that a shape's batch eval can run in parallel without allocation; only
 * the ceres backend allocates, inside Ceres. */
#include "geom/foot_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/vec.h"

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
    L->ds = malloc(L->ns * 3 * (size_t)c->dim * sizeof(double));
    if (!L->ts || !L->ps || !L->ds) {
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
    for (size_t i = 0; i < L->ns; i++) {
        dfl_bspline_eval(c, L->ts[i], 0, L->ps + i * (size_t)c->dim);
        /* the very evaluation curve_newton starts with, done once here */
        dfl_bspline_eval(c, dfl_bspline_wrap(c, L->ts[i]), 2, L->ds + i * 3 * (size_t)c->dim);
    }
    L->size = dfl_foot_extent(c->dim, c->n, c->cp);
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
    free(L->ds);
    if (L->lsq) dfl_lsq_ctx_free(L->lsq);
    free(L);
}

/* Damped Newton on g(t) = |C(t) - x|^2 / 2 from t, where D0 holds C, C',
 * C'' at dfl_bspline_wrap(c, t).  D[] ends as C, C', C'' at f->t (what
 * curve_flags needs, so it is not evaluated again). */
static void curve_newton(const dfl_bspline *c, const double *x, double t, const double *D0,
                         int maxit, dfl_curve_foot *f, double D[3 * 3])
{
    const int dim = c->dim;
    const double T = c->t1 - c->t0;
    double Dn[3 * 3], r[3];
    t = dfl_bspline_wrap(c, t);
    memcpy(D, D0, 3 * (size_t)dim * sizeof(double));
    double g = 0.5 * dfl_foot_d2(dim, D, x);
    int it = 0;
    for (; it < maxit; it++) {
        for (int j = 0; j < dim; j++) r[j] = D[j] - x[j];
        double v2 = dfl_vecn_dot(dim, D + dim, D + dim);
        double g1 = dfl_vecn_dot(dim, D + dim, r);
        double g2 = v2 + dfl_vecn_dot(dim, D + 2 * dim, r);
        if (!(v2 > 0.0)) break; /* singular point of the parametrization */
        double step = g2 > 0.0 ? -g1 / g2 : -g1 / v2;
        if (fabs(step) > 0.25 * T) step = copysign(0.25 * T, step);
        /* step control: g must not increase; near the solution g cannot
         * resolve the decrease (it is second order in the step), so a step
         * that keeps g within rounding and reduces |g'| is accepted too */
        int ok = 0;
        double tn = t, gn = g;
        const double noise = dfl_foot_g_noise(dim, D, x, g);
        for (int h = 0; h < 60; h++) {
            tn = c->closed ? dfl_bspline_wrap(c, t + step) : fmin(c->t1, fmax(c->t0, t + step));
            /* a step below rounding of t: tn == t gives gn == g and g1n ==
             * g1, so this and every shorter step are rejected (or, at a
             * bound, accepted without moving, which ends the loop below just
             * the same).  Stopping here ends Newton with the same t, D and
             * iteration count; evaluating the remaining halvings cost ~35
             * curve evaluations per converged query. */
            if (tn == t) break;
            dfl_bspline_eval(c, tn, 2, Dn);
            gn = 0.5 * dfl_foot_d2(dim, Dn, x);
            double rn[3];
            for (int j = 0; j < dim; j++) rn[j] = Dn[j] - x[j];
            double g1n = dfl_vecn_dot(dim, Dn + dim, rn);
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
        memcpy(D, Dn, sizeof Dn);
        if (moved <= 1e-15 * (fabs(t) + T)) break;
    }
    f->t = t;
    memcpy(f->p, D, (size_t)dim * sizeof(double));
    f->dist = sqrt(dfl_foot_d2(dim, D, x));
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
        r[0] = dfl_vecn_dot(dim, D + dim, rr);
        if (J) J[0] = dfl_vecn_dot(dim, D + dim, D + dim) + dfl_vecn_dot(dim, D + 2 * dim, rr);
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
    dfl_status st =
        dfl_lsq_solve(L->lsq, 1, c->dim, ceres_curve_res, &u, plo, phi, &opt, &p, &res, err);
    if (st != DFL_OK) return st;
    int iters = res.iterations;
    p = dfl_bspline_wrap(c, p);
    double P[3];
    dfl_bspline_eval(c, p, 0, P);
    double dist = sqrt(dfl_foot_d2(c->dim, P, x));
    if (c->closed || (p > c->t0 && p < c->t1)) {
        u.stationarity = 1;
        double q = p;
        st = dfl_lsq_solve(L->lsq, 1, 1, ceres_curve_res, &u, plo, phi, &opt, &q, &res, err);
        if (st != DFL_OK) return st;
        iters += res.iterations;
        q = dfl_bspline_wrap(c, q);
        double Q[3];
        dfl_bspline_eval(c, q, 0, Q);
        double dq = sqrt(dfl_foot_d2(c->dim, Q, x));
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

/* D: C, C', C'' at f->t (dfl_bspline_eval(c, f->t, 2, D)). */
static void curve_flags(const dfl_bspline *c, const double *x, const double D[3 * 3],
                        dfl_curve_foot *f)
{
    const int dim = c->dim;
    if (!c->closed && (f->t <= c->t0 || f->t >= c->t1)) f->flags |= DFL_FOOT_END;
    double v2 = dfl_vecn_dot(dim, D + dim, D + dim), r[3];
    for (int j = 0; j < dim; j++) r[j] = D[j] - x[j];
    /* g'' = |C'|^2 (1 - kappa d): vanishes at a centre of curvature */
    double g2 = v2 + dfl_vecn_dot(dim, D + 2 * dim, r);
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
        if (sqrt(dfl_foot_d2(c->dim, p, x)) > lim) return 0;
    }
    return 1;
}

typedef struct basin_ctx {
    const dfl_bspline *c;
    const double *x;
    const dfl_curve_foot *res;
} basin_ctx;

static int basin_of(const void *ctx, int kept, int cand, double tol)
{
    const basin_ctx *b = ctx;
    return curve_same_basin(b->c, b->x, &b->res[kept], &b->res[cand], tol);
}

/* Shared by the single and all-minima queries: refines the candidates into
 * res[], sorted, de-duplicated; ties flagged and ordered by parameter. */
static int curve_search(const dfl_curve_locator *L, const double *x, dfl_curve_foot *res,
                        dfl_status *st, dfl_err *err)
{
    const dfl_bspline *c = L->c;
    const int dim = c->dim;
    const size_t ns = L->ns;
    dfl_foot_topk tk = {0, L->o.candidates, {0}, {0}, {0}, {0}};
    /* local minima of the sampled squared distance (neighbours wrap on a
     * closed curve, are +inf beyond the ends of an open one); each sample's
     * distance is computed once and carried along (prev, cur, next) */
    const double first = dfl_foot_d2(dim, L->ps, x);
    double prev = c->closed ? dfl_foot_d2(dim, L->ps + (ns - 1) * (size_t)dim, x) : INFINITY;
    double cur = first;
    for (size_t i = 0; i < ns; i++) {
        const double next = i + 1 < ns ? dfl_foot_d2(dim, L->ps + (i + 1) * (size_t)dim, x)
                                       : (c->closed ? first : INFINITY);
        if (cur <= prev && cur <= next) dfl_foot_topk_insert(&tk, cur, 0, i, 0);
        prev = cur;
        cur = next;
    }
    *st = DFL_OK;
    int n = 0;
    for (int q = 0; q < tk.n; q++) {
        dfl_curve_foot f;
        double t0 = L->ts[tk.i[q]], D[3 * 3];
        if (L->o.backend == DFL_FOOT_CERES) {
            *st = curve_ceres(L, x, t0, &f, err);
            if (*st != DFL_OK) return 0;
            dfl_bspline_eval(c, f.t, 2, D);
        } else {
            curve_newton(c, x, t0, L->ds + tk.i[q] * 3 * (size_t)dim, L->o.max_iter, &f, D);
        }
        curve_flags(c, x, D, &f);
        res[n++] = f;
    }
    const basin_ctx bc = {c, x, res};
    int keep[DFL_FOOT_MAX_CAND], nt;
    const int m = dfl_foot_rank(n, dim, &res[0].dist, res[0].p, sizeof *res, L->size, L->o.tie_rel,
                                basin_of, &bc, keep, &nt);
    dfl_curve_foot kept[DFL_FOOT_MAX_CAND];
    for (int a = 0; a < m; a++) kept[a] = res[keep[a]];
    memcpy(res, kept, (size_t)m * sizeof *res);
    /* ties with the best: medial axis; order the tied ones by parameter */
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
