/* bs04 sec. 2.2-2.3 and 4.2: joins, gradient bounds at joining points,
 * (non-)associativity, the corrected join. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "rfunc/join.h"
#include "rfunc/rfield.h"
#include "rfunc/segment.h"
#include "rfunc_util.h"

static const int bound_orders[3] = {2, 7, 12};

/* eq. 14 against central differences of eq. 6, and the properties sec. 2.3
 * states: F1 + F2 <= 1 with its minimum 2^(-1/p) at phi = pi/4, |F1 - F2|
 * <= 1 and = 0 at pi/4, both = 1 at phi = 0 and pi/2; a larger p raises the
 * upper bound everywhere. */
Test(rfunc_join, eq14_partials_and_bounds)
{
    for (int ip = 0; ip < 3; ip++) {
        const int p = bound_orders[ip];
        double minsum = INFINITY, argmin = -1;
        for (int i = 0; i <= 400; i++) {
            const double phi = (DFL_PI / 2) * i / 400.0;
            double F1, F2;
            dfl_rfunc_requiv_partials_polar(phi, p, &F1, &F2);
            const double h1 = cos(phi), h2 = sin(phi), e = 1e-6;
            if (i > 0 && i < 400) {
                const double d1 = (dfl_rfunc_requiv2(h1 + e, h2, p, NULL, NULL) -
                                   dfl_rfunc_requiv2(h1 - e, h2, p, NULL, NULL)) /
                                  (2 * e);
                const double d2 = (dfl_rfunc_requiv2(h1, h2 + e, p, NULL, NULL) -
                                   dfl_rfunc_requiv2(h1, h2 - e, p, NULL, NULL)) /
                                  (2 * e);
                cr_assert_float_eq(F1, d1, 1e-7, "p=%d phi=%g", p, phi);
                cr_assert_float_eq(F2, d2, 1e-7);
                double A1, A2;
                dfl_rfunc_requiv2(h1, h2, p, &A1, &A2);
                cr_assert_float_eq(F1, A1, 1e-13);
                cr_assert_float_eq(F2, A2, 1e-13);
            }
            cr_assert(F1 + F2 <= 1 + 1e-15);
            cr_assert(fabs(F1 - F2) <= 1 + 1e-15);
            if (F1 + F2 < minsum) {
                minsum = F1 + F2;
                argmin = phi;
            }
            if (p > 2) {
                double G1, G2;
                dfl_rfunc_requiv_partials_polar(phi, bound_orders[ip - 1], &G1, &G2);
                cr_assert(F1 + F2 >= G1 + G2 - 1e-15, "upper bound grows with p");
            }
        }
        cr_assert_float_eq(argmin, DFL_PI / 4, 1e-12);
        cr_assert_float_eq(minsum, pow(2.0, -1.0 / p), 1e-14);
        double F1, F2;
        dfl_rfunc_requiv_partials_polar(DFL_PI / 4, p, &F1, &F2);
        cr_assert(fabs(F1 - F2) < 1e-15);
        dfl_rfunc_requiv_partials_polar(0, p, &F1, &F2);
        cr_assert_float_eq(F2 - F1, 1.0, 1e-15);
        dfl_rfunc_requiv_partials_polar(DFL_PI / 2, p, &F1, &F2);
        cr_assert_float_eq(F1 - F2, 1.0, 1e-15);
    }
}

/* Directional model of |grad u| at the joining point: at radius eps -> 0 the
 * trimmed fields equal the exact distances to the two rays from the vertex
 * (first-order normalization in the generalized sense, bs04 sec. 2.1), so
 * |grad u|(theta) -> G(theta) computed from exact ray distances: h_i = |P x
 * u_i| with gradient the normal on P's side when P . u_i >= 0, else h_i = 1
 * (the vertex) with gradient P, joined by eq. 6 (F_i = (u/h_i)^(p+1)). */
static double model_grad(double th, const double *u1, const double *u2, int p)
{
    const double P[2] = {cos(th), sin(th)};
    const double *u[2] = {u1, u2};
    double h[2], g[2][2];
    for (int i = 0; i < 2; i++) {
        const double pu = P[0] * u[i][0] + P[1] * u[i][1];
        if (pu >= 0) {
            const double cr = P[0] * u[i][1] - P[1] * u[i][0];
            h[i] = fabs(cr);
            /* normal (u_y, -u_x) points to the side where cr > 0 */
            const double sg = cr >= 0 ? 1.0 : -1.0;
            g[i][0] = sg * u[i][1];
            g[i][1] = -sg * u[i][0];
        } else {
            h[i] = 1.0;
            g[i][0] = P[0];
            g[i][1] = P[1];
        }
    }
    double F1, F2;
    dfl_rfunc_requiv2(h[0], h[1], p, &F1, &F2);
    return hypot(F1 * g[0][0] + F2 * g[1][0], F1 * g[0][1] + F2 * g[1][1]);
}

/* Measured |grad u| on small circles (radius eps) around the joining point
 * of two unit segments at angle alpha = 10..350 degrees, R-equivalence of
 * order 2, 7, 12, disk and strip trims.
 * (1) eq. 17 with the triangle inequality: |F1 |g1| - F2 |g2|| <= |grad u|
 *     <= F1 |g1| + F2 |g2| exactly (to rounding);
 * (2) eq. 13-14: |F1 - F2| <= |grad u| <= F1 + F2 up to the deviation of
 *     |grad h_i| from 1 near the end point, which is O(eps/d) (trim.h: h =
 *     q sqrt(1 + c q/R + q^2/(4R^2)) beyond the end point, |grad h| = 1 +
 *     2 c q/d + O(q^2), |c| <= 1): tolerance 3 eps/d;
 * (3) |grad u| = G(theta) of the directional model above, to O(eps);
 * (4) on the bisector of the convex sector (angle beta = min(alpha, 2pi -
 *     alpha)) h1 = h2 (Phi = pi/4), both gradients are the segments' unit
 *     normals (the foot points are interior) at angle pi - beta, so
 *     |grad u| = 2 * 2^(-(p+1)/p) cos((pi - beta)/2) = 2^(-1/p) sin(beta/2).
 * (5) Where the minimum is.  bs04 sec. 2.3 says it is always on the
 *     bisector.  The model shows another candidate: in the sectors where one
 *     foot point is the vertex (h_j = q, grad h_j radial) and the other is
 *     interior (h_i = q sigma, sigma = sin of the angle to segment i, and
 *     cos(angle of the gradients) = sigma), eq. 17 gives
 *         g_p(sigma)^2 = (1 + sigma^(2p+2) + 2 sigma^(p+2)) / (1 + sigma^p)^(2(p+1)/p),
 *     independent of alpha, and sigma covers (0, 1) there once beta is
 *     obtuse.  Its minimum m_p (sampled below: 0.6869 for p = 2, 0.8952
 *     for p = 7, 0.9370 for p = 12) is below the bisector value when
 *     2^(-1/p) sin(beta/2) > m_p, i.e. beta > 152.5, 162.5, 166.2 degrees.
 *     So the minimum is on the bisector for beta <= 150 degrees and off it,
 *     in the mixed sectors, for beta >= 170 degrees: a correction to the
 *     paper's statement (the bulging is worst off the bisector there). */
Test(rfunc_join, gradient_bounds_near_joining_point)
{
    const double eps = 1e-6;
    const dfl_rfunc_trim tr[2] = {DFL_RFUNC_TRIM_DISK, DFL_RFUNC_TRIM_STRIP};
    for (int ip = 0; ip < 3; ip++) {
        const int p = bound_orders[ip];
        double mp = INFINITY;
        for (int i = 0; i <= 100000; i++) {
            const double sg = i / 100000.0;
            const double g2 = (1 + pow(sg, 2 * p + 2) + 2 * pow(sg, p + 2)) /
                              pow(1 + pow(sg, p), 2.0 * (p + 1) / p);
            mp = fmin(mp, sqrt(g2));
        }
        for (int it = 0; it < 2; it++)
            for (int adeg = 10; adeg <= 350; adeg += 10) {
                const double al = adeg * DFL_PI / 180;
                const double v[6] = {1.0, 0.0, 0.0, 0.0, cos(al), sin(al)};
                const double u1[2] = {1.0, 0.0}, u2[2] = {cos(al), sin(al)};
                dfl_rfunc_seg s1, s2;
                cr_assert_eq(dfl_rfunc_seg_init(2, v + 2, v, tr[it], &s1, NULL), DFL_OK);
                cr_assert_eq(dfl_rfunc_seg_init(2, v + 2, v + 4, tr[it], &s2, NULL), DFL_OK);
                dfl_field f;
                cr_assert_eq(dfl_rfield_polyline(2, v, 3, false, DFL_RFUNC_REQUIV, p, tr[it], &f,
                                                 NULL),
                             DFL_OK);
                const double beta = adeg <= 180 ? al : 2 * DFL_PI - al;
                const double bis = adeg <= 180 ? al / 2 : al / 2 + DFL_PI;
                double xb[2] = {eps * cos(bis), eps * sin(bis)}, gb[2];
                dfl_field_eval1(&f, xb, gb);
                const double gbis = hypot(gb[0], gb[1]);
                const double expect = pow(2.0, -1.0 / p) * sin(beta / 2);
                cr_assert(fabs(gbis - expect) <= (adeg == 180 ? 3 * eps : 1e-12),
                          "alpha %d p %d: bisector |grad u| = %.15g, expected %.15g", adeg, p,
                          gbis, expect);
                double gmin = INFINITY, thmin = 0;
                const int N = 1440;
                for (int i = 0; i < N; i++) {
                    const double th = 2 * DFL_PI * i / N;
                    const double x[2] = {eps * cos(th), eps * sin(th)};
                    double g[2], g1[2], g2[2];
                    dfl_field_eval1(&f, x, g);
                    const double h1 = dfl_rfunc_seg_eval(&s1, x, g1);
                    const double h2 = dfl_rfunc_seg_eval(&s2, x, g2);
                    if (h1 == 0.0 || h2 == 0.0) continue; /* on a segment: zero set */
                    const double gu = hypot(g[0], g[1]);
                    const double n1 = hypot(g1[0], g1[1]), n2 = hypot(g2[0], g2[1]);
                    double F1, F2;
                    dfl_rfunc_requiv_partials_polar(atan2(h2, h1), p, &F1, &F2);
                    cr_assert(gu <= F1 * n1 + F2 * n2 + 1e-12);
                    cr_assert(gu >= fabs(F1 * n1 - F2 * n2) - 1e-12);
                    cr_assert(fabs(n1 - 1) <= 3 * eps && fabs(n2 - 1) <= 3 * eps,
                              "alpha %d th %g: |grad h| = %.15g %.15g", adeg, th, n1, n2);
                    cr_assert(gu <= F1 + F2 + 3 * eps, "alpha %d th %g: %g > %g", adeg, th, gu,
                              F1 + F2);
                    cr_assert(gu >= fabs(F1 - F2) - 3 * eps);
                    cr_assert(gu > 0 && gu < 1 + 3 * eps);
                    const double gm = model_grad(th, u1, u2, p);
                    cr_assert(fabs(gu - gm) <= 5 * eps, "alpha %d th %g: %.12g vs model %.12g",
                              adeg, th, gu, gm);
                    if (gu < gmin) {
                        gmin = gu;
                        thmin = th;
                    }
                }
                const double dth = fabs(remainder(thmin - bis, 2 * DFL_PI));
                if (beta <= 150 * DFL_PI / 180 + 1e-9) {
                    cr_assert(gbis <= gmin * (1 + 1e-12) + (adeg == 180 ? 3 * eps : 0.0),
                              "alpha %d p %d: bisector %.15g vs circle min %.15g", adeg, p, gbis,
                              gmin);
                    cr_assert(dth <= 2 * DFL_PI / N + 1e-12, "alpha %d p %d: argmin off bisector",
                              adeg, p);
                } else if (beta >= 170 * DFL_PI / 180 - 1e-9) {
                    cr_assert(gmin < gbis - 1e-4, "alpha %d p %d: min %.12g, bisector %.12g", adeg,
                              p, gmin, gbis);
                    cr_assert(fabs(gmin - mp) <= 1e-5 + 5 * eps, "alpha %d p %d: %g vs m_p %g",
                              adeg, p, gmin, mp);
                }
                dfl_field_destroy(&f);
            }
    }
}

/* R-conjunction is not associative: the left fold depends on the order;
 * R-equivalence is, to rounding. */
Test(rfunc_join, associativity)
{
    const double vals[3] = {1.0, 1.3, 1.1};
    const int perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (int p = 2; p <= 12; p++) {
        double req[6], rc[6];
        for (int k = 0; k < 6; k++) {
            dfl_rfunc_acc a, b;
            dfl_rfunc_acc_begin(&a, DFL_RFUNC_REQUIV, p, 2, 0);
            dfl_rfunc_acc_begin(&b, DFL_RFUNC_RCONJ, p, 2, 0);
            for (int i = 0; i < 3; i++) {
                dfl_rfunc_acc_add(&a, vals[perm[k][i]], NULL);
                dfl_rfunc_acc_add(&b, vals[perm[k][i]], NULL);
            }
            req[k] = dfl_rfunc_acc_end(&a, NULL);
            rc[k] = dfl_rfunc_acc_end(&b, NULL);
        }
        /* The closed form (sum h^-p)^(-1/p). */
        double S = 0;
        for (int i = 0; i < 3; i++) S += pow(vals[i], -p);
        double spread = 0;
        for (int k = 0; k < 6; k++) {
            cr_assert_float_eq(req[k], pow(S, -1.0 / p), 1e-15);
            spread = fmax(spread, fabs(rc[k] - rc[0]));
        }
        /* (a ^ b) ^ c vs a ^ (b ^ c) (perm 3 = (b, c, a) folds to
         * (b ^ c) ^ a = a ^ (b ^ c) by commutativity). */
        /* The difference shrinks as p grows (a ^ b -> min(a, b)), but stays
         * orders of magnitude above rounding (1e-16). */
        cr_assert(fabs(rc[3] - rc[0]) > 1e-10 * rc[0], "p=%d: %g vs %g", p, rc[0], rc[3]);
        cr_assert(spread > 1e-10 * rc[0]);
        /* Commutative in each pair: (a ^ b) ^ c == (b ^ a) ^ c. */
        cr_assert_float_eq(rc[0], rc[2], 1e-15);
    }
    /* Hand value, p = 2: (1 ^ 2) ^ 3 with x ^ y = x + y - sqrt(x^2 + y^2). */
    const double a12 = 3 - sqrt(5.0);
    const double lhs = a12 + 3 - sqrt(a12 * a12 + 9);
    const double b23 = 5 - sqrt(13.0);
    const double rhs = 1 + b23 - sqrt(1 + b23 * b23);
    cr_assert_float_eq(dfl_rfunc_rconj2(dfl_rfunc_rconj2(1, 2, 2, NULL, NULL), 3, 2, NULL, NULL),
                       lhs, 1e-15);
    cr_assert_float_eq(dfl_rfunc_rconj2(1, dfl_rfunc_rconj2(2, 3, 2, NULL, NULL), 2, NULL, NULL),
                       rhs, 1e-15);
    cr_assert(fabs(lhs - rhs) > 1e-3);

    /* The same on fields: a polyline and its reversal. */
    const double v[] = {0, 0, 1, 0.3, 1.5, 1.2, 2.6, 1.0};
    double w[8];
    for (int i = 0; i < 4; i++) {
        w[2 * i] = v[2 * (3 - i)];
        w[2 * i + 1] = v[2 * (3 - i) + 1];
    }
    for (int p = 2; p <= 12; p += 5) {
        dfl_field fr, fw, cr, cw;
        cr_assert_eq(dfl_rfield_polyline(2, v, 4, false, DFL_RFUNC_REQUIV, p, DFL_RFUNC_TRIM_DISK, &fr, NULL), DFL_OK);
        cr_assert_eq(dfl_rfield_polyline(2, w, 4, false, DFL_RFUNC_REQUIV, p, DFL_RFUNC_TRIM_DISK, &fw, NULL), DFL_OK);
        cr_assert_eq(dfl_rfield_polyline(2, v, 4, false, DFL_RFUNC_RCONJ, p, DFL_RFUNC_TRIM_DISK, &cr, NULL), DFL_OK);
        cr_assert_eq(dfl_rfield_polyline(2, w, 4, false, DFL_RFUNC_RCONJ, p, DFL_RFUNC_TRIM_DISK, &cw, NULL), DFL_OK);
        uint64_t rng = 99;
        double dmax = 0;
        for (int i = 0; i < 200; i++) {
            const double x[2] = {tu_uniform(&rng, -1, 3.5), tu_uniform(&rng, -1, 2.5)};
            const double a = dfl_field_eval1(&fr, x, NULL), b = dfl_field_eval1(&fw, x, NULL);
            cr_assert(fabs(a - b) <= 1e-15 * (1 + a));
            dmax = fmax(dmax, fabs(dfl_field_eval1(&cr, x, NULL) - dfl_field_eval1(&cw, x, NULL)));
        }
        cr_assert(dmax > 1e-6, "R-conjunction fold order should matter (p=%d: %g)", p, dmax);
        dfl_field_destroy(&fr);
        dfl_field_destroy(&fw);
        dfl_field_destroy(&cr);
        dfl_field_destroy(&cw);
    }
}

/* Corrected join (eq. 20), bs04 Fig. 14.  Two segments from the vertex at the
 * origin at angle alpha > pi; the hatched sector is theta in
 * [pi/2, alpha - pi/2] (the closest point of both segments is the vertex).
 * (1) With exact segment distances (the paper's premise h1 = h2 = q), the
 *     corrected join is u = q there, |grad u| = 1 to rounding at every
 *     radius, while eq. 6 gives 2^(-1/p).
 * (2) With the trimmed fields h_i = q (1 + c_i q/d + ...) (trim.h), u = q (1
 *     + (c1 + c2) q/d + ...) and | |grad u| - 1 | <= 5 q/d for small q
 *     (c_i <= 1; the radial derivative of q (1 + 2q/d) is 1 + 4q/d, the
 *     angular one O(q/d)): |grad u| = 1 to 1e-9 within q <= 1e-10 d. */
static double seg_dist(const double *x, const double *a, const double *b, double *g)
{
    const double ex = b[0] - a[0], ey = b[1] - a[1];
    double l = ((x[0] - a[0]) * ex + (x[1] - a[1]) * ey) / (ex * ex + ey * ey);
    l = fmin(1, fmax(0, l));
    const double wx = x[0] - a[0] - l * ex, wy = x[1] - a[1] - l * ey;
    const double dd = hypot(wx, wy);
    g[0] = wx / dd;
    g[1] = wy / dd;
    return dd;
}

Test(rfunc_join, corrected_join_hatched_sector)
{
    const int alphas[3] = {200, 240, 300};
    for (int ia = 0; ia < 3; ia++)
        for (int p = 1; p <= 12; p++) {
            const double al = alphas[ia] * DFL_PI / 180;
            const double v[6] = {1.0, 0.0, 0.0, 0.0, cos(al), sin(al)};
            dfl_field fc, fr;
            cr_assert_eq(dfl_rfield_polyline(2, v, 3, false, DFL_RFUNC_REQUIV_CORRECTED, p,
                                             DFL_RFUNC_TRIM_DISK, &fc, NULL),
                         DFL_OK);
            cr_assert_eq(dfl_rfield_polyline(2, v, 3, false, DFL_RFUNC_REQUIV, p,
                                             DFL_RFUNC_TRIM_DISK, &fr, NULL),
                         DFL_OK);
            const double lo = DFL_PI / 2, hi = al - DFL_PI / 2;
            for (int i = 1; i < 20; i++) {
                const double th = lo + (hi - lo) * i / 20.0;
                const double radii[5] = {1e-3, 0.1, 1.0, 10.0, 1e3};
                for (int ir = 0; ir < 5; ir++) {
                    /* (1) exact distances through the accumulator. */
                    const double x[2] = {radii[ir] * cos(th), radii[ir] * sin(th)};
                    double g1[2], g2[2], gq[2] = {cos(th), sin(th)}, gu[2];
                    const double h1 = seg_dist(x, v + 2, v, g1), h2 = seg_dist(x, v + 2, v + 4, g2);
                    dfl_rfunc_acc acc;
                    dfl_rfunc_acc_begin(&acc, DFL_RFUNC_REQUIV_CORRECTED, p, 2, 1);
                    dfl_rfunc_acc_add(&acc, h1, g1);
                    dfl_rfunc_acc_add(&acc, h2, g2);
                    dfl_rfunc_acc_add_q(&acc, hypot(x[0], x[1]), gq);
                    const double u = dfl_rfunc_acc_end(&acc, gu);
                    cr_assert_float_eq(u, radii[ir], 1e-13 * radii[ir]);
                    cr_assert(fabs(hypot(gu[0], gu[1]) - 1) <= 1e-9, "p=%d: |grad u| = %.15g", p,
                              hypot(gu[0], gu[1]));
                    dfl_rfunc_acc_begin(&acc, DFL_RFUNC_REQUIV, p, 2, 1);
                    dfl_rfunc_acc_add(&acc, h1, g1);
                    dfl_rfunc_acc_add(&acc, h2, g2);
                    dfl_rfunc_acc_end(&acc, gu);
                    cr_assert_float_eq(hypot(gu[0], gu[1]), pow(2.0, -1.0 / p), 1e-12);
                }
                /* (2) the trimmed fields of the rfunc field. */
                const double small[3] = {1e-3, 1e-6, 1e-10};
                for (int ir = 0; ir < 3; ir++) {
                    const double q = small[ir];
                    const double x[2] = {q * cos(th), q * sin(th)};
                    double g[2];
                    dfl_field_eval1(&fc, x, g);
                    const double dev = fabs(hypot(g[0], g[1]) - 1);
                    cr_assert(dev <= 5 * q, "alpha %d p %d q %g: | |grad u| - 1 | = %g",
                              alphas[ia], p, q, dev);
                    if (q <= 1e-10) cr_assert(dev <= 1e-9);
                    dfl_field_eval1(&fr, x, g);
                    cr_assert(fabs(hypot(g[0], g[1]) - pow(2.0, -1.0 / p)) <= 5 * q);
                }
            }
            dfl_field_destroy(&fc);
            dfl_field_destroy(&fr);
        }
}

/* The corrected join with the guard (join.h): finite everywhere, never above
 * the nearest part on an open polyline, and eq. 20 with guarded vertex
 * terms everywhere. */
Test(rfunc_join, corrected_join_floor)
{
    const double v[] = {0, 0, 1, 0.3, 1.5, 1.2, 2.6, 1.0};
    dfl_field f;
    cr_assert_eq(dfl_rfield_polyline(2, v, 4, false, DFL_RFUNC_REQUIV_CORRECTED, 2,
                                     DFL_RFUNC_TRIM_DISK, &f, NULL),
                 DFL_OK);
    dfl_rfunc_seg s[3];
    for (int i = 0; i < 3; i++)
        cr_assert_eq(dfl_rfunc_seg_init(2, v + 2 * i, v + 2 * i + 2, DFL_RFUNC_TRIM_DISK, &s[i], NULL),
                     DFL_OK);
    uint64_t rng = 17;
    int n_eq20 = 0, n_floor = 0;
    for (int i = 0; i < 2000; i++) {
        const double r = pow(10.0, tu_uniform(&rng, -3, 4)), th = tu_uniform(&rng, 0, 2 * DFL_PI);
        const double x[2] = {1.3 + r * cos(th), 0.6 + r * sin(th)};
        double S = 0, hmin = INFINITY, h[3];
        for (int k = 0; k < 3; k++) {
            h[k] = dfl_rfunc_seg_eval(&s[k], x, NULL);
            S += pow(h[k], -2);
            hmin = fmin(hmin, h[k]);
        }
        /* Vertex k joins segments k-1 and k; guard max(q, h_(k-1), h_k). */
        for (int k = 1; k <= 2; k++) {
            const double q = hypot(x[0] - v[2 * k], x[1] - v[2 * k + 1]);
            S -= pow(fmax(q, fmax(h[k - 1], h[k])), -2);
        }
        cr_assert(S >= pow(hmin, -2) * (1 - 1e-12), "open polyline: S >= h_min^-p");
        const double u = dfl_field_eval1(&f, x, NULL);
        cr_assert(isfinite(u) && u > 0 && u <= hmin * (1 + 1e-12));
        if (S > pow(2 * hmin, -2) * (1 + 1e-9)) {
            cr_assert_float_eq(u, 1 / sqrt(S), 1e-11 * u);
            n_eq20++;
        } else if (S < pow(2 * hmin, -2) * (1 - 1e-9)) {
            cr_assert_float_eq(u, 2 * hmin, 1e-15 * u);
            n_floor++;
        }
    }
    /* On an open polyline the guard alone keeps S >= h_min^-p > (2 h_min)^-p:
     * the floor never binds. */
    cr_assert(n_eq20 > 1900 && n_floor == 0, "%d %d", n_eq20, n_floor);
    dfl_field_destroy(&f);
}

/* correction = eq20: bs04's eq. 20 computed literally (unscaled, long
 * double) on random parts and vertex distances, NaN exactly where its
 * radicand is <= 0, the gradient sum_i (u/h_i)^(p+1) g_i - sum_v (u/q_v)^(p+1)
 * g_v; and its jet is a NaN jet where the radicand's leading term is not
 * positive. */
Test(rfunc_join, eq20_literal_and_nan_where_undefined)
{
    uint64_t st = 2024;
    int nans = 0, defined = 0;
    for (int it = 0; it < 4000; it++) {
        const int p = 1 + it % 12;
        double h[3], q[2], gh[3][2], gq[2][2];
        for (int i = 0; i < 3; i++) {
            h[i] = tu_uniform(&st, 0.05, 2.0);
            gh[i][0] = tu_uniform(&st, -1, 1), gh[i][1] = tu_uniform(&st, -1, 1);
        }
        for (int i = 0; i < 2; i++) {
            q[i] = tu_uniform(&st, 0.3, 3.0);
            gq[i][0] = tu_uniform(&st, -1, 1), gq[i][1] = tu_uniform(&st, -1, 1);
        }
        long double R = 0.0L;
        for (int i = 0; i < 3; i++) R += powl(h[i], -p);
        for (int i = 0; i < 2; i++) R -= powl(q[i], -p);
        dfl_rfunc_acc acc;
        dfl_rfunc_acc_begin(&acc, DFL_RFUNC_REQUIV_CORRECTED, p, 2, 1);
        dfl_rfunc_acc_set_correction(&acc, DFL_RFUNC_CORR_EQ20);
        for (int i = 0; i < 3; i++) dfl_rfunc_acc_add(&acc, h[i], gh[i]);
        for (int i = 0; i < 2; i++) dfl_rfunc_acc_add_q(&acc, q[i], gq[i]);
        double g[2];
        const double u = dfl_rfunc_acc_end(&acc, g);
        if (fabsl(R) < 1e-9L * powl(h[0], -p)) continue; /* too close to call */
        if (R <= 0.0L) {
            cr_expect(isnan(u) && isnan(g[0]) && isnan(g[1]), "p %d R %Lg: u %g", p, R, u);
            nans++;
            continue;
        }
        defined++;
        const long double ue = powl(R, -1.0L / p);
        cr_expect(fabsl(u - ue) <= 1e-11L * ue, "p %d: %.17g vs %.17Lg", p, u, ue);
        for (int j = 0; j < 2; j++) {
            long double ge = 0.0L, sc = 0.0L;
            for (int i = 0; i < 3; i++) {
                const long double w = powl(ue / h[i], p + 1) * gh[i][j];
                ge += w, sc += fabsl(w);
            }
            for (int i = 0; i < 2; i++) {
                const long double w = powl(ue / q[i], p + 1) * gq[i][j];
                ge -= w, sc += fabsl(w);
            }
            cr_expect(fabsl(g[j] - ge) <= 1e-11L * sc, "p %d grad %d: %.17g vs %.17Lg", p, j,
                      g[j], ge);
        }
    }
    cr_expect(nans > 100 && defined > 100, "nans %d defined %d", nans, defined);

    /* jets: constant parts h = 1, 1 and q = 0.5 (radicand 2 - 4 < 0) */
    dfl_jet hj[2], qj[1], out;
    dfl_jet_const(1.0, 4, &hj[0]);
    dfl_jet_const(1.0, 4, &hj[1]);
    dfl_jet_const(0.5, 4, &qj[0]);
    cr_assert_eq(dfl_rfunc_join_jet_corr(DFL_RFUNC_REQUIV_CORRECTED, DFL_RFUNC_CORR_EQ20, 2, 2,
                                         hj, 1, qj, &out, NULL),
                 DFL_OK);
    cr_expect(isnan(dfl_jet_deriv(&out, 0)) && isnan(dfl_jet_deriv(&out, 3)));
    /* q = 2: radicand 2 - 1/4, u = (7/4)^(-1/2) */
    dfl_jet_const(2.0, 4, &qj[0]);
    cr_assert_eq(dfl_rfunc_join_jet_corr(DFL_RFUNC_REQUIV_CORRECTED, DFL_RFUNC_CORR_EQ20, 2, 2,
                                         hj, 1, qj, &out, NULL),
                 DFL_OK);
    cr_expect(fabs(dfl_jet_deriv(&out, 0) - 1.0 / sqrt(1.75)) < 1e-15);
    cr_expect_eq(dfl_jet_deriv(&out, 1), 0.0);
}

/* dfl_rfunc_join_check: DFL_E_INPUT unless 1 <= p <= DFL_RFUNC_P_MAX (both
 * bounds accepted), and p >= 2 for R-conjunction (header). */
Test(rfunc_join, order_range_is_inclusive)
{
    dfl_err err;
    const dfl_rfunc_join js[3] = {DFL_RFUNC_REQUIV, DFL_RFUNC_RCONJ, DFL_RFUNC_REQUIV_CORRECTED};
    for (int i = 0; i < 3; i++) {
        const int lo = js[i] == DFL_RFUNC_RCONJ ? 2 : 1;
        cr_expect_eq(dfl_rfunc_join_check(js[i], lo, &err), DFL_OK, "join %d p %d", i, lo);
        cr_expect_eq(dfl_rfunc_join_check(js[i], DFL_RFUNC_P_MAX, &err), DFL_OK, "join %d", i);
        cr_expect_eq(dfl_rfunc_join_check(js[i], lo - 1, &err), DFL_E_INPUT, "join %d", i);
        cr_expect_eq(dfl_rfunc_join_check(js[i], DFL_RFUNC_P_MAX + 1, &err), DFL_E_INPUT,
                     "join %d", i);
    }
}

/* The guarded corrected join straight from the accumulator (p = 2, parts
 * h = 2 and 1 in that order, so h_min = 1 is the second part, one vertex
 * distance q): S = 2^-2 + 1 - q^-2.  The header's rules: u = S^(-1/2)
 * while S > (2 h_min)^-2 = 1/4, else the floor u = 2 h_min with gradient
 * 2 grad h_min.  q = 2: S = 1, u = 1; q = 0.95: S = 1.25 - 1/0.9025
 * = 0.142... in (1/16, 1/4): the floor, u = 2.  And correction = eq20 is
 * NaN where a vertex distance is 0 (q^-p = inf), the guarded form takes the
 * floor there. */
Test(rfunc_join, corrected_floor_and_zero_vertex_distance)
{
    const double g2[2] = {0.6, 0.8}, g1[2] = {-1.0, 0.0}, gq[2] = {0.0, 1.0};
    const double qs[3] = {2.0, 0.95, 0.0};
    for (int corr = 0; corr < 2; corr++)
        for (int i = 0; i < 3; i++) {
            dfl_rfunc_acc acc;
            dfl_rfunc_acc_begin(&acc, DFL_RFUNC_REQUIV_CORRECTED, 2, 2, 1);
            if (corr) dfl_rfunc_acc_set_correction(&acc, DFL_RFUNC_CORR_EQ20);
            dfl_rfunc_acc_add(&acc, 2.0, g2);
            dfl_rfunc_acc_add(&acc, 1.0, g1);
            dfl_rfunc_acc_add_q(&acc, qs[i], gq);
            double g[2];
            const double u = dfl_rfunc_acc_end(&acc, g);
            const long double S = 1.25L - (qs[i] > 0 ? 1.0L / ((long double)qs[i] * qs[i]) : 0);
            if (qs[i] == 0.0) {
                if (corr) cr_expect(isnan(u) && isnan(g[0]) && isnan(g[1]), "eq20 q = 0: %g", u);
                else cr_expect(u == 2.0 && g[0] == -2.0 && g[1] == 0.0, "guarded q = 0: %g", u);
            } else if (!corr && S <= 0.25L) {
                cr_expect_eq(u, 2.0, "q %g: S %Lg", qs[i], S);
                cr_expect(g[0] == 2.0 * g1[0] && g[1] == 2.0 * g1[1], "q %g", qs[i]);
            } else {
                const long double ue = 1.0L / sqrtl(S);
                cr_expect(fabsl(u - ue) <= 1e-14L * ue, "corr %d q %g: %.17g vs %.17Lg", corr,
                          qs[i], u, ue);
            }
        }
}
