/* Footpoints on surface patches: projected Newton and active-set Ceres
 * refinement of the sampled minima (footpoint.h). */
#include "geom/foot_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/vec.h"

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
    double g = 0.5 * dfl_foot_d2(3, D, x);
    int it = 0;
    for (; it < maxit; it++) {
        for (int j = 0; j < 3; j++) r[j] = D[j] - x[j];
        const double *Su = D + 3, *Sv = D + 6, *Suu = D + 9, *Suv = D + 12, *Svv = D + 15;
        double gu = dfl_vecn_dot(3, Su, r), gv = dfl_vecn_dot(3, Sv, r);
        double E = dfl_vecn_dot(3, Su, Su), F = dfl_vecn_dot(3, Su, Sv),
               G = dfl_vecn_dot(3, Sv, Sv);
        double Huu = E + dfl_vecn_dot(3, Suu, r), Huv = F + dfl_vecn_dot(3, Suv, r),
               Hvv = G + dfl_vecn_dot(3, Svv, r);
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
        const double noise = dfl_foot_g_noise(3, D, x, g);
        const double pg = (fu ? gu * gu : 0.0) + (fv ? gv * gv : 0.0);
        for (int h = 0; h < 60; h++) {
            un = clampd(u + du, s->u0, s->u1);
            vn = clampd(v + dv, s->v0, s->v1);
            /* no move within rounding: gn == g and pgn == pg reject this
             * and every shorter step, so stop without evaluating them (the
             * same u, v, D and iteration count as the full 60 halvings) */
            if (un == u && vn == v) break;
            dfl_surface_eval(s, un, vn, 2, Dn);
            gn = 0.5 * dfl_foot_d2(3, Dn, x);
            double rn[3];
            for (int j = 0; j < 3; j++) rn[j] = Dn[j] - x[j];
            double gun = dfl_vecn_dot(3, Dn + 3, rn), gvn = dfl_vecn_dot(3, Dn + 6, rn);
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
    f->dist = sqrt(dfl_foot_d2(3, D, x));
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
        double gu = dfl_vecn_dot(3, Su, rr), gv = dfl_vecn_dot(3, Sv, rr);
        double Huu = dfl_vecn_dot(3, Su, Su) + dfl_vecn_dot(3, D + 9, rr);
        double Huv = dfl_vecn_dot(3, Su, Sv) + dfl_vecn_dot(3, D + 12, rr);
        double Hvv = dfl_vecn_dot(3, Sv, Sv) + dfl_vecn_dot(3, D + 15, rr);
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
        double gu = dfl_vecn_dot(3, D + 3, r), gv = dfl_vecn_dot(3, D + 6, r);
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
    double dist = sqrt(dfl_foot_d2(3, P, x));
    if (fix != 2) {
        double q[2] = {prm[0], prm[1]}, Q[3];
        cu.fix = fix;
        cu.fixval = fix >= 0 ? prm[fix] : 0.0;
        cu.stationarity = 1;
        if ((st = surf_solve(L, sp, &cu, q, &iters, err)) != DFL_OK) return st;
        dfl_surface_eval(sp, q[0], q[1], 0, Q);
        double dq = sqrt(dfl_foot_d2(3, Q, x));
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
    double E = dfl_vecn_dot(3, D + 3, D + 3), F = dfl_vecn_dot(3, D + 3, D + 6),
           G = dfl_vecn_dot(3, D + 6, D + 6);
    double Huu = E + dfl_vecn_dot(3, D + 9, r), Huv = F + dfl_vecn_dot(3, D + 12, r),
           Hvv = G + dfl_vecn_dot(3, D + 15, r);
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
        if (sqrt(dfl_foot_d2(3, p, x)) > lim) return 0;
    }
    return 1;
}

typedef struct basin_ctx {
    const dfl_surface_set *s;
    const double *x;
    const dfl_surface_foot *res;
} basin_ctx;

/* same basin only within one patch */
static int basin_of(const void *ctx, int kept, int cand, double tol)
{
    const basin_ctx *b = ctx;
    const dfl_surface_foot *K = &b->res[kept], *C = &b->res[cand];
    return C->patch == K->patch && surface_same_basin(&b->s->patch[C->patch], b->x, K, C, tol);
}

dfl_status dfl_surface_footpoint(const dfl_surface_locator *L, const double x[3],
                                 dfl_surface_foot *out, dfl_err *err)
{
    const dfl_surface_set *s = L->s;
    dfl_foot_topk tk = {0, L->o.candidates, {0}, {0}, {0}, {0}};
    for (size_t p = 0; p < s->npatch; p++) {
        const size_t nu = L->nsu[p], nv = L->nsv[p];
        const double *P = L->ps + L->off[p] * 3;
        for (size_t j = 0; j < nv; j++)
            for (size_t i = 0; i < nu; i++) {
                double g = dfl_foot_d2(3, P + (i + nu * j) * 3, x);
                if ((i > 0 && dfl_foot_d2(3, P + (i - 1 + nu * j) * 3, x) < g) ||
                    (i + 1 < nu && dfl_foot_d2(3, P + (i + 1 + nu * j) * 3, x) < g) ||
                    (j > 0 && dfl_foot_d2(3, P + (i + nu * (j - 1)) * 3, x) < g) ||
                    (j + 1 < nv && dfl_foot_d2(3, P + (i + nu * (j + 1)) * 3, x) < g))
                    continue;
                dfl_foot_topk_insert(&tk, g, p, i, j);
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
    const basin_ctx bc = {s, x, res};
    int keep[DFL_FOOT_MAX_CAND], nt;
    dfl_foot_rank(n, 3, &res[0].dist, res[0].p, sizeof *res, L->size, L->o.tie_rel, basin_of, &bc,
                  keep, &nt);
    /* ties with the best: medial axis; the smallest (patch, u, v) wins */
    int best = keep[0];
    if (nt > 1) {
        for (int a = 1; a < nt; a++) {
            const dfl_surface_foot *A = &res[keep[a]], *B = &res[best];
            if (A->patch < B->patch || (A->patch == B->patch && (A->u < B->u ||
                                                                 (A->u == B->u && A->v < B->v))))
                best = keep[a];
        }
        res[best].flags |= DFL_FOOT_MEDIAL;
    }
    *out = res[best];
    return DFL_OK;
}
