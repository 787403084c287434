/* Tests for core/jet.  Expected values never come from a previous run: they
 * are closed-form Taylor coefficients (generalized binomial series, geometric
 * and exponential series, polynomial products computed here with plain
 * truncated arrays, independent of the jet code and its recurrences), or
 * long-double finite differences (Fornberg weights) at low orders. */
#include <criterion/criterion.h>

#include <limits.h>
#include <math.h>
#include <string.h>

#include "core/jet.h"

#define N 25 /* DFL_JET_MAX + 1 */

/* ------------------------------------------------ reference arithmetic */

/* Generalized binomial coefficient C(e, k) = e (e-1) ... (e-k+1) / k!. */
static double binom(double e, int k)
{
    double r = 1.0;
    for (int i = 0; i < k; i++) r *= (e - i) / (i + 1);
    return r;
}

static double fact(int k)
{
    double f = 1.0;
    for (int i = 2; i <= k; i++) f *= i;
    return f;
}

/* out = a * b truncated to n terms; out may alias. */
static void pmul(const double *a, const double *b, int n, double *out)
{
    double t[N] = {0};
    for (int k = 0; k < n; k++)
        for (int j = 0; j <= k; j++) t[k] += a[j] * b[k - j];
    memcpy(out, t, (size_t)n * sizeof *out);
}

/* out = (1 + w)^e = sum_m C(e, m) w^m, for w[0] == 0, n terms. */
static void binom_series(const double *w, double e, int n, double *out)
{
    cr_assert(w[0] == 0.0);
    double wm[N] = {0}, t[N] = {0};
    wm[0] = 1.0; /* w^0 */
    for (int m = 0; m < n; m++) {
        double b = binom(e, m);
        for (int k = 0; k < n; k++) t[k] += b * wm[k];
        pmul(wm, w, n, wm);
    }
    memcpy(out, t, (size_t)n * sizeof *out);
}

/* Checks coefficients k = k0..k1 of j against want[k] (absolute index):
 * |got - want| <= rel |want| + abs.  Since d_k = k! c_k, this is the same
 * relative test on derivatives. */
static void expect_coeffs(const dfl_jet *j, const double *want, int k0, int k1, double rel,
                          double abs, const char *what)
{
    for (int k = k0; k <= k1; k++) {
        double got = dfl_jet_coeff(j, k);
        cr_assert(isfinite(got), "%s: coefficient %d unknown (order %d)", what, k,
                  dfl_jet_order(j));
        cr_assert(fabs(got - want[k]) <= rel * fabs(want[k]) + abs,
                  "%s: c[%d] = %.17g, want %.17g (diff %.3g)", what, k, got, want[k],
                  got - want[k]);
        double d = dfl_jet_deriv(j, k);
        cr_assert(fabs(d - fact(k) * want[k]) <= rel * fact(k) * fabs(want[k]) + fact(k) * abs,
                  "%s: d%d = %.17g, want %.17g", what, k, d, fact(k) * want[k]);
    }
}

static dfl_jet poly(int K, int m, const double *a)
{
    dfl_jet j;
    dfl_jet_poly(a, m, K, &j);
    return j;
}

#define OK(call)                                                                         \
    do {                                                                                 \
        dfl_err e_;                                                                      \
        dfl_err_clear(&e_);                                                              \
        dfl_status s_ = (call);                                                          \
        cr_assert(s_ == DFL_OK, "%s failed: %s", #call, e_.msg);                         \
    } while (0)

#define FAILS(call, errp)                                                                \
    do {                                                                                 \
        dfl_err_clear(errp);                                                             \
        dfl_status s_ = (call);                                                          \
        cr_assert(s_ == DFL_E_NUMERIC, "%s should fail with DFL_E_NUMERIC", #call);      \
        cr_assert((errp)->code == DFL_E_NUMERIC && (errp)->msg[0] != '\0',               \
                  "%s: no message", #call);                                              \
    } while (0)

/* Fornberg's algorithm: weights w[i][m] of f(x[i]) for the m-th derivative at
 * x0, m <= M.  Long double throughout. */
#define FD_NODES 13
static void fornberg(long double x0, const long double *x, int n, int M,
                     long double w[FD_NODES][5])
{
    memset(w, 0, sizeof(long double) * FD_NODES * 5);
    long double c1 = 1.0L, c4 = x[0] - x0;
    w[0][0] = 1.0L;
    for (int i = 1; i < n; i++) {
        int mn = i < M ? i : M;
        long double c2 = 1.0L, c5 = c4;
        c4 = x[i] - x0;
        for (int j = 0; j < i; j++) {
            long double c3 = x[i] - x[j];
            c2 *= c3;
            if (j == i - 1) {
                for (int k = mn; k >= 1; k--)
                    w[i][k] = c1 * (k * w[i - 1][k - 1] - c5 * w[i - 1][k]) / c2;
                w[i][0] = -c1 * c5 * w[i - 1][0] / c2;
            }
            for (int k = mn; k >= 1; k--) w[j][k] = (c4 * w[j][k] - k * w[j][k - 1]) / c3;
            w[j][0] = c4 * w[j][0] / c3;
        }
        c1 = c2;
    }
}

/* d^m f / ds^m at 0 by a 13-point central stencil of step h. */
static long double fd(long double (*f)(long double), int m, long double h)
{
    long double x[FD_NODES], w[FD_NODES][5];
    for (int i = 0; i < FD_NODES; i++) x[i] = (i - FD_NODES / 2) * h;
    fornberg(0.0L, x, FD_NODES, 4, w);
    long double s = 0.0L;
    for (int i = 0; i < FD_NODES; i++) s += w[i][m] * f(x[i]);
    return s;
}

/* ------------------------------------------------- closed-form series */

#define K12 12

Test(jet, fornberg_weights_sane)
{
    /* The stencil must differentiate polynomials of degree < 13 exactly:
     * d^m/ds^m s^m = m!, and annihilate s^(m-1). */
    long double x[FD_NODES], w[FD_NODES][5];
    for (int i = 0; i < FD_NODES; i++) x[i] = (i - FD_NODES / 2) * 0.1L;
    fornberg(0.0L, x, FD_NODES, 4, w);
    for (int m = 0; m <= 4; m++) {
        long double s = 0.0L, z = 0.0L;
        for (int i = 0; i < FD_NODES; i++) {
            s += w[i][m] * powl(x[i], m);
            if (m > 0) z += w[i][m] * powl(x[i], m - 1);
        }
        cr_assert(fabsl(s - fact(m)) < 1e-12L, "m=%d: %Lg", m, s);
        cr_assert(fabsl(z) < 1e-10L, "m=%d: %Lg", m, z);
    }
}

Test(jet, pow_real_exponents_binomial)
{
    /* (c0 + a s)^e = c0^e sum_k C(e, k) (a/c0)^k s^k. */
    const double es[] = {0.5, -0.5, 1.0 / 3.0, -2.7, 3.25, -1.0 / 7.0, 1.5, 0.01};
    const double c0 = 1.7, a = -0.6;
    for (size_t i = 0; i < sizeof es / sizeof es[0]; i++) {
        double e = es[i];
        dfl_jet x, y;
        dfl_jet_linear(c0, a, K12, &x);
        OK(dfl_jet_pow(&x, e, &y, &e_));
        cr_assert_eq(y.v, 0);
        cr_assert_eq(dfl_jet_order(&y), K12);
        double want[N];
        for (int k = 0; k <= K12; k++) want[k] = pow(c0, e) * binom(e, k) * pow(a / c0, k);
        expect_coeffs(&y, want, 0, K12, 1e-10, 0.0, "pow");
    }
}

Test(jet, sqrt_binomial)
{
    /* sqrt(4 - 3 s) = 2 sum_k C(1/2, k) (-3/4)^k s^k. */
    dfl_jet x, y;
    dfl_jet_linear(4.0, -3.0, K12, &x);
    OK(dfl_jet_sqrt(&x, &y, &e_));
    double want[N];
    for (int k = 0; k <= K12; k++) want[k] = 2.0 * binom(0.5, k) * pow(-0.75, k);
    expect_coeffs(&y, want, 0, K12, 1e-10, 0.0, "sqrt");
}

Test(jet, powi_negative_leading)
{
    /* (-2 + s)^5 = sum_k C(5, k) (-2)^(5-k) s^k (a polynomial: zeros beyond 5),
     * (-2 + s)^-3 = (-1/8) sum_k C(-3, k) (-1/2)^k s^k. */
    dfl_jet x, y;
    dfl_jet_linear(-2.0, 1.0, K12, &x);
    OK(dfl_jet_powi(&x, 5, &y, &e_));
    double want[N];
    for (int k = 0; k <= K12; k++) want[k] = k <= 5 ? binom(5, k) * pow(-2.0, 5 - k) : 0.0;
    expect_coeffs(&y, want, 0, K12, 1e-12, 1e-12, "powi 5");
    OK(dfl_jet_pow(&x, 5.0, &y, &e_)); /* integer real exponent: same */
    expect_coeffs(&y, want, 0, K12, 1e-12, 1e-12, "pow 5.0");
    OK(dfl_jet_powi(&x, -3, &y, &e_));
    for (int k = 0; k <= K12; k++) want[k] = -0.125 * binom(-3, k) * pow(-0.5, k);
    expect_coeffs(&y, want, 0, K12, 1e-10, 0.0, "powi -3");
    OK(dfl_jet_powi(&x, 0, &y, &e_));
    cr_assert(y.v == 0 && y.c[0] == 1.0 && dfl_jet_coeff(&y, 3) == 0.0);
}

Test(jet, division_and_recip)
{
    /* (1 + s) / (1 - s)^2 = sum_k (2k + 1) s^k. */
    const double num[] = {1, 1}, den[] = {1, -2, 1};
    dfl_jet a = poly(K12, 2, num), b = poly(K12, 3, den), q;
    OK(dfl_jet_div(&a, &b, &q, &e_));
    double want[N];
    for (int k = 0; k <= K12; k++) want[k] = 2.0 * k + 1.0;
    expect_coeffs(&q, want, 0, K12, 1e-12, 0.0, "div");

    /* 1 / (3 - 1.5 s) = (1/3) sum_k (s/2)^k. */
    dfl_jet x, r;
    dfl_jet_linear(3.0, -1.5, K12, &x);
    OK(dfl_jet_recip(&x, &r, &e_));
    for (int k = 0; k <= K12; k++) want[k] = pow(0.5, k) / 3.0;
    expect_coeffs(&r, want, 0, K12, 1e-12, 0.0, "recip");

    /* s^3 (1 + s) / (s (2 + s)): valuation 2, = s^2 (1 + s) / (2 + s);
     * 1/(2+s) = sum (-1)^k s^k / 2^(k+1), times (1 + s). */
    const double n3[] = {0, 0, 0, 1, 1}, d1[] = {0, 2, 1};
    dfl_jet an = poly(K12, 5, n3), bd = poly(K12, 3, d1);
    OK(dfl_jet_div(&an, &bd, &q, &e_));
    cr_assert_eq(q.v, 2);
    /* relative precision: min(n_a, n_b) = min(10, 12) = 10 -> order 11 */
    cr_assert_eq(dfl_jet_order(&q), 11);
    double g[N] = {0}, one_plus_s[N] = {1, 1};
    for (int k = 0; k < N; k++) g[k] = pow(-1.0, k) / pow(2.0, k + 1);
    pmul(g, one_plus_s, N, g);
    double w2[N] = {0};
    for (int k = 2; k < N; k++) w2[k] = g[k - 2];
    expect_coeffs(&q, w2, 0, 11, 1e-12, 0.0, "div valuation");
}

Test(jet, exp_and_log_series)
{
    double want[N];
    /* exp(3 + 2 s) = e^3 sum 2^k / k! s^k */
    dfl_jet x, y;
    dfl_jet_linear(3.0, 2.0, K12, &x);
    OK(dfl_jet_exp(&x, &y, &e_));
    for (int k = 0; k <= K12; k++) want[k] = exp(3.0) * pow(2.0, k) / fact(k);
    expect_coeffs(&y, want, 0, K12, 1e-12, 0.0, "exp linear");

    /* exp(s^2) = sum s^(2m) / m!; the argument has v = 2, n = 11, and exp
     * keeps its absolute precision 13 -> order 12. */
    const double s2[] = {0, 0, 1};
    dfl_jet q = poly(K12, 3, s2);
    OK(dfl_jet_exp(&q, &y, &e_));
    cr_assert_eq(dfl_jet_order(&y), K12);
    for (int k = 0; k <= K12; k++) want[k] = k % 2 ? 0.0 : 1.0 / fact(k / 2);
    expect_coeffs(&y, want, 0, K12, 1e-14, 0.0, "exp s^2");

    /* log(2 + 3 s) = log 2 + sum_{k>=1} (-1)^(k+1) (3/2)^k / k s^k */
    dfl_jet_linear(2.0, 3.0, K12, &x);
    OK(dfl_jet_log(&x, &y, &e_));
    want[0] = log(2.0);
    for (int k = 1; k <= K12; k++) want[k] = pow(-1.0, k + 1) * pow(1.5, k) / k;
    expect_coeffs(&y, want, 0, K12, 1e-12, 0.0, "log");

    /* log(1 + s) has valuation 1 (log 1 == 0 exactly), same precision. */
    dfl_jet_linear(1.0, 1.0, K12, &x);
    OK(dfl_jet_log(&x, &y, &e_));
    cr_assert_eq(y.v, 1);
    cr_assert_eq(dfl_jet_order(&y), K12);
    want[0] = 0.0;
    for (int k = 1; k <= K12; k++) want[k] = pow(-1.0, k + 1) / k;
    expect_coeffs(&y, want, 0, K12, 1e-12, 0.0, "log1p");
}

/* sqrt(1 + s^2) / (2 + s)^1.5 */
static void comp1(int K, dfl_jet *u)
{
    const double a[] = {1, 0, 1}, b[] = {2, 1};
    dfl_jet x = poly(K, 3, a), y = poly(K, 2, b), r, t;
    OK(dfl_jet_sqrt(&x, &r, &e_));
    OK(dfl_jet_pow(&y, 1.5, &t, &e_));
    OK(dfl_jet_div(&r, &t, u, &e_));
}
static long double comp1_f(long double s) { return sqrtl(1 + s * s) / powl(2 + s, 1.5L); }

/* exp(0.3 log(1 + s)) = (1 + s)^0.3 */
static void comp2(int K, dfl_jet *u)
{
    dfl_jet x, l;
    dfl_jet_linear(1.0, 1.0, K, &x);
    OK(dfl_jet_log(&x, &l, &e_));
    dfl_jet_scale(&l, 0.3, &l);
    OK(dfl_jet_exp(&l, u, &e_));
}
static long double comp2_f(long double s) { return expl(0.3L * logl(1 + s)); }

/* (1 + 2 s + s^3)^(-1/7) */
static void comp3(int K, dfl_jet *u)
{
    const double a[] = {1, 2, 0, 1};
    dfl_jet x = poly(K, 4, a);
    OK(dfl_jet_pow(&x, -1.0 / 7.0, u, &e_));
}
static long double comp3_f(long double s) { return powl(1 + 2 * s + s * s * s, -1.0L / 7.0L); }

Test(jet, compositions_closed_form)
{
    dfl_jet u;
    double want[N];

    /* sqrt(1+s^2) = sum C(1/2, m) s^(2m); (2+s)^-1.5 = 2^-1.5 sum C(-1.5, k) (s/2)^k */
    comp1(K12, &u);
    double S[N] = {0}, T[N] = {0};
    for (int m = 0; 2 * m < N; m++) S[2 * m] = binom(0.5, m);
    for (int k = 0; k < N; k++) T[k] = pow(2.0, -1.5) * binom(-1.5, k) * pow(0.5, k);
    pmul(S, T, N, want);
    cr_assert_eq(dfl_jet_order(&u), K12);
    expect_coeffs(&u, want, 0, K12, 1e-10, 0.0, "sqrt(1+s^2)/(2+s)^1.5");

    comp2(K12, &u);
    for (int k = 0; k <= K12; k++) want[k] = binom(0.3, k);
    cr_assert_eq(dfl_jet_order(&u), K12);
    expect_coeffs(&u, want, 0, K12, 1e-10, 0.0, "exp(0.3 log(1+s))");

    comp3(K12, &u);
    double w[N] = {0, 2, 0, 1};
    binom_series(w, -1.0 / 7.0, K12 + 1, want);
    cr_assert_eq(dfl_jet_order(&u), K12);
    expect_coeffs(&u, want, 0, K12, 1e-10, 0.0, "(1+2s+s^3)^(-1/7)");
}

/* ---------------------------------------------------- finite differences */

static const double RC = 0.8, RB = 0.35, RE = -0.2; /* h2 = c + b s + e s^2 */

static int fd_p;
/* R-equivalence with h1 = s, written as its analytic continuation
 * s (1 + (s/h2)^p)^(-1/p) (equal to (s^-p + h2^-p)^(-1/p) for s > 0, checked
 * below) so that a central stencil can straddle 0. */
static long double requiv_f(long double s)
{
    long double h2 = RC + RB * s + RE * s * s;
    return s * powl(1 + powl(s / h2, fd_p), -1.0L / fd_p);
}
/* R-conjunction with h1 = s; s^p + h2^p > 0 on the stencil, so it is literal. */
static long double rconj_f(long double s)
{
    long double h2 = RC + RB * s + RE * s * s;
    return s + h2 - powl(powl(s, fd_p) + powl(h2, fd_p), 1.0L / fd_p);
}

static void requiv(int p, int K, dfl_jet *u)
{
    const double h2c[] = {RC, RB, RE};
    dfl_jet h1, h2 = poly(K, 3, h2c), a, b;
    dfl_jet_linear(0.0, 1.0, K, &h1);
    OK(dfl_jet_pow(&h1, -p, &a, &e_));
    OK(dfl_jet_pow(&h2, -p, &b, &e_));
    dfl_jet_add(&a, &b, &a);
    OK(dfl_jet_pow(&a, -1.0 / p, u, &e_));
}

static void rconj(int p, int K, dfl_jet *u)
{
    const double h2c[] = {RC, RB, RE};
    dfl_jet h1, h2 = poly(K, 3, h2c), a, b, sum;
    dfl_jet_linear(0.0, 1.0, K, &h1);
    OK(dfl_jet_powi(&h1, p, &a, &e_));
    OK(dfl_jet_powi(&h2, p, &b, &e_));
    dfl_jet_add(&a, &b, &a);
    OK(dfl_jet_pow(&a, 1.0 / p, &a, &e_));
    dfl_jet_add(&h1, &h2, &sum);
    dfl_jet_sub(&sum, &a, u);
}

/* h trades the stencil's truncation error (h / radius of convergence)^~10
 * against long-double rounding ~1e-19 / h^m; the 1e-9 tolerance sits two
 * orders above the error seen at the chosen steps. */
static void expect_fd(const dfl_jet *u, long double (*f)(long double), long double h,
                      const char *what)
{
    for (int m = 1; m <= 4; m++) {
        long double ref = fd(f, m, h);
        double got = dfl_jet_deriv(u, m);
        double tol = 1e-9 * fmax(1.0, fabs((double)ref));
        cr_assert(fabs(got - (double)ref) <= tol, "%s: d%d = %.17g, FD %.17Lg (diff %.3g)",
                  what, m, got, ref, got - (double)ref);
    }
}

Test(jet, finite_differences_low_orders)
{
    dfl_jet u;
    comp1(K12, &u);
    expect_fd(&u, comp1_f, 0.02L, "comp1");
    comp2(K12, &u);
    expect_fd(&u, comp2_f, 0.02L, "comp2");
    comp3(K12, &u);
    expect_fd(&u, comp3_f, 0.01L, "comp3"); /* root of 1+2s+s^3 at -0.45 */
    for (fd_p = 1; fd_p <= 4; fd_p++) {
        /* the continuation equals the literal R-equivalence for s > 0 */
        long double s = 0.05L, h2 = RC + RB * s + RE * s * s;
        long double lit = powl(powl(s, -fd_p) + powl(h2, -fd_p), -1.0L / fd_p);
        cr_assert(fabsl(lit - requiv_f(s)) < 1e-17L);
        requiv(fd_p, DFL_JET_MAX, &u);
        expect_fd(&u, requiv_f, 0.01L, "R-equivalence");
    }
    for (fd_p = 2; fd_p <= 4; fd_p++) {
        rconj(fd_p, DFL_JET_MAX, &u);
        expect_fd(&u, rconj_f, 0.01L, "R-conjunction");
    }
}

/* ------------------------------------------------------------ valuation */

Test(jet, valuation_hpow_add_root)
{
    /* h = s + 0.3 s^2, g regular: u = (h^-p + g)^(-1/p) = h (1 + g h^p)^(-1/p).
     * Reference: truncated polynomial products and the binomial series. */
    const double hc[] = {0, 1, 0.3}, gc[] = {0.5, 1, -0.25};
    for (int p = 1; p <= 12; p++) {
        dfl_jet h = poly(K12, 3, hc), g = poly(K12, 3, gc), hp, sum, u;
        OK(dfl_jet_pow(&h, -p, &hp, &e_));
        cr_assert_eq(hp.v, -p);
        cr_assert_eq(hp.c[0], 1.0);
        dfl_jet_add(&hp, &g, &sum);
        cr_assert_eq(sum.v, -p);
        /* h known to order 12 with v = 1 -> 12 relative terms -> h^-p known
         * to order 11 - p; adding g keeps that. */
        cr_assert_eq(dfl_jet_order(&sum), 11 - p);
        OK(dfl_jet_pow(&sum, -1.0 / p, &u, &e_));
        cr_assert_eq(u.v, 1, "p=%d: valuation %d", p, u.v);
        cr_assert_eq(u.c[0], 1.0, "p=%d: c1 = %.17g", p, u.c[0]);
        cr_assert_eq(dfl_jet_order(&u), K12, "p=%d", p);

        double H[N] = {0, 1, 0.3}, Hp[N] = {1}, G[N] = {0.5, 1, -0.25}, W[N], B[N], U[N];
        for (int i = 0; i < p; i++) pmul(Hp, H, K12 + 1, Hp);
        pmul(G, Hp, K12 + 1, W); /* W = g h^p, W[0] = 0 */
        binom_series(W, -1.0 / p, K12 + 1, B);
        pmul(H, B, K12 + 1, U);
        cr_assert_eq(U[1], 1.0);
        /* coefficients 3..p are exactly 0 in theory but come out as the
         * rounding residue of ((1 + 0.3 s)^-p)^(-1/p), whose intermediate
         * coefficients reach ~11 for p = 12 (residue measured up to 4e-15):
         * absolute 1e-13 on top of the relative 1e-10. */
        expect_coeffs(&u, U, 0, K12, 1e-10, 1e-13, "(h^-p + g)^(-1/p)");
    }
}

Test(jet, valuation_sqrt_of_s2)
{
    /* sqrt(s^2 (1 + s)) = s sum C(1/2, k) s^k at s > 0. */
    const double a[] = {0, 0, 1, 1};
    dfl_jet x = poly(K12, 4, a), y;
    cr_assert_eq(x.v, 2);
    OK(dfl_jet_sqrt(&x, &y, &e_));
    cr_assert_eq(y.v, 1);
    cr_assert_eq(y.c[0], 1.0);
    cr_assert_eq(dfl_jet_order(&y), 11); /* n = 11 relative terms kept */
    double want[N] = {0};
    for (int k = 0; k + 1 < N; k++) want[k + 1] = binom(0.5, k);
    expect_coeffs(&y, want, 0, 11, 1e-12, 0.0, "sqrt(s^2(1+s))");
}

Test(jet, valuation_inverse_root_of_pole)
{
    /* (s^-p (1 + a s))^(-1/p) = s (1 + a s)^(-1/p) = sum C(-1/p, k) a^k s^(k+1). */
    const double a = 0.7;
    for (int p = 1; p <= 12; p++) {
        dfl_jet s, sp, l, x, y;
        dfl_jet_linear(0.0, 1.0, DFL_JET_MAX, &s);
        OK(dfl_jet_powi(&s, -p, &sp, &e_));
        cr_assert(sp.v == -p && sp.c[0] == 1.0 && sp.c[1] == 0.0);
        dfl_jet_linear(1.0, a, K12, &l);
        dfl_jet_mul(&sp, &l, &x);
        cr_assert_eq(x.v, -p);
        OK(dfl_jet_pow(&x, -1.0 / p, &y, &e_));
        cr_assert_eq(y.v, 1);
        cr_assert_eq(y.c[0], 1.0);
        cr_assert_eq(dfl_jet_order(&y), K12 + 1); /* 13 relative terms from s^1 */
        double want[N] = {0};
        for (int k = 0; k + 1 < N; k++) want[k + 1] = binom(-1.0 / p, k) * pow(a, k);
        expect_coeffs(&y, want, 0, K12 + 1, 1e-10, 0.0, "(s^-p(1+as))^(-1/p)");
    }
}

/* -------------------------------------------------------- R-functions */

Test(jet, r_equivalence_order_p)
{
    /* h1 = s, h2 = c + b s + e s^2 (c > 0).  For s > 0,
     *   u = (s^-p + h2^-p)^(-1/p) = s (1 + (s/h2)^p)^(-1/p)
     *     = s - s^(p+1) / (p h2^p) + O(s^(2p+1))
     * because (1 + w)^(-1/p) = 1 - w/p + O(w^2) with w = (s/h2)^p = O(s^p).
     * So d1 = 1, d2..dp = 0 and d_(p+1) = -(p+1)!/(p c^p) != 0.  In the jet
     * the sum s^-p (1 + 0 s + ... + 0 s^(p-1) + h2^-p s^p + ...) has exact
     * zeros, and Miller's recurrence keeps them exact. */
    for (int p = 1; p <= 12; p++) {
        dfl_jet u;
        requiv(p, DFL_JET_MAX, &u);
        cr_assert_eq(u.v, 1);
        cr_assert(dfl_jet_order(&u) >= p + 1);
        cr_assert(fabs(dfl_jet_deriv(&u, 0)) <= 1e-12);
        cr_assert(fabs(dfl_jet_deriv(&u, 1) - 1.0) <= 1e-12);
        for (int k = 2; k <= p; k++)
            cr_assert(fabs(dfl_jet_deriv(&u, k)) <= 1e-12, "p=%d d%d = %g", p, k,
                      dfl_jet_deriv(&u, k));
        double want = -fact(p + 1) / (p * pow(RC, p));
        double got = dfl_jet_deriv(&u, p + 1);
        cr_assert(got != 0.0);
        cr_assert(fabs(got - want) <= 1e-10 * fabs(want), "p=%d d%d = %.17g want %.17g", p,
                  p + 1, got, want);
    }
}

Test(jet, r_conjunction_order_p_minus_1)
{
    /* u = h1 + h2 - (h1^p + h2^p)^(1/p), h1 = s:
     *   (s^p + h2^p)^(1/p) = h2 (1 + (s/h2)^p)^(1/p) = h2 + s^p / (p h2^(p-1)) + ...
     * so u = s - s^p / (p c^(p-1)) + O(s^(p+1)): coefficients 2..p-1 vanish,
     * c_p = -1/(p c^(p-1)).  Here the zeros come from cancellation of rounded
     * numbers (c - (c^p)^(1/p)), so they are ~1e-16, not exact: checked on
     * coefficients, then removed by trim. */
    for (int p = 2; p <= 12; p++) {
        dfl_jet u, t;
        rconj(p, DFL_JET_MAX, &u);
        cr_assert(fabs(dfl_jet_coeff(&u, 0)) <= 1e-14, "p=%d c0 = %g", p,
                  dfl_jet_coeff(&u, 0));
        cr_assert(fabs(dfl_jet_coeff(&u, 1) - 1.0) <= 1e-12, "p=%d", p);
        for (int k = 2; k < p; k++)
            cr_assert(fabs(dfl_jet_coeff(&u, k)) <= 1e-12, "p=%d c%d = %g", p, k,
                      dfl_jet_coeff(&u, k));
        double want = -1.0 / (p * pow(RC, p - 1));
        double got = dfl_jet_coeff(&u, p);
        cr_assert(fabs(got - want) <= 1e-10 * fabs(want), "p=%d c%d = %.17g want %.17g", p, p,
                  got, want);
        dfl_jet_trim(&u, 1e-13, &t);
        cr_assert_eq(t.v, 1, "p=%d: trimmed valuation %d", p, t.v);
        cr_assert_eq(dfl_jet_order(&t), dfl_jet_order(&u));
    }
}

/* ----------------------------------------------------- precision rules */

Test(jet, precision_mul_div_add)
{
    const double a5[] = {1, 2, 3}, b10[] = {0, 0, 4, 5};
    dfl_jet a = poly(4, 3, a5);  /* v 0, n 5, P 5 */
    dfl_jet b = poly(11, 4, b10); /* v 2, n 10, P 12 */
    cr_assert(a.v == 0 && a.n == 5 && b.v == 2 && b.n == 10);
    dfl_jet r;
    dfl_jet_mul(&a, &b, &r);
    cr_assert(r.v == 2 && r.n == 5);
    /* c = (1 + 2s + 3s^2)(4 + 5s) = 4 + 13 s + 22 s^2 + 15 s^3 */
    cr_assert(r.c[0] == 4 && r.c[1] == 13 && r.c[2] == 22 && r.c[3] == 15 && r.c[4] == 0);
    OK(dfl_jet_div(&b, &a, &r, &e_));
    cr_assert(r.v == 2 && r.n == 5);
    dfl_jet_add(&a, &b, &r);
    cr_assert(r.v == 0 && dfl_jet_order(&r) == 4);
    cr_assert(r.c[0] == 1 && r.c[1] == 2 && r.c[2] == 7 && r.c[3] == 5 && r.c[4] == 0);
    cr_assert(isnan(dfl_jet_coeff(&r, 5)));
    dfl_jet_add(&b, &a, &r); /* precision is symmetric */
    cr_assert(r.v == 0 && dfl_jet_order(&r) == 4 && r.c[2] == 7);

    /* a pole: s^-3 (1 + s) known to 6 relative terms (P = 3) plus a regular
     * jet known to order 10 -> known below s^3. */
    dfl_jet s, sp, l, x;
    dfl_jet_linear(0.0, 1.0, DFL_JET_MAX, &s);
    OK(dfl_jet_powi(&s, -3, &sp, &e_));
    dfl_jet_linear(1.0, 1.0, 5, &l);
    dfl_jet_mul(&sp, &l, &x);
    cr_assert(x.v == -3 && x.n == 6);
    dfl_jet_linear(2.0, 1.0, 10, &l);
    dfl_jet_add(&x, &l, &r);
    cr_assert(r.v == -3 && dfl_jet_order(&r) == 2);
    cr_assert(r.c[0] == 1.0 && r.c[1] == 1.0 && r.c[3] == 2.0 && r.c[4] == 1.0 && r.c[5] == 0.0);
    cr_assert(isnan(dfl_jet_deriv(&r, 1))); /* pole: no derivatives */
    cr_assert_eq(dfl_jet_coeff(&r, -4), 0.0);
    cr_assert_eq(dfl_jet_coeff(&r, -3), 1.0);
    dfl_jet_sub(&l, &x, &r); /* precision is symmetric */
    cr_assert(r.v == -3 && dfl_jet_order(&r) == 2 && r.c[0] == -1.0 && r.c[3] == 2.0);
}

Test(jet, cancellation_and_zero)
{
    const double p1[] = {1, 2, 3}, p2[] = {1, 2};
    dfl_jet a = poly(6, 3, p1), b = poly(6, 2, p2), r;
    dfl_jet_sub(&a, &b, &r);
    cr_assert(!r.zero && r.v == 2 && r.n == 5 && r.c[0] == 3.0);
    cr_assert_eq(dfl_jet_order(&r), 6);

    dfl_jet_sub(&a, &a, &r);
    cr_assert(r.zero);
    cr_assert_eq(dfl_jet_order(&r), 6);
    cr_assert_eq(dfl_jet_coeff(&r, 6), 0.0);
    cr_assert(isnan(dfl_jet_coeff(&r, 7)));
    /* (O(s^7)) * s^-3 = O(s^4) */
    dfl_jet s, sp, z;
    dfl_jet_linear(0.0, 1.0, DFL_JET_MAX, &s);
    OK(dfl_jet_powi(&s, -3, &sp, &e_));
    dfl_jet_mul(&r, &sp, &z);
    cr_assert(z.zero && dfl_jet_order(&z) == 3);
    OK(dfl_jet_powi(&s, -9, &sp, &e_));
    dfl_jet_mul(&r, &sp, &z); /* O(s^-2): known zero below s^-2 only */
    cr_assert(z.zero && dfl_jet_order(&z) == -3 && z.n >= 1);
    cr_assert(isnan(dfl_jet_coeff(&z, 0)));
    /* sqrt(O(s^7)) = O(s^3.5): zero known below s^4 */
    OK(dfl_jet_sqrt(&r, &z, &e_));
    cr_assert(z.zero && dfl_jet_order(&z) == 3);
    /* exp(O(s^7)) = 1 + O(s^7) */
    OK(dfl_jet_exp(&r, &z, &e_));
    cr_assert(!z.zero && z.c[0] == 1.0 && dfl_jet_order(&z) == 6 && z.c[1] == 0.0);

    /* const(0, K) is the zero known to order K */
    dfl_jet_const(0.0, 4, &z);
    cr_assert(z.zero && dfl_jet_order(&z) == 4);
    dfl_jet_add(&z, &a, &r);
    cr_assert(r.v == 0 && dfl_jet_order(&r) == 4 && r.c[2] == 3.0);
    /* linear with a0 == 0 gets valuation 1 and keeps absolute order */
    dfl_jet_linear(0.0, 2.0, 7, &r);
    cr_assert(r.v == 1 && r.c[0] == 2.0 && dfl_jet_order(&r) == 7);
}

Test(jet, exact_zero)
{
    dfl_jet z, a, r;
    dfl_jet_zero(&z);
    cr_assert(z.zero && z.v == 0 && z.n == DFL_JET_MAX + 1);
    const double p3[] = {0, 0, 0, 1, 2};
    a = poly(DFL_JET_MAX, 5, p3); /* v 3, n 22 */
    dfl_jet_add(&z, &a, &r);
    cr_assert(r.v == 3 && r.n == a.n && r.c[0] == 1.0 && r.c[1] == 2.0);
    dfl_jet_mul(&z, &a, &r);
    cr_assert(r.zero && r.n == DFL_JET_MAX + 1 && r.v == 0);
    dfl_jet_scale(&a, 0.0, &r);
    cr_assert(r.zero && r.n == DFL_JET_MAX + 1);
    OK(dfl_jet_div(&z, &a, &r, &e_));
    cr_assert(r.zero && r.n == DFL_JET_MAX + 1);
    OK(dfl_jet_sqrt(&z, &r, &e_));
    cr_assert(r.zero && r.n == DFL_JET_MAX + 1);
    OK(dfl_jet_pow(&z, 2.5, &r, &e_));
    cr_assert(r.zero && r.n == DFL_JET_MAX + 1);
    dfl_jet_abs(&z, &r);
    cr_assert(r.zero);
    dfl_jet_const(0.0, DFL_JET_MAX, &r);
    cr_assert(r.zero && r.n == DFL_JET_MAX + 1 && r.v == 0);
    /* add_const to a zero gives the constant */
    dfl_jet_add_const(&z, 2.5, &r);
    cr_assert(!r.zero && r.v == 0 && r.c[0] == 2.5 && r.c[1] == 0.0);
}

Test(jet, trim_and_coeff)
{
    dfl_jet a, r;
    const double c[] = {1e-17, 1.0, 0.5, 1e-20, 2.0};
    a = poly(6, 5, c);
    dfl_jet_trim(&a, 1e-12, &r);
    cr_assert(r.v == 1 && r.c[0] == 1.0 && r.c[1] == 0.5 && r.c[2] == 1e-20);
    cr_assert_eq(dfl_jet_order(&r), 6); /* absolute precision unchanged */
    cr_assert_eq(dfl_jet_coeff(&r, 0), 0.0);
    cr_assert(isnan(dfl_jet_coeff(&r, 7)));
    cr_assert_eq(dfl_jet_deriv(&r, 4), 24.0 * 2.0);
    cr_assert(isnan(dfl_jet_deriv(&r, 7)));
    cr_assert(isnan(dfl_jet_deriv(&r, -1)));
    /* tol 0 removes nothing here (c0 != 0) */
    dfl_jet_trim(&a, 0.0, &r);
    cr_assert(r.v == 0 && r.c[0] == 1e-17);
    /* everything below tol: the zero of a's precision */
    dfl_jet_trim(&a, 1.0, &r);
    cr_assert(r.zero && dfl_jet_order(&r) == 6);
    /* linear/poly drop terms beyond K */
    const double d[] = {1, 2, 3, 4, 5};
    a = poly(2, 5, d);
    cr_assert(a.n == 3 && a.c[2] == 3.0 && isnan(dfl_jet_coeff(&a, 3)));
}

/* ----------------------------------------------------------- aliasing */

static int same(const dfl_jet *x, const dfl_jet *y)
{
    return x->v == y->v && x->n == y->n && x->zero == y->zero &&
           memcmp(x->c, y->c, sizeof x->c) == 0;
}

typedef void (*binop)(const dfl_jet *, const dfl_jet *, dfl_jet *);

static void divop(const dfl_jet *a, const dfl_jet *b, dfl_jet *o)
{
    OK(dfl_jet_div(a, b, o, &e_));
}

Test(jet, aliasing)
{
    const double pa[] = {1.5, -0.7, 0.2, 0.9}, pb[] = {0.8, 0.3, -1.1};
    const binop ops[] = {dfl_jet_add, dfl_jet_sub, dfl_jet_mul, divop};
    for (size_t i = 0; i < sizeof ops / sizeof ops[0]; i++) {
        dfl_jet a = poly(10, 4, pa), b = poly(10, 3, pb), ref, x, aa;
        ops[i](&a, &b, &ref);
        x = a;
        ops[i](&x, &b, &x);
        cr_assert(same(&x, &ref), "op %zu: out == a", i);
        x = b;
        ops[i](&a, &x, &x);
        cr_assert(same(&x, &ref), "op %zu: out == b", i);
        ops[i](&a, &a, &ref);
        aa = a;
        ops[i](&aa, &aa, &aa);
        cr_assert(same(&aa, &ref), "op %zu: out == a == b", i);
    }
    dfl_jet a = poly(10, 4, pa), ref, x;
#define UNARY(call_ref, call_alias)                                                      \
    do {                                                                                 \
        call_ref;                                                                        \
        x = a;                                                                           \
        call_alias;                                                                      \
        cr_assert(same(&x, &ref), "%s", #call_alias);                                    \
    } while (0)
    UNARY(OK(dfl_jet_sqrt(&a, &ref, &e_)), OK(dfl_jet_sqrt(&x, &x, &e_)));
    UNARY(OK(dfl_jet_pow(&a, -0.37, &ref, &e_)), OK(dfl_jet_pow(&x, -0.37, &x, &e_)));
    UNARY(OK(dfl_jet_powi(&a, -3, &ref, &e_)), OK(dfl_jet_powi(&x, -3, &x, &e_)));
    UNARY(OK(dfl_jet_exp(&a, &ref, &e_)), OK(dfl_jet_exp(&x, &x, &e_)));
    UNARY(OK(dfl_jet_log(&a, &ref, &e_)), OK(dfl_jet_log(&x, &x, &e_)));
    UNARY(OK(dfl_jet_recip(&a, &ref, &e_)), OK(dfl_jet_recip(&x, &x, &e_)));
    UNARY(dfl_jet_neg(&a, &ref), dfl_jet_neg(&x, &x));
    UNARY(dfl_jet_abs(&a, &ref), dfl_jet_abs(&x, &x));
    UNARY(dfl_jet_scale(&a, 3.0, &ref), dfl_jet_scale(&x, 3.0, &x));
    UNARY(dfl_jet_add_const(&a, -1.5, &ref), dfl_jet_add_const(&x, -1.5, &x));
    UNARY(dfl_jet_trim(&a, 0.5, &ref), dfl_jet_trim(&x, 0.5, &x));
    /* the aliased results are also right, not just self-consistent */
    dfl_jet_add_const(&a, -1.5, &x);
    cr_assert(x.v == 1 && x.c[0] == -0.7);
    dfl_jet_trim(&a, 0.5, &x);
    cr_assert(x.v == 0 && x.c[0] == 1.5);
    dfl_jet_trim(&a, 1.0, &x);
    cr_assert(x.zero && dfl_jet_order(&x) == 10);
}

/* -------------------------------------------------------------- errors */

Test(jet, errors)
{
    dfl_err err;
    dfl_jet s, x, y, z, out;
    dfl_jet_linear(0.0, 1.0, 8, &s); /* v = 1 */
    dfl_jet_linear(-1.0, 1.0, 8, &x); /* c0 < 0 */
    dfl_jet_linear(2.0, 1.0, 8, &y);
    dfl_jet_const(0.0, 8, &z);
    const dfl_jet keep = y;
    out = y;

    FAILS(dfl_jet_sqrt(&s, &out, &err), &err);          /* odd valuation */
    FAILS(dfl_jet_sqrt(&x, &out, &err), &err);          /* negative leading */
    FAILS(dfl_jet_pow(&s, 0.5, &out, &err), &err);      /* v e = 1/2 */
    FAILS(dfl_jet_pow(&s, -1.0 / 3.0, &out, &err), &err);
    FAILS(dfl_jet_pow(&x, 0.5, &out, &err), &err);      /* negative base */
    FAILS(dfl_jet_pow(&z, -0.5, &out, &err), &err);     /* zero to negative power */
    FAILS(dfl_jet_pow(&y, INFINITY, &out, &err), &err);
    FAILS(dfl_jet_powi(&z, -2, &out, &err), &err);
    FAILS(dfl_jet_log(&s, &out, &err), &err);           /* v != 0 */
    FAILS(dfl_jet_log(&x, &out, &err), &err);           /* c0 < 0 */
    FAILS(dfl_jet_log(&z, &out, &err), &err);
    FAILS(dfl_jet_div(&y, &z, &out, &err), &err);       /* divide by zero jet */
    FAILS(dfl_jet_recip(&z, &out, &err), &err);
    dfl_jet big;
    dfl_jet_const(1000.0, 8, &big);
    FAILS(dfl_jet_exp(&big, &out, &err), &err);         /* overflow */
    dfl_jet pole;
    OK(dfl_jet_powi(&s, -1, &pole, &e_));
    FAILS(dfl_jet_exp(&pole, &out, &err), &err);        /* v < 0 */
    cr_assert(same(&out, &keep), "failed calls must leave out unchanged");
    /* NULL err is allowed */
    cr_assert_eq(dfl_jet_sqrt(&s, &out, NULL), DFL_E_NUMERIC);
    /* ... and v e integer up to rounding is accepted */
    dfl_jet s7;
    OK(dfl_jet_powi(&s, -7, &s7, &e_));
    OK(dfl_jet_pow(&s7, -1.0 / 7.0, &out, &e_));
    cr_assert(out.v == 1 && out.c[0] == 1.0);
}

/* Builders clamp K to [0, DFL_JET_MAX] (jet.h): on both sides of each limit
 * the result equals the one built at the limit itself, and no call aborts. */
Test(jet, builders_clamp_order)
{
    const double p[3] = {1.5, -2.0, 0.25};
    dfl_jet r, want;
    /* the limits themselves: order 0 keeps one term, DFL_JET_MAX all 25 */
    dfl_jet_poly(p, 3, 0, &r);
    cr_assert(r.v == 0 && r.n == 1 && r.c[0] == 1.5 && dfl_jet_order(&r) == 0);
    dfl_jet_poly(p, 3, DFL_JET_MAX, &r);
    cr_assert(r.v == 0 && r.n == DFL_JET_MAX + 1 && r.c[1] == -2.0 && r.c[2] == 0.25);
    dfl_jet_linear(0.0, -2.0, DFL_JET_MAX, &r);
    cr_assert(r.v == 1 && r.n == DFL_JET_MAX && dfl_jet_order(&r) == DFL_JET_MAX);
    const int K[] = {-1, -7, INT_MIN, DFL_JET_MAX + 1, 1000, INT_MAX};
    for (int i = 0; i < 6; i++) {
        const int L = K[i] < 0 ? 0 : DFL_JET_MAX;
        dfl_jet_poly(p, 3, K[i], &r);
        dfl_jet_poly(p, 3, L, &want);
        cr_assert(same(&r, &want), "poly K = %d", K[i]);
        dfl_jet_const(1.5, K[i], &r);
        dfl_jet_const(1.5, L, &want);
        cr_assert(same(&r, &want), "const K = %d", K[i]);
        dfl_jet_linear(0.0, -2.0, K[i], &r);
        dfl_jet_linear(0.0, -2.0, L, &want);
        cr_assert(same(&r, &want), "linear K = %d", K[i]);
    }
    /* the zero: known below s^1 at K <= 0, the exact zero at K >= DFL_JET_MAX */
    dfl_jet_const(0.0, -3, &r);
    cr_assert(r.zero && dfl_jet_order(&r) == 0);
    dfl_jet_const(0.0, DFL_JET_MAX + 1, &r);
    cr_assert(r.zero && r.v == 0 && r.n == DFL_JET_MAX + 1);
}

/* The rejecting form for orders that come from input. */
Test(jet, check_order_rejects_outside_range)
{
    dfl_err err;
    cr_assert_eq(dfl_jet_check_order(0, &err), DFL_OK);
    cr_assert_eq(dfl_jet_check_order(DFL_JET_MAX, &err), DFL_OK);
    cr_assert_eq(dfl_jet_check_order(-1, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "jet order -1 outside [0, 24]"), "%s", err.msg);
    cr_assert_eq(dfl_jet_check_order(DFL_JET_MAX + 1, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "jet order 25 outside [0, 24]"), "%s", err.msg);
    cr_assert_eq(dfl_jet_check_order(INT_MIN, NULL), DFL_E_INPUT);
}

/* A directional jet that records its call: the linear jet 2 + K s. */
static dfl_status probe_jet(const void *ctx, const double *x, const double *dir, int K,
                            dfl_jet *out, dfl_err *err)
{
    (void)x;
    (void)dir;
    (void)err;
    *(int *)ctx += 1;
    dfl_jet_linear(2.0, (double)K, K, out);
    return DFL_OK;
}

/* The checks in front of every public jet entry point, in their order:
 * missing jets first, then the order; the callee runs only when both pass
 * and *out is untouched otherwise. */
Test(jet, dir_call_checks_then_dispatches)
{
    dfl_err err;
    int calls = 0;
    const double x[2] = {0, 0}, dir[2] = {1, 0};
    dfl_jet out, keep;
    dfl_jet_const(7.0, 3, &out);
    keep = out;
    cr_assert_eq(dfl_jet_dir_call(NULL, &calls, "field", "plain", x, dir, 3, &out, &err),
                 DFL_E_INPUT);
    cr_assert_str_eq(err.msg, "field 'plain' has no exact derivatives (jets)");
    cr_assert_eq(dfl_jet_dir_call(NULL, &calls, "shape", "disk", x, dir, -1, &out, &err),
                 DFL_E_INPUT);
    cr_assert_str_eq(err.msg, "shape 'disk' has no exact derivatives (jets)");
    cr_assert_eq(dfl_jet_dir_call(probe_jet, &calls, "field", "f", x, dir, DFL_JET_MAX + 1, &out,
                                  &err),
                 DFL_E_INPUT);
    cr_assert(strstr(err.msg, "jet order 25 outside [0, 24]"), "%s", err.msg);
    cr_assert_eq(calls, 0);
    cr_assert(out.v == keep.v && out.n == keep.n && out.zero == keep.zero);
    cr_assert_eq(memcmp(out.c, keep.c, sizeof out.c), 0);
    cr_assert_eq(dfl_jet_dir_call(probe_jet, &calls, "field", "f", x, dir, 5, &out, &err), DFL_OK);
    cr_assert_eq(calls, 1);
    cr_assert_eq(dfl_jet_coeff(&out, 0), 2.0);
    cr_assert_eq(dfl_jet_coeff(&out, 1), 5.0);
    cr_assert_eq(dfl_jet_order(&out), 5);
}

/* A zero known below s^0 (P = 0, from O(s^7) * s^-7) is stored with
 * v = min(0, P - 1) = -1 and n = P - v = 1 (jet.h); exp needs its argument
 * known at s = 0 (precision >= 1), so exp of it fails and leaves out alone,
 * while exp(O(s^1)) = 1 + O(s). */
Test(jet, zero_of_precision_zero)
{
    dfl_jet z, s, sp, a, out, one;
    dfl_jet_const(0.0, 6, &z); /* O(s^7) */
    dfl_jet_linear(0.0, 1.0, DFL_JET_MAX, &s);
    OK(dfl_jet_powi(&s, -7, &sp, &e_));
    dfl_jet_mul(&z, &sp, &a);
    cr_assert(a.zero && a.v == -1 && a.n == 1, "v %d n %d", a.v, a.n);
    cr_assert_eq(dfl_jet_order(&a), -1);
    dfl_jet_const(3.0, 4, &out);
    const dfl_jet keep = out;
    dfl_err err;
    FAILS(dfl_jet_exp(&a, &out, &err), &err);
    cr_assert(same(&out, &keep));
    dfl_jet_const(0.0, 0, &z); /* O(s^1) */
    OK(dfl_jet_exp(&z, &one, &e_));
    cr_assert(!one.zero && one.v == 0 && one.c[0] == 1.0 && dfl_jet_order(&one) == 0);
}

/* Valuations are limited to |v| <= 2^20 (jet.h): s^e is a jet for
 * |e| = 2^20 and DFL_E_NUMERIC for |e| = 2^20 + 1, on both signs. */
Test(jet, powi_valuation_limit)
{
    dfl_jet s, r;
    dfl_err err;
    dfl_jet_linear(0.0, 1.0, DFL_JET_MAX, &s);
    OK(dfl_jet_powi(&s, 1 << 20, &r, &e_));
    cr_assert(r.v == 1 << 20 && r.c[0] == 1.0);
    OK(dfl_jet_powi(&s, -(1 << 20), &r, &e_));
    cr_assert(r.v == -(1 << 20) && r.c[0] == 1.0);
    FAILS(dfl_jet_powi(&s, (1 << 20) + 1, &r, &err), &err);
    FAILS(dfl_jet_powi(&s, -(1 << 20) - 1, &r, &err), &err);
}
