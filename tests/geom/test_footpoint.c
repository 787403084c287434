/* Footpoints against brute force, Newton against Ceres on hard cases, and
 * the closed-curve SDF's derivatives (orders 1-3, mixed) and jets against
 * central finite differences and the closed forms. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/footpoint.h"

static double urand(unsigned *s)
{
    *s = *s * 1103515245u + 12345u;
    return (double)((*s >> 8) & 0xFFFFFF) / (double)0x1000000;
}

/* the 'S' of configs/shapes/S.ini (open, clamped cubic) */
static const double S_cp[] = {0.85, 0.85, 0.6, 1.0, 0.1, 0.95, 0.1, 0.6, 0.5,
                              0.5,  0.9,  0.4, 0.9, 0.05, 0.4, 0.0, 0.15, 0.15};

/* a closed periodic cubic symmetric about both axes: points on the x axis
 * inside it are on the medial axis */
static const double blob_cp[] = {2.0, 0.0,  1.6, 0.9,  0.0, 1.0,  -1.6, 0.9,
                                 -2.0, 0.0, -1.6, -0.9, 0.0, -1.0, 1.6, -0.9};

static void make_S(dfl_bspline *c)
{
    cr_assert_eq(dfl_bspline_init(2, 4, 9, S_cp, NULL, 0, c, NULL), DFL_OK);
}

static void make_blob(dfl_bspline *c)
{
    cr_assert_eq(dfl_bspline_init_periodic(2, 4, 8, blob_cp, NULL, 0, c, NULL), DFL_OK);
}

static void make_space(dfl_bspline *c)
{
    double cp[7 * 3];
    for (int i = 0; i < 7; i++) {
        cp[3 * i] = 0.5 + 0.4 * cos(1.3 * i);
        cp[3 * i + 1] = 0.5 + 0.4 * sin(1.3 * i);
        cp[3 * i + 2] = i / 6.0;
    }
    cr_assert_eq(dfl_bspline_init(3, 4, 7, cp, NULL, 0, c, NULL), DFL_OK);
}

/* dense sampling (1e5) + golden-section refinement of the best sample */
static double brute_curve(const dfl_bspline *c, const double *x, double *tbest)
{
    const int N = 100000, dim = c->dim;
    double best = INFINITY;
    int kb = 0;
    for (int k = 0; k <= N; k++) {
        double t = c->t0 + (c->t1 - c->t0) * k / N, p[3], d = 0;
        dfl_bspline_eval(c, t, 0, p);
        for (int j = 0; j < dim; j++) d += (p[j] - x[j]) * (p[j] - x[j]);
        if (d < best) {
            best = d;
            kb = k;
        }
    }
    double lo = c->t0 + (c->t1 - c->t0) * (kb - 1) / N, hi = c->t0 + (c->t1 - c->t0) * (kb + 1) / N;
    if (!c->closed) {
        lo = fmax(lo, c->t0);
        hi = fmin(hi, c->t1);
    }
    const double gr = 0.5 * (sqrt(5.0) - 1.0);
    for (int it = 0; it < 200; it++) {
        double a = hi - gr * (hi - lo), b = lo + gr * (hi - lo), pa[3], pb[3], da = 0, db = 0;
        dfl_bspline_eval(c, a, 0, pa);
        dfl_bspline_eval(c, b, 0, pb);
        for (int j = 0; j < dim; j++) {
            da += (pa[j] - x[j]) * (pa[j] - x[j]);
            db += (pb[j] - x[j]) * (pb[j] - x[j]);
        }
        if (da < db) hi = b;
        else lo = a;
        double m = fmin(da, db);
        if (m < best) best = m;
    }
    if (tbest) *tbest = 0.5 * (lo + hi);
    return sqrt(best);
}

static void check_vs_brute(dfl_bspline *c, unsigned seed, int npts, double lo, double hi)
{
    dfl_curve_locator *L;
    dfl_err err;
    cr_assert_eq(dfl_curve_locator_new(c, NULL, &L, &err), DFL_OK, "%s", err.msg);
    for (int q = 0; q < npts; q++) {
        double x[3];
        for (int j = 0; j < c->dim; j++) x[j] = lo + (hi - lo) * urand(&seed);
        dfl_curve_foot f;
        cr_assert_eq(dfl_curve_footpoint(L, x, &f, &err), DFL_OK);
        double bf = brute_curve(c, x, NULL);
        /* brute force is an upper bound of the minimum; Newton must not be
         * worse, and both agree to rounding + golden-section accuracy */
        cr_assert(f.dist <= bf + 1e-12, "newton %.17g > brute %.17g", f.dist, bf);
        cr_assert(bf - f.dist < 1e-10, "newton %.17g brute %.17g at (%g %g)", f.dist, bf, x[0],
                  x[1]);
        double p[3];
        dfl_bspline_eval(c, f.t, 0, p);
        for (int j = 0; j < c->dim; j++) cr_assert(fabs(p[j] - f.p[j]) < 1e-15);
    }
    dfl_curve_locator_free(L);
}

Test(footpoint, curve_matches_brute_force)
{
    dfl_bspline c;
    make_S(&c);
    check_vs_brute(&c, 1, 40, -0.5, 1.5);
    dfl_bspline_free(&c);
    make_blob(&c);
    check_vs_brute(&c, 2, 40, -3.0, 3.0);
    dfl_bspline_free(&c);
    make_space(&c);
    check_vs_brute(&c, 3, 40, -0.5, 1.5);
    dfl_bspline_free(&c);
}

/* Newton and Ceres agree on hard cases */
static void agree(const dfl_curve_locator *A, const dfl_curve_locator *B, const double *x,
                  int dim, int expect_flags)
{
    dfl_curve_foot fa, fb;
    dfl_err err;
    cr_assert_eq(dfl_curve_footpoint(A, x, &fa, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_curve_footpoint(B, x, &fb, &err), DFL_OK, "%s", err.msg);
    cr_assert(fabs(fa.dist - fb.dist) <= 1e-10, "newton %.17g ceres %.17g at (%g %g)", fa.dist,
              fb.dist, x[0], x[1]);
    if (expect_flags) {
        cr_assert(fa.flags & expect_flags, "flags %d at (%g, %g)", fa.flags, x[0], x[1]);
        cr_assert(fb.flags & expect_flags);
    }
    /* the footpoints coincide unless the position is ill-conditioned
     * (medial / focal); then both are on the same circle of radius dist */
    if (!((fa.flags | fb.flags) & (DFL_FOOT_MEDIAL | DFL_FOOT_FOCAL))) {
        double e = 0;
        for (int j = 0; j < dim; j++) e += (fa.p[j] - fb.p[j]) * (fa.p[j] - fb.p[j]);
        cr_assert(sqrt(e) < 1e-9, "footpoints differ by %g", sqrt(e));
    }
}

Test(footpoint, newton_and_ceres_agree_on_hard_cases)
{
    dfl_bspline c;
    make_blob(&c);
    dfl_foot_opts on, oc;
    dfl_foot_opts_default(&on);
    dfl_foot_opts_default(&oc);
    oc.backend = DFL_FOOT_CERES;
    dfl_curve_locator *A, *B;
    dfl_err err;
    cr_assert_eq(dfl_curve_locator_new(&c, &on, &A, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_curve_locator_new(&c, &oc, &B, &err), DFL_OK, "%s", err.msg);
    /* on the medial axis (the x axis inside) and next to it */
    for (int k = -5; k <= 5; k++) {
        double x[2] = {0.2 * k, 0.0};
        agree(A, B, x, 2, DFL_FOOT_MEDIAL);
        double y[2] = {0.2 * k, 1e-7};
        agree(A, B, y, 2, 0);
    }
    /* deterministic choice on the medial axis: the smaller parameter */
    {
        double x[2] = {0.3, 0.0};
        dfl_curve_foot f[4];
        int n = dfl_curve_footpoints(A, x, f, 4, &err);
        cr_assert(n >= 2);
        cr_assert(f[0].flags & DFL_FOOT_MEDIAL);
        cr_assert(f[0].t < f[1].t);
        cr_assert(fabs(f[0].p[1] + f[1].p[1]) < 1e-9, "mirror footpoints");
    }
    /* at and near the centre of curvature of the vertex of maximal
     * curvature, found by a dense scan + golden section on kappa(t): there
     * the distance has a degenerate (quartic) minimum */
    {
        double best = 0, tb = 0;
        for (int q = 0; q < 8000; q++) {
            double t = 8.0 * q / 8000, D[3 * 2];
            dfl_bspline_eval(&c, t, 2, D);
            double v = hypot(D[2], D[3]), k = (D[2] * D[5] - D[3] * D[4]) / (v * v * v);
            if (k > best) {
                best = k;
                tb = t;
            }
        }
        double lo = tb - 1e-3, hi = tb + 1e-3;
        for (int it = 0; it < 100; it++) {
            double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3, k1, k2, D[6];
            dfl_bspline_eval(&c, m1, 2, D);
            k1 = (D[2] * D[5] - D[3] * D[4]) / pow(hypot(D[2], D[3]), 3);
            dfl_bspline_eval(&c, m2, 2, D);
            k2 = (D[2] * D[5] - D[3] * D[4]) / pow(hypot(D[2], D[3]), 3);
            if (k1 > k2) hi = m2;
            else lo = m1;
        }
        double D[6];
        dfl_bspline_eval(&c, 0.5 * (lo + hi), 2, D);
        double v = hypot(D[2], D[3]);
        double k = (D[2] * D[5] - D[3] * D[4]) / (v * v * v), rho = 1.0 / k;
        /* inward (left) normal of the counter-clockwise curve */
        double cx[2] = {D[0] - rho * D[3] / v, D[1] + rho * D[2] / v};
        agree(A, B, cx, 2, DFL_FOOT_FOCAL);
        dfl_curve_foot f;
        dfl_curve_footpoint(A, cx, &f, &err);
        cr_assert(fabs(f.dist - rho) < 1e-9, "focal distance %.17g vs radius %.17g", f.dist, rho);
        cr_assert(!(f.flags & DFL_FOOT_MEDIAL));
        for (int q = 1; q <= 4; q++) {
            double y[2] = {cx[0] + q * 1e-4, cx[1] - q * 3e-5};
            agree(A, B, y, 2, 0);
        }
    }
    /* far away */
    unsigned seed = 5;
    for (int q = 0; q < 20; q++) {
        double a = 6.283185307179586 * urand(&seed), x[2] = {300 * cos(a), 300 * sin(a)};
        agree(A, B, x, 2, 0);
    }
    /* random points */
    for (int q = 0; q < 40; q++) {
        double x[2] = {-3 + 6 * urand(&seed), -2 + 4 * urand(&seed)};
        agree(A, B, x, 2, 0);
    }
    dfl_curve_locator_free(A);
    dfl_curve_locator_free(B);
    dfl_bspline_free(&c);
}

Test(footpoint, open_curve_ends_and_ceres)
{
    dfl_bspline c;
    make_S(&c);
    dfl_foot_opts oc;
    dfl_foot_opts_default(&oc);
    oc.backend = DFL_FOOT_CERES;
    dfl_curve_locator *A, *B;
    cr_assert_eq(dfl_curve_locator_new(&c, NULL, &A, NULL), DFL_OK);
    cr_assert_eq(dfl_curve_locator_new(&c, &oc, &B, NULL), DFL_OK);
    /* beyond the ends: footpoint is the end point */
    double x[2] = {1.2, 0.9}, y[2] = {0.0, 0.1};
    agree(A, B, x, 2, DFL_FOOT_END);
    agree(A, B, y, 2, DFL_FOOT_END);
    dfl_curve_foot f;
    dfl_curve_footpoint(A, x, &f, NULL);
    cr_assert_eq(f.t, c.t0);
    cr_assert(fabs(f.dist - hypot(1.2 - 0.85, 0.9 - 0.85)) < 1e-15);
    dfl_curve_locator_free(A);
    dfl_curve_locator_free(B);
    dfl_bspline_free(&c);
}

/* ---- surfaces ---- */

static void make_two_patch(dfl_surface_set *set)
{
    dfl_surface p[2];
    double ca[48], cb[48];
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            double x = i / 3.0, y = j / 3.0;
            double *P = ca + (i + 4 * j) * 3, *Q = cb + (i + 4 * j) * 3;
            P[0] = x;
            P[1] = y;
            P[2] = 0.4 * x * (1 - y) + 0.2 * y * y;
            Q[0] = 1 + x;
            Q[1] = y;
            Q[2] = 0.4 * (1 - y) + 0.4 * (1 - y) * x - 0.5 * x * x + 0.2 * y * y;
        }
    cr_assert_eq(dfl_surface_init_bezier(4, 4, ca, &p[0], NULL), DFL_OK);
    cr_assert_eq(dfl_surface_init_bezier(4, 4, cb, &p[1], NULL), DFL_OK);
    cr_assert_eq(dfl_surface_set_init(2, p, set, NULL), DFL_OK);
}

static double brute_surface(const dfl_surface_set *s, const double *x)
{
    double best = INFINITY;
    for (size_t p = 0; p < s->npatch; p++) {
        const dfl_surface *sp = &s->patch[p];
        const int N = 300;
        double bu = 0, bv = 0, bd = INFINITY;
        for (int j = 0; j <= N; j++)
            for (int i = 0; i <= N; i++) {
                double u = sp->u0 + (sp->u1 - sp->u0) * i / N, v = sp->v0 + (sp->v1 - sp->v0) * j / N;
                double q[3];
                dfl_surface_eval(sp, u, v, 0, q);
                double d = (q[0] - x[0]) * (q[0] - x[0]) + (q[1] - x[1]) * (q[1] - x[1]) +
                           (q[2] - x[2]) * (q[2] - x[2]);
                if (d < bd) {
                    bd = d;
                    bu = u;
                    bv = v;
                }
            }
        /* compass search refinement */
        double h = 1.0 / N;
        while (h > 1e-13) {
            int moved = 0;
            for (int k = 0; k < 8; k++) {
                static const int dd[8][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1},
                                             {1, 1}, {-1, -1}, {1, -1}, {-1, 1}};
                double u = fmin(sp->u1, fmax(sp->u0, bu + dd[k][0] * h));
                double v = fmin(sp->v1, fmax(sp->v0, bv + dd[k][1] * h));
                double q[3];
                dfl_surface_eval(sp, u, v, 0, q);
                double d = (q[0] - x[0]) * (q[0] - x[0]) + (q[1] - x[1]) * (q[1] - x[1]) +
                           (q[2] - x[2]) * (q[2] - x[2]);
                if (d < bd) {
                    bd = d;
                    bu = u;
                    bv = v;
                    moved = 1;
                }
            }
            if (!moved) h *= 0.5;
        }
        best = fmin(best, bd);
    }
    return sqrt(best);
}

Test(footpoint, surface_matches_brute_force_and_ceres)
{
    dfl_surface_set s;
    make_two_patch(&s);
    dfl_foot_opts oc;
    dfl_foot_opts_default(&oc);
    oc.backend = DFL_FOOT_CERES;
    dfl_surface_locator *A, *B;
    dfl_err err;
    cr_assert_eq(dfl_surface_locator_new(&s, NULL, &A, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_surface_locator_new(&s, &oc, &B, &err), DFL_OK, "%s", err.msg);
    unsigned seed = 17;
    for (int q = 0; q < 30; q++) {
        double x[3] = {-0.3 + 2.6 * urand(&seed), -0.3 + 1.6 * urand(&seed),
                       -0.5 + 1.5 * urand(&seed)};
        if (q < 8) x[0] = 1.0 + 1e-6 * (q - 4); /* near the patch boundary */
        dfl_surface_foot fa, fb;
        cr_assert_eq(dfl_surface_footpoint(A, x, &fa, &err), DFL_OK);
        cr_assert_eq(dfl_surface_footpoint(B, x, &fb, &err), DFL_OK, "%s", err.msg);
        double bf = brute_surface(&s, x);
        cr_assert(fa.dist <= bf + 1e-12, "newton %.17g > brute %.17g", fa.dist, bf);
        cr_assert(bf - fa.dist < 1e-9, "newton %.17g brute %.17g", fa.dist, bf);
        cr_assert(fabs(fa.dist - fb.dist) < 1e-10, "newton %.17g ceres %.17g", fa.dist, fb.dist);
    }
    /* far away */
    for (int q = 0; q < 10; q++) {
        double x[3] = {100 * (urand(&seed) - 0.5), 100 * (urand(&seed) - 0.5), 100};
        dfl_surface_foot fa, fb;
        cr_assert_eq(dfl_surface_footpoint(A, x, &fa, &err), DFL_OK);
        cr_assert_eq(dfl_surface_footpoint(B, x, &fb, &err), DFL_OK);
        cr_assert(fabs(fa.dist - fb.dist) < 1e-10, "newton %.17g ceres %.17g", fa.dist, fb.dist);
    }
    dfl_surface_locator_free(A);
    dfl_surface_locator_free(B);
    dfl_surface_set_free(&s);
}

/* ---- signed distance of a closed curve ---- */

static double sdf_d(const dfl_curve_sdf *S, double x, double y, dfl_curve_sdf_val *v)
{
    double p[2] = {x, y};
    cr_assert_eq(dfl_curve_sdf_eval(S, p, 3, v, NULL), DFL_OK);
    return v->d;
}

Test(footpoint, sdf_sign_and_rejects_open_curves)
{
    dfl_bspline c;
    make_blob(&c);
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

    make_S(&c);
    cr_assert_eq(dfl_curve_sdf_new(&c, NULL, &S, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "closed curve is required"), "%s", err.msg);
    dfl_bspline_free(&c);
}

Test(footpoint, sdf_derivatives_match_finite_differences)
{
    dfl_bspline c;
    make_blob(&c);
    dfl_curve_sdf *S;
    cr_assert_eq(dfl_curve_sdf_new(&c, NULL, &S, NULL), DFL_OK);
    unsigned seed = 23;
    const double h = 1e-4;
    int tested = 0;
    for (int q = 0; q < 200 && tested < 60; q++) {
        double x = -3 + 6 * urand(&seed), y = -2 + 4 * urand(&seed);
        dfl_curve_sdf_val v, px, mx, py, my;
        sdf_d(S, x, y, &v);
        /* off the medial axis and the focal set: the stencil's footpoints
         * must stay on one branch, and 1 - kappa d well away from 0 */
        if (fabs(1.0 - v.kappa * v.d) < 0.2 || fabs(y) < 0.05) continue;
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

Test(footpoint, sdf_jets_match_closed_forms)
{
    dfl_bspline c;
    make_blob(&c);
    dfl_curve_sdf *S;
    cr_assert_eq(dfl_curve_sdf_new(&c, NULL, &S, NULL), DFL_OK);
    unsigned seed = 31;
    int tested = 0;
    for (int q = 0; q < 100 && tested < 30; q++) {
        double x[2] = {-3 + 6 * urand(&seed), -2 + 4 * urand(&seed)};
        double a = 6.283185307179586 * urand(&seed), dir[2] = {cos(a), sin(a)};
        dfl_curve_sdf_val v;
        cr_assert_eq(dfl_curve_sdf_eval(S, x, 3, &v, NULL), DFL_OK);
        if (fabs(1.0 - v.kappa * v.d) < 0.2 || fabs(x[1]) < 0.05) continue;
        tested++;
        dfl_jet j;
        dfl_err err;
        cr_assert_eq(dfl_curve_sdf_jet(S, x, dir, 6, &j, &err), DFL_OK, "%s", err.msg);
        double d1 = v.g[0] * dir[0] + v.g[1] * dir[1];
        double d2 = v.h[0] * dir[0] * dir[0] + 2 * v.h[1] * dir[0] * dir[1] + v.h[2] * dir[1] * dir[1];
        double d3 = v.t3[0] * pow(dir[0], 3) + 3 * v.t3[1] * dir[0] * dir[0] * dir[1] +
                    3 * v.t3[2] * dir[0] * dir[1] * dir[1] + v.t3[3] * pow(dir[1], 3);
        cr_assert(fabs(dfl_jet_deriv(&j, 0) - v.d) < 1e-14);
        cr_assert(fabs(dfl_jet_deriv(&j, 1) - d1) < 1e-12, "%g vs %g", dfl_jet_deriv(&j, 1), d1);
        cr_assert(fabs(dfl_jet_deriv(&j, 2) - d2) < 1e-10 * (1 + fabs(d2)), "%g vs %g",
                  dfl_jet_deriv(&j, 2), d2);
        cr_assert(fabs(dfl_jet_deriv(&j, 3) - d3) < 1e-9 * (1 + fabs(d3)), "%g vs %g",
                  dfl_jet_deriv(&j, 3), d3);
        /* order 4 against FD of the closed-form third derivative along dir */
        const double h = 1e-4;
        double d3s[2];
        for (int sgn = 0; sgn < 2; sgn++) {
            double y[2] = {x[0] + (sgn ? -h : h) * dir[0], x[1] + (sgn ? -h : h) * dir[1]};
            dfl_curve_sdf_val w;
            dfl_curve_sdf_eval(S, y, 3, &w, NULL);
            d3s[sgn] = w.t3[0] * pow(dir[0], 3) + 3 * w.t3[1] * dir[0] * dir[0] * dir[1] +
                       3 * w.t3[2] * dir[0] * dir[1] * dir[1] + w.t3[3] * pow(dir[1], 3);
        }
        double d4 = (d3s[0] - d3s[1]) / (2 * h);
        cr_assert(fabs(dfl_jet_deriv(&j, 4) - d4) < 1e-4 * (1 + fabs(d4)), "d4 %g vs %g",
                  dfl_jet_deriv(&j, 4), d4);
    }
    cr_assert(tested >= 15);
    dfl_curve_sdf_free(S);
    dfl_bspline_free(&c);
}

Test(footpoint, shapes_wrap_the_distances)
{
    dfl_bspline c;
    make_blob(&c);
    dfl_shape sh;
    dfl_err err;
    cr_assert_eq(dfl_shape_param_curve(&c, NULL, 1, &sh, &err), DFL_OK, "%s", err.msg);
    cr_assert_null(c.cp);
    double x[2] = {0.1, 0.2}, g[2];
    double d = dfl_shape_eval1(&sh, x, g);
    cr_assert(d < 0.0);
    cr_assert(fabs(hypot(g[0], g[1]) - 1.0) < 1e-14);
    dfl_jet j;
    double dir[2] = {1, 0};
    cr_assert_eq(dfl_shape_jet(&sh, x, dir, 3, &j, &err), DFL_OK, "%s", err.msg);
    cr_assert(fabs(dfl_jet_deriv(&j, 0) - d) < 1e-14);
    cr_assert(fabs(dfl_jet_deriv(&j, 1) - g[0]) < 1e-12);
    dfl_shape_free(&sh);

    /* unsigned distance to an open space curve; jet along a ray through
     * the curve: |s| |dir_perp| locally */
    make_space(&c);
    double P[2 * 3];
    dfl_bspline_eval(&c, 2.0, 1, P);
    cr_assert_eq(dfl_shape_param_curve(&c, NULL, 0, &sh, &err), DFL_OK, "%s", err.msg);
    double on[3] = {P[0], P[1], P[2]}, g3[3];
    cr_assert(dfl_shape_eval1(&sh, on, g3) < 1e-12);
    double t[3] = {P[3], P[4], P[5]}, n3[3] = {-t[1], t[0], 0.0};
    double nl = sqrt(n3[0] * n3[0] + n3[1] * n3[1]);
    n3[0] /= nl;
    n3[1] /= nl;
    cr_assert_eq(dfl_shape_jet(&sh, on, n3, 2, &j, &err), DFL_OK, "%s", err.msg);
    cr_assert(fabs(dfl_jet_deriv(&j, 1) - 1.0) < 1e-9, "%g", dfl_jet_deriv(&j, 1));
    dfl_shape_free(&sh);
}
