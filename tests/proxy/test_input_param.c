/* Parametric proxy inputs: sphere and torus against the SDF input (exact
 * footpoints), the Kallay Newton on Bezier patches against brute force and
 * against geom's independent surface locator, the cone against its closed
 * form. */
#include <criterion/criterion.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "core/vec.h"
#include "geom/footpoint.h"
#include "geom/surface_random.h"
#include "proxy/input_param.h"
#include "proxy/input_sdf.h"

static void expect_same(const dfl_surfpoint *a, const dfl_surfpoint *b, double tp, double tk)
{
    for (int j = 0; j < 3; j++) {
        cr_assert(fabs(a->p[j] - b->p[j]) < tp, "p %.17g vs %.17g", a->p[j], b->p[j]);
        cr_assert(fabs(a->n[j] - b->n[j]) < tp, "n %g vs %g", a->n[j], b->n[j]);
    }
    cr_assert(fabs(a->d - b->d) < tp);
    cr_assert(fabs(a->curv.k1 - b->curv.k1) < tk && fabs(a->curv.k2 - b->curv.k2) < tk,
              "k %g %g vs %g %g", a->curv.k1, a->curv.k2, b->curv.k1, b->curv.k2);
}

Test(input_param, sphere_matches_the_sdf_input)
{
    const double c[3] = {0.05, 0, -0.1}, r = 0.5;
    dfl_proxy_input ip, is;
    dfl_shape s;
    cr_assert_eq(dfl_proxy_input_param_sphere(c, r, NULL, &ip, NULL), DFL_OK);
    cr_assert_eq(dfl_shape_sphere(c, r, &s, NULL), DFL_OK);
    cr_assert_eq(dfl_proxy_input_sdf(&s, DFL_PROXY_CURV_ANALYTIC, NULL, &is, NULL), DFL_OK);
    cr_assert_eq(ip.has_inside, 1);
    uint64_t seed = 5;
    for (int i = 0; i < 300; i++) {
        double x[3];
        for (int j = 0; j < 3; j++) x[j] = dfl_rng_splitmix(&seed, -1, 1);
        dfl_surfpoint a, b;
        cr_assert_eq(dfl_proxy_input_query(&ip, 1, x, 1, &a, NULL), DFL_OK);
        cr_assert_eq(dfl_proxy_input_query(&is, 1, x, 1, &b, NULL), DFL_OK);
        cr_assert(a.certified);
        expect_same(&a, &b, 1e-12, 1e-9);
        cr_assert(fabs(a.curv.k1 - 1 / r) < 1e-9);
    }
    dfl_proxy_input_free(&ip);
    dfl_proxy_input_free(&is);
}

Test(input_param, torus_matches_the_sdf_input)
{
    const double c[3] = {0, 0.1, 0}, ax[3] = {0.3, 0, 1}, R = 0.6, r = 0.25;
    dfl_proxy_input ip, is;
    dfl_shape s;
    cr_assert_eq(dfl_proxy_input_param_torus(c, ax, R, r, NULL, &ip, NULL), DFL_OK);
    cr_assert_eq(dfl_shape_torus(c, ax, R, r, &s, NULL), DFL_OK);
    cr_assert_eq(dfl_proxy_input_sdf(&s, DFL_PROXY_CURV_ANALYTIC, NULL, &is, NULL), DFL_OK);
    uint64_t seed = 9;
    int n = 0;
    while (n < 300) {
        double x[3];
        for (int j = 0; j < 3; j++) x[j] = dfl_rng_splitmix(&seed, -1, 1);
        dfl_surfpoint a, b;
        cr_assert_eq(dfl_proxy_input_query(&is, 1, x, 1, &b, NULL), DFL_OK);
        /* off the medial axis: the tube's centre circle (d = -r) and the
         * axis (|x - c| x w small, d >= R - r) */
        if (b.d < -0.9 * r || b.d > R - r - 0.05) continue;
        n++;
        cr_assert_eq(dfl_proxy_input_query(&ip, 1, x, 1, &a, NULL), DFL_OK);
        cr_assert(a.certified);
        expect_same(&a, &b, 1e-11, 1e-8);
    }
    dfl_proxy_input_free(&ip);
    dfl_proxy_input_free(&is);
}

Test(input_param, cone_lateral_surface_closed_form)
{
    /* a = 0, b = z, radii 0.5 -> 0.1: the distance to the lateral surface
     * in the meridian half-plane is that to the segment (0.5, 0)-(0.1, 1) */
    const double a[3] = {0, 0, 0}, b[3] = {0, 0, 1}, ra = 0.5, rb = 0.1;
    dfl_proxy_input ip;
    cr_assert_eq(dfl_proxy_input_param_cone(a, b, ra, rb, NULL, &ip, NULL), DFL_OK);
    cr_assert_eq(ip.has_inside, 0);
    uint64_t seed = 2;
    for (int i = 0; i < 200; i++) {
        double x[3] = {dfl_rng_splitmix(&seed, -0.4, 0.4), dfl_rng_splitmix(&seed, -0.4, 0.4),
                       dfl_rng_splitmix(&seed, -0.3, 1.3)};
        double rho = hypot(x[0], x[1]);
        if (rho < 0.05) continue; /* near the axis several footpoints tie */
        double s0[2] = {ra, 0}, s1[2] = {rb, 1}, q[2] = {rho, x[2]};
        double e[2] = {s1[0] - s0[0], s1[1] - s0[1]};
        double t = ((q[0] - s0[0]) * e[0] + (q[1] - s0[1]) * e[1]) / (e[0] * e[0] + e[1] * e[1]);
        t = t < 0 ? 0 : (t > 1 ? 1 : t);
        double want = hypot(q[0] - s0[0] - t * e[0], q[1] - s0[1] - t * e[1]);
        dfl_surfpoint o;
        cr_assert_eq(dfl_proxy_input_query(&ip, 1, x, 1, &o, NULL), DFL_OK);
        cr_assert(fabs(o.d - want) < 1e-12, "%g vs %g", o.d, want);
        cr_assert(fabs(x[0] - o.p[0] - o.d * o.n[0]) < 1e-12);
        if (t > 0 && t < 1) {
            /* k = 0 along the generator, cos(alpha)/radius around */
            double rad = ra + t * (rb - ra), ca = 1 / hypot(1, rb - ra);
            double s = (q[0] - s0[0]) * e[1] - (q[1] - s0[1]) * e[0] > 0 ? 1 : -1;
            double kr = s * ca / rad;
            cr_assert(fabs(fmin(o.curv.k1, o.curv.k2)) < 1e-9 ||
                          fabs(fmax(o.curv.k1, o.curv.k2)) < 1e-9);
            cr_assert(fabs(o.curv.k1 + o.curv.k2 - kr) < 1e-9, "%g + %g vs %g", o.curv.k1,
                      o.curv.k2, kr);
        }
    }
    dfl_proxy_input_free(&ip);
}

/* Brute force: the minimum over a 401^2 parameter grid bounds the distance
 * from above, and from below by it minus the grid's half diagonal in R^3
 * (every surface point is within that of a node). */
Test(input_param, kallay_newton_vs_brute_force_on_bezier)
{
    for (uint64_t sd = 1; sd <= 3; sd++) {
        dfl_surface_set set, copy;
        cr_assert_eq(dfl_surface_random_bezier(sd, 4, 0.8, 0.4, &set, NULL), DFL_OK);
        cr_assert_eq(dfl_surface_random_bezier(sd, 4, 0.8, 0.4, &copy, NULL), DFL_OK);
        dfl_surface_locator *L;
        cr_assert_eq(dfl_surface_locator_new(&copy, NULL, &L, NULL), DFL_OK);
        dfl_proxy_input ip;
        cr_assert_eq(dfl_proxy_input_param_surfaces(&set, NULL, &ip, NULL), DFL_OK);
        enum { NG = 401 };
        double *S = malloc(NG * NG * 3 * sizeof *S), hmax = 0;
        for (int j = 0; j < NG; j++)
            for (int i = 0; i < NG; i++)
                dfl_surface_eval(&copy.patch[0], i / (NG - 1.0), j / (NG - 1.0), 0,
                                 S + 3 * (i + NG * j));
        for (int j = 0; j + 1 < NG; j++)
            for (int i = 0; i + 1 < NG; i++) {
                const double *p0 = S + 3 * (i + NG * j), *p1 = S + 3 * (i + 1 + NG * (j + 1));
                double dd[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
                hmax = fmax(hmax, dfl_vec3_norm(dd));
            }
        uint64_t seed = 100 + sd;
        for (int k = 0; k < 60; k++) {
            double x[3] = {dfl_rng_splitmix(&seed, -1, 1), dfl_rng_splitmix(&seed, -1, 1),
                           dfl_rng_splitmix(&seed, -0.8, 0.8)};
            double best = HUGE_VAL;
            for (int t = 0; t < NG * NG; t++) {
                double dd[3] = {S[3 * t] - x[0], S[3 * t + 1] - x[1], S[3 * t + 2] - x[2]};
                best = fmin(best, dfl_vec3_norm(dd));
            }
            dfl_surfpoint o;
            cr_assert_eq(dfl_proxy_input_query(&ip, 1, x, 1, &o, NULL), DFL_OK);
            cr_assert(o.d <= best + 1e-12 && o.d >= best - 0.5 * hmax, "seed %d: %g vs %g",
                      (int)sd, o.d, best);
            dfl_surface_foot f;
            cr_assert_eq(dfl_surface_footpoint(L, x, &f, NULL), DFL_OK);
            cr_assert(fabs(f.dist - o.d) < 1e-10, "locator %g vs %g", f.dist, o.d);
        }
        free(S);
        dfl_surface_locator_free(L);
        dfl_surface_set_free(&copy);
        dfl_proxy_input_free(&ip);
    }
}

/* Every cell centre of a 32^3 grid, poles included (the two charts): the
 * parametric sphere is the exact SDF. */
Test(input_param, sphere_all_cell_centres)
{
    const double c[3] = {0, 0, 0}, r = 0.5;
    dfl_proxy_input ip;
    cr_assert_eq(dfl_proxy_input_param_sphere(c, r, NULL, &ip, NULL), DFL_OK);
    const int N = 32;
    for (int k = 0; k < N; k++)
        for (int j = 0; j < N; j++)
            for (int i = 0; i < N; i++) {
                double x[3] = {-1 + (i + 0.5) * 2.0 / N, -1 + (j + 0.5) * 2.0 / N,
                               -1 + (k + 0.5) * 2.0 / N};
                dfl_surfpoint o;
                dfl_proxy_input_query(&ip, 1, x, 1, &o, NULL);
                cr_assert(o.certified && fabs(o.d - (dfl_vec3_norm(x) - r)) < 1e-12 &&
                              fabs(o.curv.k1 - 1 / r) < 1e-9,
                          "(%g %g %g): d %g", x[0], x[1], x[2], o.d);
            }
    dfl_proxy_input_free(&ip);
}

/* The pruned node scans (opts.prune = 1, the default) answer every query
 * bit for bit as the brute-force scans do: sphere (two charts), torus,
 * cone, one- and several-patch Bezier sets, at points near the surface, far
 * away, on the axis and at a pole, with 1 and 3 starts and a fine grid. */
static void expect_bitwise(const dfl_surfpoint *a, const dfl_surfpoint *b, const double x[3])
{
    cr_assert(memcmp(a, b, offsetof(dfl_surfpoint, certified)) == 0 &&
                  a->certified == b->certified,
              "pruned and brute-force answers differ at (%.17g, %.17g, %.17g): d %.17g vs %.17g",
              x[0], x[1], x[2], a->d, b->d);
}

static void make_input(int kind, const dfl_param_input_opts *o, dfl_proxy_input *ip)
{
    const double c[3] = {0.05, -0.02, 0.01}, ax[3] = {0.2, 0.1, 1};
    const double a[3] = {0, 0, -0.5}, b[3] = {0.1, 0, 0.5};
    dfl_surface_set set;
    switch (kind) {
    case 0: cr_assert_eq(dfl_proxy_input_param_sphere(c, 0.5, o, ip, NULL), DFL_OK); break;
    case 1: cr_assert_eq(dfl_proxy_input_param_torus(c, ax, 0.6, 0.2, o, ip, NULL), DFL_OK); break;
    case 2: cr_assert_eq(dfl_proxy_input_param_cone(a, b, 0.4, 0.1, o, ip, NULL), DFL_OK); break;
    case 3:
        cr_assert_eq(dfl_surface_random_bezier(7, 4, 0.8, 0.4, &set, NULL), DFL_OK);
        cr_assert_eq(dfl_proxy_input_param_surfaces(&set, o, ip, NULL), DFL_OK);
        break;
    default: { /* three biquadratic patches side by side, wavy heights */
        dfl_surface pt[3];
        for (int q = 0; q < 3; q++) {
            double cp[27];
            for (int j = 0; j < 3; j++)
                for (int i = 0; i < 3; i++) {
                    double *v = cp + 3 * (i + 3 * j);
                    v[0] = -0.9 + 0.6 * q + 0.3 * i;
                    v[1] = -0.6 + 0.6 * j;
                    v[2] = 0.2 * sin(3.0 * v[0] + 2.0 * v[1] + q);
                }
            cr_assert_eq(dfl_surface_init_bezier(3, 3, cp, &pt[q], NULL), DFL_OK);
        }
        cr_assert_eq(dfl_surface_set_init(3, pt, &set, NULL), DFL_OK);
        cr_assert_eq(dfl_proxy_input_param_surfaces(&set, o, ip, NULL), DFL_OK);
    }
    }
}

Test(input_param, pruned_scans_equal_brute_force_bit_for_bit)
{
    static const int grids[] = {16, 5, 40}, starts[] = {3, 1, 3};
    for (int kind = 0; kind < 5; kind++)
        for (int g = 0; g < 3; g++) {
            dfl_param_input_opts po, bo;
            dfl_param_input_opts_default(&po);
            cr_assert_eq(po.prune, 1, "the default prunes");
            po.grid = grids[g];
            po.starts = starts[g];
            bo = po;
            bo.prune = 0;
            dfl_proxy_input pi, bi;
            make_input(kind, &po, &pi);
            make_input(kind, &bo, &bi);
            uint64_t seed = 77 + (uint64_t)(10 * kind + g);
            enum { NQ = 300 };
            for (int k = 0; k < NQ; k++) {
                double s = k < NQ / 2 ? 0.8 : 4.0; /* near, then far */
                double x[3] = {dfl_rng_splitmix(&seed, -s, s), dfl_rng_splitmix(&seed, -s, s),
                               dfl_rng_splitmix(&seed, -s, s)};
                if (k == 0) x[0] = 0.05, x[1] = -0.02, x[2] = 0.3; /* on an axis */
                if (k == 1) x[0] = 0.05, x[1] = -0.02, x[2] = 0.51; /* over a pole */
                dfl_surfpoint op, ob;
                cr_assert_eq(dfl_proxy_input_query(&pi, 1, x, 1, &op, NULL), DFL_OK);
                cr_assert_eq(dfl_proxy_input_query(&bi, 1, x, 1, &ob, NULL), DFL_OK);
                expect_bitwise(&op, &ob, x);
            }
            dfl_proxy_input_free(&pi);
            dfl_proxy_input_free(&bi);
        }
}
