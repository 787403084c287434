/* One proxy: its encoding into stored scalars, their decoding into a
 * plane / cylinder / sphere / torus, and the exact distance to it
 * (hvb25 Sec. 4 and 6, eq. 5-10, derived below because the extraction
 * garbles them and dflab's curvature sign differs from the paper's).
 *
 * Function index
 *   dfl_proxy_geom           a decoded proxy: footpoint, frame, curvatures
 *   DFL_PROXY_NSCALAR(order) stored scalars per proxy: 3 (order 1), 8 (order 2)
 *   dfl_proxy_encode         a surface point seen from a cell centre -> scalars
 *   dfl_proxy_decode         stored scalars (loaded as double) -> dfl_proxy_geom
 *   dfl_proxy_geom_eval      signed distance to the proxy and its gradient
 *
 * Stored scalars (in this order; "pos" is the footpoint p, as p - x_c or as
 * p, see store.h):
 *   order 1: pos (3).  The normal is n = sigma (x_c - p) / |x_c - p|, with
 *            sigma = +1, or the side of x_c (a separate sign byte, proxy.h)
 *            when the input has an inside; the proxy is the plane (p, n).
 *   order 2: pos (3), kappa_r, kappa_R, L t (3).  kappa_r is the principal
 *            curvature of larger magnitude (|kappa_r| >= |kappa_R|), t its
 *            unit principal direction; n = s (p - x_c) / |p - x_c| (eq. 5)
 *            and the sign s = +1 | -1 is folded into t's length:
 *            L = 1 for s = +1, L = 2 for s = -1 (decoded as |Lt|^2 > 2.25).
 *            Curvatures follow geom/curvature.h: dn(e) = kappa e, a sphere
 *            with outward normal has kappa = +1/r and its centre at
 *            p - n / kappa (the paper's eq. 7, 9 take the opposite sign).
 *
 * The decoding, derived (v = x - p, v_n = v.n, v_t = v.t, v_b = v.b with
 * b = n x t; all formulas hold for any signs of the curvatures and stay
 * finite as they go to 0):
 *   1. The signed distance (positive on n's side) from a point at in-plane
 *      offset (a, z) to a circle through p with normal n and curvature k
 *      (centre at p - n/k) is
 *          C(a, z; k) = (k (a^2 + z^2) + 2 a) / (1 + S),
 *          S = sqrt((1 + k a)^2 + (k z)^2),
 *      i.e. |(a,z) + n/k| - 1/k rationalised, so k = 0 gives the line
 *      C = a without cancellation; its gradient is ((1 + k a), k z) / S.
 *   2. The osculating torus has the footpoint on an equator (the paper's
 *      assumption): its tube is the circle of curvature kappa_r in the
 *      plane (n, t) through p, its equator through p the circle of
 *      curvature kappa_R in the plane (n, b), with centre
 *      c = p - n / kappa_R on the axis (direction t).  Rotating x about
 *      that axis into the meridian half-plane of p moves it to the offset
 *          a = C(v_n, v_b; kappa_R)   along n (signed radial offset),
 *          z = v_t                    along t,
 *      and the distance to the surface of revolution is the distance to
 *      the tube circle there:
 *          phi(x) = C(a, v_t; kappa_r).
 *      Then R' = 1/|kappa_R| (eq. 8's circle of p), r = 1/|kappa_r| and
 *      the core radius is R = |1/kappa_R - 1/kappa_r|: R' + r when the
 *      curvatures have opposite signs (p on the inner equator, hyperbolic),
 *      R' - r when they agree (outer equator, elliptic), as eq. 8 states.
 *      Choosing |kappa_r| >= |kappa_R| (the paper: t along the larger
 *      curvature) keeps the tube on p's side of the axis (R' >= r), so p
 *      lies on the outer equator of a ring, horn or spindle torus (same
 *      signs) or the inner equator of a ring torus (opposite signs); the
 *      formula itself matches the surface to second order at p either way.
 *   3. The cases of eq. 10 are limits of this one formula, with no branch:
 *      kappa_R = 0 gives a = v_n, a cylinder about the line through
 *      p - n/kappa_r along b (eq. 6-7); kappa_r = kappa_R = 0 the plane
 *      phi = v_n (eq. 5); kappa_r = kappa_R the sphere (R = 0, the
 *      umbilic case): phi = |x - c| - 1/kappa.
 *   phi is the exact signed distance to a ring torus (R >= r), a cylinder,
 *   a sphere or a plane; for a spindle torus (R < r) it is the distance to
 *   the surface of revolution of the whole tube circle, exact near p.
 *   grad phi = ((1 + kappa_r a) grad a + kappa_r v_t t) / S_r with
 *   grad a = ((1 + kappa_R v_n) n + kappa_R v_b b) / S_R (a zero S, on the
 *   axis or the tube's core, falls back to the inner gradient, resp. n).
 *
 * Pure functions, no allocation, thread-safe.
 */
#ifndef DFL_PROXY_DECODE_H
#define DFL_PROXY_DECODE_H

#include <math.h>

#include "core/vec.h"
#include "proxy/input.h"
#include "proxy/store.h"

#define DFL_PROXY_NSCALAR(order) ((order) == 1 ? 3 : 8)
#define DFL_PROXY_NSCALAR_MAX 8

typedef struct dfl_proxy_geom {
    double p[3];    /* footpoint */
    double n[3];    /* unit normal; phi > 0 on its side */
    double t[3];    /* unit, orthogonal to n: direction of kr (order 2) */
    double b[3];    /* n x t */
    double kr, kR;  /* principal curvatures w.r.t. n (0 for order 1) */
} dfl_proxy_geom;

/* The logical scalars of the proxy of sp seen from the cell centre xc, with
 * the footpoint as an absolute position in s[0..2] (the grid builder turns
 * it into a displacement when asked).  offset (may be NULL) is added to the
 * footpoint first (the noise study).  When |p - xc| < delta (a cell centre
 * on the surface, whose normal p - xc cannot carry) the footpoint moves to
 * xc - delta n along the input's normal n, an error of at most 2 delta.
 * *side receives the side of xc (+1 when sp->d >= 0, else -1).  Order 2
 * needs sp->curv (finite).  Returns 1 when the footpoint was moved, else 0.
 * s must hold DFL_PROXY_NSCALAR(order) doubles. */
int dfl_proxy_encode(int order, const double xc[3], const dfl_surfpoint *sp,
                     const double *offset, double delta, double *s, int *side);

/* Decodes the scalars s (as stored, loaded as double) of the cell with
 * centre xc.  side is the order-1 sign (+1 when the grid has no signs;
 * ignored for order 2).  A footpoint equal to xc (only possible from a
 * corrupt grid) gives a NaN normal.  (Inline: the filters' hot path.) */
static inline void dfl_proxy_decode(int order, dfl_proxy_position pos, const double xc[3],
                                    const double *s, int side, dfl_proxy_geom *g);

/* phi(x), the signed distance to the proxy (positive on n's side; exact,
 * see above), and its gradient into grad when grad is not NULL.  order 1
 * evaluates the plane only (kr, kR, t, b unread).  (Inline.) */
static inline double dfl_proxy_geom_eval(const dfl_proxy_geom *g, int order, const double x[3],
                                         double *grad);

/* ---- inline bodies; the order of operations keeps every formula finite
 * at zero curvature (no 1/kappa anywhere) */

static inline void dfl_proxy_decode(int order, dfl_proxy_position pos, const double xc[3], const double *s,
                      int side, dfl_proxy_geom *g)
{
    double d[3];
    for (int j = 0; j < 3; j++) {
        if (pos == DFL_PROXY_DISPLACEMENT) {
            d[j] = s[j];
            g->p[j] = xc[j] + s[j];
        } else {
            g->p[j] = s[j];
            d[j] = s[j] - xc[j];
        }
    }
    const double dl = dfl_vec3_norm(d);
    if (order == 1) {
        /* n points from the footpoint to xc, flipped inside. */
        const double f = -(double)side / dl;
        for (int j = 0; j < 3; j++) g->n[j] = f * d[j];
        g->kr = g->kR = 0.0;
        for (int j = 0; j < 3; j++) g->t[j] = g->b[j] = 0.0;
        return;
    }
    const double *lt = s + 5;
    const double l2 = dfl_vec3_dot(lt, lt);
    const double sgn = l2 > 2.25 ? -1.0 : 1.0;
    const double in = sgn / dl;
    for (int j = 0; j < 3; j++) g->n[j] = in * d[j];
    /* t is orthogonal to n up to the storage's rounding; project it back
     * so that (n, t, b) is orthonormal. */
    const double tn = dfl_vec3_dot(lt, g->n);
    double t[3];
    for (int j = 0; j < 3; j++) t[j] = lt[j] - tn * g->n[j];
    const double it = 1.0 / dfl_vec3_norm(t);
    for (int j = 0; j < 3; j++) g->t[j] = it * t[j];
    dfl_vec3_cross(g->n, g->t, g->b);
    g->kr = s[3];
    g->kR = s[4];
}

static inline double dfl_proxy_geom_eval(const dfl_proxy_geom *g, int order, const double x[3], double *grad)
{
    const double v[3] = {x[0] - g->p[0], x[1] - g->p[1], x[2] - g->p[2]};
    const double vn = dfl_vec3_dot(v, g->n);
    if (order == 1) {
        if (grad)
            for (int j = 0; j < 3; j++) grad[j] = g->n[j];
        return vn;
    }
    const double vt = dfl_vec3_dot(v, g->t), vb = dfl_vec3_dot(v, g->b);
    const double kR = g->kR, kr = g->kr;
    /* radial offset in p's meridian half-plane: the equator circle */
    const double uR = 1.0 + kR * vn, wR = kR * vb;
    const double SR = sqrt(uR * uR + wR * wR);
    const double a = (kR * (vn * vn + vb * vb) + 2.0 * vn) / (1.0 + SR);
    /* distance to the tube circle */
    const double ur = 1.0 + kr * a, wr = kr * vt;
    const double Sr = sqrt(ur * ur + wr * wr);
    const double phi = (kr * (a * a + vt * vt) + 2.0 * a) / (1.0 + Sr);
    if (grad) {
        double ga[3];
        if (SR > 0) {
            const double i = 1.0 / SR;
            for (int j = 0; j < 3; j++) ga[j] = i * (uR * g->n[j] + wR * g->b[j]);
        } else {
            for (int j = 0; j < 3; j++) ga[j] = g->n[j];
        }
        if (Sr > 0) {
            const double i = 1.0 / Sr;
            for (int j = 0; j < 3; j++) grad[j] = i * (ur * ga[j] + wr * g->t[j]);
        } else {
            for (int j = 0; j < 3; j++) grad[j] = ga[j];
        }
    }
    return phi;
}

#endif
