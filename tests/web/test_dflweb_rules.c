/* The rules src/web/dflweb.h states, one test each, beside
 * tests/web/test_dflweb.c: argument checks (codes, vertex counts, jet
 * orders, bound counts), the clamping of the panel's angle, the grid's
 * layout (cell centres, row 0 at the top, nx by ny, any output NULL), the
 * exact distance as a minimum over every segment, the ring's angles and
 * phi, the bulge's NAN, the curve measure's groups, and the error message
 * that a success clears.  Expected values come from the header's wording
 * and from the library called directly (the API adds nothing of its own). */
#include <criterion/criterion.h>
#include <limits.h>
#include <math.h>
#include <stdbool.h>
#include <string.h>

#include "core/jet.h"
#include "core/vec.h"
#include "field/field.h"
#include "field/normorder.h"
#include "geom/segdist.h"
#include "rfunc/gradbound.h"
#include "rfunc/join.h"
#include "rfunc/rfield.h"
#include "rfunc/segment.h"
#include "web/dflweb.h"

/* a three-segment zigzag: no two segments symmetric about anything */
static const double zig[8] = {0.1, 0.2, 0.35, 0.7, 0.6, 0.3, 0.9, 0.75};

Test(dflweb_rules, alpha_is_clamped_to_10_350_and_arms_hang_symmetric)
{
    double v[6], w[6];
    dflw_two_segments(350, w);
    const double over[] = {350.5, 355, 360, 1000, INFINITY};
    for (size_t i = 0; i < sizeof over / sizeof *over; i++) {
        dflw_two_segments(over[i], v);
        cr_expect(memcmp(v, w, sizeof v) == 0, "alpha %g is not clamped to 350", over[i]);
    }
    dflw_two_segments(10, w);
    const double under[] = {9.5, 0, -90, -INFINITY};
    for (size_t i = 0; i < sizeof under / sizeof *under; i++) {
        dflw_two_segments(under[i], v);
        cr_expect(memcmp(v, w, sizeof v) == 0, "alpha %g is not clamped to 10", under[i]);
    }
    /* inside the range: vertex (0.5, 0.6), arms of length 0.4 at alpha/2 on
     * each side of the downward vertical */
    for (double a = 10; a <= 350; a += 20) {
        dflw_two_segments(a, v);
        cr_expect(v[2] == 0.5 && v[3] == 0.6);
        const double h = a / 2 * DFL_PI / 180;
        cr_expect_float_eq(atan2(v[2] - v[0], v[3] - v[1]), h, 1e-12, "alpha %g", a);
        cr_expect_float_eq(atan2(v[4] - v[2], v[3] - v[5]), h, 1e-12, "alpha %g", a);
        cr_expect_float_eq(hypot(v[0] - v[2], v[1] - v[3]), 0.4, 1e-15);
        cr_expect_float_eq(hypot(v[4] - v[2], v[5] - v[3]), 0.4, 1e-15);
    }
}

Test(dflweb_rules, the_outer_bisector_points_away_from_both_arms)
{
    const double alphas[] = {-5, 10, 90, 179.5, 180, 180.5, 270, 350, 400};
    for (size_t i = 0; i < sizeof alphas / sizeof *alphas; i++) {
        const double a = alphas[i];
        double v[6], dir[2];
        dflw_two_segments(a, v);
        dflw_two_bisector(a, dir);
        cr_expect(dir[0] == 0 && fabs(dir[1]) == 1, "alpha %g: not vertical", a);
        cr_expect(dir[1] == (a <= 180 ? 1.0 : -1.0), "alpha %g: dir %g", a, dir[1]);
        /* the reflex side: away from the arms (a straight line: either way) */
        cr_expect(dir[1] * (v[1] - v[3]) <= 1e-15 && dir[1] * (v[5] - v[3]) <= 1e-15,
                  "alpha %g: the bisector runs along the arms' side", a);
    }
}

/* dflw_scene_polyline with (join, trim) in range fails exactly when the
 * library does; outside the codes' range it is DFL_E_INPUT, with a message
 * and no field. */
Test(dflweb_rules, codes_in_range_are_the_library_s_and_others_refused)
{
    dflw_scene *s = dflw_scene_new();
    for (int join = 0; join < DFL_RFUNC_JOIN_COUNT; join++)
        for (int trim = 0; trim < DFL_RFUNC_TRIM_COUNT; trim++)
            for (int p = 1; p <= 3; p++) {
                dfl_field f;
                const int lib = dfl_rfield_polyline(2, zig, 4, false, (dfl_rfunc_join)join, p,
                                                    (dfl_rfunc_trim)trim, &f, NULL);
                if (lib == 0) dfl_field_destroy(&f);
                const int web = dflw_scene_polyline(s, zig, 4, join, p, trim);
                cr_expect_eq(web, lib, "join %d trim %d p %d: %d, library %d", join, trim, p,
                             web, lib);
                cr_expect_eq(dflw_scene_nvertices(s), web ? 0 : 4);
            }
    const int bad[][2] = {{-1, 0}, {DFL_RFUNC_JOIN_COUNT, 0}, {0, -1}, {0, DFL_RFUNC_TRIM_COUNT},
                          {INT_MIN, 0}, {0, 1000}};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        cr_assert_eq(dflw_scene_polyline(s, zig, 4, DFL_RFUNC_REQUIV, 2, DFL_RFUNC_TRIM_STRIP), 0);
        cr_expect_eq(dflw_scene_polyline(s, zig, 4, bad[i][0], 2, bad[i][1]), DFL_E_INPUT,
                     "join %d trim %d", bad[i][0], bad[i][1]);
        cr_expect_str_not_empty(dflw_scene_error(s));
        cr_expect_eq(dflw_scene_nvertices(s), 0);
        cr_expect_eq(dflw_scene_exact(s, zig, 4, bad[i][0], 2),
                     bad[i][0] >= 0 && bad[i][0] < DFL_RFUNC_JOIN_COUNT ? 0 : DFL_E_INPUT,
                     "exact join %d", bad[i][0]);
    }
    dflw_scene_free(s);
}

Test(dflweb_rules, a_polyline_needs_two_vertices)
{
    dflw_scene *s = dflw_scene_new();
    /* one segment is a polyline */
    cr_expect_eq(dflw_scene_polyline(s, zig, 2, DFL_RFUNC_REQUIV, 2, DFL_RFUNC_TRIM_STRIP), 0,
                 "%s", dflw_scene_error(s));
    cr_expect_eq(dflw_scene_nvertices(s), 2);
    cr_expect_eq(dflw_scene_exact(s, zig, 2, DFL_RFUNC_REQUIV, 2), 0, "%s", dflw_scene_error(s));
    cr_expect_eq(dflw_scene_nvertices(s), 2);
    const int few[] = {1, 0, -1};
    for (size_t i = 0; i < 3; i++) {
        cr_expect_eq(dflw_scene_polyline(s, zig, few[i], DFL_RFUNC_REQUIV, 2, DFL_RFUNC_TRIM_STRIP),
                     DFL_E_INPUT, "n = %d", few[i]);
        cr_expect_eq(dflw_scene_nvertices(s), 0);
        cr_expect_eq(dflw_scene_exact(s, zig, few[i], DFL_RFUNC_REQUIV, 2), DFL_E_INPUT);
        cr_expect_eq(dflw_scene_nvertices(s), 0);
    }
    dflw_scene_free(s);
}

Test(dflweb_rules, a_success_clears_the_last_message)
{
    dflw_scene *s = dflw_scene_new();
    cr_expect_str_empty(dflw_scene_error(s));
    cr_assert_neq(dflw_scene_polyline(s, zig, 1, DFL_RFUNC_REQUIV, 2, DFL_RFUNC_TRIM_STRIP), 0);
    cr_assert_str_not_empty(dflw_scene_error(s));
    cr_expect_eq(dflw_scene_polyline(s, zig, 4, DFL_RFUNC_REQUIV, 2, DFL_RFUNC_TRIM_STRIP), 0);
    cr_expect_str_empty(dflw_scene_error(s));
    cr_assert_neq(dflw_scene_exact(s, zig, 4, -1, 2), 0);
    cr_expect_eq(dflw_scene_exact(s, zig, 4, DFL_RFUNC_REQUIV, 2), 0);
    cr_expect_str_empty(dflw_scene_error(s));
    double lo[3], hi[3], d[3];
    const double x[2] = {0.3, 0.3}, dir[2] = {1, 0};
    cr_assert_neq(dflw_bounds(s, DFL_RFUNC_REQUIV, 2, 1, lo, hi), 0);
    cr_expect_eq(dflw_bounds(s, DFL_RFUNC_REQUIV, 2, 3, lo, hi), 0);
    cr_expect_str_empty(dflw_scene_error(s));
    /* jets: the R-function field has them (the exact one does not) */
    cr_assert_eq(dflw_scene_polyline(s, zig, 4, DFL_RFUNC_REQUIV, 2, DFL_RFUNC_TRIM_STRIP), 0);
    cr_assert_neq(dflw_jet(s, x, dir, DFL_JET_MAX + 1, d), 0);
    cr_expect_eq(dflw_jet(s, x, dir, 3, d), 0);
    cr_expect_str_empty(dflw_scene_error(s));
    dflw_scene_free(s);
}

/* nx x ny cell centres of [x0, x1] x [y0, y1], row j = 0 at the top: node
 * (i, j) at (x0 + (i + 1/2)(x1 - x0)/nx, y1 - (j + 1/2)(y1 - y0)/ny), index
 * j nx + i; u and |grad u| those of dflw_eval there, d that of dflw_dist. */
Test(dflweb_rules, grid_nodes_are_cell_centres_row_0_at_the_top)
{
    dflw_scene *s = dflw_scene_new();
    cr_assert_eq(dflw_scene_polyline(s, zig, 4, DFL_RFUNC_RCONJ, 2, DFL_RFUNC_TRIM_STRIP), 0);
    enum { NX = 5, NY = 3 };
    const double x0 = 0.1, y0 = 0.2, x1 = 0.7, y1 = 0.5;
    float u[NX * NY], d[NX * NY], gn[NX * NY], d2[NX * NY];
    dflw_grid(s, NX, NY, x0, y0, x1, y1, u, d, gn);
    for (int j = 0; j < NY; j++)
        for (int i = 0; i < NX; i++) {
            const double x[2] = {x0 + (i + 0.5) * (x1 - x0) / NX, y1 - (j + 0.5) * (y1 - y0) / NY};
            double val, g[2], dd;
            dflw_eval(s, 1, x, &val, g);
            dflw_dist(s, 1, x, &dd);
            const int k = j * NX + i;
            cr_expect_float_eq(u[k], (float)val, 1e-6 * (1 + fabs(val)), "u (%d, %d)", i, j);
            cr_expect_float_eq(gn[k], (float)hypot(g[0], g[1]), 1e-6, "|grad u| (%d, %d)", i, j);
            cr_expect_float_eq(d[k], (float)dd, 1e-6, "d (%d, %d)", i, j);
        }
    /* any output may be NULL: the others are the same */
    dflw_grid(s, NX, NY, x0, y0, x1, y1, NULL, d2, NULL);
    cr_expect(memcmp(d, d2, sizeof d) == 0);
    dflw_grid(s, NX, NY, x0, y0, x1, y1, NULL, NULL, d2);
    cr_expect(memcmp(gn, d2, sizeof gn) == 0);
    dflw_grid(s, NX, NY, x0, y0, x1, y1, d2, NULL, NULL);
    cr_expect(memcmp(u, d2, sizeof u) == 0);
    /* no field: u and |grad u| are NAN */
    cr_assert_neq(dflw_scene_polyline(s, zig, 1, DFL_RFUNC_RCONJ, 2, DFL_RFUNC_TRIM_STRIP), 0);
    dflw_grid(s, NX, NY, x0, y0, x1, y1, u, NULL, gn);
    for (int k = 0; k < NX * NY; k++) cr_expect(isnan(u[k]) && isnan(gn[k]), "node %d", k);
    dflw_scene_free(s);
}

Test(dflweb_rules, the_exact_distance_is_the_minimum_over_every_segment)
{
    dflw_scene *s = dflw_scene_new();
    cr_assert_eq(dflw_scene_polyline(s, zig, 4, DFL_RFUNC_REQUIV, 2, DFL_RFUNC_TRIM_STRIP), 0);
    /* points nearest the first, middle and last segment, and the ends */
    const double pts[] = {0.2, 0.42, 0.5, 0.5, 0.8, 0.5, 0.95, 0.8, 0.0, 0.1, 0.3, 0.9};
    const int m = (int)(sizeof pts / sizeof *pts / 2);
    double d[6];
    dflw_dist(s, m, pts, d);
    for (int i = 0; i < m; i++) {
        double want = INFINITY;
        for (int q = 0; q < 3; q++)
            want = fmin(want, dfl_point_segment_dist(2, pts + 2 * i, zig + 2 * q, zig + 2 * q + 2));
        cr_expect_eq(d[i], want, "point %d: %.17g, want %.17g", i, d[i], want);
    }
    /* and with the last segment the nearest by far */
    const double near_last[2] = {0.9, 0.76};
    dflw_dist(s, 1, near_last, d);
    cr_expect_float_eq(d[0], dfl_point_segment_dist(2, near_last, zig + 4, zig + 6), 1e-15);
    cr_expect_lt(d[0], 0.02);
    dflw_scene_free(s);
}

Test(dflweb_rules, jets_are_the_library_s_for_k_1_to_K_up_to_24)
{
    dflw_scene *s = dflw_scene_new();
    cr_assert_eq(dflw_scene_polyline(s, zig, 4, DFL_RFUNC_REQUIV, 3, DFL_RFUNC_TRIM_STRIP), 0);
    dfl_field f;
    cr_assert_eq(dfl_rfield_polyline(2, zig, 4, false, DFL_RFUNC_REQUIV, 3, DFL_RFUNC_TRIM_STRIP,
                                     &f, NULL), 0);
    const double x[2] = {0.45, 0.42}, dir[2] = {0.6, 0.8};
    const int Ks[] = {1, 5, DFL_JET_MAX};
    for (size_t t = 0; t < 3; t++) {
        const int K = Ks[t];
        double d[DFL_JET_MAX + 2];
        for (int k = 0; k < DFL_JET_MAX + 2; k++) d[k] = -12345;
        cr_assert_eq(dflw_jet(s, x, dir, K, d), 0, "K = %d: %s", K, dflw_scene_error(s));
        dfl_jet j;
        cr_assert_eq(dfl_field_jet(&f, x, dir, K, &j, NULL), 0);
        for (int k = 1; k <= K; k++)
            cr_expect(d[k - 1] == dfl_jet_deriv(&j, k) || (isnan(d[k - 1]) && isnan(dfl_jet_deriv(&j, k))),
                      "K %d: d%d = %.17g, library %.17g", K, k, d[k - 1], dfl_jet_deriv(&j, k));
        cr_expect_eq(d[K], -12345, "K %d: wrote d[K]", K);
    }
    double d[4] = {0};
    cr_expect_neq(dflw_jet(s, x, dir, DFL_JET_MAX + 1, d), 0);
    cr_expect_neq(dflw_jet(s, x, dir, -1, d), 0);
    /* no field: an error, not a jet */
    cr_assert_neq(dflw_scene_polyline(s, zig, 0, DFL_RFUNC_REQUIV, 3, DFL_RFUNC_TRIM_STRIP), 0);
    cr_expect_neq(dflw_jet(s, x, dir, 2, d), 0);
    cr_expect_str_not_empty(dflw_scene_error(s));
    int kf = 77;
    cr_expect_eq(dflw_order(s, x, dir, 4, 0.4, 1e-9, &kf), -2);
    cr_expect_eq(kf, 77);
    cr_expect_str_not_empty(dflw_scene_error(s));
    dfl_field_destroy(&f);
    dflw_scene_free(s);
}

Test(dflweb_rules, order_is_the_library_s_measure)
{
    dflw_scene *s = dflw_scene_new();
    cr_assert_eq(dflw_scene_polyline(s, zig, 4, DFL_RFUNC_REQUIV, 3, DFL_RFUNC_TRIM_STRIP), 0);
    dfl_field f;
    cr_assert_eq(dfl_rfield_polyline(2, zig, 4, false, DFL_RFUNC_REQUIV, 3, DFL_RFUNC_TRIM_STRIP,
                                     &f, NULL), 0);
    /* on the first segment, along its normal */
    const double e[2] = {zig[2] - zig[0], zig[3] - zig[1]}, len = hypot(e[0], e[1]);
    const double x[2] = {zig[0] + 0.4 * e[0], zig[1] + 0.4 * e[1]};
    const double dirs[2][2] = {{-e[1] / len, e[0] / len}, {e[1] / len, -e[0] / len}};
    for (int t = 0; t < 2; t++)
        for (int K = 2; K <= 12; K += 5) {
            dfl_jet j;
            dfl_normorder o;
            cr_assert_eq(dfl_field_jet(&f, x, dirs[t], K, &j, NULL), 0);
            cr_assert_eq(dfl_normorder_measure(&j, 1.0, 0.4, 1e-9, &o, NULL), 0);
            int kf = -99;
            cr_expect_eq(dflw_order(s, x, dirs[t], K, 0.4, 1e-9, &kf), o.order, "dir %d K %d", t, K);
            cr_expect_eq(kf, o.k, "dir %d K %d", t, K);
        }
    int kf = 5;
    cr_expect_eq(dflw_order(s, x, dirs[0], DFL_JET_MAX + 1, 0.4, 1e-9, &kf), -2);
    cr_expect_eq(dflw_order(s, x, dirs[0], 4, -1, 1e-9, &kf), -2); /* L <= 0 */
    cr_expect_str_not_empty(dflw_scene_error(s));
    dfl_field_destroy(&f);
    dflw_scene_free(s);
}

/* phi_i = i (pi/2) / (n - 1) for n >= 2; DFL_E_INPUT and nothing written
 * for n < 2, a join out of range or one the bounds do not cover. */
Test(dflweb_rules, bounds_span_0_to_pi_over_2_in_n_angles)
{
    dflw_scene *s = dflw_scene_new();
    for (int join = 0; join < DFL_RFUNC_JOIN_COUNT; join++)
        for (int p = 1; p <= 4; p++)
            for (int n = 2; n <= 7; n += 5) {
                double lo[7], hi[7];
                const int lib = dfl_gradbound_check((dfl_rfunc_join)join, p, NULL);
                const int web = dflw_bounds(s, join, p, n, lo, hi);
                cr_expect_eq(web, lib, "join %d p %d", join, p);
                if (web) continue;
                for (int i = 0; i < n; i++) {
                    double F1, F2, l, h;
                    dfl_gradbound_partials((dfl_rfunc_join)join, p, i * (DFL_PI / 2) / (n - 1),
                                           &F1, &F2);
                    dfl_gradbound_band(F1, F2, 1.0, 1.0, &l, &h);
                    cr_expect(lo[i] == l && hi[i] == h, "join %d p %d n %d i %d", join, p, n, i);
                }
            }
    const int bad[][2] = {{DFL_RFUNC_REQUIV, 1}, {DFL_RFUNC_REQUIV, 0}, {DFL_RFUNC_REQUIV, -3},
                          {-1, 5}, {DFL_RFUNC_JOIN_COUNT, 5}};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        double lo[5] = {7, 7, 7, 7, 7}, hi[5] = {7, 7, 7, 7, 7};
        cr_expect_eq(dflw_bounds(s, bad[i][0], 2, bad[i][1], lo, hi), DFL_E_INPUT,
                     "join %d n %d", bad[i][0], bad[i][1]);
        cr_expect_str_not_empty(dflw_scene_error(s));
        for (int k = 0; k < 5; k++) cr_expect(lo[k] == 7 && hi[k] == 7, "written");
    }
    dflw_scene_free(s);
}

Test(dflweb_rules, ring_angles_and_phi_of_two_segments)
{
    double v[6];
    dflw_two_segments(120, v);
    dflw_scene *s = dflw_scene_new();
    cr_assert_eq(dflw_scene_polyline(s, v, 3, DFL_RFUNC_REQUIV, 2, DFL_RFUNC_TRIM_STRIP), 0);
    enum { N = 12 };
    const double c[2] = {0.45, 0.55}, r = 0.08;
    double g[N], phi[N], g2[N];
    dflw_ring(s, c, r, N, g, phi);
    for (int i = 0; i < N; i++) {
        const double t = 2 * DFL_PI * i / N, x[2] = {c[0] + r * cos(t), c[1] + r * sin(t)};
        double u, gr[2];
        dflw_eval(s, 1, x, &u, gr);
        cr_expect_float_eq(g[i], hypot(gr[0], gr[1]), 1e-14, "i %d", i);
        const double h1 = dfl_point_segment_dist(2, x, v, v + 2);
        const double h2 = dfl_point_segment_dist(2, x, v + 2, v + 4);
        cr_expect_float_eq(phi[i], atan2(h2, h1), 1e-14, "i %d: phi %g, h1 %g h2 %g", i, phi[i],
                           h1, h2);
    }
    dflw_ring(s, c, r, N, g2, NULL); /* phi may be NULL */
    cr_expect(memcmp(g, g2, sizeof g) == 0);
    /* three segments: no phi */
    cr_assert_eq(dflw_scene_polyline(s, zig, 4, DFL_RFUNC_REQUIV, 2, DFL_RFUNC_TRIM_STRIP), 0);
    dflw_ring(s, c, r, N, g, phi);
    for (int i = 0; i < N; i++) cr_expect(isnan(phi[i]) && isfinite(g[i]), "i %d", i);
    /* one segment: no phi either */
    cr_assert_eq(dflw_scene_polyline(s, zig, 2, DFL_RFUNC_REQUIV, 2, DFL_RFUNC_TRIM_STRIP), 0);
    dflw_ring(s, c, r, N, g, phi);
    for (int i = 0; i < N; i++) cr_expect(isnan(phi[i]), "i %d", i);
    dflw_scene_free(s);
}

Test(dflweb_rules, bulge_is_nan_when_u_does_not_reach_c)
{
    double v[6];
    dflw_two_segments(90, v);
    dflw_scene *s = dflw_scene_new();
    const double up[2] = {0, 1};
    cr_expect(isnan(dflw_bulge(s, v + 2, up, 0.05, 0.35)), "no field");
    cr_assert_eq(dflw_scene_polyline(s, v, 3, DFL_RFUNC_REQUIV, 2, DFL_RFUNC_TRIM_STRIP), 0);
    const double tmax = 0.1, end[2] = {v[2], v[3] + tmax};
    double umax;
    dflw_eval(s, 1, end, &umax, NULL);
    cr_assert(umax > 0);
    cr_expect(isnan(dflw_bulge(s, v + 2, up, 1.5 * umax, tmax)), "c above u(tmax)");
    /* reached: u(v + (1 + b) c dir) = c */
    const double c = 0.5 * umax, b = dflw_bulge(s, v + 2, up, c, tmax);
    cr_assert(isfinite(b));
    const double x[2] = {v[2], v[3] + (1 + b) * c};
    double u;
    dflw_eval(s, 1, x, &u, NULL);
    cr_expect_float_eq(u, c, 1e-12);
    dflw_scene_free(s);
}

Test(dflweb_rules, curve_bulge_groups_and_only_with_a_curve)
{
    const double cp[14] = {0.05, 0.95, 0.2, 0.05, 0.35, 0.05, 0.5, 0.75, 0.65, 0.05, 0.8, 0.05, 0.95, 0.95};
    dflw_scene *s = dflw_scene_new();
    cr_assert_eq(dflw_scene_curve(s, cp, 7, 4, 0.02, DFL_RFUNC_REQUIV, 3, DFL_RFUNC_TRIM_STRIP), 0,
                 "%s", dflw_scene_error(s));
    double r[4];
    /* no cap rays: the cap group is empty (NAN), the sides are not */
    cr_assert_eq(dflw_curve_bulge(s, 0.05, 41, 0, r), 0, "%s", dflw_scene_error(s));
    cr_expect(isnan(r[3]), "cap max %g with ncap = 0", r[3]);
    cr_expect(isfinite(r[1]) && isfinite(r[2]));
    cr_expect_eq(r[0], fmax(r[1], r[2]));
    /* with caps: the overall max is the largest group max */
    cr_assert_eq(dflw_curve_bulge(s, 0.05, 41, 6, r), 0, "%s", dflw_scene_error(s));
    cr_expect(isfinite(r[3]));
    cr_expect_eq(r[0], fmax(fmax(r[1], r[2]), r[3]));
    /* a polyline scene after the curve scene has no curve */
    cr_assert_eq(dflw_scene_polyline(s, zig, 4, DFL_RFUNC_REQUIV, 3, DFL_RFUNC_TRIM_STRIP), 0);
    cr_expect_eq(dflw_curve_bulge(s, 0.05, 41, 6, r), DFL_E_INPUT);
    for (int i = 0; i < 4; i++) cr_expect(isnan(r[i]));
    /* a negative control-point count is refused, not read as a huge one */
    cr_expect_neq(dflw_scene_curve(s, cp, -7, 4, 0.02, DFL_RFUNC_REQUIV, 3, DFL_RFUNC_TRIM_STRIP), 0);
    cr_expect_eq(dflw_scene_nvertices(s), 0);
    dflw_scene_free(s);
}
