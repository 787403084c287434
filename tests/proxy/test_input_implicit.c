/* Implicit proxy inputs: robust footpoints of the torus quartic agree with
 * the parametric torus; the sphere's three inputs agree (kappa = +1/r); on
 * the scrambled ellipsoid the robust answers are certified and never
 * farther than the paper method's, and the certificate rejects far-side
 * critical points. */
#include <criterion/criterion.h>
#include <math.h>

#include "core/rng.h"
#include "core/vec.h"
#include "proxy/input_implicit.h"
#include "proxy/input_param.h"
#include "proxy/input_sdf.h"

static void cell_centre(uint64_t *seed, int N, double x[3])
{
    for (int j = 0; j < 3; j++) {
        int i = (int)dfl_rng_splitmix(seed, 0, N);
        x[j] = -1 + (i + 0.5) * 2.0 / N;
    }
}

Test(input_implicit, torus_robust_matches_parametric)
{
    const double c[3] = {0, 0, 0}, ax[3] = {0, 0, 1}, R = 0.6, r = 0.25;
    dfl_implicit *imp;
    cr_assert_eq(dfl_implicit_torus(c, ax, R, r, NULL, &imp, NULL), DFL_OK);
    dfl_proxy_input ii, ip;
    cr_assert_eq(dfl_proxy_input_implicit(&imp, DFL_IMPLICIT_FOOT_ROBUST, &ii, NULL), DFL_OK);
    cr_assert_null(imp);
    cr_assert_eq(dfl_proxy_input_param_torus(c, ax, R, r, NULL, &ip, NULL), DFL_OK);
    uint64_t seed = 21;
    int n = 0;
    while (n < 150) {
        double x[3];
        cell_centre(&seed, 32, x);
        /* off the medial axis: the centre circle and the z axis */
        double rho = hypot(x[0], x[1]), dc = hypot(rho - R, x[2]);
        if (dc < 0.1 * r || rho < 0.1) continue;
        n++;
        dfl_surfpoint a, b;
        cr_assert_eq(dfl_proxy_input_query(&ii, 1, x, 1, &a, NULL), DFL_OK);
        cr_assert_eq(dfl_proxy_input_query(&ip, 1, x, 1, &b, NULL), DFL_OK);
        cr_assert(a.certified && b.certified);
        for (int j = 0; j < 3; j++) {
            cr_assert(fabs(a.p[j] - b.p[j]) < 1e-9, "p %.17g vs %.17g", a.p[j], b.p[j]);
            cr_assert(fabs(a.n[j] - b.n[j]) < 1e-9);
        }
        cr_assert(fabs(a.d - b.d) < 1e-9);
        cr_assert(fabs(a.curv.k1 - b.curv.k1) < 1e-8 && fabs(a.curv.k2 - b.curv.k2) < 1e-8);
    }
    dfl_proxy_input_free(&ii);
    dfl_proxy_input_free(&ip);
}

Test(input_implicit, sphere_three_inputs_agree)
{
    const double c[3] = {0, 0, 0}, r = 0.5;
    dfl_proxy_input in[4];
    dfl_implicit *i1, *i2;
    dfl_shape s;
    cr_assert_eq(dfl_shape_sphere(c, r, &s, NULL), DFL_OK);
    cr_assert_eq(dfl_proxy_input_sdf(&s, DFL_PROXY_CURV_ANALYTIC, NULL, &in[0], NULL), DFL_OK);
    cr_assert_eq(dfl_proxy_input_param_sphere(c, r, NULL, &in[1], NULL), DFL_OK);
    cr_assert_eq(dfl_implicit_sphere(c, r, NULL, &i1, NULL), DFL_OK);
    cr_assert_eq(dfl_implicit_sphere(c, r, NULL, &i2, NULL), DFL_OK);
    cr_assert_eq(dfl_proxy_input_implicit(&i1, DFL_IMPLICIT_FOOT_ROBUST, &in[2], NULL), DFL_OK);
    cr_assert_eq(dfl_proxy_input_implicit(&i2, DFL_IMPLICIT_FOOT_PAPER, &in[3], NULL), DFL_OK);
    uint64_t seed = 4;
    for (int t = 0; t < 100; t++) {
        double x[3];
        cell_centre(&seed, 16, x);
        dfl_surfpoint o[4];
        for (int k = 0; k < 4; k++) {
            cr_assert_eq(dfl_proxy_input_query(&in[k], 1, x, 1, &o[k], NULL), DFL_OK);
            cr_assert(o[k].certified, "input %d", k);
            cr_assert(fabs(o[k].curv.k1 - 1 / r) < 1e-9 && fabs(o[k].curv.k2 - 1 / r) < 1e-9,
                      "input %d: %g %g", k, o[k].curv.k1, o[k].curv.k2);
            for (int j = 0; j < 3; j++) {
                cr_assert(fabs(o[k].p[j] - o[0].p[j]) < 1e-12, "input %d", k);
                cr_assert(fabs(o[k].n[j] - o[0].n[j]) < 1e-12, "input %d", k);
            }
            cr_assert(fabs(o[k].d - o[0].d) < 1e-12, "input %d", k);
        }
    }
    for (int k = 0; k < 4; k++) dfl_proxy_input_free(&in[k]);
}

Test(input_implicit, scrambled_ellipsoid_robust_vs_paper)
{
    const double c[3] = {0, 0, 0}, semi[3] = {0.7, 0.5, 0.35};
    dfl_implicit *i1, *i2;
    cr_assert_eq(dfl_implicit_ellipsoid(c, semi, 4, NULL, &i1, NULL), DFL_OK);
    cr_assert_eq(dfl_implicit_ellipsoid(c, semi, 4, NULL, &i2, NULL), DFL_OK);
    const dfl_implicit *S = i1;
    dfl_proxy_input rb, pp;
    cr_assert_eq(dfl_proxy_input_implicit(&i1, DFL_IMPLICIT_FOOT_ROBUST, &rb, NULL), DFL_OK);
    cr_assert_eq(dfl_proxy_input_implicit(&i2, DFL_IMPLICIT_FOOT_PAPER, &pp, NULL), DFL_OK);
    int N = 8, worse = 0;
    for (int k = 0; k < N; k++)
        for (int j = 0; j < N; j++)
            for (int i = 0; i < N; i++) {
                double x[3] = {-1 + (i + 0.5) * 2.0 / N, -1 + (j + 0.5) * 2.0 / N,
                               -1 + (k + 0.5) * 2.0 / N};
                dfl_surfpoint a, b;
                cr_assert_eq(dfl_proxy_input_query(&rb, 1, x, 1, &a, NULL), DFL_OK);
                cr_assert_eq(dfl_proxy_input_query(&pp, 1, x, 1, &b, NULL), DFL_OK);
                cr_assert(a.certified, "(%g %g %g)", x[0], x[1], x[2]);
                cr_assert(fabs(x[0] - a.p[0] - a.d * a.n[0]) < 1e-9);
                if (b.certified) {
                    cr_assert(fabs(a.d) <= fabs(b.d) + 1e-12);
                    if (fabs(b.d) > fabs(a.d) + 1e-6) worse++;
                }
            }
    /* the far side of the ellipsoid is a critical point of the distance but
     * not a minimum: the certificate refuses it */
    double x[3] = {0.9, 0, 0}, far[3] = {-0.7, 0, 0};
    cr_assert(dfl_proxy_implicit_certify(S, x, (double[3]){0.7, 0, 0}, 0.2));
    cr_assert(!dfl_proxy_implicit_certify(S, x, far, -1.6));
    cr_assert(!dfl_proxy_implicit_certify(S, x, far, 1.6));
    cr_log_info("paper footpoints farther than robust: %d of %d", worse, N * N * N);
    dfl_proxy_input_free(&rb);
    dfl_proxy_input_free(&pp);
}

/* The robust method's fast path (one Newton from the nearest sample, kept
 * when the cap test passes) answers what geom's full search answers, on
 * Goursat's surface (several components) and the scrambled ellipsoid. */
Test(input_implicit, fast_path_matches_the_full_search)
{
    const double c[3] = {0, 0, 0}, semi[3] = {0.7, 0.5, 0.35};
    for (int shape = 0; shape < 2; shape++) {
        dfl_implicit *a, *b;
        if (shape == 0) {
            cr_assert_eq(dfl_implicit_goursat(c, 0, -0.8, 0.30208, NULL, &a, NULL), DFL_OK);
            cr_assert_eq(dfl_implicit_goursat(c, 0, -0.8, 0.30208, NULL, &b, NULL), DFL_OK);
        } else {
            cr_assert_eq(dfl_implicit_ellipsoid(c, semi, 4, NULL, &a, NULL), DFL_OK);
            cr_assert_eq(dfl_implicit_ellipsoid(c, semi, 4, NULL, &b, NULL), DFL_OK);
        }
        dfl_proxy_input in;
        cr_assert_eq(dfl_proxy_input_implicit(&a, DFL_IMPLICIT_FOOT_ROBUST, &in, NULL), DFL_OK);
        uint64_t seed = 40 + shape;
        for (int t = 0; t < 150; t++) {
            double x[3];
            cell_centre(&seed, 32, x);
            dfl_surfpoint o;
            dfl_footpoint f;
            cr_assert_eq(dfl_proxy_input_query(&in, 1, x, 1, &o, NULL), DFL_OK);
            cr_assert_eq(dfl_implicit_footpoint(b, x, &f, NULL), DFL_OK);
            cr_assert(o.certified && fabs(o.d - f.d) < 1e-9, "shape %d (%g %g %g): %g vs %g", shape,
                      x[0], x[1], x[2], o.d, f.d);
        }
        dfl_proxy_input_free(&in);
        dfl_implicit_free(b);
    }
}

/* The three readings of the paper's starts, each as its header states:
 * outside the surface (g > 0) paper_against takes the paper's starts, so its
 * answers are the paper's bit for bit; on the implicit sphere every reading
 * converges to the exact footpoint (Newton on the square system of a
 * sphere from any start off the centre), inside and outside, d = |x| - r;
 * an unknown method is refused and the surface freed. */
Test(input_implicit, paper_start_readings)
{
    const double c[3] = {0, 0, 0}, ax[3] = {0, 0, 1};
    static const dfl_implicit_foot_method ms[3] = {
        DFL_IMPLICIT_FOOT_PAPER, DFL_IMPLICIT_FOOT_AGAINST, DFL_IMPLICIT_FOOT_WALK};
    dfl_proxy_input tor[3], sph[3];
    for (int m = 0; m < 3; m++) {
        dfl_implicit *t, *s;
        cr_assert_eq(dfl_implicit_torus(c, ax, 0.6, 0.25, NULL, &t, NULL), DFL_OK);
        cr_assert_eq(dfl_implicit_sphere(c, 0.5, NULL, &s, NULL), DFL_OK);
        cr_assert_eq(dfl_proxy_input_implicit(&t, ms[m], &tor[m], NULL), DFL_OK);
        cr_assert_eq(dfl_proxy_input_implicit(&s, ms[m], &sph[m], NULL), DFL_OK);
    }
    uint64_t seed = 3;
    int outside = 0, inside = 0;
    for (int k = 0; k < 400; k++) {
        double x[3];
        for (int j = 0; j < 3; j++) x[j] = dfl_rng_splitmix(&seed, -1, 1);
        const double rho = hypot(x[0], x[1]), dt = hypot(rho - 0.6, x[2]) - 0.25;
        dfl_surfpoint a, b;
        if (dt > 0) {
            outside++;
            cr_assert_eq(dfl_proxy_input_query(&tor[0], 1, x, 1, &a, NULL), DFL_OK);
            cr_assert_eq(dfl_proxy_input_query(&tor[1], 1, x, 1, &b, NULL), DFL_OK);
            cr_expect_eq(a.certified, b.certified);
            for (int j = 0; j < 3; j++) cr_expect(a.p[j] == b.p[j] || (isnan(a.p[j]) && isnan(b.p[j])));
        }
        const double nx = dfl_vec3_norm(x);
        if (nx < 0.05) continue;
        inside += nx < 0.5;
        for (int m = 0; m < 3; m++) {
            cr_assert_eq(dfl_proxy_input_query(&sph[m], 1, x, 1, &a, NULL), DFL_OK);
            cr_expect(a.certified, "method %d", m);
            cr_expect(fabs(a.d - (nx - 0.5)) < 1e-12, "method %d: d %.17g vs %.17g", m, a.d,
                      nx - 0.5);
            for (int j = 0; j < 3; j++)
                cr_expect(fabs(a.p[j] - 0.5 * x[j] / nx) < 1e-12, "method %d", m);
        }
    }
    cr_expect(outside > 100 && inside > 20, "%d outside, %d inside", outside, inside);
    for (int m = 0; m < 3; m++) dfl_proxy_input_free(&tor[m]), dfl_proxy_input_free(&sph[m]);
    dfl_implicit *t;
    cr_assert_eq(dfl_implicit_sphere(c, 0.5, NULL, &t, NULL), DFL_OK);
    dfl_proxy_input in;
    cr_expect_eq(dfl_proxy_input_implicit(&t, (dfl_implicit_foot_method)DFL_IMPLICIT_FOOT_COUNT,
                                          &in, NULL), DFL_E_INPUT);
    cr_expect_null(t);
    dfl_implicit_foot_method fm;
    cr_expect_eq(dfl_implicit_foot_parse("paper_walk", &fm, NULL), DFL_OK);
    cr_expect_eq(fm, DFL_IMPLICIT_FOOT_WALK);
}
