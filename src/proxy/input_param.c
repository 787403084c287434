/* Parametric proxy inputs: grid starts and Kallay's geometric Newton (see
 * proxy/input_param.h). */
#include "proxy/input_param.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/vec.h"

enum { P_SPHERE, P_TORUS, P_CONE, P_SURFACE };
#define NSTART 3 /* most starts (dfl_param_input_opts.starts) */
#define GRID_MAX 512 /* most nodes per row (dfl_param_input_opts.grid) */
#define NODE_TABLE_MAX (1 << 16) /* most nodes (all patches) with a start table */

typedef struct patch {
    int type;
    double c[3], e1[3], e2[3], w[3];   /* analytic: centre (cone: a) and frame */
    double R, r, len, ra, rb;          /* torus R, r (sphere R = 0); cone */
    const dfl_surface *s;              /* P_SURFACE */
    double u0, u1, v0, v1;
    int per_u, per_v;                  /* periodic in u, v */
} patch;

/* A grid node as Newton's start: (u, v) after clamp_uv, its bound flags
 * and patch_eval there. */
typedef struct node {
    double u, v, D[18];
    int bu, bv;
} node;

typedef struct param_ctx {
    int npatch, grid, max_iter, closed, starts, prune;
    patch *pt;
    double *samp;        /* npatch * grid * grid points */
    double *rowbox;      /* per (patch, row j): lo[3], hi[3] of its grid nodes */
    node *node;          /* per (patch, row j, node i) when prune and small, else NULL */
    double scale;
    dfl_surface_set set; /* owned patches (P_SURFACE) */
} param_ctx;

void dfl_param_input_opts_default(dfl_param_input_opts *o)
{
    o->grid = 16;
    o->max_iter = 60;
    o->starts = 3;
    o->prune = 1;
}

/* S, Su, Sv, Suu, Suv, Svv at (u, v) into D[18]. */
static void patch_eval(const patch *P, double u, double v, double D[18])
{
    if (P->type == P_SURFACE) {
        dfl_surface_eval(P->s, u, v, 2, D);
        return;
    }
    double cu = cos(u), su = sin(u), rho[3], phi[3];
    for (int j = 0; j < 3; j++) {
        rho[j] = cu * P->e1[j] + su * P->e2[j];
        phi[j] = -su * P->e1[j] + cu * P->e2[j];
    }
    if (P->type == P_CONE) {
        double rad = P->ra + v * (P->rb - P->ra), dr = P->rb - P->ra;
        for (int j = 0; j < 3; j++) {
            D[j] = P->c[j] + v * P->len * P->w[j] + rad * rho[j];
            D[3 + j] = rad * phi[j];
            D[6 + j] = P->len * P->w[j] + dr * rho[j];
            D[9 + j] = -rad * rho[j];
            D[12 + j] = dr * phi[j];
            D[15 + j] = 0.0;
        }
        return;
    }
    double cv = cos(v), sv = sin(v), rad = P->R + P->r * cv;
    for (int j = 0; j < 3; j++) {
        D[j] = P->c[j] + rad * rho[j] + P->r * sv * P->w[j];
        D[3 + j] = rad * phi[j];
        D[6 + j] = -P->r * sv * rho[j] + P->r * cv * P->w[j];
        D[9 + j] = -rad * rho[j];
        D[12 + j] = -P->r * sv * phi[j];
        D[15 + j] = -P->r * cv * rho[j] - P->r * sv * P->w[j];
    }
}

static double grid_u(const param_ctx *c, const patch *P, int i)
{
    return P->per_u ? P->u0 + (P->u1 - P->u0) * i / c->grid
                    : P->u0 + (P->u1 - P->u0) * i / (c->grid - 1);
}

static double grid_v(const param_ctx *c, const patch *P, int j)
{
    return P->per_v ? P->v0 + (P->v1 - P->v0) * j / c->grid
                    : P->v0 + (P->v1 - P->v0) * j / (c->grid - 1);
}

static double dist2(const double *a, const double *b)
{
    double s = 0;
    for (int j = 0; j < 3; j++) s += (a[j] - b[j]) * (a[j] - b[j]);
    return s;
}

typedef struct start {
    int patch, i, j;
    double d2;
} start;

/* A lower bound of dist2(x, s) over the nodes s of row (p, j), in floating
 * point too: per axis the gap to the box is no larger in magnitude than
 * x - s (rounding is monotone), squares and the same left-to-right sum are
 * monotone, so the bound never exceeds a node's computed dist2.  NaN
 * (x not finite): no pruning follows, as every comparison is false. */
static double row_bound(const param_ctx *c, int p, int j, const double x[3])
{
    const double *b = c->rowbox + 6 * ((size_t)p * c->grid + j);
    double s = 0;
    for (int a = 0; a < 3; a++) {
        double g = x[a] < b[a] ? x[a] - b[a] : x[a] > b[3 + a] ? x[a] - b[3 + a] : 0.0;
        s += g * g;
    }
    return s;
}

/* dist2(x, node) of the G nodes of row (p, j), in dist2's operations
 * (one row at a time, so that the loop vectorizes; same bits). */
static void row_dist2(const param_ctx *c, int p, int j, const double x[3], double *rd)
{
    const int G = c->grid;
    const double *s = c->samp + 3 * ((size_t)(p * G + j) * G);
    const double x0 = x[0], x1 = x[1], x2 = x[2];
#pragma omp simd
    for (int i = 0; i < G; i++) {
        const double a = x0 - s[3 * i], b = x1 - s[3 * i + 1], e = x2 - s[3 * i + 2];
        rd[i] = 0.0 + a * a + b * b + e * e;
    }
}

/* The c->starts nearest grid nodes, pairwise at least two grid steps apart
 * (or on different patches); returns their count. */
static int find_starts(const param_ctx *c, const double x[3], start *st)
{
    int n = 0;
    const int G = c->grid;
    for (int p = 0; p < c->npatch; p++)
        for (int j = 0; j < G; j++) {
            /* every node of the row would take the `continue` below */
            if (c->prune && n == c->starts && row_bound(c, p, j, x) >= st[n - 1].d2) continue;
            double rd[GRID_MAX];
            row_dist2(c, p, j, x, rd);
            for (int i = 0; i < G; i++) {
                double d2 = rd[i];
                if (n == c->starts && d2 >= st[n - 1].d2) continue;
                int near = -1;
                for (int k = 0; k < n; k++) {
                    int di = abs(st[k].i - i);
                    int dj = abs(st[k].j - j);
                    if (c->pt[p].per_u && G - di < di) di = G - di;
                    if (c->pt[p].per_v && G - dj < dj) dj = G - dj;
                    if (st[k].patch == p && di < 2 && dj < 2) { near = k; break; }
                }
                if (near >= 0 && d2 >= st[near].d2) continue;
                int k = near >= 0 ? near : (n < c->starts ? n++ : n - 1);
                st[k] = (start){p, i, j, d2};
                while (k > 0 && st[k].d2 < st[k - 1].d2) {
                    start t = st[k];
                    st[k] = st[k - 1];
                    st[k - 1] = t;
                    k--;
                }
            }
        }
    return n;
}

typedef struct foot {
    double u, v, f, D[18];
    int ok, bound;   /* stationarity met; footpoint on a domain bound */
} foot;

static void clamp_uv(const patch *P, double *u, double *v, int *bu, int *bv)
{
    *bu = *bv = 0;
    if (P->per_u) {
        double per = P->u1 - P->u0;
        *u = P->u0 + (*u - P->u0) - per * floor((*u - P->u0) / per);
    } else if (*u <= P->u0) { *u = P->u0; *bu = -1; }
    else if (*u >= P->u1) { *u = P->u1; *bu = 1; }
    if (P->per_v) {
        double per = P->v1 - P->v0;
        *v = P->v0 + (*v - P->v0) - per * floor((*v - P->v0) / per);
    } else if (*v <= P->v0) { *v = P->v0; *bv = -1; }
    else if (*v >= P->v1) { *v = P->v1; *bv = 1; }
}

/* |tangential part of S - x| / parameter speed, the stationarity measure. */
static double tangential(const double D[18], const double x[3])
{
    double r[3] = {D[0] - x[0], D[1] - x[1], D[2] - x[2]};
    double E = dfl_vec3_dot(D + 3, D + 3), G = dfl_vec3_dot(D + 6, D + 6);
    double gu = dfl_vec3_dot(D + 3, r), gv = dfl_vec3_dot(D + 6, r);
    return (E > 0 ? gu * gu / E : 0) + (G > 0 ? gv * gv / G : 0);
}

/* Rounding of f = |S - x|^2 / 2: |r| times the rounding of the coordinates
 * (of size scale) plus f's own. */
static double f_noise(const param_ctx *c, double f)
{
    return 8 * DBL_EPSILON * (sqrt(2 * f) * c->scale + f);
}

/* Geometric Newton from (u, v); see the header for the method. */
/* Newton's start at node (i, j) of patch p: (u, v) clamped, its bound
 * flags and S's derivatives, from the node table when there is one. */
static void node_start(const param_ctx *c, int p, int i, int j, double *u, double *v, int *bu,
                       int *bv, double D[18])
{
    if (c->node) {
        const node *nd = c->node + ((size_t)p * c->grid + j) * c->grid + i;
        *u = nd->u;
        *v = nd->v;
        *bu = nd->bu;
        *bv = nd->bv;
        memcpy(D, nd->D, sizeof nd->D);
        return;
    }
    const patch *P = &c->pt[p];
    *u = grid_u(c, P, i);
    *v = grid_v(c, P, j);
    clamp_uv(P, u, v, bu, bv);
    patch_eval(P, *u, *v, D);
}

static void newton(const param_ctx *c, int p, int i0, int j0, const double x[3], foot *o)
{
    const patch *P = &c->pt[p];
    double D[18], r[3], u, v;
    int bu, bv;
    node_start(c, p, i0, j0, &u, &v, &bu, &bv, D);
    double f = 0.5 * dist2(D, x);
    o->ok = 0;
    for (int it = 0; it < c->max_iter; it++) {
        for (int j = 0; j < 3; j++) r[j] = D[j] - x[j];
        const double *Su = D + 3, *Sv = D + 6;
        double gu = dfl_vec3_dot(Su, r), gv = dfl_vec3_dot(Sv, r);
        double E = dfl_vec3_dot(Su, Su), F = dfl_vec3_dot(Su, Sv), G = dfl_vec3_dot(Sv, Sv);
        /* active set: a bound the gradient pushes against holds its parameter */
        int fu = !(bu < 0 && gu > 0) && !(bu > 0 && gu < 0);
        int fv = !(bv < 0 && gv > 0) && !(bv > 0 && gv < 0);
        double gn = (fu ? gu * gu / (E > 0 ? E : 1) : 0) + (fv ? gv * gv / (G > 0 ? G : 1) : 0);
        if (sqrt(gn) <= 1e-13 * c->scale) { o->ok = 1; break; }
        double Huu = E + dfl_vec3_dot(D + 9, r), Huv = F + dfl_vec3_dot(D + 12, r);
        double Hvv = G + dfl_vec3_dot(D + 15, r);
        double du = 0, dv = 0;
        if (fu && fv) {
            double det = Huu * Hvv - Huv * Huv;
            if (!(Huu > 0 && det > 1e-14 * (Huu * Hvv + 1e-300))) {
                Huu = E; Huv = F; Hvv = G; /* Kallay's tangent-plane step */
                det = E * G - F * F;
            }
            if (!(det > 0)) break;
            du = -(Hvv * gu - Huv * gv) / det;
            dv = -(Huu * gv - Huv * gu) / det;
        } else if (fu) {
            du = -gu / (Huu > 0 ? Huu : E);
        } else if (fv) {
            dv = -gv / (Hvv > 0 ? Hvv : G);
        } else {
            o->ok = 1;  /* a corner both gradients push into */
            break;
        }
        if (!isfinite(du) || !isfinite(dv)) break;
        double lam = 1.0, un, vn, Dn[18], fn = f;
        int bun, bvn, acc = 0;
        for (int h = 0; h < 40; h++, lam *= 0.5) {
            un = u + lam * du;
            vn = v + lam * dv;
            clamp_uv(P, &un, &vn, &bun, &bvn);
            patch_eval(P, un, vn, Dn);
            fn = 0.5 * dist2(Dn, x);
            /* near the footpoint f changes by O(error^2), below its own
             * rounding: there a step that keeps f within rounding and
             * shrinks the tangential residual is progress too */
            if (fn < f || (fn <= f + f_noise(c, f) && tangential(Dn, x) < tangential(D, x))) {
                acc = 1;
                break;
            }
        }
        if (!acc) { o->ok = 1; break; } /* f at its rounding floor */
        double moved = fabs(un - u) * sqrt(E) + fabs(vn - v) * sqrt(G);
        u = un; v = vn; bu = bun; bv = bvn; f = fn;
        memcpy(D, Dn, sizeof D);
        if (moved <= 1e-15 * c->scale) { o->ok = 1; break; }
    }
    o->u = u;
    o->v = v;
    o->f = f;
    o->bound = bu != 0 || bv != 0;
    memcpy(o->D, D, sizeof D);
}

/* Each patch's nearest node, for patches the NSTART nearest nodes missed
 * (a chart's dense pole region can crowd out the chart that is regular
 * there); appended to st (capacity NSTART + MAXEXTRA). */
#define MAXEXTRA 8
static int add_patch_starts(const param_ctx *c, const double x[3], start *st, int n)
{
    const int G = c->grid;
    for (int p = 0; p < c->npatch && n < NSTART + MAXEXTRA; p++) {
        int have = 0;
        for (int k = 0; k < n; k++) have |= st[k].patch == p;
        if (have) continue;
        start b = {p, 0, 0, HUGE_VAL};
        for (int j = 0; j < G; j++) {
            if (c->prune && row_bound(c, p, j, x) >= b.d2) continue; /* no node beats b */
            double rd[GRID_MAX];
            row_dist2(c, p, j, x, rd);
            for (int i = 0; i < G; i++)
                if (rd[i] < b.d2) b = (start){p, i, j, rd[i]};
        }
        st[n++] = b;
    }
    return n;
}

static void point_query(const param_ctx *c, const double x[3], int need_curv, dfl_surfpoint *o)
{
    start st[NSTART + MAXEXTRA];
    int ns = find_starts(c, x, st);
    if (c->npatch > 1) ns = add_patch_starts(c, x, st, ns);
    foot best = {0}, cur;
    int have = 0;
    for (int k = 0; k < ns; k++) {
        newton(c, st[k].patch, st[k].i, st[k].j, x, &cur);
        /* within f's rounding the smaller stationarity residual wins */
        if (!have || cur.f < best.f - f_noise(c, best.f) ||
            (cur.f <= best.f + f_noise(c, best.f) && tangential(cur.D, x) < tangential(best.D, x))) {
            best = cur;
            have = 1;
        }
    }
    const double *D = best.D;
    double n0[3], u[3] = {x[0] - D[0], x[1] - D[1], x[2] - D[2]};
    dfl_vec3_cross(D + 3, D + 6, n0);
    double nl = dfl_vec3_norm(n0), ul = dfl_vec3_norm(u);
    memcpy(o->p, D, 3 * sizeof *D);
    o->certified = best.ok && nl > 1e-12 * c->scale * c->scale;
    if (c->closed) {
        for (int j = 0; j < 3; j++) o->n[j] = n0[j] / nl;
        o->d = dfl_vec3_dot(u, o->n);
    } else {
        o->d = ul;
        if (best.bound && ul > 0) {
            for (int j = 0; j < 3; j++) o->n[j] = u[j] / ul;
        } else {
            double s = dfl_vec3_dot(u, n0) < 0 ? -1.0 : 1.0;
            for (int j = 0; j < 3; j++) o->n[j] = s * n0[j] / nl;
        }
    }
    if (!(nl > 0)) {
        /* singular point (pole, apex): the normal from the offset */
        for (int j = 0; j < 3; j++) o->n[j] = ul > 0 ? u[j] / ul : NAN;
        o->d = ul;
    }
    if (!need_curv || dfl_curvature_parametric(D + 3, D + 6, D + 9, D + 12, D + 15, o->n,
                                               &o->curv, NULL) != DFL_OK)
        dfl_curvature_set_nan(&o->curv);
}

static dfl_status param_query(const void *vctx, size_t m, const double *x, int need_curv,
                              dfl_surfpoint *out, dfl_err *err)
{
    (void)err;
    for (size_t i = 0; i < m; i++) point_query(vctx, x + 3 * i, need_curv, out + i);
    return DFL_OK;
}

static void param_destroy(void *vctx)
{
    param_ctx *c = vctx;
    free(c->pt);
    free(c->samp);
    free(c->rowbox);
    free(c->node);
    dfl_surface_set_free(&c->set);
    free(c);
}

/* Fills samples and scale; installs the input.  Frees c on failure. */
static dfl_status finish(param_ctx *c, const dfl_param_input_opts *opt, dfl_proxy_input *out,
                         dfl_err *err)
{
    dfl_param_input_opts d;
    dfl_param_input_opts_default(&d);
    if (opt) d = *opt;
    if (d.grid < 4 || d.grid > GRID_MAX || d.max_iter < 1 || d.starts < 1 || d.starts > NSTART) {
        param_destroy(c);
        return dfl_err_set(err, DFL_E_INPUT,
                           "parametric input: grid %d (4..512), max_iter %d (>= 1), starts %d (1..%d)",
                           d.grid, d.max_iter, d.starts, NSTART);
    }
    c->starts = d.starts;
    c->grid = d.grid;
    c->max_iter = d.max_iter;
    c->prune = d.prune != 0;
    size_t G = (size_t)d.grid;
    if (!(c->samp = malloc((size_t)c->npatch * G * G * 3 * sizeof *c->samp)) ||
        !(c->rowbox = malloc((size_t)c->npatch * G * 6 * sizeof *c->rowbox))) {
        param_destroy(c);
        return dfl_err_set(err, DFL_E_NOMEM, "parametric input: out of memory");
    }
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (int p = 0; p < c->npatch; p++)
        for (size_t j = 0; j < G; j++)
            for (size_t i = 0; i < G; i++) {
                double D[18], *s = c->samp + 3 * ((p * G + j) * G + i);
                patch_eval(&c->pt[p], grid_u(c, &c->pt[p], (int)i), grid_v(c, &c->pt[p], (int)j),
                           D);
                memcpy(s, D, 3 * sizeof *s);
                double *rb = c->rowbox + 6 * (p * G + j);
                for (int a = 0; a < 3; a++) {
                    lo[a] = fmin(lo[a], s[a]);
                    hi[a] = fmax(hi[a], s[a]);
                    rb[a] = i == 0 ? s[a] : fmin(rb[a], s[a]);
                    rb[3 + a] = i == 0 ? s[a] : fmax(rb[3 + a], s[a]);
                }
            }
    c->scale = 1.0 + sqrt(dist2(lo, hi));
    /* the starts' evaluations, once per node instead of per query (the
     * same calls, so the same bits); not for huge tables */
    if (c->prune && (size_t)c->npatch * G * G <= NODE_TABLE_MAX &&
        (c->node = malloc((size_t)c->npatch * G * G * sizeof *c->node)))
        for (int p = 0; p < c->npatch; p++)
            for (size_t j = 0; j < G; j++)
                for (size_t i = 0; i < G; i++) {
                    node *nd = c->node + (p * G + j) * G + i;
                    const patch *P = &c->pt[p];
                    nd->u = grid_u(c, P, (int)i);
                    nd->v = grid_v(c, P, (int)j);
                    clamp_uv(P, &nd->u, &nd->v, &nd->bu, &nd->bv);
                    patch_eval(P, nd->u, nd->v, nd->D);
                }
    out->name = "parametric";
    out->query = param_query;
    out->destroy = param_destroy;
    out->ctx = c;
    out->has_inside = c->closed;
    return DFL_OK;
}

static param_ctx *new_ctx(int npatch, dfl_err *err)
{
    param_ctx *c = calloc(1, sizeof *c);
    if (c && !(c->pt = calloc((size_t)npatch, sizeof *c->pt))) {
        free(c);
        c = NULL;
    }
    if (!c) dfl_err_set(err, DFL_E_NOMEM, "parametric input: out of memory");
    else c->npatch = npatch;
    return c;
}

static int unit_frame(const double *axis, patch *P)
{
    double l = axis ? dfl_vec3_norm(axis) : 0;
    if (!(l > 0) || !isfinite(l)) return 0;
    for (int j = 0; j < 3; j++) P->w[j] = axis[j] / l;
    dfl_vec3_tangent_basis(P->w, P->e1, P->e2);
    return 1;
}

dfl_status dfl_proxy_input_param_torus(const double c[3], const double axis[3], double R,
                                       double r, const dfl_param_input_opts *opt,
                                       dfl_proxy_input *out, dfl_err *err)
{
    if (!(r > 0) || !(R > r) || !isfinite(R))
        return dfl_err_set(err, DFL_E_INPUT, "parametric torus: need 0 < minor < major");
    param_ctx *x = new_ctx(1, err);
    if (!x) return DFL_E_NOMEM;
    patch *P = x->pt;
    if (!unit_frame(axis, P)) {
        param_destroy(x);
        return dfl_err_set(err, DFL_E_INPUT, "parametric torus: zero axis");
    }
    P->type = P_TORUS;
    memcpy(P->c, c, sizeof P->c);
    P->R = R;
    P->r = r;
    P->u0 = 0; P->u1 = 2 * DFL_PI; P->per_u = 1;
    P->v0 = 0; P->v1 = 2 * DFL_PI; P->per_v = 1;
    x->closed = 1;
    return finish(x, opt, out, err);
}

dfl_status dfl_proxy_input_param_sphere(const double c[3], double r,
                                        const dfl_param_input_opts *opt, dfl_proxy_input *out,
                                        dfl_err *err)
{
    if (!(r > 0) || !isfinite(r))
        return dfl_err_set(err, DFL_E_INPUT, "parametric sphere: need radius > 0");
    /* two charts, polar axes z and x: each covers the other's poles, where
     * S_u vanishes and Newton stalls; the better footpoint of the two wins */
    param_ctx *x = new_ctx(2, err);
    if (!x) return DFL_E_NOMEM;
    for (int k = 0; k < 2; k++) {
        patch *P = &x->pt[k];
        const double w[2][3] = {{0, 0, 1}, {1, 0, 0}};
        unit_frame(w[k], P);
        P->type = P_SPHERE;
        memcpy(P->c, c, sizeof P->c);
        P->R = 0;
        P->r = r;
        P->u0 = 0; P->u1 = 2 * DFL_PI; P->per_u = 1;
        P->v0 = -0.5 * DFL_PI; P->v1 = 0.5 * DFL_PI;
    }
    x->closed = 1;
    return finish(x, opt, out, err);
}

dfl_status dfl_proxy_input_param_cone(const double a[3], const double b[3], double ra, double rb,
                                      const dfl_param_input_opts *opt, dfl_proxy_input *out,
                                      dfl_err *err)
{
    double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    if (!(ra >= 0) || !(rb >= 0) || !(ra + rb > 0) || !(dfl_vec3_norm(ab) > 0))
        return dfl_err_set(err, DFL_E_INPUT, "parametric cone: need ra, rb >= 0, not both 0, a != b");
    param_ctx *x = new_ctx(1, err);
    if (!x) return DFL_E_NOMEM;
    patch *P = x->pt;
    unit_frame(ab, P);
    P->type = P_CONE;
    memcpy(P->c, a, sizeof P->c);
    P->len = dfl_vec3_norm(ab);
    P->ra = ra;
    P->rb = rb;
    P->u0 = 0; P->u1 = 2 * DFL_PI; P->per_u = 1;
    P->v0 = 0; P->v1 = 1;
    x->closed = 0;
    return finish(x, opt, out, err);
}

dfl_status dfl_proxy_input_param_surfaces(dfl_surface_set *set, const dfl_param_input_opts *opt,
                                          dfl_proxy_input *out, dfl_err *err)
{
    if (!set || set->npatch == 0) {
        if (set) dfl_surface_set_free(set);
        return dfl_err_set(err, DFL_E_INPUT, "parametric input: no patches");
    }
    param_ctx *x = new_ctx((int)set->npatch, err);
    if (!x) {
        dfl_surface_set_free(set);
        return DFL_E_NOMEM;
    }
    x->set = *set;
    memset(set, 0, sizeof *set);
    for (int p = 0; p < x->npatch; p++) {
        patch *P = &x->pt[p];
        const dfl_surface *s = &x->set.patch[p];
        P->type = P_SURFACE;
        P->s = s;
        P->u0 = s->u0; P->u1 = s->u1; P->v0 = s->v0; P->v1 = s->v1;
    }
    x->closed = 0;
    return finish(x, opt, out, err);
}
