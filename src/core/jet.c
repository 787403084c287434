/* Truncated Taylor arithmetic with a valuation.
 *
 * Every operation builds its result in a local dfl_jet and copies it out at
 * the end: that is what makes aliasing (out == a or out == b) safe without
 * special cases, and costs one 200-byte copy.
 *
 * Powers and square roots work on the normalized series g = c / c[0]
 * (g[0] = 1) and multiply by c[0]^e afterwards, so the valuation never enters
 * the recurrences: s^v * c0 * g(s) raised to e is s^(v e) * c0^e * g(s)^e,
 * which is why h^(-p), sqrt of s^2 (...) and (s^(-p) (...))^(-1/p) lose
 * neither precision nor order.
 */
#include "core/jet.h"

#include <assert.h>
#include <limits.h>
#include <math.h>
#include <string.h>

#define NMAX (DFL_JET_MAX + 1)
/* Valuations beyond this are nonsense for a Taylor jet of 25 terms; the bound
 * keeps v + n, v_a + v_b and P * e far away from int overflow. */
#define VAL_LIMIT (1 << 20)

static int imin(int a, int b) { return a < b ? a : b; }

/* The header promises clamping (see dfl_jet_check_order for rejection). */
static int clamp_order(int K)
{
    if (K < 0) return 0;
    if (K > DFL_JET_MAX) return DFL_JET_MAX;
    return K;
}

static void check(const dfl_jet *a)
{
    (void)a;
    assert(a);
    assert(a->n >= 1 && a->n <= NMAX);
    assert(a->zero == 0 || a->zero == 1);
    assert(a->zero ? a->c[0] == 0.0 : a->c[0] != 0.0);
}

static int is_exact_zero(const dfl_jet *a)
{
    return a->zero && a->v == 0 && a->n == NMAX;
}

/* Absolute precision: coefficients of s^k, k < prec, are known. */
static int prec(const dfl_jet *a) { return a->v + a->n; }

/* Zero known below s^P.  P >= NMAX is the exact zero: a zero jet that is
 * known to all 25 stored orders cannot be told apart from it anyway. */
static void set_zero(long long P, dfl_jet *out)
{
    memset(out->c, 0, sizeof out->c);
    out->zero = 1;
    if (P >= NMAX) {
        out->v = 0;
        out->n = NMAX;
        return;
    }
    if (P < -VAL_LIMIT) P = -VAL_LIMIT;
    out->v = P >= 1 ? 0 : (int)P - 1;
    out->n = (int)P - out->v;
    assert(out->n >= 1 && out->n <= NMAX);
}

/* Removes leading coefficients with |c| <= thresh (thresh = 0 removes exact
 * zeros only), keeping the absolute precision.  Also the guard for c[0]
 * underflowing to 0 in products. */
static void strip(dfl_jet *r, double thresh)
{
    int k = 0;
    while (k < r->n && fabs(r->c[k]) <= thresh) k++;
    if (k == r->n) {
        set_zero((long long)r->v + r->n, r);
        return;
    }
    if (k > 0) {
        memmove(r->c, r->c + k, (size_t)(r->n - k) * sizeof r->c[0]);
        memset(r->c + (r->n - k), 0, (size_t)k * sizeof r->c[0]);
        r->v += k;
        r->n -= k;
    }
    r->zero = 0;
}

static void blank(dfl_jet *r)
{
    memset(r, 0, sizeof *r);
}

/* Absolute coefficient of s^idx, 0 outside the stored range.  Callers only
 * ask below the operand's precision. */
static double at(const dfl_jet *a, int idx)
{
    if (a->zero || idx < a->v || idx >= a->v + a->n) return 0.0;
    return a->c[idx - a->v];
}

/* ---------------------------------------------------------------- build */

dfl_status dfl_jet_check_order(int K, dfl_err *err)
{
    if (K < 0 || K > DFL_JET_MAX)
        return dfl_err_set(err, DFL_E_INPUT, "jet order %d outside [0, %d]", K, DFL_JET_MAX);
    return DFL_OK;
}

dfl_status dfl_jet_dir_call(dfl_dir_jet_fn jet, const void *ctx, const char *what,
                            const char *name, const double *x, const double *dir, int K,
                            dfl_jet *out, dfl_err *err)
{
    if (!jet)
        return dfl_err_set(err, DFL_E_INPUT, "%s '%s' has no exact derivatives (jets)", what,
                           name);
    const dfl_status st = dfl_jet_check_order(K, err);
    if (st != DFL_OK) return st;
    return jet(ctx, x, dir, K, out, err);
}

void dfl_jet_zero(dfl_jet *out)
{
    set_zero(NMAX, out);
}

void dfl_jet_const(double a, int K, dfl_jet *out)
{
    dfl_jet_poly(&a, 1, K, out);
}

void dfl_jet_linear(double a0, double a1, int K, dfl_jet *out)
{
    const double a[2] = {a0, a1};
    dfl_jet_poly(a, 2, K, out);
}

void dfl_jet_poly(const double *a, int m, int K, dfl_jet *out)
{
    assert(m >= 0 && (m == 0 || a));
    K = clamp_order(K);
    int top = imin(m, K + 1); /* terms a[0..top-1] lie within order K */
    int k0 = 0;
    while (k0 < top && a[k0] == 0.0) k0++;
    dfl_jet r;
    if (k0 == top) {
        set_zero((long long)K + 1, &r);
        *out = r;
        return;
    }
    blank(&r);
    r.v = k0;
    r.n = K + 1 - k0;
    for (int k = k0; k < top; k++) r.c[k - k0] = a[k];
    r.zero = 0;
    check(&r);
    *out = r;
}

/* ------------------------------------------------------------ add, scale */

/* a + sb * b where Pa, Pb are the operands' absolute precisions (INT_MAX for
 * an exactly known operand). */
static void add_core(const dfl_jet *a, int Pa, const dfl_jet *b, int Pb, double sb,
                     dfl_jet *out)
{
    dfl_jet r;
    if (a->zero && b->zero) {
        set_zero(imin(Pa, Pb), &r);
        *out = r;
        return;
    }
    /* Zero operands have no coefficients to place; their v is irrelevant. */
    int vlo = a->zero ? b->v : b->zero ? a->v : imin(a->v, b->v);
    int P = imin(imin(Pa, Pb), vlo + NMAX);
    if (P <= vlo) { /* the non-zero operand starts beyond what is known */
        set_zero(P, &r);
        *out = r;
        return;
    }
    blank(&r);
    r.v = vlo;
    r.n = P - vlo;
    for (int k = 0; k < r.n; k++) r.c[k] = at(a, vlo + k) + sb * at(b, vlo + k);
    strip(&r, 0.0);
    check(&r);
    *out = r;
}

static int add_prec(const dfl_jet *a)
{
    return is_exact_zero(a) ? INT_MAX : prec(a);
}

void dfl_jet_add(const dfl_jet *a, const dfl_jet *b, dfl_jet *out)
{
    check(a);
    check(b);
    add_core(a, add_prec(a), b, add_prec(b), 1.0, out);
}

void dfl_jet_sub(const dfl_jet *a, const dfl_jet *b, dfl_jet *out)
{
    check(a);
    check(b);
    add_core(a, add_prec(a), b, add_prec(b), -1.0, out);
}

void dfl_jet_add_const(const dfl_jet *a, double k, dfl_jet *out)
{
    check(a);
    if (k == 0.0) {
        *out = *a;
        return;
    }
    dfl_jet t;
    set_zero(NMAX, &t);
    t.c[0] = k;
    t.zero = 0;
    add_core(a, add_prec(a), &t, INT_MAX, 1.0, out);
}

void dfl_jet_scale(const dfl_jet *a, double k, dfl_jet *out)
{
    check(a);
    dfl_jet r = *a;
    if (k == 0.0) {
        set_zero(NMAX, &r);
    } else if (!r.zero) {
        for (int i = 0; i < r.n; i++) r.c[i] *= k;
        strip(&r, 0.0); /* k tiny: c[0] may underflow */
    }
    *out = r;
}

void dfl_jet_neg(const dfl_jet *a, dfl_jet *out)
{
    dfl_jet_scale(a, -1.0, out);
}

void dfl_jet_abs(const dfl_jet *a, dfl_jet *out)
{
    check(a);
    if (!a->zero && a->c[0] < 0.0)
        dfl_jet_scale(a, -1.0, out);
    else
        *out = *a;
}

/* ---------------------------------------------------------- mul and div */

void dfl_jet_mul(const dfl_jet *a, const dfl_jet *b, dfl_jet *out)
{
    check(a);
    check(b);
    dfl_jet r;
    if (is_exact_zero(a) || is_exact_zero(b)) {
        set_zero(NMAX, &r);
    } else if (a->zero || b->zero) {
        /* O(s^Pa) * s^vb (...) = O(s^(Pa + vb)); both zero: O(s^(Pa + Pb)). */
        long long P = (long long)(a->zero ? prec(a) : a->v) + (b->zero ? prec(b) : b->v);
        set_zero(P, &r);
    } else {
        blank(&r);
        r.v = a->v + b->v;
        r.n = imin(a->n, b->n);
        for (int k = 0; k < r.n; k++) {
            double s = 0.0;
            for (int j = 0; j <= k; j++) s += a->c[j] * b->c[k - j];
            r.c[k] = s;
        }
        strip(&r, 0.0);
    }
    check(&r);
    *out = r;
}

dfl_status dfl_jet_div(const dfl_jet *a, const dfl_jet *b, dfl_jet *out, dfl_err *err)
{
    check(a);
    check(b);
    if (b->zero)
        return dfl_err_set(err, DFL_E_NUMERIC,
                           "jet division: divisor is zero (to order %d)", prec(b) - 1);
    dfl_jet r;
    if (is_exact_zero(a)) {
        set_zero(NMAX, &r);
    } else if (a->zero) {
        set_zero((long long)prec(a) - b->v, &r);
    } else {
        /* q * b = a, coefficient of s^k: sum_{j<=k} b_j q_{k-j} = a_k. */
        blank(&r);
        r.v = a->v - b->v;
        r.n = imin(a->n, b->n);
        const double inv = 1.0 / b->c[0];
        for (int k = 0; k < r.n; k++) {
            double s = a->c[k];
            for (int j = 1; j <= k; j++) s -= b->c[j] * r.c[k - j];
            r.c[k] = s * inv;
        }
        strip(&r, 0.0);
    }
    check(&r);
    *out = r;
    return DFL_OK;
}

dfl_status dfl_jet_recip(const dfl_jet *a, dfl_jet *out, dfl_err *err)
{
    dfl_jet one;
    set_zero(NMAX, &one);
    one.c[0] = 1.0;
    one.zero = 0;
    return dfl_jet_div(&one, a, out, err);
}

/* ------------------------------------------------------------- powers */

/* f = g^e for g[0] = 1, n terms (J. C. P. Miller's recurrence).  From
 * g f' = e g' f, the coefficient of s^(k-1) reads
 *   sum_{j=0..k} (k-j) g_j f_{k-j} = e sum_{j=0..k} j g_j f_{k-j},
 * hence  k f_k = sum_{j=1..k} ((e+1) j - k) g_j f_{k-j}.
 * Zeros g_1 = .. = g_{p-1} = 0 give f_1 = .. = f_{p-1} = 0 exactly, which is
 * what makes the R-equivalence orders come out exact. */
static void miller(const double *g, int n, double e, double *f)
{
    assert(g[0] == 1.0);
    f[0] = 1.0;
    for (int k = 1; k < n; k++) {
        double s = 0.0;
        for (int j = 1; j <= k; j++) s += ((e + 1.0) * j - k) * g[j] * f[k - j];
        f[k] = s / k;
    }
}

/* s^v c0 g(s) -> s^vout c0^e g^e, with c0pow = c0^e computed by the caller
 * (so that powi can raise a negative c0). */
static dfl_status power_core(const dfl_jet *a, double e, int vout, double c0pow,
                             dfl_jet *out, dfl_err *err)
{
    if (!isfinite(c0pow) || c0pow == 0.0)
        return dfl_err_set(err, DFL_E_NUMERIC,
                           "jet power: leading coefficient %g to the power %g is not a"
                           " finite non-zero number",
                           a->c[0], e);
    double g[NMAX];
    const double inv = 1.0 / a->c[0];
    g[0] = 1.0;
    for (int k = 1; k < a->n; k++) g[k] = a->c[k] * inv;
    dfl_jet r;
    blank(&r);
    r.v = vout;
    r.n = a->n;
    miller(g, a->n, e, r.c);
    for (int k = 0; k < r.n; k++) r.c[k] *= c0pow;
    strip(&r, 0.0);
    check(&r);
    *out = r;
    return DFL_OK;
}

static void const_one(int n, dfl_jet *out)
{
    dfl_jet r;
    blank(&r);
    r.n = n;
    r.c[0] = 1.0;
    *out = r;
}

/* A zero jet to the power e != 0 (fn names the caller in the message).
 * O(s^P)^e = O(s^(P e)): the coefficients below s^ceil(P e) vanish; for an
 * integer e (powi) P e is an exact integer in double, so ceil keeps it. */
static dfl_status zero_power(const dfl_jet *a, double e, const char *fn, dfl_jet *out,
                             dfl_err *err)
{
    if (e < 0.0)
        return dfl_err_set(err, DFL_E_NUMERIC,
                           "jet %s: zero jet (to order %d) to the negative power %g", fn,
                           prec(a) - 1, e);
    dfl_jet r;
    set_zero(is_exact_zero(a) ? NMAX : (long long)ceil(prec(a) * e), &r);
    *out = r;
    return DFL_OK;
}

dfl_status dfl_jet_powi(const dfl_jet *a, int e, dfl_jet *out, dfl_err *err)
{
    check(a);
    if (e == 0) { /* 0^0 = 1 by the usual convention */
        const_one(a->n, out);
        return DFL_OK;
    }
    if (a->zero) return zero_power(a, e, "powi", out, err);
    long long vout = (long long)a->v * e;
    if (vout > VAL_LIMIT || vout < -VAL_LIMIT)
        return dfl_err_set(err, DFL_E_NUMERIC,
                           "jet powi: valuation %d * %d is out of range", a->v, e);
    return power_core(a, (double)e, (int)vout, pow(a->c[0], (double)e), out, err);
}

dfl_status dfl_jet_pow(const dfl_jet *a, double e, dfl_jet *out, dfl_err *err)
{
    check(a);
    if (!isfinite(e))
        return dfl_err_set(err, DFL_E_NUMERIC, "jet pow: exponent %g is not finite", e);
    if (e == nearbyint(e) && fabs(e) <= VAL_LIMIT) return dfl_jet_powi(a, (int)e, out, err);
    if (a->zero) return zero_power(a, e, "pow", out, err);
    if (!(a->c[0] > 0.0))
        return dfl_err_set(err, DFL_E_NUMERIC,
                           "jet pow: leading coefficient %g is not positive (exponent %g)",
                           a->c[0], e);
    /* e = -1/p applied to valuation -p must give exactly 1 although
     * (-p) * (-1/p) may round to 0.999...; anything farther than rounding
     * from an integer is a genuine branch point. */
    double ve = a->v * e;
    double vr = nearbyint(ve);
    if (fabs(ve - vr) > 1e-9 * fmax(1.0, fabs(ve)))
        return dfl_err_set(err, DFL_E_NUMERIC,
                           "jet pow: valuation %d times exponent %.17g = %.17g is not an"
                           " integer (s^%g has no Taylor series)",
                           a->v, e, ve, ve);
    if (fabs(vr) > VAL_LIMIT)
        return dfl_err_set(err, DFL_E_NUMERIC,
                           "jet pow: valuation %d * %g is out of range", a->v, e);
    return power_core(a, e, (int)vr, pow(a->c[0], e), out, err);
}

dfl_status dfl_jet_sqrt(const dfl_jet *a, dfl_jet *out, dfl_err *err)
{
    check(a);
    dfl_jet r;
    if (a->zero) {
        if (is_exact_zero(a)) {
            set_zero(NMAX, &r);
        } else {
            /* sqrt(O(s^P)) = O(s^(P/2)): zero below s^ceil(P/2). */
            int P = prec(a);
            set_zero(P >= 0 ? (P + 1) / 2 : -((-P) / 2), &r);
        }
        *out = r;
        return DFL_OK;
    }
    if (a->v % 2 != 0)
        return dfl_err_set(err, DFL_E_NUMERIC,
                           "jet sqrt: odd valuation %d (series starts at s^%d, its root is"
                           " not a Taylor series)",
                           a->v, a->v);
    if (!(a->c[0] > 0.0))
        return dfl_err_set(err, DFL_E_NUMERIC,
                           "jet sqrt: leading coefficient %g (of s^%d) is not positive",
                           a->c[0], a->v);
    /* r^2 = a: coefficient of s^k gives 2 r_0 r_k + sum_{j=1..k-1} r_j r_{k-j} = a_k.
     * Cheaper and better conditioned than Miller with e = 1/2. */
    blank(&r);
    r.v = a->v / 2;
    r.n = a->n;
    r.c[0] = sqrt(a->c[0]);
    const double inv2 = 0.5 / r.c[0];
    for (int k = 1; k < r.n; k++) {
        double s = a->c[k];
        for (int j = 1; j < k; j++) s -= r.c[j] * r.c[k - j];
        r.c[k] = s * inv2;
    }
    check(&r);
    *out = r;
    return DFL_OK;
}

/* ------------------------------------------------------------ exp, log */

dfl_status dfl_jet_exp(const dfl_jet *a, dfl_jet *out, dfl_err *err)
{
    check(a);
    int P = prec(a);
    if (a->v < 0 && !a->zero)
        return dfl_err_set(err, DFL_E_NUMERIC,
                           "jet exp: argument has a pole (valuation %d)", a->v);
    if (P < 1)
        return dfl_err_set(err, DFL_E_NUMERIC,
                           "jet exp: argument is unknown at s = 0 (precision %d)", P);
    dfl_jet r;
    blank(&r);
    r.n = is_exact_zero(a) ? NMAX : imin(P, NMAX);
    /* Absolute coefficients of a; v >= 0 so they start at s^0. */
    double A[NMAX];
    for (int k = 0; k < r.n; k++) A[k] = at(a, k);
    r.c[0] = exp(A[0]);
    if (!isfinite(r.c[0]) || r.c[0] == 0.0)
        return dfl_err_set(err, DFL_E_NUMERIC,
                           "jet exp: exp(%g) overflows or underflows", A[0]);
    /* b = exp(a), b' = a' b: k b_k = sum_{j=1..k} j a_j b_{k-j}. */
    for (int k = 1; k < r.n; k++) {
        double s = 0.0;
        for (int j = 1; j <= k; j++) s += j * A[j] * r.c[k - j];
        r.c[k] = s / k;
    }
    check(&r);
    *out = r;
    return DFL_OK;
}

dfl_status dfl_jet_log(const dfl_jet *a, dfl_jet *out, dfl_err *err)
{
    check(a);
    if (a->zero)
        return dfl_err_set(err, DFL_E_NUMERIC, "jet log: argument is zero (to order %d)",
                           prec(a) - 1);
    if (a->v != 0)
        return dfl_err_set(err, DFL_E_NUMERIC,
                           "jet log: argument has valuation %d (needs 0: log s has no"
                           " Taylor series)",
                           a->v);
    if (!(a->c[0] > 0.0))
        return dfl_err_set(err, DFL_E_NUMERIC,
                           "jet log: leading coefficient %g is not positive", a->c[0]);
    /* log(c0 g) = log c0 + b with b = log g, g_0 = 1.  g b' = g' gives
     * k b_k = k g_k - sum_{j=1..k-1} j b_j g_{k-j}. */
    double g[NMAX];
    const double inv = 1.0 / a->c[0];
    for (int k = 0; k < a->n; k++) g[k] = a->c[k] * inv;
    dfl_jet r;
    blank(&r);
    r.n = a->n;
    r.c[0] = log(a->c[0]);
    for (int k = 1; k < r.n; k++) {
        double s = k * g[k];
        for (int j = 1; j < k; j++) s -= j * r.c[j] * g[k - j];
        r.c[k] = s / k;
    }
    strip(&r, 0.0); /* log(1 + ...) starts at s^1 or later */
    check(&r);
    *out = r;
    return DFL_OK;
}

/* ------------------------------------------------------ trim and access */

void dfl_jet_trim(const dfl_jet *a, double tol, dfl_jet *out)
{
    check(a);
    dfl_jet r = *a;
    if (!r.zero) {
        double m = 0.0;
        for (int k = 0; k < r.n; k++) m = fmax(m, fabs(r.c[k]));
        strip(&r, tol * m);
    }
    check(&r);
    *out = r;
}

int dfl_jet_order(const dfl_jet *a)
{
    check(a);
    return prec(a) - 1;
}

double dfl_jet_coeff(const dfl_jet *a, int k)
{
    check(a);
    if (k < a->v) return 0.0;
    if (k >= prec(a)) return NAN;
    return a->c[k - a->v];
}

double dfl_jet_deriv(const dfl_jet *a, int k)
{
    check(a);
    if (k < 0 || (a->v < 0 && !a->zero)) return NAN;
    double c = dfl_jet_coeff(a, k);
    double f = 1.0;
    for (int i = 2; i <= k; i++) f *= i;
    return f * c;
}
