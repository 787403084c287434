/* Surface footpoints (foot_surface.c) against a brute-force grid and
 * compass search, and Newton against Ceres. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "geom/footpoint.h"

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

/* Keeps (u, v) as the best parameter if S(u, v) is closer to x than *bd
 * (squared distances); 1 if it was. */
static int try_uv(const dfl_surface *sp, const double *x, double u, double v, double *bd,
                  double *bu, double *bv)
{
    double q[3];
    dfl_surface_eval(sp, u, v, 0, q);
    double d = (q[0] - x[0]) * (q[0] - x[0]) + (q[1] - x[1]) * (q[1] - x[1]) +
               (q[2] - x[2]) * (q[2] - x[2]);
    if (!(d < *bd)) return 0;
    *bd = d;
    *bu = u;
    *bv = v;
    return 1;
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
                try_uv(sp, x, u, v, &bd, &bu, &bv);
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
                moved |= try_uv(sp, x, u, v, &bd, &bu, &bv);
            }
            if (!moved) h *= 0.5;
        }
        best = fmin(best, bd);
    }
    return sqrt(best);
}

Test(foot_surface, surface_matches_brute_force_and_ceres)
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
        double x[3] = {-0.3 + 2.6 * dfl_rng_lcg(&seed), -0.3 + 1.6 * dfl_rng_lcg(&seed),
                       -0.5 + 1.5 * dfl_rng_lcg(&seed)};
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
        double x[3] = {100 * (dfl_rng_lcg(&seed) - 0.5), 100 * (dfl_rng_lcg(&seed) - 0.5), 100};
        dfl_surface_foot fa, fb;
        cr_assert_eq(dfl_surface_footpoint(A, x, &fa, &err), DFL_OK);
        cr_assert_eq(dfl_surface_footpoint(B, x, &fb, &err), DFL_OK);
        cr_assert(fabs(fa.dist - fb.dist) < 1e-10, "newton %.17g ceres %.17g", fa.dist, fb.dist);
    }
    dfl_surface_locator_free(A);
    dfl_surface_locator_free(B);
    dfl_surface_set_free(&s);
}

