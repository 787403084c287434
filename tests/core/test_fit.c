/* core/fit: exact power laws, noise that cancels, the normal-equations
 * formula bit for bit, and degenerate data. */
#include <criterion/criterion.h>
#include <math.h>

#include "core/fit.h"

/* y = c x^k is fitted with slope k, whatever c. */
Test(fit, power_law_slope_is_its_exponent)
{
    const double ks[4] = {-0.5, 1.0, 2.0, 3.25};
    double x[6], y[6];
    for (int q = 0; q < 4; q++) {
        for (int i = 0; i < 6; i++) {
            x[i] = pow(10.0, -(double)i);
            y[i] = 7.0 * pow(x[i], ks[q]);
        }
        cr_expect_float_eq(dfl_fit_loglog_slope(6, x, y), ks[q], 1e-12, "k = %g", ks[q]);
    }
}

/* Two points: the slope of the line through them in log-log. */
Test(fit, two_points_give_the_secant)
{
    const double x[2] = {1e-3, 1e-1}, y[2] = {400.0, 4.0};
    cr_expect_float_eq(dfl_fit_loglog_slope(2, x, y), -1.0, 1e-14);
}

/* A least-squares fit, not a secant: log residuals +e, -e, -e, +e about
 * y = x^2 are orthogonal to the centred log x and leave the slope 2;
 * residuals +e, 0, 0, -e tilt it, to the centred least-squares value. */
Test(fit, least_squares_not_endpoints)
{
    const double x[4] = {1.0, 10.0, 100.0, 1000.0};
    const double e = 0.3;
    const double y[4] = {exp(e), 10.0 * 10.0 * exp(-e), 1e4 * exp(-e), 1e6 * exp(e)};
    cr_expect_float_eq(dfl_fit_loglog_slope(4, x, y), 2.0, 1e-12);
    const double z[4] = {exp(e), 100.0, 1e4, 1e6 * exp(-e)};
    const double lx[4] = {0, log(10.0), log(100.0), log(1000.0)};
    double mx = (lx[0] + lx[1] + lx[2] + lx[3]) / 4, num = 0, den = 0, my = 0;
    for (int i = 0; i < 4; i++) my += log(z[i]) / 4;
    for (int i = 0; i < 4; i++) {
        num += (lx[i] - mx) * (log(z[i]) - my);
        den += (lx[i] - mx) * (lx[i] - mx);
    }
    cr_expect_float_eq(dfl_fit_loglog_slope(4, x, z), num / den, 1e-12);
    cr_expect(fabs(dfl_fit_loglog_slope(4, x, z) - 2.0) > 1e-3);
}

/* The documented formula, to the last bit. */
Test(fit, normal_equations_bit_for_bit)
{
    const double x[5] = {1e-2, 5e-3, 2.5e-3, 1.25e-3, 6.25e-4};
    const double y[5] = {12, 17, 24, 34, 48};
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int i = 0; i < 5; i++) {
        const double lx = log(x[i]), ly = log(y[i]);
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
    }
    const double want = (5.0 * sxy - sx * sy) / (5.0 * sxx - sx * sx);
    cr_expect_eq(dfl_fit_loglog_slope(5, x, y), want);
}

/* Degenerate data never traps: one point, none, x = 1 throughout (the
 * sums cancel exactly) and a negative x are not numbers. */
Test(fit, degenerate_data_is_not_a_number)
{
    const double x[3] = {1.0, 1.0, 1.0}, y[3] = {1.0, 2.0, 3.0};
    cr_expect(isnan(dfl_fit_loglog_slope(3, x, y)));
    const double x2[2] = {2.0, 4.0};
    cr_expect(isnan(dfl_fit_loglog_slope(1, x2, y)));
    cr_expect(isnan(dfl_fit_loglog_slope(0, x2, y)));
    const double xn[2] = {-1.0, 2.0};
    cr_expect(isnan(dfl_fit_loglog_slope(2, xn, y)));
}
