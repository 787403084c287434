#include "rfunc/normalize.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Workspace layout.  Graded storage makes truncation a prefix, so one
 * buffer serves any degree up to its capacity. */
typedef struct layout {
    int N[DFL_RFUNC_NORM_MAX + 1]; /* N[k]: degree to which fk is needed */
    int D;                         /* degree of f's expansion */
    dfl_mt P0, G[3], den, tmp, rs, f1, nu[3];
    dfl_mt nupow[3][DFL_RFUNC_NORM_MAX + 1];
    dfl_mt f1pow[2], prod, prod2, T, term, cur, next, da, db;
} layout;

static size_t take(dfl_mt *mt, int dim, int deg, double *work, size_t at)
{
    mt->dim = dim;
    mt->deg = deg;
    mt->c = work ? work + at : NULL;
    return at + dfl_mt_size(dim, deg);
}

static size_t plan(int dim, int m, int nout, double *work, layout *L)
{
    L->N[m] = nout;
    for (int k = m; k >= 2; k--) L->N[k - 1] = L->N[k] + k;
    const int N1 = L->N[1], N2 = m >= 2 ? L->N[2] : 0;
    L->D = N1 + 1;
    size_t at = 0;
    at = take(&L->P0, dim, L->D, work, at);
    for (int i = 0; i < dim; i++) at = take(&L->G[i], dim, N1, work, at);
    at = take(&L->den, dim, N1, work, at);
    at = take(&L->tmp, dim, N1, work, at);
    at = take(&L->rs, dim, N1, work, at);
    at = take(&L->f1, dim, N1, work, at);
    at = take(&L->cur, dim, N1, work, at);
    at = take(&L->next, dim, N1, work, at);
    at = take(&L->da, dim, N1, work, at);
    at = take(&L->db, dim, N1, work, at);
    if (m >= 2) {
        for (int i = 0; i < dim; i++) {
            at = take(&L->nu[i], dim, N2, work, at);
            for (int k = 0; k <= m; k++) at = take(&L->nupow[i][k], dim, N2, work, at);
        }
        at = take(&L->f1pow[0], dim, N2, work, at);
        at = take(&L->f1pow[1], dim, N2, work, at);
        at = take(&L->prod, dim, N2, work, at);
        at = take(&L->prod2, dim, N2, work, at);
        at = take(&L->T, dim, N2, work, at);
        at = take(&L->term, dim, N2, work, at);
    }
    return at;
}

size_t dfl_rfunc_normalize_work(int dim, int m, int nout)
{
    assert(m >= 1 && m <= DFL_RFUNC_NORM_MAX && nout >= 0);
    layout L;
    return plan(dim, m, nout, NULL, &L);
}

/* A view of mt truncated to degree deg (a prefix). */
static dfl_mt view(const dfl_mt *mt, int deg)
{
    assert(deg <= mt->deg);
    dfl_mt v = *mt;
    v.deg = deg;
    return v;
}

dfl_status dfl_rfunc_normalize_at(dfl_rfunc_taylor_fn src, const void *ctx, int m,
                                  const double *x, dfl_mt *out, double *work, dfl_err *err)
{
    if (m < 1 || m > DFL_RFUNC_NORM_MAX)
        return dfl_err_set(err, DFL_E_INPUT, "normalization order %d outside [1, %d]", m,
                           DFL_RFUNC_NORM_MAX);
    const int dim = out->dim;
    layout L;
    plan(dim, m, out->deg, work, &L);
    const int N1 = L.N[1];
    dfl_status st = src(ctx, x, &L.P0, err);
    if (st != DFL_OK) return st;

    /* A.1: f1 = f (f^2 + |grad f|^2)^(-1/2). */
    dfl_mt P0v = view(&L.P0, N1);
    for (int i = 0; i < dim; i++) dfl_mt_deriv(&L.P0, i, &L.G[i]);
    dfl_mt_mul(&P0v, &P0v, &L.den);
    for (int i = 0; i < dim; i++) {
        dfl_mt_mul(&L.G[i], &L.G[i], &L.tmp);
        dfl_mt_axpy(&L.den, 1.0, &L.tmp, &L.den);
    }
    if ((st = dfl_mt_pow(&L.den, -0.5, &L.rs, err)) != DFL_OK) return st;
    dfl_mt_mul(&P0v, &L.rs, &L.f1);
    if (m == 1) {
        dfl_mt_copy(&L.f1, out);
        return DFL_OK;
    }

    /* nu = grad f / |grad f| and its powers, to degree N2. */
    const int N2 = L.N[2];
    dfl_mt gsq = view(&L.tmp, N2), ginv = view(&L.rs, N2), t2 = view(&L.den, N2);
    dfl_mt_const(0.0, &gsq);
    for (int i = 0; i < dim; i++) {
        dfl_mt Gi = view(&L.G[i], N2);
        dfl_mt_mul(&Gi, &Gi, &t2);
        dfl_mt_axpy(&gsq, 1.0, &t2, &gsq);
    }
    if (!(gsq.c[0] > 0.0))
        return dfl_err_set(err, DFL_E_NUMERIC,
                           "recursive normalization: grad f vanishes at the point (normal"
                           " direction undefined)");
    if ((st = dfl_mt_pow(&gsq, -0.5, &ginv, err)) != DFL_OK) return st;
    for (int i = 0; i < dim; i++) {
        dfl_mt Gi = view(&L.G[i], N2);
        dfl_mt_mul(&Gi, &ginv, &L.nu[i]);
        dfl_mt_const(1.0, &L.nupow[i][0]);
        for (int k = 1; k <= m; k++) dfl_mt_mul(&L.nupow[i][k - 1], &L.nu[i], &L.nupow[i][k]);
    }

    /* A.4 for k = 2..m:  fk = f(k-1) - f1^k sum_{|a|=k} nu^a d^a f(k-1) / a!  */
    dfl_mt_copy(&L.f1, &L.cur);
    dfl_mt *cur = &L.cur, *next = &L.next;
    int fp = 0; /* f1pow[fp] holds f1^(k-1) */
    dfl_mt_copy(&L.f1, &L.f1pow[0]);
    for (int k = 2; k <= m; k++) {
        const int Nk = L.N[k], Nkm1 = L.N[k - 1];
        dfl_mt T = view(&L.T, Nk), term = view(&L.term, Nk), prod = view(&L.prod, Nk);
        dfl_mt_const(0.0, &T);
        int a[3] = {0, 0, 0};
        /* all exponent vectors of total degree k */
        for (a[0] = k; a[0] >= 0; a[0]--)
            for (a[1] = k - a[0]; a[1] >= 0; a[1]--) {
                a[2] = k - a[0] - a[1];
                if (dim == 2 && a[2] != 0) continue;
                /* d^a f(k-1), degree Nkm1 - k = Nk */
                const dfl_mt *src_d = cur;
                dfl_mt bufs[2] = {L.da, L.db};
                int which = 0, deg = Nkm1;
                for (int v = 0; v < dim; v++)
                    for (int r = 0; r < a[v]; r++) {
                        dfl_mt o = view(&bufs[which], deg - 1);
                        dfl_mt_deriv(src_d, v, &o);
                        bufs[which] = o;
                        src_d = &bufs[which];
                        which ^= 1;
                        deg--;
                    }
                assert(deg == Nk);
                /* nu^a */
                dfl_mt p0 = view(&L.nupow[0][a[0]], Nk), p1 = view(&L.nupow[1][a[1]], Nk);
                if (dim == 2) {
                    dfl_mt_mul(&p0, &p1, &prod);
                } else {
                    dfl_mt p2 = view(&L.nupow[2][a[2]], Nk), pp = view(&L.prod2, Nk);
                    dfl_mt_mul(&p0, &p1, &pp);
                    dfl_mt_mul(&pp, &p2, &prod);
                }
                dfl_mt_mul(&prod, src_d, &term);
                double afact = 1.0;
                for (int v = 0; v < dim; v++)
                    for (int r = 2; r <= a[v]; r++) afact *= r;
                dfl_mt_axpy(&T, 1.0 / afact, &term, &T);
            }
        /* f1^k to degree Nk */
        /* f1pow[fp] is known to degree N(k-1) >= Nk (N2 at k = 2). */
        dfl_mt fprev = view(&L.f1pow[fp], Nk), fk = view(&L.f1pow[fp ^ 1], Nk);
        dfl_mt f1v = view(&L.f1, Nk);
        dfl_mt_mul(&fprev, &f1v, &fk);
        fp ^= 1;
        dfl_mt_mul(&fk, &T, &term);
        dfl_mt nx = view(next, Nk);
        dfl_mt_axpy(cur, -1.0, &term, &nx);
        *next = nx;
        dfl_mt *sw = cur;
        cur = next;
        next = sw;
        next->deg = L.N[1];
    }
    dfl_mt_copy(cur, out);
    return DFL_OK;
}

/* ---- polynomial source ------------------------------------------------- */

dfl_status dfl_rfunc_poly_init(int dim, int nterms, const double *coef, const int *exps,
                               dfl_rfunc_poly *out, dfl_err *err)
{
    if (dim != 2 && dim != 3)
        return dfl_err_set(err, DFL_E_INPUT, "polynomial: dimension %d (expected 2 or 3)", dim);
    if (nterms < 1) return dfl_err_set(err, DFL_E_INPUT, "polynomial: no terms");
    for (int t = 0; t < nterms; t++) {
        if (!isfinite(coef[t]))
            return dfl_err_set(err, DFL_E_INPUT, "polynomial: non-finite coefficient");
        for (int i = 0; i < dim; i++)
            if (exps[t * dim + i] < 0)
                return dfl_err_set(err, DFL_E_INPUT, "polynomial: negative exponent");
    }
    dfl_rfunc_poly p;
    p.dim = dim;
    p.nterms = nterms;
    p.coef = malloc((size_t)nterms * sizeof *p.coef);
    p.exps = malloc((size_t)nterms * dim * sizeof *p.exps);
    if (!p.coef || !p.exps) {
        free(p.coef);
        free(p.exps);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    }
    memcpy(p.coef, coef, (size_t)nterms * sizeof *p.coef);
    memcpy(p.exps, exps, (size_t)nterms * dim * sizeof *p.exps);
    *out = p;
    return DFL_OK;
}

dfl_status dfl_rfunc_poly_ellipse(double a, double b, dfl_rfunc_poly *out, dfl_err *err)
{
    if (!(a > 0.0) || !(b > 0.0) || !isfinite(a) || !isfinite(b))
        return dfl_err_set(err, DFL_E_INPUT, "ellipse: semi-axes must be > 0 (got %g, %g)", a, b);
    const double coef[3] = {1.0 / (a * a), 1.0 / (b * b), -1.0};
    const int exps[6] = {2, 0, 0, 2, 0, 0};
    return dfl_rfunc_poly_init(2, 3, coef, exps, out, err);
}

void dfl_rfunc_poly_free(dfl_rfunc_poly *p)
{
    if (!p) return;
    free(p->coef);
    free(p->exps);
    memset(p, 0, sizeof *p);
}

dfl_status dfl_rfunc_poly_taylor(const void *ctx, const double *x, dfl_mt *out, dfl_err *err)
{
    (void)err;
    const dfl_rfunc_poly *p = ctx;
    assert(p->dim == out->dim);
    dfl_mt_poly_expand(p->nterms, p->coef, p->exps, x, out);
    return DFL_OK;
}

/* ---- field --------------------------------------------------------------- */

typedef struct nfield {
    dfl_rfunc_poly poly;
    int m;
} nfield;

static void nfield_eval(const void *ctx, size_t npts, const double *pts, double *val, double *grad)
{
    const nfield *f = ctx;
    const int dim = f->poly.dim;
    /* One workspace per batch: the per-point work is ~1e5 flops, an
     * allocation per call is noise; eval must not share scratch across
     * threads, so it cannot live in ctx. */
    const size_t nw = dfl_rfunc_normalize_work(dim, f->m, 1);
    double *work = malloc((nw + dfl_mt_size(dim, 1)) * sizeof *work);
    for (size_t i = 0; i < npts; i++) {
        const double *x = pts + i * (size_t)dim;
        double *g = grad ? grad + i * (size_t)dim : NULL;
        if (!work) { /* out of memory: no way to report from eval */
            val[i] = NAN;
            if (g)
                for (int j = 0; j < dim; j++) g[j] = NAN;
            continue;
        }
        dfl_mt out = {dim, 1, work + nw};
        dfl_status st = dfl_rfunc_normalize_at(dfl_rfunc_poly_taylor, &f->poly, f->m, x, &out,
                                               work, NULL);
        if (st == DFL_OK) {
            val[i] = out.c[0];
            if (g)
                for (int j = 0; j < dim; j++) g[j] = out.c[1 + j];
            continue;
        }
        /* grad f = 0: fm undefined; return f1 (documented), gradient 0. */
        st = dfl_rfunc_normalize_at(dfl_rfunc_poly_taylor, &f->poly, 1, x, &out, work, NULL);
        val[i] = st == DFL_OK ? out.c[0] : 0.0;
        if (g)
            for (int j = 0; j < dim; j++) g[j] = 0.0;
    }
    free(work);
}

static dfl_status nfield_jet(const void *ctx, const double *x, const double *dir, int K,
                             dfl_jet *out, dfl_err *err)
{
    const nfield *f = ctx;
    const int dim = f->poly.dim;
    const size_t nw = dfl_rfunc_normalize_work(dim, f->m, K);
    double *work = malloc((nw + dfl_mt_size(dim, K)) * sizeof *work);
    if (!work) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    dfl_mt res = {dim, K, work + nw};
    dfl_status st = dfl_rfunc_normalize_at(dfl_rfunc_poly_taylor, &f->poly, f->m, x, &res, work, err);
    if (st == DFL_OK) dfl_mt_ray(&res, dir, K, out);
    free(work);
    return st;
}

static void nfield_destroy(void *ctx)
{
    nfield *f = ctx;
    dfl_rfunc_poly_free(&f->poly);
    free(f);
}

static const dfl_field_ops nfield_ops = {"rfunc_normalized", nfield_eval, nfield_jet,
                                         nfield_destroy, NULL};

dfl_status dfl_rfunc_normalized_field(const dfl_rfunc_poly *poly, int m, dfl_field *out,
                                      dfl_err *err)
{
    if (m < 1 || m > DFL_RFUNC_NORM_MAX)
        return dfl_err_set(err, DFL_E_INPUT, "normalization order %d outside [1, %d]", m,
                           DFL_RFUNC_NORM_MAX);
    nfield *f = calloc(1, sizeof *f);
    if (!f) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    dfl_status st = dfl_rfunc_poly_init(poly->dim, poly->nterms, poly->coef, poly->exps, &f->poly, err);
    if (st != DFL_OK) {
        free(f);
        return st;
    }
    f->m = m;
    out->dim = poly->dim;
    out->ops = &nfield_ops;
    out->ctx = f;
    return DFL_OK;
}
