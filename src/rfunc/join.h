/* bs04 joining operations (sec. 2.2 and 4.2) on non-negative part fields
 * h_1..h_n (h_i = 0 exactly on part i), in values + gradients and in jets.
 *
 * R-equivalence of order p (eq. 6), for n parts (associative):
 *     u = (sum_i h_i^(-p))^(-1/p) = h_min (sum_i (h_min / h_i)^p)^(-1/p),
 * evaluated in the second form (ratios <= 1: nothing overflows, nothing
 * divides by zero; u = 0 when some h_i = 0).  du/dh_i = (u / h_i)^(p+1).
 * At an interior point of part i (h_i = s, the others positive):
 *     u = h_i (1 + h_i^p C)^(-1/p) = h_i - h_i^(p+1) C / p + ...,
 * C = sum_(j != i) h_j^(-p): normalized to order p exactly (d^(p+1)u/ds^(p+1)
 * = -(p+1)! C / p != 0) when h_i is normalized to order >= p.
 *
 * R-conjunction of order p (eq. 7), a left fold in part order (it is not
 * associative, bs04 sec. 2.2):  u = ((h_1 ^ h_2) ^ h_3) ^ ... with
 *     a ^ b = a + b - (a^p + b^p)^(1/p)
 *           = lo - hi ((1 + (lo/hi)^p)^(1/p) - 1),  lo = min, hi = max,
 * the second form without cancellation (log1p / expm1).  For a = s, b > 0:
 * a ^ b = a - a^p b^(1-p) / p + ...: normalized to order p - 1.  p must be
 * >= 2: for p = 1 and non-negative arguments a ^ b = 0 identically.
 *
 * Corrected R-equivalence (eq. 20) with q_v = |x - v| for shared vertices v:
 *     u = (sum_i h_i^(-p) - sum_v q_v^(-p))^(-1/p).
 * In the hatched sector of a vertex (closest point of both adjacent parts
 * is v) exact distances give h_i = h_j = q_v and u = q_v: |grad u| = 1
 * where eq. 6 gives 2^(-1/p).  Eq. 20 relies on h_i <= q_v for the parts
 * i, j adjacent to v (true for exact distances: the distance to a part is
 * at most the distance to its end point).  Trimmed fields break it beyond
 * the end points: h = q (1 + c q/d + ...) there (trim.h), so
 * (h_i/q)^(-p) + (h_j/q)^(-p) - 1 ~ 2 exp(-p c q/d) - 1 turns negative at
 * q/d ~ ln 2/(p c) (6% of the segment for p = 12): u blows up or is
 * undefined.  dflab therefore subtracts, per vertex,
 *     qt_v^(-p),  qt_v = max(q_v, h_i, h_j)          (guard)
 * which is q_v^(-p) whenever h_i, h_j <= q_v (always for exact distances:
 * eq. 20 verbatim) and otherwise removes no more than one adjacent part
 * contributes; on open polylines S = sum h^-p - sum qt^-p >= h_min^(-p)
 * (each vertex term is charged to one part), so u <= h_min.  On closed
 * polylines S >= 0 only, so u is also floored:
 *     u = (max(S, (2 h_min)^(-p)))^(-1/p)  (u <= 2 h_min).
 * (S reaches 0 e.g. at the centre of a fine regular polygon whose trimmed
 * fields all exceed the vertex distances).  The guard is continuous but not
 * differentiable where h_i = q_v, which only happens where trimming errors
 * occur; in the hatched sector itself trimmed fields give qt = max(h_i, h_j)
 * and u = min(h_i, h_j), so |grad u| = 1 + O(q/d) instead of exactly 1.
 * This guarded form is dflab's regularisation, not bs04's formula: with
 * disk-trimmed parts it is active at most grid nodes and reduces to
 * min(h_i, h_j) in the hatched sector.
 *
 * Correction (dfl_rfunc_correction, config key `correction`): GUARDED is
 * the form above (the default); EQ20 is bs04's eq. 20 literally, with the
 * raw q_v and no floor:
 *     S = sum_i h_i^(-p) - sum_v q_v^(-p),  u = S^(-1/p) where S > 0,
 *     u = NaN (and gradient NaN) where S <= 0 (eq. 20 is undefined there).
 * With exact distances S >= h_min^(-p) > 0 wherever the reflex-side
 * argument holds; with trimmed parts S turns negative in the hatched
 * sector beyond a radius r*: for the disk trim h = q sqrt(1 + 2 a rho +
 * rho^2) there (rho = q/L, a = -(x.e)/q), and on the sector's bisector
 * (a = cos(alpha'/2), alpha' = min(alpha, 2 pi - alpha) the convex angle)
 * S = 0 at  r* = L (sqrt(cos^2(alpha'/2) + 2^(2/p) - 1) - cos(alpha'/2)),
 * the smallest onset radius in the sector (Jensen: g(a) = (1 + 2 a rho +
 * rho^2)^(-p/2) is convex and decreasing, a_1 + a_2 is largest on the
 * bisector).
 *
 * Domain of validity.  Values are computed in the scaled form above (every
 * ratio <= 1), so any finite non-negative h, q give a finite u (no
 * overflow or underflow of h^(-p) however large or small h is); jets scale
 * by the smallest dominant leading coefficient and fail with DFL_E_NUMERIC
 * (never an abort) when a coefficient is not finite.
 * Jets: exact along rays with the valuation rules of core/jet.h; a part
 * whose jet is zero (the ray runs inside the part) makes u zero.
 */
#ifndef DFL_RFUNC_JOIN_H
#define DFL_RFUNC_JOIN_H

#include <stddef.h>

#include "core/jet.h"
#include "core/names.h"
#include "core/status.h"

/* The joins: one list from which the codes (0, 1, ... in this order) and
 * their config names come (core/names.h).  X(code, name, where in bs04). */
#define DFL_RFUNC_JOIN_LIST(X)                                      \
    X(DFL_RFUNC_REQUIV, "requiv", "eq. 6")                          \
    X(DFL_RFUNC_RCONJ, "rconj", "eq. 7, left fold")                 \
    X(DFL_RFUNC_REQUIV_CORRECTED, "requiv_corrected", "eq. 20, guarded or literal (correction)")

typedef enum dfl_rfunc_join { DFL_RFUNC_JOIN_LIST(DFL_NAMES_CODE) } dfl_rfunc_join;

/* Number of joins. */
enum { DFL_RFUNC_JOIN_COUNT = 0 DFL_RFUNC_JOIN_LIST(DFL_NAMES_ONE) };

/* The corrected join's two forms (header): X(code, name, note). */
#define DFL_RFUNC_CORRECTION_LIST(X)                                        \
    X(DFL_RFUNC_CORR_GUARDED, "guarded", "dflab's guard qt = max(q, h_i, h_j) and floor") \
    X(DFL_RFUNC_CORR_EQ20, "eq20", "bs04 eq. 20 literally, NaN where the radicand <= 0")

typedef enum dfl_rfunc_correction {
    DFL_RFUNC_CORRECTION_LIST(DFL_NAMES_CODE)
} dfl_rfunc_correction;

enum { DFL_RFUNC_CORRECTION_COUNT = 0 DFL_RFUNC_CORRECTION_LIST(DFL_NAMES_ONE) };

/* Config names indexed by code. */
extern const char *const dfl_rfunc_correction_names[DFL_RFUNC_CORRECTION_COUNT];

/* Config name of a correction ("guarded", "eq20"); "?" outside the list. */
const char *dfl_rfunc_correction_name(dfl_rfunc_correction c);

/* The correction named name into *out; DFL_E_INPUT otherwise (*out untouched). */
dfl_status dfl_rfunc_correction_parse(const char *name, dfl_rfunc_correction *out, dfl_err *err);

/* Config names indexed by code (for dfl_cfg_enum-style readers: names,
 * DFL_RFUNC_JOIN_COUNT). */
extern const char *const dfl_rfunc_join_names[DFL_RFUNC_JOIN_COUNT];

/* Largest supported order p (integer powers by repeated squaring). */
#define DFL_RFUNC_P_MAX 64

/* Config name of a join ("requiv", "rconj", "requiv_corrected"); "?" for
 * a value outside the list. */
const char *dfl_rfunc_join_name(dfl_rfunc_join join);

/* The join whose config name is name (exact, case-sensitive match) into
 * *out.  DFL_E_INPUT naming the value and the accepted names otherwise;
 * *out is untouched then. */
dfl_status dfl_rfunc_join_parse(const char *name, dfl_rfunc_join *out, dfl_err *err);

/* Checks p against the join: DFL_E_INPUT unless 1 <= p <= DFL_RFUNC_P_MAX,
 * and p >= 2 for R-conjunction. */
dfl_status dfl_rfunc_join_check(dfl_rfunc_join join, int p, dfl_err *err);

/* x^p for integer p >= 0 by repeated squaring (no pow()). */
double dfl_rfunc_ipow(double x, int p);

/* eq. 14: partial derivatives of eq. 6 (two arguments) in polar coordinates
 * of the (h1, h2) plane, h1 = rho cos(phi), h2 = rho sin(phi), phi in
 * [0, pi/2]:  F1 = dF/dh1 = sin^(p+1) / (cos^p + sin^p)^((p+1)/p),
 *             F2 = dF/dh2 = cos^(p+1) / (cos^p + sin^p)^((p+1)/p).
 * eq. 13 then bounds |grad u| between |F1 - F2| and F1 + F2 when
 * |grad h1| = |grad h2| = 1. */
void dfl_rfunc_requiv_partials_polar(double phi, int p, double *F1, double *F2);

/* Two-argument joins with partial derivatives (pointers may be NULL);
 * arguments >= 0. */
double dfl_rfunc_requiv2(double h1, double h2, int p, double *F1, double *F2);
double dfl_rfunc_rconj2(double a, double b, int p, double *Fa, double *Fb);

/* Streaming accumulator: add the parts in order (and, for the corrected
 * join, the vertex distances in any order), then read u and its gradient.
 * No allocation; dim <= 3. */
typedef struct dfl_rfunc_acc {
    dfl_rfunc_join join;
    int p, dim, grad;
    int zero;            /* some h_i == 0: u = 0 */
    int qzero;           /* some q_v == 0 while no h_i == 0 */
    int nh;              /* parts added */
    double m;            /* scale: running min of all h and q */
    double S, Sq;        /* sum (m/h_i)^p, sum (m/q_v)^p */
    double V[3], Vq[3];  /* sum (m/h)^(p+1) grad h, same for q */
    double hmin, ghmin[3];
    double u, gu[3];     /* R-conjunction fold state */
    dfl_rfunc_correction corr; /* corrected join: guarded (default) or eq20 */
} dfl_rfunc_acc;

/* grad != 0: gradients are accumulated (then every add needs one). */
void dfl_rfunc_acc_begin(dfl_rfunc_acc *acc, dfl_rfunc_join join, int p, int dim, int grad);
void dfl_rfunc_acc_add(dfl_rfunc_acc *acc, double h, const double *gh);
/* Corrected join only, right after dfl_rfunc_acc_begin: which form
 * dfl_rfunc_acc_end computes (guarded by default; see the header). */
void dfl_rfunc_acc_set_correction(dfl_rfunc_acc *acc, dfl_rfunc_correction corr);
/* Corrected join only: the distance q >= 0 of a shared vertex, guarded
 * (dfl_rfunc_guard) for DFL_RFUNC_CORR_GUARDED, raw for DFL_RFUNC_CORR_EQ20. */
void dfl_rfunc_acc_add_q(dfl_rfunc_acc *acc, double q, const double *gq);

/* The corrected join's guard qt = max(q, hi, hj) of a vertex with adjacent
 * parts i, j; its gradient (dim doubles) is that of the maximum (g may be
 * NULL; the input gradients may then be NULL too). */
double dfl_rfunc_guard(int dim, double q, const double *gq, double hi, const double *ghi,
                       double hj, const double *ghj, double *g);
/* The same on jets: the larger branch as s -> 0+. */
void dfl_rfunc_guard_jet(const dfl_jet *q, const dfl_jet *hi, const dfl_jet *hj, dfl_jet *out);
/* 1 when u is already known to be 0 (remaining parts can be skipped). */
int dfl_rfunc_acc_is_zero(const dfl_rfunc_acc *acc);
/* u (and gradient into gu when accumulated; gu may be NULL).  Needs at
 * least one part.  u = 0 and gradient 0 on the zero set; NaN (value and
 * gradient) where eq. 20 (DFL_RFUNC_CORR_EQ20) is undefined. */
double dfl_rfunc_acc_end(const dfl_rfunc_acc *acc, double *gu);

/* Jet of the join from the parts' jets h[0..n-1] (n >= 1) and, for the
 * corrected join, the guarded vertex distances' jets q[0..nq-1] (ignored
 * otherwise).  DFL_E_NUMERIC if coefficients overflow (a ray through one
 * part within ~1e-25 of another one). */
dfl_status dfl_rfunc_join_jet(dfl_rfunc_join join, int p, size_t n, const dfl_jet *h,
                              size_t nq, const dfl_jet *q, dfl_jet *out, dfl_err *err);
/* The same for the corrected join's form corr (ignored by the other
 * joins): with DFL_RFUNC_CORR_EQ20, q are the raw vertex distances' jets,
 * and where the radicand's jet is not positive as s -> 0+ (eq. 20 is
 * undefined on the ray's start) *out is a jet of NaN coefficients
 * (valuation 0, n = K + 1 from the parts) and DFL_OK is returned. */
dfl_status dfl_rfunc_join_jet_corr(dfl_rfunc_join join, dfl_rfunc_correction corr, int p,
                                   size_t n, const dfl_jet *h, size_t nq, const dfl_jet *q,
                                   dfl_jet *out, dfl_err *err);

#endif
