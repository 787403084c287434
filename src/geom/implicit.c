#include "geom/implicit.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/vec.h"

#include "solve/lsq.h"

/* ---- sparse polynomials in three variables ------------------------------ */

typedef struct poly {
    int n;
    int deg;
    double c[DFL_IMPLICIT_MAX_TERMS];
    int e[DFL_IMPLICIT_MAX_TERMS][3];
} poly;

/* Adds c * u^e0 v^e1 w^e2, merging like terms; 0 if full. */
static int poly_term(poly *P, double c, int e0, int e1, int e2)
{
    if (c == 0.0) return 1;
    for (int k = 0; k < P->n; k++) {
        if (P->e[k][0] == e0 && P->e[k][1] == e1 && P->e[k][2] == e2) {
            P->c[k] += c;
            return 1;
        }
    }
    if (P->n >= DFL_IMPLICIT_MAX_TERMS) return 0;
    P->c[P->n] = c;
    P->e[P->n][0] = e0;
    P->e[P->n][1] = e1;
    P->e[P->n][2] = e2;
    P->n++;
    if (e0 + e1 + e2 > P->deg) P->deg = e0 + e1 + e2;
    return 1;
}

/* out = a * b (out must not alias); 0 if it does not fit. */
static int poly_mul(const poly *a, const poly *b, poly *out)
{
    memset(out, 0, sizeof *out);
    for (int i = 0; i < a->n; i++)
        for (int j = 0; j < b->n; j++)
            if (!poly_term(out, a->c[i] * b->c[j], a->e[i][0] + b->e[j][0],
                           a->e[i][1] + b->e[j][1], a->e[i][2] + b->e[j][2]))
                return 0;
    return 1;
}

/* out += k * a */
static int poly_axpy(double k, const poly *a, poly *out)
{
    for (int i = 0; i < a->n; i++)
        if (!poly_term(out, k * a->c[i], a->e[i][0], a->e[i][1], a->e[i][2])) return 0;
    return 1;
}

static void poly_deriv(const poly *P, int axis, poly *out)
{
    memset(out, 0, sizeof *out);
    for (int k = 0; k < P->n; k++) {
        int e[3] = {P->e[k][0], P->e[k][1], P->e[k][2]};
        if (e[axis] == 0) continue;
        double c = P->c[k] * e[axis];
        e[axis]--;
        poly_term(out, c, e[0], e[1], e[2]); /* a derivative has no more terms */
    }
}

/* Value and partial derivatives up to order `order` (0..3) at local q.
 * H (9) and T (27) are full symmetric arrays. */
static double poly_eval(const poly *P, const double q[3], int order, double gr[3], double H[9],
                        double T[27])
{
    double pw[3][DFL_IMPLICIT_MAX_DEGREE + 1];
    for (int a = 0; a < 3; a++) {
        pw[a][0] = 1.0;
        for (int k = 1; k <= P->deg; k++) pw[a][k] = pw[a][k - 1] * q[a];
    }
    double g = 0.0;
    if (order >= 1) memset(gr, 0, 3 * sizeof *gr);
    if (order >= 2) memset(H, 0, 9 * sizeof *H);
    if (order >= 3) memset(T, 0, 27 * sizeof *T);
    for (int k = 0; k < P->n; k++) {
        /* D[a][m] = d^m/dq_a^m q_a^e_a */
        double D[3][4];
        for (int a = 0; a < 3; a++) {
            int e = P->e[k][a];
            double ff = 1.0;
            for (int m = 0; m <= order; m++) {
                D[a][m] = (e >= m) ? ff * pw[a][e - m] : 0.0;
                ff *= (double)(e - m);
            }
        }
        double c = P->c[k];
        g += c * D[0][0] * D[1][0] * D[2][0];
        if (order < 1) continue;
        for (int i = 0; i < 3; i++) {
            int m[3] = {0, 0, 0};
            m[i]++;
            gr[i] += c * D[0][m[0]] * D[1][m[1]] * D[2][m[2]];
            if (order < 2) continue;
            for (int j = 0; j < 3; j++) {
                int mj[3] = {m[0], m[1], m[2]};
                mj[j]++;
                H[3 * i + j] += c * D[0][mj[0]] * D[1][mj[1]] * D[2][mj[2]];
                if (order < 3) continue;
                for (int l = 0; l < 3; l++) {
                    int ml[3] = {mj[0], mj[1], mj[2]};
                    ml[l]++;
                    T[9 * i + 3 * j + l] += c * D[0][ml[0]] * D[1][ml[1]] * D[2][ml[2]];
                }
            }
        }
    }
    return g;
}

/* ---- truncated power series (coefficients 0..K) ------------------------- */

typedef struct ser {
    double c[DFL_JET_MAX + 1];
} ser;

static void ser_mul(const ser *a, const ser *b, int K, ser *out)
{
    ser r;
    for (int k = 0; k <= K; k++) {
        double s = 0.0;
        for (int i = 0; i <= k; i++) s += a->c[i] * b->c[k - i];
        r.c[k] = s;
    }
    *out = r;
}

/* sqrt of a series with a->c[0] > 0 (Cauchy product solved term by term). */
static int ser_sqrt(const ser *a, int K, ser *out)
{
    if (!(a->c[0] > 0.0)) return 0;
    ser r;
    r.c[0] = sqrt(a->c[0]);
    for (int k = 1; k <= K; k++) {
        double s = a->c[k];
        for (int i = 1; i < k; i++) s -= r.c[i] * r.c[k - i];
        r.c[k] = s / (2.0 * r.c[0]);
    }
    *out = r;
    return 1;
}

/* Polynomial at a series point: value series. */
static void poly_eval_ser(const poly *P, const ser X[3], int K, ser *out)
{
    ser pw[3][DFL_IMPLICIT_MAX_DEGREE + 1];
    for (int a = 0; a < 3; a++) {
        memset(&pw[a][0], 0, sizeof(ser));
        pw[a][0].c[0] = 1.0;
        for (int k = 1; k <= P->deg; k++) ser_mul(&pw[a][k - 1], &X[a], K, &pw[a][k]);
    }
    memset(out, 0, sizeof *out);
    for (int t = 0; t < P->n; t++) {
        ser m;
        ser_mul(&pw[0][P->e[t][0]], &pw[1][P->e[t][1]], K, &m);
        ser_mul(&m, &pw[2][P->e[t][2]], K, &m);
        for (int k = 0; k <= K; k++) out->c[k] += P->c[t] * m.c[k];
    }
}

/* ---- small dense algebra ------------------------------------------------- */


/* LU with partial pivoting of a 4x4 matrix in place; 0 if (numerically)
 * singular relative to its largest entry. */
static int lu4(double A[16], int piv[4], double tol)
{
    double amax = 0.0;
    for (int i = 0; i < 16; i++) amax = fmax(amax, fabs(A[i]));
    if (!(amax > 0.0)) return 0;
    for (int k = 0; k < 4; k++) {
        int p = k;
        for (int i = k + 1; i < 4; i++)
            if (fabs(A[4 * i + k]) > fabs(A[4 * p + k])) p = i;
        if (!(fabs(A[4 * p + k]) > tol * amax)) return 0;
        piv[k] = p;
        if (p != k)
            for (int j = 0; j < 4; j++) {
                double t = A[4 * k + j];
                A[4 * k + j] = A[4 * p + j];
                A[4 * p + j] = t;
            }
        for (int i = k + 1; i < 4; i++) {
            double f = A[4 * i + k] /= A[4 * k + k];
            for (int j = k + 1; j < 4; j++) A[4 * i + j] -= f * A[4 * k + j];
        }
    }
    return 1;
}

static void lu4_solve(const double A[16], const int piv[4], double b[4])
{
    /* lu4 swaps whole rows (multipliers included), so L refers to the final
     * row order: permute b completely before the forward substitution */
    for (int k = 0; k < 4; k++) {
        if (piv[k] != k) {
            double t = b[k];
            b[k] = b[piv[k]];
            b[piv[k]] = t;
        }
    }
    for (int k = 0; k < 4; k++)
        for (int i = k + 1; i < 4; i++) b[i] -= A[4 * i + k] * b[k];
    for (int i = 3; i >= 0; i--) {
        for (int j = i + 1; j < 4; j++) b[i] -= A[4 * i + j] * b[j];
        b[i] /= A[4 * i + i];
    }
}

/* Footpoint system Jacobian [[I + t H, G], [G^T, 0]]. */
static void foot_jacobian(const double G[3], const double H[9], double t, double J[16])
{
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) J[4 * i + j] = (i == j ? 1.0 : 0.0) + t * H[3 * i + j];
        J[4 * i + 3] = G[i];
        J[12 + i] = G[i];
    }
    J[15] = 0.0;
}

/* ---- the implicit surface ------------------------------------------------ */

struct dfl_implicit {
    poly g, gd[3];
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

void dfl_implicit_options_default(dfl_implicit_options *opt)
{
    opt->backend = DFL_FOOT_NEWTON;
    opt->resolution = 64;
    opt->max_iterations = 100;
    opt->ceres_max_iterations = 1000;
}

static void to_local(const dfl_implicit *s, const double x[3], double q[3])
{
    double d[3] = {x[0] - s->o[0], x[1] - s->o[1], x[2] - s->o[2]};
    for (int i = 0; i < 3; i++) q[i] = dfl_vec3_dot(s->Q + 3 * i, d);
}

static void vec_to_local(const dfl_implicit *s, const double v[3], double q[3])
{
    for (int i = 0; i < 3; i++) q[i] = dfl_vec3_dot(s->Q + 3 * i, v);
}

static void vec_to_world(const dfl_implicit *s, const double q[3], double v[3])
{
    for (int j = 0; j < 3; j++) v[j] = s->Q[j] * q[0] + s->Q[3 + j] * q[1] + s->Q[6 + j] * q[2];
}

static void to_world(const dfl_implicit *s, const double q[3], double x[3])
{
    vec_to_world(s, q, x);
    for (int j = 0; j < 3; j++) x[j] += s->o[j];
}

static double g_local(const dfl_implicit *s, const double q[3], double G[3], double H[9])
{
    if (H) return poly_eval(&s->g, q, 2, G, H, NULL);
    if (G) return poly_eval(&s->g, q, 1, G, NULL, NULL);
    return poly_eval(&s->g, q, 0, NULL, NULL, NULL);
}

double dfl_implicit_g(const dfl_implicit *s, const double x[3], double grad[3], double hess[9])
{
    double q[3], G[3], H[9];
    to_local(s, x, q);
    double g = poly_eval(&s->g, q, hess ? 2 : (grad ? 1 : 0), G, H, NULL);
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
    poly_eval(&s->g, q, 3, G, H, T);
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

static void bucket_of(const dfl_implicit *s, const double q[3], int c[3])
{
    for (int a = 0; a < 3; a++) {
        double f = floor((q[a] - s->blo[a]) / s->bcell);
        int i = f < 0.0 ? 0 : (f >= s->nb[a] ? s->nb[a] - 1 : (int)f);
        c[a] = i;
    }
}

static size_t bucket_index(const dfl_implicit *s, int i, int j, int k)
{
    return ((size_t)k * (size_t)s->nb[1] + (size_t)j) * (size_t)s->nb[0] + (size_t)i;
}

/* Projects q onto g = 0 along the gradient (Newton on g restricted to the
 * gradient line); 1 if it converged. */
static int project(const dfl_implicit *s, double q[3])
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

/* ---- starts -------------------------------------------------------------- */

typedef struct start_set {
    int n;
    size_t idx[DFL_IMPLICIT_MAX_STARTS];
    double dist[DFL_IMPLICIT_MAX_STARTS];
    double d0;                  /* distance of the nearest sample */
} start_set;

static double dist2_to(const double *a, const double *b)
{
    double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return dfl_vec3_dot(d, d);
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
            for (int j = c0[1] - r; j <= c0[1] + r; j++) {
                if (j < 0 || j >= s->nb[1]) continue;
                for (int i = c0[0] - r; i <= c0[0] + r; i++) {
                    if (i < 0 || i >= s->nb[0]) continue;
                    if (abs(i - c0[0]) < r && abs(j - c0[1]) < r && abs(k - c0[2]) < r) continue;
                    size_t b = bucket_index(s, i, j, k);
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
        double mm = 0.5 * (a + c), rr = hypot(0.5 * (a - c), b), th = 0.5 * atan2(2.0 * b, a - c);
        double lam[2] = {mm + rr, mm - rr};
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

/* ---- jets along a ray ------------------------------------------------------ */

dfl_status dfl_implicit_jet(const dfl_implicit *s, const dfl_footpoint *foot, const double x[3],
                            const double dir[3], int K, dfl_jet *out, dfl_err *err)
{
    if (K < 0 || K > DFL_JET_MAX)
        return dfl_err_set(err, DFL_E_INPUT, "jet order %d outside [0, %d]", K, DFL_JET_MAX);
    dfl_footpoint fp;
    if (!foot) {
        dfl_status st = dfl_implicit_footpoint(s, x, &fp, err);
        if (st != DFL_OK) return st;
        foot = &fp;
    }
    double q[3], dl[3], p[3];
    to_local(s, x, q);
    vec_to_local(s, dir, dl);
    to_local(s, foot->p, p);
    double G[3], H[9], J[16];
    int piv[4];
    g_local(s, p, G, H);
    double t = foot->t;
    foot_jacobian(G, H, t, J);
    if (!lu4(J, piv, 1e-13))
        return dfl_err_set(err, DFL_E_NUMERIC,
                           "implicit jet at (%g, %g, %g): singular footpoint system (focal point)",
                           x[0], x[1], x[2]);
    /* Unknowns P(s), T(s) with F = (P - q - s dl + T grad g(P), g(P)) = 0.
     * Frozen-Jacobian Newton: the error is O(s^k) after k steps. */
    ser P[3], T, GS[3], gs;
    memset(P, 0, sizeof P);
    memset(&T, 0, sizeof T);
    for (int a = 0; a < 3; a++) P[a].c[0] = p[a];
    T.c[0] = t;
    for (int it = 0; it < K; it++) {
        for (int a = 0; a < 3; a++) poly_eval_ser(&s->gd[a], P, K, &GS[a]);
        poly_eval_ser(&s->g, P, K, &gs);
        ser F[4];
        for (int a = 0; a < 3; a++) {
            ser tg;
            ser_mul(&T, &GS[a], K, &tg);
            for (int k = 0; k <= K; k++) {
                double xs = (k == 0 ? q[a] : (k == 1 ? dl[a] : 0.0));
                F[a].c[k] = P[a].c[k] - xs + tg.c[k];
            }
        }
        F[3] = gs;
        /* coefficient 0 is already solved; keep it to avoid drift */
        for (int k = 1; k <= K; k++) {
            double b[4] = {-F[0].c[k], -F[1].c[k], -F[2].c[k], -F[3].c[k]};
            lu4_solve(J, piv, b);
            for (int a = 0; a < 3; a++) P[a].c[k] += b[a];
            T.c[k] += b[3];
        }
    }
    /* d(s) = T(s) |grad g(P(s))|: x - p = t grad g and n = grad g / |grad g| */
    for (int a = 0; a < 3; a++) poly_eval_ser(&s->gd[a], P, K, &GS[a]);
    ser n2, tmp;
    memset(&n2, 0, sizeof n2);
    for (int a = 0; a < 3; a++) {
        ser_mul(&GS[a], &GS[a], K, &tmp);
        for (int k = 0; k <= K; k++) n2.c[k] += tmp.c[k];
    }
    if (!ser_sqrt(&n2, K, &tmp))
        return dfl_err_set(err, DFL_E_NUMERIC, "implicit jet: grad g vanishes at the footpoint");
    ser_mul(&T, &tmp, K, &tmp);
    /* the value itself is the footpoint's (sign of g), the rest the series' */
    tmp.c[0] = foot->d;
    dfl_jet_poly(tmp.c, K + 1, K, out);
    return DFL_OK;
}

dfl_status dfl_implicit_sdf_derivs(const dfl_implicit *s, const double x[3], dfl_sdf_derivs *out,
                                   dfl_err *err)
{
    dfl_status st = dfl_implicit_footpoint(s, x, &out->foot, err);
    if (st != DFL_OK) return st;
    out->d = out->foot.d;
    memcpy(out->g, out->foot.n, sizeof out->g);
    dfl_jet j;
    double D2[3];
    for (int i = 0; i < 3; i++) {
        double e[3] = {0, 0, 0};
        e[i] = 1.0;
        if ((st = dfl_implicit_jet(s, &out->foot, x, e, 2, &j, err)) != DFL_OK) return st;
        D2[i] = dfl_jet_deriv(&j, 2);
        out->H[4 * i] = D2[i];
    }
    /* D^2_{e_i + e_j} = H_ii + 2 H_ij + H_jj */
    for (int i = 0; i < 3; i++)
        for (int k = i + 1; k < 3; k++) {
            double e[3] = {0, 0, 0};
            e[i] = e[k] = 1.0;
            if ((st = dfl_implicit_jet(s, &out->foot, x, e, 2, &j, err)) != DFL_OK) return st;
            double hik = 0.5 * (dfl_jet_deriv(&j, 2) - D2[i] - D2[k]);
            out->H[3 * i + k] = out->H[3 * k + i] = hik;
        }
    static const double E[4][3] = {{1, 1, 1}, {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}};
    double acc = 0.0;
    for (int m = 0; m < 4; m++) {
        if ((st = dfl_implicit_jet(s, &out->foot, x, E[m], 3, &j, err)) != DFL_OK) return st;
        acc += E[m][0] * E[m][1] * E[m][2] * dfl_jet_deriv(&j, 3);
    }
    out->dxyz = acc / 24.0;
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
        poly_term(&s->g, m->c, m->e[0], m->e[1], m->e[2]);
    }
    for (int a = 0; a < 3; a++) poly_deriv(&s->g, a, &s->gd[a]);
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

/* Deterministic right-handed frame with w as third row. */
static void frame_rows(const double w[3], double Q[9])
{
    double t[3] = {0, 0, 0};
    int k = 0;
    for (int j = 1; j < 3; j++)
        if (fabs(w[j]) < fabs(w[k])) k = j;
    t[k] = 1.0;
    double tw = dfl_vec3_dot(t, w), u[3], v[3];
    for (int j = 0; j < 3; j++) u[j] = t[j] - tw * w[j];
    double un = sqrt(dfl_vec3_dot(u, u));
    for (int j = 0; j < 3; j++) u[j] /= un;
    dfl_vec3_cross(w, u, v);
    memcpy(Q, u, sizeof u);
    memcpy(Q + 3, v, sizeof v);
    memcpy(Q + 6, w, 3 * sizeof *w);
}

static int poly_to_terms(const poly *P, dfl_monomial *t)
{
    for (int k = 0; k < P->n; k++) {
        t[k].c = P->c[k];
        memcpy(t[k].e, P->e[k], sizeof t[k].e);
    }
    return P->n;
}

dfl_status dfl_implicit_torus(const double c[3], const double axis[3], double R, double r,
                              const dfl_implicit_options *opt, dfl_implicit **out, dfl_err *err)
{
    if (!(R > 0.0) || !(r > 0.0) || !(r < R) || !isfinite(R))
        return dfl_err_set(err, DFL_E_INPUT, "implicit torus: need 0 < minor < major, got %g, %g",
                           r, R);
    double an = sqrt(dfl_vec3_dot(axis, axis));
    if (!(an > 0.0) || !isfinite(an))
        return dfl_err_set(err, DFL_E_INPUT, "implicit torus: axis is the zero vector");
    double w[3] = {axis[0] / an, axis[1] / an, axis[2] / an}, Q[9];
    frame_rows(w, Q);
    /* (u^2 + v^2 + w^2 + R^2 - r^2)^2 - 4 R^2 (u^2 + v^2) */
    poly a, a2;
    memset(&a, 0, sizeof a);
    poly_term(&a, 1, 2, 0, 0);
    poly_term(&a, 1, 0, 2, 0);
    poly_term(&a, 1, 0, 0, 2);
    poly_term(&a, R * R - r * r, 0, 0, 0);
    poly_mul(&a, &a, &a2);
    poly_term(&a2, -4 * R * R, 2, 0, 0);
    poly_term(&a2, -4 * R * R, 0, 2, 0);
    dfl_monomial t[DFL_IMPLICIT_MAX_TERMS];
    int n = poly_to_terms(&a2, t);
    double m = 1.05 * (R + r), lo[3] = {-m, -m, -1.05 * r}, hi[3] = {m, m, 1.05 * r};
    return dfl_implicit_new(n, t, c, Q, lo, hi, opt, out, err);
}

dfl_status dfl_implicit_goursat(const double centre[3], double a, double b, double c,
                                const dfl_implicit_options *opt, dfl_implicit **out,
                                dfl_err *err)
{
    if (!(a > -1.0 / 3.0) || !isfinite(a) || !isfinite(b) || !isfinite(c))
        return dfl_err_set(err, DFL_E_INPUT, "implicit goursat: need a > -1/3, got %g", a);
    /* x^4 + y^4 + z^4 >= |q|^4 / 3, so g >= al rho^4 + b rho^2 + c with
     * al = 1/3 + a > 0: the zero set lies in rho^2 <= (-b + sqrt(b^2 - 4 al c)) / (2 al). */
    double al = 1.0 / 3.0 + a, disc = b * b - 4.0 * al * c;
    if (disc < 0.0 || (-b + sqrt(disc)) <= 0.0)
        return dfl_err_set(err, DFL_E_INPUT,
                           "implicit goursat: a = %g, b = %g, c = %g give an empty surface", a, b,
                           c);
    double rho = sqrt((-b + sqrt(disc)) / (2.0 * al)) * 1.02;
    poly r2, r4, g;
    memset(&r2, 0, sizeof r2);
    poly_term(&r2, 1, 2, 0, 0);
    poly_term(&r2, 1, 0, 2, 0);
    poly_term(&r2, 1, 0, 0, 2);
    poly_mul(&r2, &r2, &r4);
    memset(&g, 0, sizeof g);
    poly_term(&g, 1, 4, 0, 0);
    poly_term(&g, 1, 0, 4, 0);
    poly_term(&g, 1, 0, 0, 4);
    poly_axpy(a, &r4, &g);
    poly_axpy(b, &r2, &g);
    poly_term(&g, c, 0, 0, 0);
    dfl_monomial t[DFL_IMPLICIT_MAX_TERMS];
    int n = poly_to_terms(&g, t);
    double lo[3] = {-rho, -rho, -rho}, hi[3] = {rho, rho, rho};
    return dfl_implicit_new(n, t, centre, NULL, lo, hi, opt, out, err);
}

dfl_status dfl_implicit_genus2(const double centre[3], double eps, const dfl_implicit_options *opt,
                               dfl_implicit **out, dfl_err *err)
{
    if (!(eps > 0.0) || !(eps < 0.25))
        return dfl_err_set(err, DFL_E_INPUT, "implicit genus2: need 0 < eps < 1/4, got %g", eps);
    /* L = (x^2 + y^2)^2 - x^2 + y^2 */
    poly r2, L, L2;
    memset(&r2, 0, sizeof r2);
    poly_term(&r2, 1, 2, 0, 0);
    poly_term(&r2, 1, 0, 2, 0);
    poly_mul(&r2, &r2, &L);
    poly_term(&L, -1, 2, 0, 0);
    poly_term(&L, 1, 0, 2, 0);
    poly_mul(&L, &L, &L2);
    poly_term(&L2, 1, 0, 0, 2);
    poly_term(&L2, -eps * eps, 0, 0, 0);
    dfl_monomial t[DFL_IMPLICIT_MAX_TERMS];
    int n = poly_to_terms(&L2, t);
    /* |L| <= eps and L >= r^4 - r^2 give r^2 <= (1 + sqrt(1 + 4 eps)) / 2 */
    double rm = sqrt(0.5 * (1.0 + sqrt(1.0 + 4.0 * eps))) * 1.02;
    double lo[3] = {-rm, -rm, -1.05 * eps}, hi[3] = {rm, rm, 1.05 * eps};
    return dfl_implicit_new(n, t, centre, NULL, lo, hi, opt, out, err);
}

/* ---- as a shape ------------------------------------------------------------ */

static void implicit_eval(const void *impl, size_t m, const double *pts, double *val,
                          double *grad)
{
    const dfl_implicit *s = impl;
    for (size_t i = 0; i < m; i++) {
        dfl_footpoint f;
        if (dfl_implicit_footpoint(s, pts + 3 * i, &f, NULL) != DFL_OK) {
            val[i] = NAN;
            if (grad) grad[3 * i] = grad[3 * i + 1] = grad[3 * i + 2] = NAN;
            continue;
        }
        val[i] = f.d;
        if (grad) memcpy(grad + 3 * i, f.n, sizeof f.n);
    }
}

static dfl_status implicit_jet_op(const void *impl, const double *x, const double *dir, int K,
                                  dfl_jet *out, dfl_err *err)
{
    return dfl_implicit_jet(impl, NULL, x, dir, K, out, err);
}

static void implicit_free_op(void *impl) { dfl_implicit_free(impl); }

static const dfl_shape_ops implicit_ops = {"implicit", implicit_eval, implicit_jet_op,
                                           implicit_free_op};

dfl_status dfl_implicit_shape(dfl_implicit **s, dfl_shape *out, dfl_err *err)
{
    if (!s || !*s) return dfl_err_set(err, DFL_E_INPUT, "implicit shape: no surface");
    out->dim = 3;
    out->ops = &implicit_ops;
    out->impl = *s;
    *s = NULL;
    return DFL_OK;
}

const dfl_implicit *dfl_implicit_of_shape(const dfl_shape *shape)
{
    return (shape && shape->ops == &implicit_ops) ? shape->impl : NULL;
}
