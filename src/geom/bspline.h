/* B-spline and Bezier curves of any order in R^1..R^3.
 *
 * A curve of order k (degree p = k - 1, 2 <= k <= DFL_BSPLINE_MAX_ORDER) is
 * stored in one general form: n control points P_0..P_{n-1} (dim doubles
 * each) and a knot vector tau_0..tau_{n+k-1}, non-decreasing.  The curve is
 * C(t) = sum_i N_{i,k}(t) P_i on the domain [t0, t1] = [tau_{k-1}, tau_n].
 *
 *   open curves: the knot vector is given by the user (n + k values) or is
 *     the clamped uniform one (k-fold end knots, interior knots 1..n-k at
 *     unit spacing, domain [0, n-k+1]).  Unclamped knot vectors are allowed
 *     (the domain is still [tau_{k-1}, tau_n]).
 *   closed (periodic) curves: the user gives m distinct control points and
 *     m + 1 breakpoints u_0 <= ... <= u_m (period T = u_m - u_0 > 0; default
 *     0, 1, ..., m).  Internally the first p points are appended again
 *     (n = m + p) and the knots are extended periodically,
 *     tau_{p+j} = u_{j mod m} + floor(j/m) T for j = -p .. m + p, so that C is
 *     T-periodic and C^{p-mult} at each breakpoint of multiplicity mult.
 *     Parameters outside [t0, t1) are wrapped (dfl_bspline_wrap).
 *   Bezier curves: the B-spline with knots (0^k, 1^k), domain [0, 1].
 *
 * Derivatives are parametric, d^r C / dt^r, available to any order (zero
 * beyond the degree); at a knot they are the right-sided ones, except at t1
 * of an open curve (left-sided), unless a side is requested explicitly.
 *
 * Ownership: dfl_bspline_init* allocate cp and knots; dfl_bspline_free
 * releases them.  A dfl_bspline is read-only after init and may be shared by
 * threads.  No function except init allocates.
 */
#ifndef DFL_GEOM_BSPLINE_H
#define DFL_GEOM_BSPLINE_H

#include <stddef.h>

#include "core/status.h"

#define DFL_BSPLINE_MAX_ORDER 16

typedef struct dfl_bspline {
    int dim;         /* 1..3 */
    int order;       /* k, 2..DFL_BSPLINE_MAX_ORDER */
    int closed;      /* 1: periodic (wrapped control points, periodic knots) */
    size_t n;        /* number of control points in the general form */
    size_t nuser;    /* control points given by the user (closed: n - (k-1)) */
    double *cp;      /* n*dim */
    double *knots;   /* n + k */
    double t0, t1;   /* parameter domain */
} dfl_bspline;

/* Validates a knot vector for an open curve: nknots == ncp + order,
 * finite, non-decreasing, interior multiplicity <= order - 1, end
 * multiplicity <= order, non-empty domain tau_{k-1} < tau_{ncp}.
 * For a closed curve (periodic != 0) it validates ncp + 1 breakpoints
 * (non-decreasing, multiplicity <= order - 1, u_m > u_0).
 * DFL_E_INPUT with a message that states what was expected. */
dfl_status dfl_bspline_check_knots(int order, size_t ncp, const double *knots, size_t nknots,
                                   int periodic, dfl_err *err);

/* Validates control points: finite, at least `order` of them for an open
 * curve (at least 3 for a closed one), not all coincident (extent > 0).
 * DFL_E_INPUT otherwise. */
dfl_status dfl_bspline_check_control(int dim, int order, size_t ncp, const double *cp,
                                     int periodic, dfl_err *err);

/* Open curve.  knots may be NULL (clamped uniform); otherwise nknots must be
 * ncp + order.  DFL_E_INPUT for invalid data (order out of range, see the
 * check functions), DFL_E_NOMEM.  *out is untouched on failure. */
dfl_status dfl_bspline_init(int dim, int order, size_t ncp, const double *cp,
                            const double *knots, size_t nknots, dfl_bspline *out, dfl_err *err);

/* Closed periodic curve through m = ncp distinct control points; breaks may
 * be NULL (uniform 0..m), otherwise nbreaks must be ncp + 1. */
dfl_status dfl_bspline_init_periodic(int dim, int order, size_t ncp, const double *cp,
                                     const double *breaks, size_t nbreaks, dfl_bspline *out,
                                     dfl_err *err);

/* Bezier curve of degree ncp - 1 (ncp >= 2) on [0, 1]. */
dfl_status dfl_bspline_init_bezier(int dim, size_t ncp, const double *cp, dfl_bspline *out,
                                   dfl_err *err);

/* Deep copy (DFL_E_NOMEM). */
dfl_status dfl_bspline_copy(const dfl_bspline *c, dfl_bspline *out, dfl_err *err);

/* Releases cp and knots and zeroes *c.  c may be NULL or already freed. */
void dfl_bspline_free(dfl_bspline *c);

/* Closed: t mapped into [t0, t1) modulo the period.  Open: t clamped to
 * [t0, t1]. */
double dfl_bspline_wrap(const dfl_bspline *c, double t);

/* 1 if the curve is closed: periodic, or open with first and last points
 * C(t0), C(t1) within tol * (1 + extent of the control points). */
int dfl_bspline_is_closed(const dfl_bspline *c, double tol);

/* Index j of the non-empty knot span [tau_j, tau_{j+1}) holding t (t is
 * wrapped/clamped first), k-1 <= j <= n-1.  side < 0 picks the span to the
 * left when t is exactly a knot (and t > t0); side >= 0 the right one (at
 * t1 of an open curve: the last span). */
size_t dfl_bspline_span(const dfl_bspline *c, double t, int side);

/* The same on a raw knot vector U of an open spline with n control points
 * (domain [U[order-1], U[n]]; t clamped into it). */
size_t dfl_knot_span(const double *U, int order, size_t n, double t, int side);

/* Number of non-empty spans in the domain, and the index of the s-th one
 * (0 <= s < count) in knot numbering. */
size_t dfl_bspline_span_count(const dfl_bspline *c);
size_t dfl_bspline_span_index(const dfl_bspline *c, size_t s);

/* Basis functions N_{span-p..span} and their derivatives of order 0..nder
 * at t in span: ders[r*order + i] = d^r/dt^r N_{span-p+i}(t).  Any nder >= 0
 * (orders above the degree are zero); ders holds (nder+1)*order doubles.
 * knots must give a non-empty span [knots[span], knots[span+1]). */
void dfl_bspline_basis(const double *knots, int order, size_t span, double t, int nder,
                       double *ders);

/* Curve derivatives of order 0..nder at t: out[r*dim + j] = d^r C_j/dt^r.
 * out holds (nder+1)*dim doubles.  side as in dfl_bspline_span. */
void dfl_bspline_eval(const dfl_bspline *c, double t, int nder, double *out);
void dfl_bspline_eval_side(const dfl_bspline *c, double t, int side, int nder, double *out);

/* Bezier control points (order points, dim doubles each) of the polynomial
 * piece of span j restricted to [a, b] (a, b any reals; usually inside the
 * span).  Computed by blossoming: b_i = f(a^(p-i), b^i). */
void dfl_bspline_span_bezier(const dfl_bspline *c, size_t span, double a, double b,
                             double *bez);

/* The same for raw data: the order control points of one span
 * (cp_span[i*dim + j] = P_{span-p+i}), the knot vector and span index,
 * shared by curves and tensor-product surfaces. */
void dfl_blossom_bezier(const double *knots, int order, size_t span, const double *cp_span,
                        int dim, double a, double b, double *bez);

/* de Casteljau: splits the Bezier curve bez (np points of dim) at s in
 * [0, 1] into left and right halves (np points each).  left/right may not
 * alias bez. */
void dfl_bezier_split(const double *bez, int np, int dim, double s, double *left,
                      double *right);

/* Bezier curve value at s by de Casteljau (np <= DFL_BSPLINE_MAX_ORDER). */
void dfl_bezier_eval(const double *bez, int np, int dim, double s, double *out);

#endif
