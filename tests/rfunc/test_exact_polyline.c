/* Open polylines of exact segment distances joined by R-functions
 * (rfunc/exact_polyline.h).  Expected values: the segment distances of
 * geom/segdist.h, the join formulas evaluated directly with pow(), central
 * differences, and the closed forms of eq. 20 in the hatched sector. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "core/rng.h"
#include "geom/segdist.h"
#include "rfunc/exact_polyline.h"


static double fd_norm(const dfl_field *f, const double *x, double h)
{
    double g[2];
    for (int j = 0; j < 2; j++) {
        double xp[2] = {x[0], x[1]}, xm[2] = {x[0], x[1]};
        xp[j] += h;
        xm[j] -= h;
        g[j] = (dfl_field_eval1(f, xp, NULL) - dfl_field_eval1(f, xm, NULL)) / (xp[j] - xm[j]);
    }
    return hypot(g[0], g[1]);
}

Test(exact_polyline, one_segment_polyline_is_the_segment_distance)
{
    const double v[4] = {0.2, 0.1, 0.9, -0.4};
    const dfl_rfunc_join joins[3] = {DFL_RFUNC_REQUIV, DFL_RFUNC_RCONJ, DFL_RFUNC_REQUIV_CORRECTED};
    uint64_t seed = 11;
    for (int j = 0; j < 3; j++) {
        dfl_field f;
        dfl_err err;
        cr_assert_eq(dfl_rfunc_exact_polyline_field(2, v, 2, joins[j], 3, &f, &err), DFL_OK, "%s",
                     err.msg);
        for (int it = 0; it < 100; it++) {
            double x[2] = {dfl_rng_splitmix(&seed, -1, 2), dfl_rng_splitmix(&seed, -1, 1)}, g[2], gs[2];
            double u = dfl_field_eval1(&f, x, g);
            double h = dfl_segdist_eval(2, v, v + 2, x, gs);
            cr_assert_eq(u, h);
            cr_assert_eq(g[0], gs[0]);
            cr_assert_eq(g[1], gs[1]);
        }
        dfl_field_destroy(&f);
    }
}

/* Two segments O-P1, O-P2 (polyline P1, O, P2) at 90 degrees. */
Test(exact_polyline, joins_match_their_formulas_and_fd)
{
    const double v[6] = {1, 0, 0, 0, 0, 1};
    const int ps[3] = {2, 7, 12};
    uint64_t seed = 5;
    for (int ip = 0; ip < 3; ip++) {
        const int p = ps[ip];
        dfl_field fe, fc, fr;
        cr_assert_eq(dfl_rfunc_exact_polyline_field(2, v, 3, DFL_RFUNC_REQUIV, p, &fe, NULL), DFL_OK);
        cr_assert_eq(dfl_rfunc_exact_polyline_field(2, v, 3, DFL_RFUNC_REQUIV_CORRECTED, p, &fc, NULL),
                     DFL_OK);
        cr_assert_eq(dfl_rfunc_exact_polyline_field(2, v, 3, DFL_RFUNC_RCONJ, p, &fr, NULL), DFL_OK);
        for (int it = 0; it < 300; it++) {
            double x[2] = {dfl_rng_splitmix(&seed, -1.5, 1.5), dfl_rng_splitmix(&seed, -1.5, 1.5)}, g[2];
            double h1 = dfl_segdist_eval(2, v, v + 2, x, NULL);
            double h2 = dfl_segdist_eval(2, v + 2, v + 4, x, NULL);
            double q = hypot(x[0], x[1]);
            if (h1 < 1e-3 || h2 < 1e-3) continue;
            /* eq. 6 */
            double ue = pow(pow(h1, -p) + pow(h2, -p), -1.0 / p);
            cr_expect_float_eq(dfl_field_eval1(&fe, x, g), ue, 1e-13 * ue, "p %d", p);
            cr_expect_float_eq(hypot(g[0], g[1]), fd_norm(&fe, x, 1e-6), 1e-6);
            /* eq. 7 */
            double ur = h1 + h2 - pow(pow(h1, p) + pow(h2, p), 1.0 / p);
            cr_expect_float_eq(dfl_field_eval1(&fr, x, g), ur, 1e-12, "p %d", p);
            cr_expect_float_eq(hypot(g[0], g[1]), fd_norm(&fr, x, 1e-6), 1e-6);
            /* eq. 20 (exact distances: the guard never binds) */
            double uc = pow(pow(h1, -p) + pow(h2, -p) - pow(q, -p), -1.0 / p);
            double u = dfl_field_eval1(&fc, x, g);
            cr_expect_float_eq(u, uc, 1e-12 * uc, "p %d x %g %g", p, x[0], x[1]);
            /* hatched sector: u = q exactly, |grad u| = 1; where one
             * closest point is the vertex: u = the other distance */
            if (x[0] <= 0 && x[1] <= 0) {
                cr_expect_float_eq(u, q, 1e-15 * q);
                cr_expect_float_eq(hypot(g[0], g[1]), 1.0, 1e-14);
            } else if (x[0] <= 0 || x[1] <= 0) {
                cr_expect_float_eq(u, fmin(h1, h2), 1e-14 * u, "x %g %g", x[0], x[1]);
            }
        }
        dfl_field_destroy(&fe);
        dfl_field_destroy(&fc);
        dfl_field_destroy(&fr);
    }
}

Test(exact_polyline, bad_input)
{
    dfl_field f;
    dfl_err err;
    const double v[6] = {0, 0, 1, 1, 1, 1};
    cr_expect_eq(dfl_rfunc_exact_polyline_field(2, v, 1, DFL_RFUNC_REQUIV, 2, &f, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_rfunc_exact_polyline_field(2, v, 3, DFL_RFUNC_REQUIV, 2, &f, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "coincide") != NULL, "%s", err.msg);
    cr_expect_eq(dfl_rfunc_exact_polyline_field(4, v, 2, DFL_RFUNC_REQUIV, 2, &f, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_rfunc_exact_polyline_field(2, v, 2, DFL_RFUNC_RCONJ, 1, &f, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_rfunc_exact_polyline_field(2, v, 2, DFL_RFUNC_REQUIV, 0, &f, &err), DFL_E_INPUT);
    const double w[4] = {0, NAN, 1, 1};
    cr_expect_eq(dfl_rfunc_exact_polyline_field(2, w, 2, DFL_RFUNC_REQUIV, 2, &f, &err), DFL_E_INPUT);
    /* no jets */
    const double s[4] = {0, 0, 1, 0};
    cr_assert_eq(dfl_rfunc_exact_polyline_field(2, s, 2, DFL_RFUNC_REQUIV, 2, &f, &err), DFL_OK);
    dfl_jet j;
    const double x[2] = {0.5, 0.5}, dir[2] = {0, 1};
    cr_expect_eq(dfl_field_jet(&f, x, dir, 2, &j, &err), DFL_E_INPUT);
    dfl_field_destroy(&f);
}
