/* Tensor-product patches reuse the curve machinery (knot checks, basis
 * derivatives, blossoming) so surfaces and curves cannot disagree. */
#include "geom/surface.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define KMAX DFL_BSPLINE_MAX_ORDER
#define P3 (3 * sizeof(double)) /* bytes of one point */

static void clamped_uniform(int k, size_t n, double *U)
{
    size_t nk = n + (size_t)k;
    double vmax = (double)(n - (size_t)k + 1);
    for (size_t i = 0; i < nk; i++) {
        double v = (double)i - (double)(k - 1);
        U[i] = v < 0.0 ? 0.0 : (v > vmax ? vmax : v);
    }
}

dfl_status dfl_surface_init(int ku, int kv, size_t nu, size_t nv, const double *cp,
                            const double *knots_u, size_t nknots_u, const double *knots_v,
                            size_t nknots_v, dfl_surface *out, dfl_err *err)
{
    if (ku < 2 || ku > KMAX || kv < 2 || kv > KMAX)
        return dfl_err_set(err, DFL_E_INPUT, "orders (%d, %d) out of range, expected 2..%d", ku,
                           kv, KMAX);
    if (nu < (size_t)ku || nv < (size_t)kv)
        return dfl_err_set(err, DFL_E_INPUT,
                           "control grid %zu x %zu too small for orders (%d, %d): expected at "
                           "least order points in each direction",
                           nu, nv, ku, kv);
    dfl_status st;
    if (knots_u && (st = dfl_bspline_check_knots(ku, nu, knots_u, nknots_u, 0, err)) != DFL_OK) {
        dfl_err_prefix(err, "u knots");
        return st;
    }
    if (knots_v && (st = dfl_bspline_check_knots(kv, nv, knots_v, nknots_v, 0, err)) != DFL_OK) {
        dfl_err_prefix(err, "v knots");
        return st;
    }
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < nu * nv; i++)
        for (int j = 0; j < 3; j++) {
            double v = cp[i * 3 + (size_t)j];
            if (!isfinite(v))
                return dfl_err_set(err, DFL_E_INPUT, "control point %zu is not finite", i);
            lo[j] = fmin(lo[j], v);
            hi[j] = fmax(hi[j], v);
        }
    if (!(fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2])) > 0.0))
        return dfl_err_set(err, DFL_E_INPUT, "degenerate control net: all %zu points coincide",
                           nu * nv);
    dfl_surface s;
    memset(&s, 0, sizeof s);
    s.cp = malloc(nu * nv * 3 * sizeof(double));
    s.knots_u = malloc((nu + (size_t)ku) * sizeof(double));
    s.knots_v = malloc((nv + (size_t)kv) * sizeof(double));
    if (!s.cp || !s.knots_u || !s.knots_v) {
        free(s.cp);
        free(s.knots_u);
        free(s.knots_v);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory for a surface patch");
    }
    s.ku = ku;
    s.kv = kv;
    s.nu = nu;
    s.nv = nv;
    memcpy(s.cp, cp, nu * nv * 3 * sizeof(double));
    if (knots_u) memcpy(s.knots_u, knots_u, (nu + (size_t)ku) * sizeof(double));
    else clamped_uniform(ku, nu, s.knots_u);
    if (knots_v) memcpy(s.knots_v, knots_v, (nv + (size_t)kv) * sizeof(double));
    else clamped_uniform(kv, nv, s.knots_v);
    s.u0 = s.knots_u[ku - 1];
    s.u1 = s.knots_u[nu];
    s.v0 = s.knots_v[kv - 1];
    s.v1 = s.knots_v[nv];
    *out = s;
    return DFL_OK;
}

dfl_status dfl_surface_init_bezier(int ku, int kv, const double *cp, dfl_surface *out,
                                   dfl_err *err)
{
    if (ku < 2 || ku > KMAX || kv < 2 || kv > KMAX)
        return dfl_err_set(err, DFL_E_INPUT, "orders (%d, %d) out of range, expected 2..%d", ku,
                           kv, KMAX);
    double U[2 * KMAX], V[2 * KMAX];
    for (int i = 0; i < 2 * ku; i++) U[i] = i < ku ? 0.0 : 1.0;
    for (int i = 0; i < 2 * kv; i++) V[i] = i < kv ? 0.0 : 1.0;
    return dfl_surface_init(ku, kv, (size_t)ku, (size_t)kv, cp, U, (size_t)(2 * ku), V,
                            (size_t)(2 * kv), out, err);
}

void dfl_surface_free(dfl_surface *s)
{
    if (!s) return;
    free(s->cp);
    free(s->knots_u);
    free(s->knots_v);
    memset(s, 0, sizeof *s);
}

void dfl_surface_clamp(const dfl_surface *s, double *u, double *v)
{
    if (*u < s->u0) *u = s->u0;
    if (*u > s->u1) *u = s->u1;
    if (*v < s->v0) *v = s->v0;
    if (*v > s->v1) *v = s->v1;
}

void dfl_surface_eval(const dfl_surface *s, double u, double v, int nder, double *out)
{
    assert(nder >= 0 && nder <= DFL_SURFACE_MAX_DER);
    dfl_surface_clamp(s, &u, &v);
    const int ku = s->ku, kv = s->kv;
    size_t su = dfl_knot_span(s->knots_u, ku, s->nu, u, 1);
    size_t sv = dfl_knot_span(s->knots_v, kv, s->nv, v, 1);
    double Nu[(DFL_SURFACE_MAX_DER + 1) * KMAX], Nv[(DFL_SURFACE_MAX_DER + 1) * KMAX];
    dfl_bspline_basis(s->knots_u, ku, su, u, nder, Nu);
    dfl_bspline_basis(s->knots_v, kv, sv, v, nder, Nv);
    const size_t iu0 = su - (size_t)(ku - 1), iv0 = sv - (size_t)(kv - 1);
    for (int tot = 0; tot <= nder; tot++)
        for (int b = 0; b <= tot; b++) {
            int a = tot - b;
            double acc[3] = {0, 0, 0};
            for (int j = 0; j < kv; j++) {
                double row[3] = {0, 0, 0};
                const double *P = s->cp + ((iv0 + (size_t)j) * s->nu + iu0) * 3;
                for (int i = 0; i < ku; i++) {
                    double w = Nu[a * ku + i];
                    row[0] += w * P[3 * i];
                    row[1] += w * P[3 * i + 1];
                    row[2] += w * P[3 * i + 2];
                }
                double w = Nv[b * kv + j];
                acc[0] += w * row[0];
                acc[1] += w * row[1];
                acc[2] += w * row[2];
            }
            memcpy(out + DFL_SURF_IDX(a, b) * 3, acc, sizeof acc);
        }
}

double dfl_surface_normal(const dfl_surface *s, double u, double v, double n[3])
{
    double d[3 * 3];
    dfl_surface_eval(s, u, v, 1, d);
    const double *Su = d + 3, *Sv = d + 6;
    double c[3] = {Su[1] * Sv[2] - Su[2] * Sv[1], Su[2] * Sv[0] - Su[0] * Sv[2],
                   Su[0] * Sv[1] - Su[1] * Sv[0]};
    double len = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    for (int j = 0; j < 3; j++) n[j] = len > 0.0 ? c[j] / len : 0.0;
    return len;
}

size_t dfl_surface_span_count(const dfl_surface *s, int dir)
{
    const double *U = dir == 0 ? s->knots_u : s->knots_v;
    const int k = dir == 0 ? s->ku : s->kv;
    const size_t n = dir == 0 ? s->nu : s->nv;
    size_t cnt = 0;
    for (size_t j = (size_t)k - 1; j < n; j++)
        if (U[j] < U[j + 1]) cnt++;
    return cnt;
}

size_t dfl_surface_span_index(const dfl_surface *s, int dir, size_t idx)
{
    const double *U = dir == 0 ? s->knots_u : s->knots_v;
    const int k = dir == 0 ? s->ku : s->kv;
    const size_t n = dir == 0 ? s->nu : s->nv;
    for (size_t j = (size_t)k - 1; j < n; j++)
        if (U[j] < U[j + 1]) {
            if (idx == 0) return j;
            idx--;
        }
    assert(0 && "span index out of range");
    return n - 1;
}

void dfl_surface_cell_bezier(const dfl_surface *s, size_t su, size_t sv, double ua, double ub,
                             double va, double vb, double *bez)
{
    const int ku = s->ku, kv = s->kv;
    double rows[KMAX * KMAX * 3], col[KMAX * 3], colb[KMAX * 3];
    const size_t iu0 = su - (size_t)(ku - 1), iv0 = sv - (size_t)(kv - 1);
    /* u-direction Bezier points of every control row of the span */
    for (int j = 0; j < kv; j++)
        dfl_blossom_bezier(s->knots_u, ku, su, s->cp + ((iv0 + (size_t)j) * s->nu + iu0) * 3, 3,
                           ua, ub, rows + (size_t)j * (size_t)ku * 3);
    /* then each column of those along v */
    for (int i = 0; i < ku; i++) {
        for (int j = 0; j < kv; j++) memcpy(col + j * 3, rows + ((size_t)j * ku + i) * 3, P3);
        dfl_blossom_bezier(s->knots_v, kv, sv, col, 3, va, vb, colb);
        for (int j = 0; j < kv; j++) memcpy(bez + ((size_t)j * ku + i) * 3, colb + j * 3, P3);
    }
}

dfl_status dfl_surface_set_init(size_t npatch, dfl_surface *patches, dfl_surface_set *out,
                                dfl_err *err)
{
    if (npatch == 0) return dfl_err_set(err, DFL_E_INPUT, "a surface needs at least one patch");
    dfl_surface *p = malloc(npatch * sizeof *p);
    if (!p) return dfl_err_set(err, DFL_E_NOMEM, "out of memory for %zu patches", npatch);
    memcpy(p, patches, npatch * sizeof *p);
    memset(patches, 0, npatch * sizeof *p);
    out->npatch = npatch;
    out->patch = p;
    return DFL_OK;
}

void dfl_surface_set_free(dfl_surface_set *s)
{
    if (!s) return;
    for (size_t i = 0; i < s->npatch; i++) dfl_surface_free(&s->patch[i]);
    free(s->patch);
    s->patch = NULL;
    s->npatch = 0;
}

/* (u, v) of fraction f along edge e, and the inward cross-boundary
 * derivative (pointing into the patch). */
static void edge_point(const dfl_surface *s, int e, double f, double *pos, double *inward,
                       double *normal)
{
    double u, v;
    switch (e) {
    case 0: u = s->u0 + f * (s->u1 - s->u0); v = s->v0; break;
    case 1: u = s->u1; v = s->v0 + f * (s->v1 - s->v0); break;
    case 2: u = s->u0 + f * (s->u1 - s->u0); v = s->v1; break;
    default: u = s->u0; v = s->v0 + f * (s->v1 - s->v0); break;
    }
    double d[9];
    dfl_surface_eval(s, u, v, 1, d);
    memcpy(pos, d, P3);
    const double *Su = d + 3, *Sv = d + 6;
    for (int j = 0; j < 3; j++)
        inward[j] = e == 0 ? Sv[j] : e == 1 ? -Su[j] : e == 2 ? -Sv[j] : Su[j];
    dfl_surface_normal(s, u, v, normal);
}

static double net_size(const dfl_surface *s)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < s->nu * s->nv; i++)
        for (int j = 0; j < 3; j++) {
            lo[j] = fmin(lo[j], s->cp[3 * i + (size_t)j]);
            hi[j] = fmax(hi[j], s->cp[3 * i + (size_t)j]);
        }
    return fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
}

dfl_join dfl_surface_join(const dfl_surface *a, int ea, const dfl_surface *b, int eb, double tol,
                          double tol_angle, int samples, int *reversed)
{
    assert(samples >= 2);
    const double scale = 1.0 + fmax(net_size(a), net_size(b));
    for (int rev = 0; rev <= 1; rev++) {
        int c0 = 1, g1 = 1;
        for (int q = 0; q < samples && c0; q++) {
            double f = (double)q / (samples - 1);
            double pa[3], ia[3], na[3], pb[3], ib[3], nb[3];
            edge_point(a, ea, f, pa, ia, na);
            edge_point(b, eb, rev ? 1.0 - f : f, pb, ib, nb);
            double gap = 0.0;
            for (int j = 0; j < 3; j++) gap = fmax(gap, fabs(pa[j] - pb[j]));
            if (gap > tol * scale) {
                c0 = 0;
                break;
            }
            double cr[3] = {na[1] * nb[2] - na[2] * nb[1], na[2] * nb[0] - na[0] * nb[2],
                            na[0] * nb[1] - na[1] * nb[0]};
            double sn = sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
            double nn = na[0] * na[0] + na[1] * na[1] + na[2] * na[2];
            double mm = nb[0] * nb[0] + nb[1] * nb[1] + nb[2] * nb[2];
            /* inward cross-boundary derivatives must point away from each
             * other (no fold-back) once the common tangent is removed */
            double in_dot = ia[0] * ib[0] + ia[1] * ib[1] + ia[2] * ib[2];
            if (!(nn > 0.5 && mm > 0.5) || sn > sin(tol_angle) || !(in_dot < 0.0)) g1 = 0;
        }
        if (c0) {
            if (reversed) *reversed = rev;
            return g1 ? DFL_JOIN_G1 : DFL_JOIN_C0;
        }
    }
    if (reversed) *reversed = 0;
    return DFL_JOIN_NONE;
}

dfl_join dfl_surface_set_joins(const dfl_surface_set *s, double tol, double tol_angle,
                               size_t *nshared, size_t *isolated)
{
    dfl_join weakest = DFL_JOIN_G1;
    size_t shared = 0;
    *isolated = s->npatch;
    for (size_t p = 0; p < s->npatch; p++) {
        int has = 0;
        for (size_t q = 0; q < s->npatch; q++) {
            if (q == p) continue;
            for (int ea = 0; ea < 4; ea++)
                for (int eb = 0; eb < 4; eb++) {
                    dfl_join j =
                        dfl_surface_join(&s->patch[p], ea, &s->patch[q], eb, tol, tol_angle, 9,
                                         NULL);
                    if (j == DFL_JOIN_NONE) continue;
                    has = 1;
                    if (q > p) shared++;
                    if (j < weakest) weakest = j;
                }
        }
        if (!has && *isolated == s->npatch) *isolated = p;
    }
    *nshared = shared;
    return shared ? weakest : DFL_JOIN_NONE;
}
