/* Truncated univariate Taylor series ("jets") with a valuation.
 *
 * A jet represents a function of one variable s near s = 0+ as
 *
 *     a(s) = s^v * (c[0] + c[1] s + ... + c[n-1] s^(n-1)) + O(s^(v+n))
 *
 * with integer valuation v (may be negative) and n known coefficients
 * (1 <= n <= DFL_JET_MAX + 1).  c[0] != 0 unless zero == 1.  c[k] = 0 for
 * k >= n.
 *
 * Zero jets (zero == 1, all c = 0) mean "every coefficient below s^P is 0",
 * P = v + n being their absolute precision; they are stored with
 * v = min(0, P - 1), n = P - v.  The exact zero is the zero jet with v = 0,
 * n = DFL_JET_MAX + 1: it is absorbing (0 * a = 0, 0 + a = a with a's full
 * precision).  A zero of lower precision comes from cancellation in
 * add/sub (a - a), from dfl_jet_const(0, K) with K < DFL_JET_MAX, or from
 * dfl_jet_trim, and propagates its precision honestly (O(s^P) * b is
 * O(s^(P + v_b)), etc.).
 *
 * Keeping the leading power apart makes the operations bs04 needs exact:
 * h^(-p) of a series starting at s (valuation -p), sqrt of a series starting
 * at s^2 (valuation 1) and (.)^(-1/p) of a series starting at s^(-p)
 * (valuation 1).  Multiplication, division and powers keep the relative
 * precision n = min(n_a, n_b); addition keeps the absolute precision
 * min(v_a + n_a, v_b + n_b) and strips leading coefficients that cancel to
 * exactly 0.0 (use dfl_jet_trim for cancellation up to rounding).  exp keeps
 * the absolute precision of its argument (capped to DFL_JET_MAX + 1 terms).
 *
 * Absolute coefficient k (of s^k) is known when k < v + n; the k-th
 * derivative at 0+ is k! times it.
 *
 * All functions accept aliasing of inputs and output.  None allocate.  A
 * failing function returns DFL_E_NUMERIC, fills err (which may be NULL) and
 * leaves *out unchanged.  Valuations are limited to |v| <= 2^20 (more is
 * reported as DFL_E_NUMERIC by the powers).
 */
#ifndef DFL_CORE_JET_H
#define DFL_CORE_JET_H

#include "core/status.h"

#define DFL_JET_MAX 24

typedef struct dfl_jet {
    int v;                       /* valuation: power of s of c[0] */
    int n;                       /* number of known coefficients, 1..DFL_JET_MAX+1 */
    int zero;                    /* 1 iff the jet is exactly zero (to its precision) */
    double c[DFL_JET_MAX + 1];
} dfl_jet;

/* DFL_OK if 0 <= K <= DFL_JET_MAX; otherwise DFL_E_INPUT with "jet order K
 * outside [0, DFL_JET_MAX]" in err (may be NULL).  For callers that take an
 * order from user input and must reject it rather than let the builders
 * below clamp it. */
dfl_status dfl_jet_check_order(int K, dfl_err *err);

/* A directional jet: the jet of s -> g(x + s dir) at s = 0+ to absolute
 * order K (0 <= K <= DFL_JET_MAX) of the function g that ctx describes; dir
 * need not be unit length; thread-safe for a shared ctx.  The signature of
 * the jet member of dfl_field_ops (field/field.h) and dfl_shape_ops
 * (geom/shape.h). */
typedef dfl_status (*dfl_dir_jet_fn)(const void *ctx, const double *x, const double *dir, int K,
                                     dfl_jet *out, dfl_err *err);

/* jet(ctx, x, dir, K, out, err) behind the checks of the public jet entry
 * points (dfl_field_jet, dfl_shape_jet): DFL_E_INPUT with "<what> '<name>'
 * has no exact derivatives (jets)" when jet is NULL, then dfl_jet_check_order;
 * *out is untouched when either fails.  Otherwise jet's own status. */
dfl_status dfl_jet_dir_call(dfl_dir_jet_fn jet, const void *ctx, const char *what,
                            const char *name, const double *x, const double *dir, int K,
                            dfl_jet *out, dfl_err *err);

/* The exact zero (absorbing, precision DFL_JET_MAX + 1). */
void dfl_jet_zero(dfl_jet *out);

/* Builders.  The absolute order K is clamped to [0, DFL_JET_MAX]: K < 0
 * builds as K = 0 and K > DFL_JET_MAX as K = DFL_JET_MAX (never an abort, no
 * status).  They are for internal use with orders already checked; an order
 * from input goes through dfl_jet_check_order first. */
/* The constant a, known to absolute order K.  a == 0.0 gives the zero known
 * below s^(K+1) (the exact zero when K == DFL_JET_MAX). */
void dfl_jet_const(double a, int K, dfl_jet *out);
/* The polynomial a0 + a1 s, known to absolute order K.  If a0 == 0.0 exactly,
 * the valuation is 1. */
void dfl_jet_linear(double a0, double a1, int K, dfl_jet *out);
/* The polynomial a[0] + a[1] s + ... + a[m-1] s^(m-1) known to order K
 * (terms beyond K are dropped, leading exact zeros give the valuation).
 * m >= 0 and a may be NULL only when m == 0 (asserted: a caller bug). */
void dfl_jet_poly(const double *a, int m, int K, dfl_jet *out);

void dfl_jet_add(const dfl_jet *a, const dfl_jet *b, dfl_jet *out);
void dfl_jet_sub(const dfl_jet *a, const dfl_jet *b, dfl_jet *out);
void dfl_jet_neg(const dfl_jet *a, dfl_jet *out);
/* k * a; k == 0.0 gives the exact zero. */
void dfl_jet_scale(const dfl_jet *a, double k, dfl_jet *out);
/* a + k, k an exact constant (the result keeps a's absolute precision as
 * far as DFL_JET_MAX + 1 terms allow). */
void dfl_jet_add_const(const dfl_jet *a, double k, dfl_jet *out);
void dfl_jet_mul(const dfl_jet *a, const dfl_jet *b, dfl_jet *out);
/* a / b.  DFL_E_NUMERIC if b is a zero jet. */
dfl_status dfl_jet_div(const dfl_jet *a, const dfl_jet *b, dfl_jet *out, dfl_err *err);
/* 1 / a.  DFL_E_NUMERIC if a is a zero jet. */
dfl_status dfl_jet_recip(const dfl_jet *a, dfl_jet *out, dfl_err *err);
/* sqrt(a): needs c[0] > 0 and an even valuation (or a zero jet, whose
 * square root is the zero known below s^ceil(P/2)).  Result valuation v/2. */
dfl_status dfl_jet_sqrt(const dfl_jet *a, dfl_jet *out, dfl_err *err);
/* a^e for real e: needs c[0] > 0 and v*e an integer (to 1e-9 relative, so
 * that e = -1/p on valuation -p works; v = 0 always works).  Result
 * valuation round(v*e), relative precision n.  An integer-valued e (exactly)
 * is handed to dfl_jet_powi, so any sign of c[0] is then accepted.  A zero
 * jet to a positive power is a zero jet (the exact zero stays exact); a zero
 * jet to a negative power is an error, and to the power 0 (an integer, so
 * dfl_jet_powi's rule) the constant 1. */
dfl_status dfl_jet_pow(const dfl_jet *a, double e, dfl_jet *out, dfl_err *err);
/* a^e for integer e (any sign of c[0]; e < 0 needs a non-zero jet).
 * a^0 is the constant 1 with a's n. */
dfl_status dfl_jet_powi(const dfl_jet *a, int e, dfl_jet *out, dfl_err *err);
/* exp(a): needs v >= 0 (a zero jet needs precision >= 1).  Result has v = 0
 * and n = min(v_a + n_a, DFL_JET_MAX + 1).  DFL_E_NUMERIC if exp(a(0))
 * overflows or underflows to 0. */
dfl_status dfl_jet_exp(const dfl_jet *a, dfl_jet *out, dfl_err *err);
/* log(a): needs v == 0 and c[0] > 0.  Same n; log(1 + ...) has valuation
 * >= 1 (leading exact zeros stripped). */
dfl_status dfl_jet_log(const dfl_jet *a, dfl_jet *out, dfl_err *err);
/* |a| away from 0: sign of c[0].  A zero jet stays zero. */
void dfl_jet_abs(const dfl_jet *a, dfl_jet *out);

/* Strips leading coefficients with |c[k]| <= tol * max_j |c[j]|, raising the
 * valuation and lowering n accordingly (absolute precision unchanged; if
 * every coefficient goes, the result is the zero jet of a's precision).
 * Use it on quantities known to vanish at s = 0 that carry rounding residue
 * (e.g. a line function evaluated at a point computed to lie on the line). */
void dfl_jet_trim(const dfl_jet *a, double tol, dfl_jet *out);

/* Absolute order up to which the jet is known: v + n - 1. */
int dfl_jet_order(const dfl_jet *a);
/* Coefficient of s^k.  0 for k < v; NAN for k > dfl_jet_order(a). */
double dfl_jet_coeff(const dfl_jet *a, int k);
/* k-th derivative at s = 0+: k! * dfl_jet_coeff(a, k) for k >= 0.  NAN for
 * k < 0, for k > dfl_jet_order(a), and for a non-zero jet with v < 0 (a pole
 * has no derivatives). */
double dfl_jet_deriv(const dfl_jet *a, int k);

#endif
