#include "rfunc/join.h"

#include <assert.h>
#include <math.h>
#include <string.h>

#include "rfunc/trim.h"

DFL_NAMES_DEFINE(dfl_rfunc_join, DFL_RFUNC_JOIN_LIST, DFL_RFUNC_JOIN_COUNT, dfl_rfunc_join_names,
                 dfl_rfunc_join_name, dfl_rfunc_join_parse, "join")
DFL_NAMES_DEFINE(dfl_rfunc_correction, DFL_RFUNC_CORRECTION_LIST, DFL_RFUNC_CORRECTION_COUNT,
                 dfl_rfunc_correction_names, dfl_rfunc_correction_name,
                 dfl_rfunc_correction_parse, "correction")

dfl_status dfl_rfunc_join_check(dfl_rfunc_join join, int p, dfl_err *err)
{
    if ((int)join < 0 || (int)join >= DFL_RFUNC_JOIN_COUNT)
        return dfl_err_set(err, DFL_E_INPUT, "unknown join %d", (int)join);
    if (p < 1 || p > DFL_RFUNC_P_MAX)
        return dfl_err_set(err, DFL_E_INPUT, "join order p = %d outside [1, %d]", p,
                           DFL_RFUNC_P_MAX);
    if (join == DFL_RFUNC_RCONJ && p < 2)
        return dfl_err_set(err, DFL_E_INPUT,
                           "R-conjunction needs p >= 2: for p = 1, a + b - (a + b) is"
                           " identically 0 on non-negative fields");
    return DFL_OK;
}

double dfl_rfunc_ipow(double x, int p)
{
    assert(p >= 0);
    double r = 1.0;
    while (p > 0) {
        if (p & 1) r *= x;
        x *= x;
        p >>= 1;
    }
    return r;
}

/* y^(-1/p) for y > 0; the common orders without pow(). */
static double inv_root(double y, int p)
{
    switch (p) {
    case 1: return 1.0 / y;
    case 2: return 1.0 / sqrt(y);
    default: return pow(y, -1.0 / p);
    }
}

void dfl_rfunc_requiv_partials_polar(double phi, int p, double *F1, double *F2)
{
    const double c = cos(phi), s = sin(phi);
    const double den = pow(pow(c, p) + pow(s, p), (p + 1.0) / p);
    *F1 = pow(s, p + 1) / den;
    *F2 = pow(c, p + 1) / den;
}

double dfl_rfunc_requiv2(double h1, double h2, int p, double *F1, double *F2)
{
    assert(h1 >= 0.0 && h2 >= 0.0);
    if (h1 == 0.0 || h2 == 0.0) {
        if (F1) *F1 = h2 == 0.0 ? 0.0 : 1.0;
        if (F2) *F2 = h1 == 0.0 ? 0.0 : 1.0;
        return 0.0;
    }
    const double m = fmin(h1, h2);
    const double r1 = m / h1, r2 = m / h2;
    const double w = inv_root(dfl_rfunc_ipow(r1, p) + dfl_rfunc_ipow(r2, p), p);
    if (F1) *F1 = dfl_rfunc_ipow(r1 * w, p + 1);
    if (F2) *F2 = dfl_rfunc_ipow(r2 * w, p + 1);
    return m * w;
}

double dfl_rfunc_rconj2(double a, double b, int p, double *Fa, double *Fb)
{
    assert(a >= 0.0 && b >= 0.0 && p >= 2);
    if (a == 0.0 || b == 0.0) {
        /* 0 ^ b = 0 for all b >= 0; the partials are the one-sided limits. */
        if (Fa) *Fa = b == 0.0 ? 0.0 : 1.0;
        if (Fb) *Fb = a == 0.0 ? 0.0 : 1.0;
        return 0.0;
    }
    const int a_hi = a >= b;
    const double hi = a_hi ? a : b, lo = a_hi ? b : a;
    const double r = lo / hi;
    /* w - 1 = (1 + r^p)^(1/p) - 1 = expm1(log1p(r^p) / p): no cancellation in
     * F = lo - hi (w - 1) when r^p is tiny. */
    const double wm1 = expm1(log1p(dfl_rfunc_ipow(r, p)) / p);
    const double F = lo - hi * wm1;
    if (Fa || Fb) {
        /* dF/da = 1 - (a / N)^(p-1), N = hi w: 1 - w^(1-p) for hi, 1 - (r/w)^(p-1)
         * for lo.  Absolute accuracy ~ p eps is what a gradient needs. */
        const double iw = 1.0 / (1.0 + wm1);
        const double d_hi = 1.0 - dfl_rfunc_ipow(iw, p - 1);
        const double d_lo = 1.0 - dfl_rfunc_ipow(r * iw, p - 1);
        if (Fa) *Fa = a_hi ? d_hi : d_lo;
        if (Fb) *Fb = a_hi ? d_lo : d_hi;
    }
    return F;
}

/* ---- accumulator ------------------------------------------------------ */

void dfl_rfunc_acc_begin(dfl_rfunc_acc *acc, dfl_rfunc_join join, int p, int dim, int grad)
{
    assert(dim >= 1 && dim <= 3);
    assert(p >= 1 && p <= DFL_RFUNC_P_MAX && (join != DFL_RFUNC_RCONJ || p >= 2));
    memset(acc, 0, sizeof *acc);
    acc->join = join;
    acc->p = p;
    acc->dim = dim;
    acc->grad = grad;
}

void dfl_rfunc_acc_set_correction(dfl_rfunc_acc *acc, dfl_rfunc_correction corr)
{
    assert(acc->nh == 0);
    acc->corr = corr;
}

int dfl_rfunc_acc_is_zero(const dfl_rfunc_acc *acc) { return acc->zero; }

/* Brings the running sums to the smaller scale mnew < m. */
static void rescale(dfl_rfunc_acc *acc, double mnew)
{
    const double r = mnew / acc->m;
    const double rp = dfl_rfunc_ipow(r, acc->p), rp1 = rp * r;
    acc->S *= rp;
    acc->Sq *= rp;
    if (acc->grad)
        for (int j = 0; j < acc->dim; j++) {
            acc->V[j] *= rp1;
            acc->Vq[j] *= rp1;
        }
    acc->m = mnew;
}

static void add_scaled(dfl_rfunc_acc *acc, double x, const double *gx, double *S, double *V)
{
    if (acc->m == 0.0)
        acc->m = x;
    else if (x < acc->m)
        rescale(acc, x);
    const double r = acc->m / x;
    const double rp = dfl_rfunc_ipow(r, acc->p);
    *S += rp;
    if (acc->grad)
        for (int j = 0; j < acc->dim; j++) V[j] += rp * r * gx[j];
}

void dfl_rfunc_acc_add(dfl_rfunc_acc *acc, double h, const double *gh)
{
    assert(!(h < 0.0));
    assert(!acc->grad || gh);
    if (acc->zero) return;
    if (!(h > 0.0)) {
        acc->zero = 1;
        acc->nh++;
        return;
    }
    if (acc->join == DFL_RFUNC_RCONJ) {
        if (acc->nh == 0) {
            acc->u = h;
            if (acc->grad) memcpy(acc->gu, gh, (size_t)acc->dim * sizeof *gh);
        } else {
            double Fa, Fb;
            acc->u = dfl_rfunc_rconj2(acc->u, h, acc->p, &Fa, &Fb);
            if (acc->grad)
                for (int j = 0; j < acc->dim; j++) acc->gu[j] = Fa * acc->gu[j] + Fb * gh[j];
            /* a ^ b > 0 for a, b > 0 in exact arithmetic; an underflow to 0
             * still means "on the zero set" to the caller. */
            if (!(acc->u > 0.0)) acc->zero = 1;
        }
        acc->nh++;
        return;
    }
    if (acc->nh == 0 || h < acc->hmin) {
        acc->hmin = h;
        if (acc->grad) memcpy(acc->ghmin, gh, (size_t)acc->dim * sizeof *gh);
    }
    acc->nh++;
    add_scaled(acc, h, gh, &acc->S, acc->V);
}

void dfl_rfunc_acc_add_q(dfl_rfunc_acc *acc, double q, const double *gq)
{
    assert(acc->join == DFL_RFUNC_REQUIV_CORRECTED);
    assert(!acc->grad || gq);
    if (acc->zero) return;
    if (!(q > 0.0)) {
        acc->qzero = 1;
        return;
    }
    add_scaled(acc, q, gq, &acc->Sq, acc->Vq);
}

double dfl_rfunc_acc_end(const dfl_rfunc_acc *acc, double *gu)
{
    assert(acc->nh >= 1);
    const int dim = acc->dim;
    if (acc->zero) {
        if (gu && acc->grad) memset(gu, 0, (size_t)dim * sizeof *gu);
        return 0.0;
    }
    if (acc->join == DFL_RFUNC_RCONJ) {
        if (gu && acc->grad) memcpy(gu, acc->gu, (size_t)dim * sizeof *gu);
        return acc->u;
    }
    const int p = acc->p;
    if (acc->join == DFL_RFUNC_REQUIV_CORRECTED && acc->corr == DFL_RFUNC_CORR_EQ20) {
        /* bs04's formula as printed: undefined (NaN) where the radicand is
         * not positive, including q_v = 0 off the parts (q^-p = inf). */
        const double S = acc->S - acc->Sq;
        if (acc->qzero || !(S > 0.0)) {
            if (gu && acc->grad)
                for (int j = 0; j < dim; j++) gu[j] = NAN;
            return NAN;
        }
        const double w = inv_root(S, p);
        if (gu && acc->grad) {
            const double wp1 = dfl_rfunc_ipow(w, p + 1);
            for (int j = 0; j < dim; j++) gu[j] = wp1 * (acc->V[j] - acc->Vq[j]);
        }
        return acc->m * w;
    }
    if (acc->join == DFL_RFUNC_REQUIV_CORRECTED) {
        const double S = acc->S - acc->Sq;
        const double floor = dfl_rfunc_ipow(acc->m / (2.0 * acc->hmin), p);
        if (acc->qzero || !(S > floor)) {
            if (gu && acc->grad)
                for (int j = 0; j < dim; j++) gu[j] = 2.0 * acc->ghmin[j];
            return 2.0 * acc->hmin;
        }
        const double w = inv_root(S, p);
        if (gu && acc->grad) {
            const double wp1 = dfl_rfunc_ipow(w, p + 1);
            for (int j = 0; j < dim; j++) gu[j] = wp1 * (acc->V[j] - acc->Vq[j]);
        }
        return acc->m * w;
    }
    /* u = m S^(-1/p); grad u = sum (u/h_i)^(p+1) grad h_i = (u/m)^(p+1) V. */
    const double w = inv_root(acc->S, p);
    if (gu && acc->grad) {
        const double wp1 = dfl_rfunc_ipow(w, p + 1);
        for (int j = 0; j < dim; j++) gu[j] = wp1 * acc->V[j];
    }
    return acc->m * w;
}

double dfl_rfunc_guard(int dim, double q, const double *gq, double hi, const double *ghi,
                       double hj, const double *ghj, double *g)
{
    const double *gm = gq;
    double m = q;
    if (hi > m) {
        m = hi;
        gm = ghi;
    }
    if (hj > m) {
        m = hj;
        gm = ghj;
    }
    if (g) memcpy(g, gm, (size_t)dim * sizeof *g);
    return m;
}

/* ---- jets -------------------------------------------------------------- */

/* Sign of a - b for small s > 0. */
static int jet_cmp(const dfl_jet *a, const dfl_jet *b)
{
    dfl_jet d;
    dfl_jet_sub(a, b, &d);
    return dfl_rfunc_jet_sign(&d);
}

void dfl_rfunc_guard_jet(const dfl_jet *q, const dfl_jet *hi, const dfl_jet *hj, dfl_jet *out)
{
    const dfl_jet *m = q;
    if (jet_cmp(hi, m) > 0) m = hi;
    if (jet_cmp(hj, m) > 0) m = hj;
    *out = *m;
}

/* acc += sign * (x / c)^(-p).  A term whose leading coefficient would
 * underflow is dropped: a non-dominant one (lower valuation) contributes
 * below e^-700 relative at every order, and so does a dominant one (same
 * valuation) with ratio^-p < e^-700 beside the term of ratio 1 (a far
 * part next to a near one, e.g. far along a ray at large coordinates). */
static dfl_status add_inv_pow(dfl_jet *acc, const dfl_jet *x, double c, int p, double sign,
                              dfl_err *err)
{
    const double ratio = x->c[0] / c;
    if (p * log(ratio) > 700.0) return DFL_OK;
    dfl_jet t;
    dfl_status st;
    dfl_jet_scale(x, 1.0 / c, &t);
    if ((st = dfl_jet_powi(&t, -p, &t, err)) != DFL_OK) return st;
    if (sign < 0.0) dfl_jet_neg(&t, &t);
    dfl_jet_add(acc, &t, acc);
    return DFL_OK;
}

static dfl_status rconj2_jet(const dfl_jet *a, const dfl_jet *b, int p, dfl_jet *out,
                             dfl_err *err)
{
    if (a->zero || b->zero) {
        *out = a->zero ? *a : *b;
        return DFL_OK;
    }
    /* lo - hi ((1 + (lo/hi)^p)^(1/p) - 1): the bracket starts at the order
     * of (lo/hi)^p, with exact zeros below (Miller's recurrence keeps them),
     * so lo's order-(p-1) normalization survives without residue. */
    const dfl_jet *lo = a, *hi = b;
    if (jet_cmp(a, b) > 0) {
        lo = b;
        hi = a;
    }
    dfl_jet x, w;
    dfl_status st;
    if ((st = dfl_jet_div(lo, hi, &x, err)) != DFL_OK) return st;
    if (p * log(fabs(x.c[0])) < -700.0) {
        /* (lo/hi)^p underflows: the bracket is below e^-700 relative to lo
         * at every order, a ^ b = lo (a far part beside a near one). */
        *out = *lo;
        return DFL_OK;
    }
    if ((st = dfl_jet_powi(&x, p, &x, err)) != DFL_OK) return st;
    dfl_jet_add_const(&x, 1.0, &x);
    if ((st = dfl_jet_pow(&x, 1.0 / p, &w, err)) != DFL_OK) return st;
    dfl_jet_add_const(&w, -1.0, &w);
    dfl_jet_trim(&w, 0.0, &w);
    dfl_jet_mul(hi, &w, &w);
    dfl_jet_sub(lo, &w, out);
    return DFL_OK;
}

dfl_status dfl_rfunc_join_jet(dfl_rfunc_join join, int p, size_t n, const dfl_jet *h,
                              size_t nq, const dfl_jet *q, dfl_jet *out, dfl_err *err)
{
    return dfl_rfunc_join_jet_corr(join, DFL_RFUNC_CORR_GUARDED, p, n, h, nq, q, out, err);
}

/* The undefined value of eq. 20 as a jet: NaN coefficients to the parts'
 * absolute precision. */
static void nan_jet(const dfl_jet *h, dfl_jet *out)
{
    int P = h->v + h->n;
    if (P < 1) P = 1;
    if (P > DFL_JET_MAX + 1) P = DFL_JET_MAX + 1;
    memset(out, 0, sizeof *out);
    out->v = 0;
    out->n = P;
    for (int k = 0; k < P; k++) out->c[k] = NAN;
}

dfl_status dfl_rfunc_join_jet_corr(dfl_rfunc_join join, dfl_rfunc_correction corr, int p,
                                   size_t n, const dfl_jet *h, size_t nq, const dfl_jet *q,
                                   dfl_jet *out, dfl_err *err)
{
    dfl_status st = dfl_rfunc_join_check(join, p, err);
    if (st != DFL_OK) return st;
    if (n == 0) return dfl_err_set(err, DFL_E_INTERNAL, "join of no parts");
    for (size_t i = 0; i < n; i++)
        if (h[i].zero) {
            /* The ray runs inside part i: u vanishes to h_i's precision. */
            *out = h[i];
            return DFL_OK;
        }
    if (join == DFL_RFUNC_RCONJ) {
        dfl_jet u = h[0];
        for (size_t i = 1; i < n; i++)
            if ((st = rconj2_jet(&u, &h[i], p, &u, err)) != DFL_OK) return st;
        *out = u;
        return DFL_OK;
    }
    if (join != DFL_RFUNC_REQUIV_CORRECTED) nq = 0;
    int qzero = 0;
    for (size_t i = 0; i < nq; i++) qzero |= q[i].zero;
    /* Scale: the smallest leading coefficient among the jets of largest
     * valuation (they dominate as s -> 0+), so that every dominant
     * (x/c)^(-p) has a leading coefficient <= 1 and nothing overflows. */
    int vmax = h[0].v;
    double c = INFINITY;
    for (int pass = 0; pass < 2; pass++)
        for (size_t i = 0; i < n + nq; i++) {
            const dfl_jet *x = i < n ? &h[i] : &q[i - n];
            if (x->zero) continue;
            if (pass == 0 && x->v > vmax) vmax = x->v;
            if (pass == 1 && x->v == vmax && x->c[0] < c) c = x->c[0];
        }
    /* Non-finite leading coefficients come from coordinates beyond the
     * fields' domain (rfield.h); the callers reject those, this is the
     * last line of defence (a status, not an abort). */
    if (!(isfinite(c) && c > 0.0))
        return dfl_err_set(err, DFL_E_NUMERIC,
                           "join jet: part coefficients are not finite (coordinates too large)");
    const int eq20 = join == DFL_RFUNC_REQUIV_CORRECTED && corr == DFL_RFUNC_CORR_EQ20;
    dfl_jet S;
    dfl_rfunc_jet_zero(&S);
    for (size_t i = 0; i < n; i++)
        if ((st = add_inv_pow(&S, &h[i], c, p, 1.0, err)) != DFL_OK) return st;
    if (join == DFL_RFUNC_REQUIV_CORRECTED) {
        for (size_t i = 0; i < nq; i++)
            if (!q[i].zero && (st = add_inv_pow(&S, &q[i], c, p, -1.0, err)) != DFL_OK)
                return st;
        if (eq20) {
            if (qzero || S.zero || !(S.c[0] > 0.0)) {
                nan_jet(&h[0], out);
                return DFL_OK;
            }
            goto root;
        }
        /* Floor (2 h_min)^(-p), compared with S as s -> 0+. */
        const dfl_jet *hmin = &h[0];
        for (size_t i = 1; i < n; i++)
            if (jet_cmp(&h[i], hmin) < 0) hmin = &h[i];
        dfl_jet fl;
        dfl_jet_scale(hmin, 2.0 / c, &fl);
        if ((st = dfl_jet_powi(&fl, -p, &fl, err)) != DFL_OK) return st;
        if (qzero || jet_cmp(&S, &fl) <= 0) S = fl;
    }
root:
    if (S.zero || !(S.c[0] > 0.0))
        return dfl_err_set(err, DFL_E_NUMERIC, "R-equivalence jet: sum of h^-p is not positive");
    if ((st = dfl_jet_pow(&S, -1.0 / p, out, err)) != DFL_OK) return st;
    dfl_jet_scale(out, c, out);
    return DFL_OK;
}
