/* eq. 13-14 bounds (rfunc/gradbound.h).  Expected values: finite
 * differences of the join formulas written out here with pow(), the
 * library's own two-argument joins, and brute-force scans of |grad u|
 * around a vertex of exact segment distances (central differences of a
 * field evaluated from first principles in this file). */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "core/vec.h"
#include "rfunc/gradbound.h"

static double F_requiv(double a, double b, int p) { return pow(pow(a, -p) + pow(b, -p), -1.0 / p); }
static double F_rconj(double a, double b, int p) { return a + b - pow(pow(a, p) + pow(b, p), 1.0 / p); }
static double F_join(dfl_rfunc_join j, double a, double b, int p)
{
    return j == DFL_RFUNC_REQUIV ? F_requiv(a, b, p) : F_rconj(a, b, p);
}

Test(gradbound, polar_partials_are_the_partial_derivatives)
{
    const dfl_rfunc_join joins[2] = {DFL_RFUNC_REQUIV, DFL_RFUNC_RCONJ};
    const int ps[4] = {2, 3, 7, 12};
    for (int j = 0; j < 2; j++)
        for (int ip = 0; ip < 4; ip++)
            for (int k = 1; k < 30; k++) {
                const int p = ps[ip];
                double phi = k * (DFL_PI / 2) / 30, F1, F2;
                dfl_gradbound_partials(joins[j], p, phi, &F1, &F2);
                /* at any radius: the partials are homogeneous of degree 0 */
                const double rho = 0.37, h1 = rho * cos(phi), h2 = rho * sin(phi), e = 1e-6;
                double d1 = (F_join(joins[j], h1 + e, h2, p) - F_join(joins[j], h1 - e, h2, p)) / (2 * e);
                double d2 = (F_join(joins[j], h1, h2 + e, p) - F_join(joins[j], h1, h2 - e, p)) / (2 * e);
                cr_expect_float_eq(F1, d1, 1e-7, "join %d p %d phi %g", j, p, phi);
                cr_expect_float_eq(F2, d2, 1e-7, "join %d p %d phi %g", j, p, phi);
                /* and the library's two-argument partials */
                double L1, L2;
                if (joins[j] == DFL_RFUNC_REQUIV) dfl_rfunc_requiv2(h1, h2, p, &L1, &L2);
                else dfl_rfunc_rconj2(h1, h2, p, &L1, &L2);
                cr_expect_float_eq(F1, L1, 1e-13);
                cr_expect_float_eq(F2, L2, 1e-13);
            }
}

Test(gradbound, band_and_claims_of_fig5)
{
    double lo, hi;
    dfl_gradbound_band(0.7, 0.2, 1.0, 1.0, &lo, &hi);
    cr_expect_float_eq(lo, 0.5, 1e-15);
    cr_expect_float_eq(hi, 0.9, 1e-15);
    dfl_gradbound_band(0.2, 0.7, 1.5, 0.5, &lo, &hi);
    cr_expect_float_eq(lo, 0.05, 1e-15);
    cr_expect_float_eq(hi, 0.65, 1e-15);
    const int ps[3] = {2, 7, 12};
    for (int ip = 0; ip < 3; ip++) {
        const int p = ps[ip];
        double phi, smax, dmax;
        /* R-equivalence: F1 + F2 = (|v|_(p+1) / |v|_p)^(p+1), smallest at
         * equal components: 2^(-1/p); R-conjunction: 2 - 2^(1/p) */
        double m = dfl_gradbound_sum_min(DFL_RFUNC_REQUIV, p, &phi, &smax, &dmax);
        cr_expect_float_eq(m, pow(2.0, -1.0 / p), 1e-14);
        cr_expect_float_eq(phi, DFL_PI / 4, 1e-6);
        cr_expect_float_eq(smax, 1.0, 1e-14);
        cr_expect_float_eq(dmax, 1.0, 1e-14);
        m = dfl_gradbound_sum_min(DFL_RFUNC_RCONJ, p, &phi, &smax, &dmax);
        cr_expect_float_eq(m, 2.0 - pow(2.0, 1.0 / p), 1e-14);
        cr_expect_float_eq(phi, DFL_PI / 4, 1e-6);
        cr_expect_float_eq(smax, 1.0, 1e-14);
        double F1, F2;
        dfl_gradbound_partials(DFL_RFUNC_REQUIV, p, DFL_PI / 4, &F1, &F2);
        cr_expect_float_eq(F1 - F2, 0.0, 1e-15);
        cr_expect_float_eq(F1, pow(2.0, -(p + 1.0) / p), 1e-15);
    }
}

static double sq(void *ctx, double x)
{
    (void)ctx;
    return (x - 0.3) * (x - 0.3);
}

Test(gradbound, golden_section)
{
    double fm;
    double x = dfl_gradbound_golden(sq, NULL, 0.0, 1.0, 1e-12, &fm);
    cr_expect_float_eq(x, 0.3, 1e-12);
    cr_expect(fm >= 0.0 && fm < 1e-24);
}

/* From first principles: u = F(h1, h2) of the exact distances to the
 * segments from O = 0 along (1, 0) and (cos a, sin a), length 1. */
static double seg_d(double ex, double ey, const double *x)
{
    double t = fmin(fmax(x[0] * ex + x[1] * ey, 0.0), 1.0);
    return hypot(x[0] - t * ex, x[1] - t * ey);
}

static double u_pair(dfl_rfunc_join j, int p, double a, const double *x)
{
    return F_join(j, seg_d(1, 0, x), seg_d(cos(a), sin(a), x), p);
}

static double fd_grad(dfl_rfunc_join j, int p, double a, const double *x, double h)
{
    double xp[2] = {x[0] + h, x[1]}, xm[2] = {x[0] - h, x[1]};
    double gx = (u_pair(j, p, a, xp) - u_pair(j, p, a, xm)) / (2 * h);
    double yp[2] = {x[0], x[1] + h}, ym[2] = {x[0], x[1] - h};
    double gy = (u_pair(j, p, a, yp) - u_pair(j, p, a, ym)) / (2 * h);
    return hypot(gx, gy);
}

Test(gradbound, bisector_and_mixed_values_match_finite_differences)
{
    const dfl_rfunc_join joins[2] = {DFL_RFUNC_REQUIV, DFL_RFUNC_RCONJ};
    const double r = 1e-2;
    for (int j = 0; j < 2; j++)
        for (int p = 2; p <= 12; p += 5)
            for (int ad = 20; ad < 360; ad += 20) {
                const double a = ad * DFL_PI / 180;
                /* convex bisector */
                const double tb = ad <= 180 ? a / 2 : a / 2 + DFL_PI;
                const double x[2] = {r * cos(tb), r * sin(tb)};
                cr_expect_float_eq(dfl_gradbound_bisector(joins[j], p, a),
                                   fd_grad(joins[j], p, a, x, 1e-8), 1e-6, "alpha %d p %d", ad, p);
            }
    /* mixed regime: alpha = 150, direction -30 degrees: segment 1 interior
     * (cos > 0), segment 2's closest point O (cos(-180) < 0), s = 1/2 */
    for (int j = 0; j < 2; j++)
        for (int p = 2; p <= 12; p += 5) {
            const double a = 150 * DFL_PI / 180, t = -30 * DFL_PI / 180;
            const double x[2] = {r * cos(t), r * sin(t)};
            cr_expect_float_eq(dfl_gradbound_mixed(joins[j], p, 0.5),
                               fd_grad(joins[j], p, a, x, 1e-8), 1e-6, "p %d", p);
        }
}

Test(gradbound, vertex_min_is_the_brute_force_circle_minimum)
{
    const dfl_rfunc_join joins[2] = {DFL_RFUNC_REQUIV, DFL_RFUNC_RCONJ};
    const int alphas[7] = {30, 90, 150, 170, 180, 190, 300};
    const double r = 1e-2;
    for (int j = 0; j < 2; j++)
        for (int p = 2; p <= 12; p += 5)
            for (int ia = 0; ia < 7; ia++) {
                const double a = alphas[ia] * DFL_PI / 180;
                /* coarse scan, then a fine scan around the best sample */
                double best = INFINITY, tbest = 0;
                for (int k = 0; k < 3600; k++) {
                    double t = 2 * DFL_PI * (k + 0.5) / 3600;
                    double x[2] = {r * cos(t), r * sin(t)};
                    double g = fd_grad(joins[j], p, a, x, 1e-8);
                    if (g < best) best = g, tbest = t;
                }
                for (int k = -1000; k <= 1000; k++) {
                    double t = tbest + k * (2 * DFL_PI / 3600) / 1000;
                    double x[2] = {r * cos(t), r * sin(t)};
                    best = fmin(best, fd_grad(joins[j], p, a, x, 1e-8));
                }
                int where;
                double m = dfl_gradbound_vertex_min(joins[j], p, a, &where, NULL);
                /* FD error ~1e-7; the fine scan's step 1e-4 degrees */
                cr_expect(fabs(best - m) < 2e-6, "join %d p %d alpha %d: %.9f vs %.9f",
                          j, p, alphas[ia], m, best);
                /* near-collinear joins have their minimum off the bisector */
                if (j == 0 && (alphas[ia] == 170 || alphas[ia] == 180 || alphas[ia] == 190))
                    cr_expect_eq(where, 1, "p %d alpha %d", p, alphas[ia]);
                if (alphas[ia] <= 90 || alphas[ia] == 300) cr_expect_eq(where, 0);
            }
}

Test(gradbound, check)
{
    dfl_err err;
    cr_expect_eq(dfl_gradbound_check(DFL_RFUNC_REQUIV, 2, &err), DFL_OK);
    cr_expect_eq(dfl_gradbound_check(DFL_RFUNC_RCONJ, 1, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_gradbound_check(DFL_RFUNC_REQUIV_CORRECTED, 2, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "requiv_corrected") != NULL, "%s", err.msg);
}

/* vertex_min: the mixed regime only exists for s in [max(cos alpha', 0), 1]
 * (header), so its minimizer s_min lies there, and the returned minimum is
 * the least of the bisector value and the mixed values over that range
 * (checked against a plain scan of dfl_gradbound_mixed on it). */
Test(gradbound, vertex_min_scans_only_the_available_s)
{
    const dfl_rfunc_join joins[2] = {DFL_RFUNC_REQUIV, DFL_RFUNC_RCONJ};
    const int alphas[8] = {10, 20, 40, 60, 80, 100, 200, 340};
    for (int j = 0; j < 2; j++)
        for (int p = 2; p <= 12; p += 5)
            for (int ia = 0; ia < 8; ia++) {
                const double a = alphas[ia] * DFL_PI / 180;
                const double ap = a <= DFL_PI ? a : 2 * DFL_PI - a, lo = fmax(cos(ap), 0.0);
                int where;
                double s;
                const double m = dfl_gradbound_vertex_min(joins[j], p, a, &where, &s);
                cr_expect(s >= lo - 1e-15 && s <= 1.0, "join %d p %d alpha %d: s %.17g < %.17g", j,
                          p, alphas[ia], s, lo);
                double scan = dfl_gradbound_bisector(joins[j], p, a);
                for (int k = 0; k <= 4000; k++)
                    scan = fmin(scan, dfl_gradbound_mixed(joins[j], p, lo + (1.0 - lo) * k / 4000));
                cr_expect(m <= scan + 1e-12 && m >= scan - 1e-6, "join %d p %d alpha %d: %.17g vs %.17g",
                          j, p, alphas[ia], m, scan);
            }
}

/* where = 0 when the bisector value is the least, ties within 1e-12
 * included (header).  Near the angle where the bisector value crosses the
 * mixed minimum (found by bisection on alpha) the two differ by less than
 * 1e-12: there where must be 0 whenever bisector <= minimum + 1e-12. */
Test(gradbound, vertex_min_ties_go_to_the_bisector)
{
    const dfl_rfunc_join joins[2] = {DFL_RFUNC_REQUIV, DFL_RFUNC_RCONJ};
    int close = 0;
    for (int j = 0; j < 2; j++)
        for (int p = 2; p <= 12; p += 5) {
            /* bis - min is 0 (bisector least) for small alpha, > 0 past the crossing */
            double lo = 1e-3, hi = DFL_PI;
            int w;
            dfl_gradbound_vertex_min(joins[j], p, hi, &w, NULL);
            if (w == 0) continue; /* no crossing for this join and order */
            for (int it = 0; it < 60; it++) {
                const double mid = 0.5 * (lo + hi);
                const double m = dfl_gradbound_vertex_min(joins[j], p, mid, NULL, NULL);
                if (dfl_gradbound_bisector(joins[j], p, mid) > m) hi = mid;
                else lo = mid;
            }
            for (int k = 0; k < 8; k++) {
                const double a = hi + k * 1e-14;
                const double m = dfl_gradbound_vertex_min(joins[j], p, a, &w, NULL);
                const double bis = dfl_gradbound_bisector(joins[j], p, a);
                if (bis <= m + 1e-12) {
                    close += bis > m;
                    cr_expect_eq(w, 0, "join %d p %d alpha %.17g: bis %.17g min %.17g", j, p, a, bis, m);
                }
            }
        }
    cr_expect(close > 0, "no point strictly within the tie band");
}
