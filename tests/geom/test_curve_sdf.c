/* The closed-curve SDF (curve_sdf.c): sign and orientation, rejection of
 * open curves, derivatives of orders 1-3 (and mixed) against central finite
 * differences, and the curvature convention of geom/curvature.h. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/curve_fixtures.h"
#include "geom/footpoint.h"
#include "geom/curvature.h"
#include "core/vec.h"

static double sdf_d(const dfl_curve_sdf *S, double x, double y, dfl_curve_sdf_val *v)
{
    double p[2] = {x, y};
    cr_assert_eq(dfl_curve_sdf_eval(S, p, 3, v, NULL), DFL_OK);
    return v->d;
}

Test(curve_sdf, sdf_sign_and_rejects_open_curves)
{
    dfl_bspline c;
    cf_make_blob(&c);
    dfl_curve_sdf *S;
    dfl_err err;
    cr_assert_eq(dfl_curve_sdf_new(&c, NULL, &S, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_curve_sdf_orientation(S), 1); /* listed counter-clockwise */
    dfl_curve_sdf_val v;
    cr_assert(sdf_d(S, 0.0, 0.0, &v) < 0.0);
    cr_assert_eq(v.winding, 1);
    cr_assert(sdf_d(S, 5.0, 0.0, &v) > 0.0);
    cr_assert_eq(v.winding, 0);
    /* just inside / outside the curve along the normal */
    double D[2 * 2];
    dfl_bspline_eval(&c, 1.3, 1, D);
    double len = hypot(D[2], D[3]), N[2] = {D[3] / len, -D[2] / len};
    cr_assert(sdf_d(S, D[0] + 1e-9 * N[0], D[1] + 1e-9 * N[1], &v) > 0.0);
    cr_assert(fabs(v.d - 1e-9) < 1e-14);
    cr_assert(sdf_d(S, D[0] - 1e-9 * N[0], D[1] - 1e-9 * N[1], &v) < 0.0);
    dfl_curve_sdf_free(S);
    dfl_bspline_free(&c);

    cf_make_S(&c);
    cr_assert_eq(dfl_curve_sdf_new(&c, NULL, &S, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "closed curve is required"), "%s", err.msg);
    dfl_bspline_free(&c);
}

Test(curve_sdf, sdf_derivatives_match_finite_differences)
{
    dfl_bspline c;
    dfl_curve_sdf *S = cf_blob_sdf(&c);
    unsigned seed = 23;
    const double h = 1e-4;
    int tested = 0;
    for (int q = 0; q < 200 && tested < 60; q++) {
        double x = -3 + 6 * dfl_rng_lcg(&seed), y = -2 + 4 * dfl_rng_lcg(&seed);
        dfl_curve_sdf_val v, px, mx, py, my;
        sdf_d(S, x, y, &v);
        /* off the medial axis and the focal set: the stencil's footpoints
         * must stay on one branch, and 1 + kappa d well away from 0 */
        if (fabs(1.0 + v.kappa * v.d) < 0.2 || fabs(y) < 0.05) continue;
        sdf_d(S, x + h, y, &px);
        sdf_d(S, x - h, y, &mx);
        sdf_d(S, x, y + h, &py);
        sdf_d(S, x, y - h, &my);
        double T = c.t1 - c.t0;
        int jump = 0;
        const dfl_curve_sdf_val *st[4] = {&px, &mx, &py, &my};
        for (int k = 0; k < 4; k++) {
            double dt = fabs(st[k]->t - v.t);
            if (fmin(dt, T - dt) > 0.05) jump = 1;
        }
        if (jump || (v.flags & DFL_FOOT_MEDIAL)) continue;
        tested++;
        /* first */
        cr_assert(fabs((px.d - mx.d) / (2 * h) - v.g[0]) < 1e-7, "dx");
        cr_assert(fabs((py.d - my.d) / (2 * h) - v.g[1]) < 1e-7, "dy");
        cr_assert(fabs(hypot(v.g[0], v.g[1]) - 1.0) < 1e-14);
        /* second: FD of the exact gradient */
        double s2 = 1e-6 * (1 + fabs(v.h[0]) + fabs(v.h[2]));
        cr_assert(fabs((px.g[0] - mx.g[0]) / (2 * h) - v.h[0]) < s2, "dxx %g %g",
                  (px.g[0] - mx.g[0]) / (2 * h), v.h[0]);
        cr_assert(fabs((py.g[0] - my.g[0]) / (2 * h) - v.h[1]) < s2, "dxy");
        cr_assert(fabs((px.g[1] - mx.g[1]) / (2 * h) - v.h[1]) < s2, "dyx");
        cr_assert(fabs((py.g[1] - my.g[1]) / (2 * h) - v.h[2]) < s2, "dyy");
        /* third (mixed): FD of the exact Hessian */
        double s3 = 1e-5 * (1 + fabs(v.t3[0]) + fabs(v.t3[1]) + fabs(v.t3[2]) + fabs(v.t3[3]));
        cr_assert(fabs((px.h[0] - mx.h[0]) / (2 * h) - v.t3[0]) < s3, "dxxx %g %g",
                  (px.h[0] - mx.h[0]) / (2 * h), v.t3[0]);
        cr_assert(fabs((py.h[0] - my.h[0]) / (2 * h) - v.t3[1]) < s3, "dxxy %g %g",
                  (py.h[0] - my.h[0]) / (2 * h), v.t3[1]);
        cr_assert(fabs((px.h[1] - mx.h[1]) / (2 * h) - v.t3[1]) < s3, "dxyx");
        cr_assert(fabs((py.h[1] - my.h[1]) / (2 * h) - v.t3[2]) < s3, "dxyy");
        cr_assert(fabs((px.h[2] - mx.h[2]) / (2 * h) - v.t3[2]) < s3, "dyyx");
        cr_assert(fabs((py.h[2] - my.h[2]) / (2 * h) - v.t3[3]) < s3, "dyyy");
        /* second order directly from values (independent of the gradient) */
        double dxy = 0.0;
        {
            dfl_curve_sdf_val a, b, cc, d;
            dxy = (sdf_d(S, x + h, y + h, &a) - sdf_d(S, x + h, y - h, &b) -
                   sdf_d(S, x - h, y + h, &cc) + sdf_d(S, x - h, y - h, &d)) /
                  (4 * h * h);
        }
        cr_assert(fabs(dxy - v.h[1]) < 1e-4 * (1 + fabs(v.h[1])), "dxy from values %g vs %g", dxy,
                  v.h[1]);
    }
    cr_assert(tested >= 30, "only %d points tested", tested);
    dfl_curve_sdf_free(S);
    dfl_bspline_free(&c);
}


/* The curvature convention of geom/curvature.h: dN/ds = kappa T for the
 * outward normal N, whatever the orientation of the curve.  The blob is
 * convex, so kappa > 0 at every footpoint of both orientations; kappa
 * equals dfl_curvature_curve2 with the outward normal, and the Hessian is
 * curvature.h's kappa / (1 + kappa d) T T^T. */
Test(curve_sdf, curvature_convention_of_curvature_h)
{
    for (int rev = 0; rev < 2; rev++) {
        dfl_bspline c;
        cf_make_blob(&c);
        if (rev) { /* the same curve traversed clockwise */
            dfl_bspline_free(&c);
            static const double cp[] = {1.6, -0.9, 0.0, -1.0, -1.6, -0.9, -2.0, 0.0,
                                        -1.6, 0.9, 0.0, 1.0,  1.6,  0.9,  2.0, 0.0};
            cr_assert_eq(dfl_bspline_init_periodic(2, 4, 8, cp, NULL, 0, &c, NULL), DFL_OK);
        }
        dfl_curve_sdf *S;
        cr_assert_eq(dfl_curve_sdf_new(&c, NULL, &S, NULL), DFL_OK);
        cr_assert_eq(dfl_curve_sdf_orientation(S), rev ? -1 : 1);
        uint64_t seed = 41;
        for (int q = 0; q < 60; q++) {
            double x[2] = {dfl_rng_splitmix(&seed, -3, 3), dfl_rng_splitmix(&seed, -2, 2)};
            dfl_curve_sdf_val v;
            cr_assert_eq(dfl_curve_sdf_eval(S, x, 2, &v, NULL), DFL_OK);
            cr_assert(v.kappa > 0.0, "rev %d: kappa %g at (%g %g)", rev, v.kappa, x[0], x[1]);
            double D[3 * 2];
            dfl_bspline_eval(&c, v.t, 2, D);
            double sp = hypot(D[2], D[3]), T[2] = {D[2] / sp, D[3] / sp};
            double N[2] = {rev ? -T[1] : T[1], rev ? T[0] : -T[0]}; /* outward */
            cr_assert((fabs(v.g[0] - N[0]) < 1e-12 && fabs(v.g[1] - N[1]) < 1e-12) ||
                      (v.flags & DFL_FOOT_MEDIAL));
            double k2 = dfl_curvature_curve2(D + 2, D + 4, N);
            cr_assert(fabs(v.kappa - k2) < 1e-12 * (1 + fabs(k2)), "%.17g vs %.17g", v.kappa, k2);
            if (v.flags & (DFL_FOOT_MEDIAL | DFL_FOOT_FOCAL)) continue;
            double a = v.kappa / (1.0 + v.kappa * v.d);
            cr_assert(fabs(v.h[0] - a * T[0] * T[0]) < 1e-12 * (1 + fabs(a)));
            cr_assert(fabs(v.h[1] - a * T[0] * T[1]) < 1e-12 * (1 + fabs(a)));
            cr_assert(fabs(v.h[2] - a * T[1] * T[1]) < 1e-12 * (1 + fabs(a)));
        }
        dfl_curve_sdf_free(S);
        dfl_bspline_free(&c);
    }
}

/* d < 0 inside, where the winding number around x is non-zero: for a
 * clockwise curve it is -1 there (header), so the sign does not depend on
 * the orientation.  The same closed curve listed both ways gives the same
 * d, with winding +1 and -1 at its centre (far from the curve, where the
 * polygon's winding number decides). */
Test(curve_sdf, clockwise_curve_is_negative_inside)
{
    double ccw[8 * 2], cw[8 * 2];
    for (int i = 0; i < 8; i++) {
        const double th = 2.0 * DFL_PI * i / 8;
        ccw[2 * i] = 1.5 * cos(th);
        ccw[2 * i + 1] = sin(th);
        cw[2 * (7 - i)] = ccw[2 * i];
        cw[2 * (7 - i) + 1] = ccw[2 * i + 1];
    }
    dfl_bspline c1, c2;
    cr_assert_eq(dfl_bspline_init_periodic(2, 4, 8, ccw, NULL, 0, &c1, NULL), DFL_OK);
    cr_assert_eq(dfl_bspline_init_periodic(2, 4, 8, cw, NULL, 0, &c2, NULL), DFL_OK);
    dfl_curve_sdf *S1, *S2;
    dfl_err err;
    cr_assert_eq(dfl_curve_sdf_new(&c1, NULL, &S1, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_curve_sdf_new(&c2, NULL, &S2, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_curve_sdf_orientation(S1), 1);
    cr_assert_eq(dfl_curve_sdf_orientation(S2), -1);
    dfl_curve_sdf_val v1, v2;
    const double pts[][2] = {{0, 0}, {0.3, -0.2}, {3, 0}, {0, -2.5}};
    for (size_t i = 0; i < sizeof pts / sizeof *pts; i++) {
        const double d1 = sdf_d(S1, pts[i][0], pts[i][1], &v1);
        const double d2 = sdf_d(S2, pts[i][0], pts[i][1], &v2);
        const int inside = i < 2;
        cr_expect(inside ? d1 < 0.0 : d1 > 0.0, "point %zu: %g", i, d1);
        cr_expect(inside ? d2 < 0.0 : d2 > 0.0, "point %zu: %g", i, d2);
        cr_expect_eq(v1.winding, inside ? 1 : 0, "point %zu", i);
        cr_expect_eq(v2.winding, inside ? -1 : 0, "point %zu", i);
        cr_expect(fabs(d1 - d2) <= 1e-12, "point %zu: %.17g vs %.17g", i, d1, d2);
    }
    dfl_curve_sdf_free(S1);
    dfl_curve_sdf_free(S2);
    dfl_bspline_free(&c1);
    dfl_bspline_free(&c2);
}

/* DFL_FOOT_FOCAL is set when |g| = |1 + kappa d| < 1e-6 (header).  On the
 * inner normal of the vertex of largest curvature (the curve is symmetric
 * about the x axis, so its point on the positive axis is a vertex, and the
 * ellipse-like shape makes it the sharpest) the footpoint stays that
 * vertex up to the centre of curvature; just short of the centre g is a
 * small positive number. */
Test(curve_sdf, focal_flag_at_the_centre_of_curvature)
{
    double cp[8 * 2];
    for (int i = 0; i < 8; i++) {
        cp[2 * i] = 1.5 * cos(2.0 * DFL_PI * i / 8);
        cp[2 * i + 1] = sin(2.0 * DFL_PI * i / 8);
    }
    dfl_bspline c;
    cr_assert_eq(dfl_bspline_init_periodic(2, 4, 8, cp, NULL, 0, &c, NULL), DFL_OK);
    dfl_curve_sdf *S;
    dfl_err err;
    cr_assert_eq(dfl_curve_sdf_new(&c, NULL, &S, &err), DFL_OK, "%s", err.msg);
    dfl_curve_sdf_val v;
    sdf_d(S, 1.2, 0.0, &v);
    cr_assert(fabs(v.foot[1]) < 1e-12 && v.foot[0] > 1.2, "foot (%g, %g)", v.foot[0], v.foot[1]);
    cr_assert(v.kappa > 0.0);
    cr_expect(!(v.flags & DFL_FOOT_FOCAL), "g = %g", 1.0 + v.kappa * v.d);
    const double R = 1.0 / v.kappa, x = v.foot[0] - R * (1.0 - 1e-8);
    sdf_d(S, x, 0.0, &v);
    const double g = 1.0 + v.kappa * v.d;
    cr_assert(fabs(v.foot[1]) < 1e-6, "foot (%g, %g)", v.foot[0], v.foot[1]);
    cr_assert(g > 0.0 && g < 1e-6, "g = %g", g);
    cr_expect(v.flags & DFL_FOOT_FOCAL, "g = %g, flags %d", g, v.flags);
    dfl_curve_sdf_free(S);
    dfl_bspline_free(&c);
}

/* A closed curve that encloses no area (here one that runs out along a
 * line and back: the polygon's signed area is 0) has no inside: DFL_E_INPUT
 * (header). */
Test(curve_sdf, rejects_a_curve_that_encloses_no_area)
{
    const double cp[5 * 2] = {0, 0, 1, 0, 2, 0, 1, 0, 0, 0};
    dfl_bspline c;
    cr_assert_eq(dfl_bspline_init(2, 4, 5, cp, NULL, 0, &c, NULL), DFL_OK);
    cr_assert(dfl_bspline_is_closed(&c, 1e-12));
    dfl_curve_sdf *S = NULL;
    dfl_err err;
    cr_expect_eq(dfl_curve_sdf_new(&c, NULL, &S, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "encloses no area"), "%s", err.msg);
    if (S) dfl_curve_sdf_free(S);
    dfl_bspline_free(&c);
}
