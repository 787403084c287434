/* Footpoints of implicit surfaces: starts from the surface samples, the
 * Riemannian Newton and the Ceres solvers, and the choice among them (see
 * geom/implicit.h). */
#include "geom/implicit_impl.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/linalg.h"

/* ---- starts -------------------------------------------------------------- */

typedef struct start_set {
    int n;
    size_t idx[DFL_IMPLICIT_MAX_STARTS];
    double dist[DFL_IMPLICIT_MAX_STARTS];
    double d0;                  /* distance of the nearest sample */
} start_set;

/* A lower bound of dist2_to(q, t) over the samples t of bucket (i, j, k):
 * the squared distance to the bucket's cube grown by BUCKET_SLACK of its
 * side, and without end on a side where the grid ends (bucket_of clamps a
 * sample beyond the grid, as projected samples of a surface leaving the
 * box may be, into the last cube).  bucket_of places any other sample
 * within a few roundings of its cube (relative 1e-16 of the coordinates),
 * far inside the slack, and the
 * slack outweighs the roundings of this sum and of dist2_to's for any
 * finite geometry (gaps below 1e6 cube sides), so the bound never exceeds
 * a sample's computed distance.  q not finite: 0 (no comparison holds).
 * slab_gap is one axis' term (cell c of axis a); with the terms of some
 * axes taken as 0 the sum is no larger (rounding is monotone), a bound
 * for a whole row or plane of buckets. */
#define BUCKET_SLACK 1e-6
static double slab_gap(const dfl_implicit *s, const double q[3], int a, int c)
{
    const double m = BUCKET_SLACK * s->bcell, b = s->blo[a] + c * s->bcell - m;
    const double lo = c == 0 ? -HUGE_VAL : b, hi = c == s->nb[a] - 1 ? HUGE_VAL : b + s->bcell + 2 * m;
    return q[a] < lo ? lo - q[a] : (q[a] > hi ? q[a] - hi : 0.0);
}

static double bucket_lb2(const dfl_implicit *s, const double q[3], int i, int j, int k)
{
    const double o0 = slab_gap(s, q, 0, i), o1 = slab_gap(s, q, 1, j), o2 = slab_gap(s, q, 2, k);
    return 0.0 + o0 * o0 + o1 * o1 + o2 * o2;
}

static double nearest_sample(const dfl_implicit *s, const double q[3])
{
    double qc[3];
    for (int a = 0; a < 3; a++) {
        double top = s->blo[a] + s->nb[a] * s->bcell;
        qc[a] = q[a] < s->blo[a] ? s->blo[a] : (q[a] > top ? top : q[a]);
    }
    int c0[3];
    bucket_of(s, qc, c0);
    int rmax = s->nb[0] + s->nb[1] + s->nb[2];
    double best2 = HUGE_VAL;
    for (int r = 0; r <= rmax; r++) {
        for (int k = c0[2] - r; k <= c0[2] + r; k++) {
            if (k < 0 || k >= s->nb[2]) continue;
            const double o2 = slab_gap(s, q, 2, k);
            if (0.0 + 0.0 + 0.0 + o2 * o2 >= best2) continue; /* the plane's bound */
            for (int j = c0[1] - r; j <= c0[1] + r; j++) {
                if (j < 0 || j >= s->nb[1]) continue;
                const double o1 = slab_gap(s, q, 1, j);
                if (0.0 + 0.0 + o1 * o1 + o2 * o2 >= best2) continue; /* the row's */
                /* a row through the ring's inside holds two of its buckets
                 * (the same buckets in the same order, fewer steps) */
                const int step = abs(j - c0[1]) < r && abs(k - c0[2]) < r ? 2 * r : 1;
                for (int i = c0[0] - r; i <= c0[0] + r; i += i == c0[0] - r ? step : 1) {
                    if (i < 0 || i >= s->nb[0]) continue;
                    if (abs(i - c0[0]) < r && abs(j - c0[1]) < r && abs(k - c0[2]) < r) continue;
                    size_t b = bucket_index(s, i, j, k);
                    /* only the smallest distance is kept, so a bucket no
                     * nearer than it changes nothing */
                    if (s->bstart[b] == s->bstart[b + 1] || bucket_lb2(s, q, i, j, k) >= best2)
                        continue;
                    for (size_t t = s->bstart[b]; t < s->bstart[b + 1]; t++) {
                        double d2 = dist2_to(q, s->samp + 3 * t);
                        if (d2 < best2) best2 = d2;
                    }
                }
            }
        }
        /* projection onto the box is non-expansive, so points of ring r+1
         * are at least r * bcell away from q */
        if (best2 < HUGE_VAL && sqrt(best2) <= r * s->bcell) break;
    }
    return sqrt(best2);
}

static void collect_starts(const dfl_implicit *s, const double q[3], start_set *st)
{
    const double h = s->h, sep2 = 9.0 * h * h;
    st->n = 0;
    st->d0 = nearest_sample(s, q);
    double rb = st->d0 + 1.5 * h;
    int clo[3], chi[3];
    double lo[3] = {q[0] - rb, q[1] - rb, q[2] - rb}, hi[3] = {q[0] + rb, q[1] + rb, q[2] + rb};
    bucket_of(s, lo, clo);
    bucket_of(s, hi, chi);
    for (int k = clo[2]; k <= chi[2]; k++)
        for (int j = clo[1]; j <= chi[1]; j++)
            for (int i = clo[0]; i <= chi[0]; i++) {
                size_t b = bucket_index(s, i, j, k);
                /* every sample of a bucket beyond rb takes the `continue`
                 * below (sqrt is monotone) */
                if (s->bstart[b] == s->bstart[b + 1] || sqrt(bucket_lb2(s, q, i, j, k)) > rb)
                    continue;
                for (size_t t = s->bstart[b]; t < s->bstart[b + 1]; t++) {
                    const double *p = s->samp + 3 * t;
                    double d = sqrt(dist2_to(q, p));
                    if (d > rb) continue;
                    int near = -1, far = -1;
                    for (int m = 0; m < st->n; m++) {
                        if (near < 0 && dist2_to(p, s->samp + 3 * st->idx[m]) < sep2) near = m;
                        if (far < 0 || st->dist[m] > st->dist[far]) far = m;
                    }
                    if (near >= 0) {
                        if (d < st->dist[near]) { st->idx[near] = t; st->dist[near] = d; }
                    } else if (st->n < DFL_IMPLICIT_MAX_STARTS) {
                        st->idx[st->n] = t;
                        st->dist[st->n] = d;
                        st->n++;
                    } else if (d < st->dist[far]) {
                        st->idx[far] = t;
                        st->dist[far] = d;
                    }
                }
            }
    assert(st->n > 0);
}

/* ---- local solvers --------------------------------------------------------- */

/* Accepts p as a footpoint of q: on the surface and q - p along the normal,
 * both to a tolerance far below any distance the tests resolve. */
static int accept_foot(const dfl_implicit *s, const double q[3], const double p[3])
{
    double G[3];
    double g = g_local(s, p, G, NULL);
    double gn = sqrt(dfl_vec3_dot(G, G));
    if (!(gn > 0.0)) return 0;
    double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, c[3];
    dfl_vec3_cross(u, G, c);
    double un = sqrt(dfl_vec3_dot(u, u));
    return fabs(g) / gn <= 1e-11 * s->scale && sqrt(dfl_vec3_dot(c, c)) / gn <= 1e-9 * (s->scale + un);
}

/* Newton on the surface: minimizes f(p) = |p - q|^2 / 2 over g(p) = 0 with
 * the Riemannian Newton step in the tangent plane and the projection onto
 * g = 0 as retraction.  In the tangent basis (t1, t2) at p with outward n,
 * grad f = -P (q - p) and Hess f = I + d W, d = (q - p).n, W = dn (the
 * shape operator, t_i^T Hess g t_j / |grad g|), whose eigenvalues 1 + k_i d
 * are the SDF's Hessian denominators.
 * Why not Newton on the square system (p - q + t grad g, g) = 0: near the
 * medial axis (close to a torus' axis a circle of footpoints nearly ties)
 * that Jacobian is nearly singular along the circle and a straight
 * tangential step leaves the curved valley, so Newton and LM crawl.  Here a
 * tangential step is followed by the projection, so the ill-conditioned
 * direction converges like Newton on a 1D function.  Negative or tiny
 * eigenvalues (near the far footpoint, focal points) are replaced by their
 * absolute values / a floor, and steps are halved until f decreases. */
static int newton_foot(const dfl_implicit *s, const double q[3], const double p0[3],
                       double maxstep, double p[3])
{
    double G[3], H[9];
    memcpy(p, p0, 3 * sizeof *p);
    if (!project(s, p)) return 0;
    double f = 0.5 * dist2_to(p, q);
    for (int it = 0; it < s->opt.max_iterations; it++) {
        g_local(s, p, G, H);
        double gn = sqrt(dfl_vec3_dot(G, G));
        if (!(gn > 0.0)) return 0;
        double n[3] = {G[0] / gn, G[1] / gn, G[2] / gn}, t1[3], t2[3];
        dfl_vec3_tangent_basis(n, t1, t2);
        double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
        double d = dfl_vec3_dot(u, n);
        double gr[2] = {-dfl_vec3_dot(t1, u), -dfl_vec3_dot(t2, u)};
        double Ht1[3], Ht2[3];
        for (int i = 0; i < 3; i++) {
            Ht1[i] = dfl_vec3_dot(H + 3 * i, t1);
            Ht2[i] = dfl_vec3_dot(H + 3 * i, t2);
        }
        double a = 1.0 + d * dfl_vec3_dot(t1, Ht1) / gn, c = 1.0 + d * dfl_vec3_dot(t2, Ht2) / gn;
        double b = d * 0.5 * (dfl_vec3_dot(t1, Ht2) + dfl_vec3_dot(t2, Ht1)) / gn;
        /* eigen-decomposition of [[a, b], [b, c]] */
        double lam[2], th;
        dfl_sym2_eigen(a, b, c, &lam[1], &lam[0], &th);
        double ev[2][2] = {{cos(th), sin(th)}, {-sin(th), cos(th)}};
        double v2[2] = {0.0, 0.0};
        for (int k = 0; k < 2; k++) {
            double l = fmax(fabs(lam[k]), 1e-12);
            double c_k = (ev[k][0] * gr[0] + ev[k][1] * gr[1]) / l;
            v2[0] -= c_k * ev[k][0];
            v2[1] -= c_k * ev[k][1];
        }
        double v[3];
        for (int j = 0; j < 3; j++) v[j] = v2[0] * t1[j] + v2[1] * t2[j];
        double step = sqrt(dfl_vec3_dot(v, v));
        if (!(step > 0.0)) break;
        if (step <= 1e-6 * s->scale) {
            /* Quadratic basin: f = |p - q|^2/2 resolves the tangential
             * position only to sqrt(eps), so a decrease test would stop
             * early; take the full step, whose error is O(step^2). */
            double pt[3] = {p[0] + v[0], p[1] + v[1], p[2] + v[2]};
            if (!project(s, pt)) break;
            memcpy(p, pt, sizeof pt);
            f = 0.5 * dist2_to(p, q);
            if (step <= 1e-12 * s->scale) break;
            continue;
        }
        double lamb = step > maxstep ? maxstep / step : 1.0;
        int moved = 0;
        for (int ls = 0; ls < 50; ls++, lamb *= 0.5) {
            double pt[3] = {p[0] + lamb * v[0], p[1] + lamb * v[1], p[2] + lamb * v[2]};
            if (!project(s, pt)) continue;
            double ft = 0.5 * dist2_to(pt, q);
            if (ft < f) {
                memcpy(p, pt, sizeof pt);
                f = ft;
                moved = 1;
                break;
            }
        }
        /* no decrease at any step length: give the acceptance test the say */
        if (!moved) break;
    }
    return accept_foot(s, q, p);
}

typedef struct lsq_user {
    const dfl_implicit *s;
    const double *q;
} lsq_user;

/* r = (g(p), grad g(p) x (p - q)); J rows: grad g^T and [G]x - [u]x H
 * (d(G x u) = dG x u + G x du = -[u]x H dp + [G]x dp). */
static int foot_residual(void *user, const double *p, double *r, double *Jr)
{
    const lsq_user *U = user;
    double G[3], H[9];
    double g = g_local(U->s, p, G, H);
    double u[3] = {p[0] - U->q[0], p[1] - U->q[1], p[2] - U->q[2]};
    r[0] = g;
    dfl_vec3_cross(G, u, r + 1);
    if (Jr) {
        double Gx[9] = {0, -G[2], G[1], G[2], 0, -G[0], -G[1], G[0], 0};
        double ux[9] = {0, -u[2], u[1], u[2], 0, -u[0], -u[1], u[0], 0};
        for (int j = 0; j < 3; j++) Jr[j] = G[j];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                double v = Gx[3 * i + j];
                for (int k = 0; k < 3; k++) v -= ux[3 * i + k] * H[3 * k + j];
                Jr[3 * (i + 1) + j] = v;
            }
    }
    return isfinite(r[0] + r[1] + r[2] + r[3]) ? 0 : 1;
}

static int ceres_foot(const dfl_implicit *s, const double q[3], const double p0[3], double half,
                      double p[3])
{
    double lo[3], hi[3];
    for (int a = 0; a < 3; a++) {
        lo[a] = q[a] - half;
        hi[a] = q[a] + half;
        p[a] = p0[a] < lo[a] ? lo[a] : (p0[a] > hi[a] ? hi[a] : p0[a]);
    }
    lsq_user U = {s, q};
    dfl_lsq_options opt;
    dfl_lsq_options_default(&opt);
    opt.max_iterations = s->opt.ceres_max_iterations;
    dfl_lsq_result res;
    if (dfl_lsq_solve(s->lsq, 3, 4, foot_residual, &U, lo, hi, &opt, p, &res, NULL) != DFL_OK)
        return 0;
    return accept_foot(s, q, p);
}

/* Lexicographic order on footpoints, for the deterministic medial choice. */
static int lex_less(const double a[3], const double b[3])
{
    for (int i = 0; i < 3; i++)
        if (a[i] != b[i]) return a[i] < b[i];
    return 0;
}

dfl_status dfl_implicit_footpoint_with(const dfl_implicit *s, dfl_foot_backend backend,
                                       const double x[3], dfl_footpoint *out, dfl_err *err)
{
    /* a NaN coordinate would make bucket_of cast NaN to int (undefined: on
     * x86 INT_MIN, a read far outside the buckets), an infinite one too
     * through q - rb = inf - inf; and no start converges to either */
    if (!(isfinite(x[0]) && isfinite(x[1]) && isfinite(x[2])))
        return dfl_err_set(err, DFL_E_NUMERIC, "implicit footpoint of (%g, %g, %g): not finite",
                           x[0], x[1], x[2]);
    double q[3];
    to_local(s, x, q);
    start_set st;
    collect_starts(s, q, &st);
    double cand[DFL_IMPLICIT_MAX_STARTS][3], cd[DFL_IMPLICIT_MAX_STARTS];
    int nc = 0;
    double half = st.d0 + 2.0 * s->h;
    for (int m = 0; m < st.n; m++) {
        const double *p0 = s->samp + 3 * st.idx[m];
        int ok = backend == DFL_FOOT_CERES ? ceres_foot(s, q, p0, half, cand[nc])
                                           : newton_foot(s, q, p0, half, cand[nc]);
        if (!ok) continue;
        cd[nc] = sqrt(dist2_to(q, cand[nc]));
        nc++;
    }
    if (nc == 0)
        return dfl_err_set(err, DFL_E_NUMERIC,
                           "implicit footpoint of (%g, %g, %g): none of %d starts converged", x[0],
                           x[1], x[2], st.n);
    double dmin = HUGE_VAL;
    for (int m = 0; m < nc; m++) dmin = fmin(dmin, cd[m]);
    const double dtol = 1e-9 * s->scale, ptol2 = 1e-12 * s->scale * s->scale;
    int best = -1, medial = 0;
    for (int m = 0; m < nc; m++) {
        if (cd[m] > dmin + dtol) continue;
        if (best < 0) { best = m; continue; }
        if (dist2_to(cand[m], cand[best]) > ptol2) medial = 1;
        if (lex_less(cand[m], cand[best])) best = m;
    }
    const double *p = cand[best];
    double G[3];
    g_local(s, p, G, NULL);
    double gx = g_local(s, q, NULL, NULL);
    double gn = sqrt(dfl_vec3_dot(G, G));
    double nl[3] = {G[0] / gn, G[1] / gn, G[2] / gn};
    double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    to_world(s, p, out->p);
    vec_to_world(s, nl, out->n);
    out->d = (gx < 0.0 ? -1.0 : 1.0) * cd[best];
    if (gx == 0.0) out->d = 0.0;
    out->t = dfl_vec3_dot(u, G) / (gn * gn);
    out->medial = medial;
    out->converged = nc;
    return DFL_OK;
}

dfl_status dfl_implicit_footpoint(const dfl_implicit *s, const double x[3], dfl_footpoint *out,
                                  dfl_err *err)
{
    return dfl_implicit_footpoint_with(s, s->opt.backend, x, out, err);
}
