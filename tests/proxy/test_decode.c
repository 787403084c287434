/* Encoding + decoding of single proxies against exact shapes: order 2 is
 * exact for a sphere, cylinder and plane (and a torus at equator
 * footpoints), order 1 for a plane; elsewhere on a torus the error of the
 * osculating torus grows like rho^3. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "core/fit.h"
#include "core/rng.h"
#include "core/vec.h"
#include "proxy/analytic_inputs.h"
#include "proxy/decode.h"

static void make_geom(int order, const ta_shape *s, const double xc[3], dfl_proxy_position pos,
                      dfl_proxy_geom *g)
{
    dfl_surfpoint sp;
    ta_answer(s, xc, &sp);
    double sc[8];
    int side;
    cr_assert_eq(dfl_proxy_encode(order, xc, &sp, NULL, 1e-14, sc, &side), 0);
    if (pos == DFL_PROXY_DISPLACEMENT)
        for (int j = 0; j < 3; j++) sc[j] -= xc[j];
    dfl_proxy_decode(order, pos, xc, sc, side, g);
}

/* max |phi - sdf| over points within h of random cell centres within h of
 * the surface */
static double max_err(int order, const ta_shape *s, double h, uint64_t seed)
{
    double worst = 0;
    for (int k = 0; k < 200; k++) {
        double xc[3], x[3];
        int tries = 0; /* bounded: a bug that rejects every centre fails, not hangs */
        do {
            cr_assert_lt(tries++, 100000, "no centre within %g of the surface", h);
            for (int j = 0; j < 3; j++) xc[j] = dfl_rng_splitmix(&seed, -1, 1);
        } while (fabs(ta_sdf(s, xc)) > h);
        dfl_proxy_geom g;
        make_geom(order, s, xc, k % 2 ? DFL_PROXY_ABSOLUTE : DFL_PROXY_DISPLACEMENT, &g);
        for (int q = 0; q < 20; q++) {
            for (int j = 0; j < 3; j++) x[j] = xc[j] + dfl_rng_splitmix(&seed, -h, h);
            double gr[3];
            const double e = fabs(dfl_proxy_geom_eval(&g, order, x, gr) - ta_sdf(s, x));
            if (e > worst) worst = e;
        }
    }
    return worst;
}

static const ta_shape sphere = {TA_SPHERE, {0.1, -0.05, 0.02}, {0, 0, 1}, 0.5, 0};
static const ta_shape cylinder = {TA_CYLINDER, {0.1, 0.0, -0.1}, {0.6, 0.0, 0.8}, 0.4, 0};
static const ta_shape plane = {TA_PLANE, {0.1, 0.2, 0.3}, {0.48, 0.6, 0.64}, 0, 0};

Test(proxy_decode, order2_exact_sphere_cylinder_plane)
{
    cr_expect_lt(max_err(2, &sphere, 0.125, 1), 1e-10);
    cr_expect_lt(max_err(2, &cylinder, 0.125, 2), 1e-10);
    cr_expect_lt(max_err(2, &plane, 0.125, 3), 1e-10);
}

Test(proxy_decode, order1_exact_plane)
{
    cr_expect_lt(max_err(1, &plane, 0.25, 4), 1e-12);
    /* and not for a sphere: the tangent plane misses the curvature */
    cr_expect_gt(max_err(1, &sphere, 0.125, 5), 1e-3);
}

static const ta_shape torus = {TA_TORUS, {0.05, -0.02, 0.03}, {0, 0.6, 0.8}, 0.6, 0.25};

/* A point of the torus at tube angle th and azimuth ph (frame of ortho(a)). */
static void torus_point(double th, double ph, double dist, double x[3])
{
    double e1[3], e2[3];
    dfl_vec3_tangent_basis(torus.a, e1, e2);
    const double rad = torus.R + (torus.r + dist) * cos(th);
    for (int j = 0; j < 3; j++)
        x[j] = torus.c[j] + rad * (cos(ph) * e1[j] + sin(ph) * e2[j]) +
               (torus.r + dist) * sin(th) * torus.a[j];
}

Test(proxy_decode, torus_exact_at_equator_footpoints)
{
    uint64_t seed = 7;
    for (int k = 0; k < 40; k++) {
        /* outer (th = 0) and inner (th = pi) equator, either side */
        const double th = k % 2 ? DFL_PI : 0.0, ph = dfl_rng_splitmix(&seed, 0, 6.28);
        double xc[3];
        torus_point(th, ph, dfl_rng_splitmix(&seed, -0.1, 0.1), xc);
        dfl_proxy_geom g;
        make_geom(2, &torus, xc, DFL_PROXY_DISPLACEMENT, &g);
        for (int q = 0; q < 20; q++) {
            double x[3];
            for (int j = 0; j < 3; j++) x[j] = xc[j] + dfl_rng_splitmix(&seed, -0.12, 0.12);
            cr_expect_lt(fabs(dfl_proxy_geom_eval(&g, 2, x, NULL) - ta_sdf(&torus, x)), 1e-10,
                         "th %g", th);
        }
    }
}

Test(proxy_decode, torus_error_rho_cubed_elsewhere)
{
    const double th0[] = {0.7, 2.2, -1.1, 4.0};
    for (int c = 0; c < 4; c++) {
        double xc[3];
        torus_point(th0[c], 0.3, 0.05, xc);
        dfl_proxy_geom g;
        make_geom(2, &torus, xc, DFL_PROXY_DISPLACEMENT, &g);
        double rho[6], err[6];
        for (int k = 0; k < 6; k++) {
            const double e = 0.04 * pow(0.5, k);
            double q[3], p[3];
            /* surface points off both principal directions */
            torus_point(th0[c] + e / torus.r, 0.3 + e / torus.R, 0, q);
            torus_point(th0[c], 0.3, 0, p);
            double v[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
            rho[k] = dfl_vec3_norm(v);
            err[k] = fabs(dfl_proxy_geom_eval(&g, 2, q, NULL));
        }
        const double slope = dfl_fit_loglog_slope(6, rho, err);
        cr_expect(fabs(slope - 3.0) < 0.1, "theta %g: error ~ rho^%g", th0[c], slope);
        cr_expect_gt(err[0], 1e-8);
    }
}

/* The sign folded into t's length: phi at the cell centre is the input's
 * signed distance, inside and outside, for both orders. */
Test(proxy_decode, signed_value_at_centre)
{
    const ta_shape *sh[] = {&sphere, &cylinder, &torus};
    uint64_t seed = 11;
    for (int s = 0; s < 3; s++)
        for (int k = 0; k < 50; k++) {
            double xc[3];
            for (int j = 0; j < 3; j++) xc[j] = dfl_rng_splitmix(&seed, -0.9, 0.9);
            for (int order = 1; order <= 2; order++) {
                dfl_proxy_geom g;
                make_geom(order, sh[s], xc, DFL_PROXY_DISPLACEMENT, &g);
                double gr[3];
                const double d = ta_sdf(sh[s], xc);
                cr_expect_float_eq(dfl_proxy_geom_eval(&g, order, xc, gr), d, 1e-12);
                dfl_surfpoint sp;
                ta_answer(sh[s], xc, &sp);
                for (int j = 0; j < 3; j++) cr_expect_float_eq(gr[j], sp.n[j], 1e-12);
            }
        }
}

/* The gradient is the derivative of phi (central differences). */
Test(proxy_decode, gradient_matches_differences)
{
    uint64_t seed = 13;
    for (int k = 0; k < 100; k++) {
        double xc[3], x[3];
        for (int j = 0; j < 3; j++) xc[j] = dfl_rng_splitmix(&seed, -0.9, 0.9);
        torus_point(dfl_rng_splitmix(&seed, 0, 6.3), dfl_rng_splitmix(&seed, 0, 6.3), 0.08, xc);
        dfl_proxy_geom g;
        make_geom(2, &torus, xc, DFL_PROXY_DISPLACEMENT, &g);
        for (int j = 0; j < 3; j++) x[j] = xc[j] + dfl_rng_splitmix(&seed, -0.1, 0.1);
        double gr[3];
        dfl_proxy_geom_eval(&g, 2, x, gr);
        for (int j = 0; j < 3; j++) {
            double a[3] = {x[0], x[1], x[2]}, b[3] = {x[0], x[1], x[2]};
            a[j] += 1e-6;
            b[j] -= 1e-6;
            const double fd = (dfl_proxy_geom_eval(&g, 2, a, NULL) -
                               dfl_proxy_geom_eval(&g, 2, b, NULL)) / 2e-6;
            cr_expect_float_eq(gr[j], fd, 1e-7);
        }
    }
}

/* A cell centre on the surface moves its footpoint by delta along -n. */
Test(proxy_decode, centre_on_surface_moves)
{
    const double xc[3] = {0.1 + 0.5, -0.05, 0.02};
    dfl_surfpoint sp;
    ta_answer(&sphere, xc, &sp);
    double sc[8];
    int side;
    cr_expect_eq(dfl_proxy_encode(2, xc, &sp, NULL, 1e-9, sc, &side), 1);
    dfl_proxy_geom g;
    dfl_proxy_decode(2, DFL_PROXY_ABSOLUTE, xc, sc, side, &g);
    for (int j = 0; j < 3; j++) cr_expect_float_eq(g.n[j], sp.n[j], 1e-12);
    const double x[3] = {0.7, 0.1, 0.0};
    cr_expect_lt(fabs(dfl_proxy_geom_eval(&g, 2, x, NULL) - ta_sdf(&sphere, x)), 2.1e-9);
}

/* decode.h: the stored t is orthogonal to n only up to the storage's
 * rounding, and decoding projects it back, so (n, t, b) is orthonormal and
 * right-handed (b = n x t) for any stored L t not along n: here L t is the
 * true direction tilted towards n by up to 0.3 (far more than half
 * rounding), for both signs L = 1, 2, both positions. */
Test(proxy_decode, frame_orthonormal_after_tilt)
{
    static const double tilts[] = {0, 1e-3, -0x1p-11, 0.05, -0.3};
    uint64_t seed = 21;
    for (int k = 0; k < 100; k++) {
        double xc[3];
        for (int j = 0; j < 3; j++) xc[j] = dfl_rng_splitmix(&seed, -1, 1);
        dfl_surfpoint sp;
        ta_answer(&torus, xc, &sp);
        double sc[8];
        int side;
        cr_assert_eq(dfl_proxy_encode(2, xc, &sp, NULL, 1e-14, sc, &side), 0);
        /* n as decoded: along +-(p - x_c) */
        double d[3], n[3];
        for (int j = 0; j < 3; j++) d[j] = sc[j] - xc[j];
        const double dl = dfl_vec3_norm(d), L = dfl_vec3_norm(sc + 5);
        const double sgn = L > 1.5 ? -1 : 1;
        for (int j = 0; j < 3; j++) n[j] = sgn * d[j] / dl;
        const double tilt = tilts[k % 5];
        for (int j = 0; j < 3; j++) sc[5 + j] += L * tilt * n[j];
        for (int pos = 0; pos < 2; pos++) {
            double s2[8];
            memcpy(s2, sc, sizeof s2);
            if (pos == DFL_PROXY_DISPLACEMENT)
                for (int j = 0; j < 3; j++) s2[j] -= xc[j];
            dfl_proxy_geom g;
            dfl_proxy_decode(2, (dfl_proxy_position)pos, xc, s2, side, &g);
            const double *v[3] = {g.n, g.t, g.b};
            for (int a = 0; a < 3; a++)
                for (int b = a; b < 3; b++)
                    cr_expect(fabs(dfl_vec3_dot(v[a], v[b]) - (a == b)) < 1e-14,
                              "k %d tilt %g pos %d: <%d,%d> = %.17g", k, tilt, pos, a, b,
                              dfl_vec3_dot(v[a], v[b]));
            double nt[3];
            dfl_vec3_cross(g.n, g.t, nt);
            for (int j = 0; j < 3; j++) cr_expect(fabs(nt[j] - g.b[j]) < 1e-14);
        }
    }
}

/* decode.h (dfl_proxy_encode): the footpoint moves exactly when
 * |p - xc| < delta (a length: compared with delta, not delta^2), and
 * *side is +1 when sp->d >= 0, so a centre on the surface (d = 0) counts
 * as outside. */
Test(proxy_decode, encode_moves_below_delta_and_side_of_zero)
{
    const double xc[3] = {0.2, -0.1, 0.3};
    dfl_surfpoint sp;
    memset(&sp, 0, sizeof sp);
    /* footpoint 0.5 below xc along n = +z: d = 0.5, |p - xc| = 0.5 */
    for (int j = 0; j < 3; j++) sp.p[j] = xc[j], sp.n[j] = j == 2 ? 1.0 : 0.0;
    sp.p[2] -= 0.5;
    sp.d = 0.5;
    double sc[8];
    int side = 0;
    cr_expect_eq(dfl_proxy_encode(1, xc, &sp, NULL, 0.3, sc, &side), 0, "0.5 >= delta 0.3");
    cr_expect_eq(sc[2], xc[2] - 0.5, "footpoint kept");
    cr_expect_eq(side, 1);
    cr_expect_eq(dfl_proxy_encode(1, xc, &sp, NULL, 0.6, sc, &side), 1, "0.5 < delta 0.6");
    cr_expect_float_eq(sc[2], xc[2] - 0.6, 1e-15, "moved to xc - delta n");
    /* the centre on the surface: d = 0 is the outside (+1) */
    for (int j = 0; j < 3; j++) sp.p[j] = xc[j];
    sp.d = 0.0;
    side = 0;
    cr_expect_eq(dfl_proxy_encode(1, xc, &sp, NULL, 1e-9, sc, &side), 1);
    cr_expect_eq(side, 1, "d = 0 counts as d >= 0");
    sp.d = -0x1p-1074; /* the smallest negative: inside */
    cr_expect_eq(dfl_proxy_encode(1, xc, &sp, NULL, 1e-9, sc, &side), 1);
    cr_expect_eq(side, -1);
}
