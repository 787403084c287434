/* The page's C API (src/web/dflweb.h) natively, so that make sanitize runs
 * it under ASan/UBSan and LSan: every entry point on a two-segment scene,
 * a curve scene and the failure paths.  Expected values come from the
 * library called directly (the API must add nothing of its own) and from
 * exact cases (the geometry, the exact-distance bulge 2^(1/p) - 1). */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "core/vec.h"
#include "field/field.h"
#include "geom/segdist.h"
#include "rfunc/rfield.h"
#include "web/dflweb.h"

Test(dflweb, two_segment_geometry_is_symmetric_with_arms_of_length_0_4)
{
    double v[6];
    dflw_two_segments(180, v);
    cr_assert_float_eq(v[1], 0.6, 1e-15);
    cr_assert_float_eq(v[5], 0.6, 1e-15);
    cr_assert_float_eq(v[0], 0.1, 1e-15);
    cr_assert_float_eq(v[4], 0.9, 1e-15);
    dflw_two_segments(90, v);
    cr_assert_float_eq(hypot(v[0] - 0.5, v[1] - 0.6), 0.4, 1e-15);
    cr_assert_float_eq(v[0] + v[4], 1.0, 1e-15);
    cr_assert_float_eq((v[0] - v[2]) * (v[4] - v[2]) + (v[1] - v[3]) * (v[5] - v[3]), 0.0, 1e-15);
    dflw_two_segments(1, v); /* clamped to 10 degrees */
    double w[6];
    dflw_two_segments(10, w);
    cr_assert(memcmp(v, w, sizeof v) == 0);
}

Test(dflweb, eval_grid_and_jets_are_the_library_s)
{
    double v[6];
    dflw_two_segments(120, v);
    dflw_scene *s = dflw_scene_new();
    cr_assert_not_null(s);
    cr_assert_eq(dflw_scene_polyline(s, v, 3, DFL_RFUNC_REQUIV, 7, DFL_RFUNC_TRIM_STRIP), 0);
    cr_assert_str_empty(dflw_scene_error(s));
    cr_assert_eq(dflw_scene_nvertices(s), 3);
    dfl_field f;
    cr_assert_eq(dfl_rfield_polyline(2, v, 3, false, DFL_RFUNC_REQUIV, 7, DFL_RFUNC_TRIM_STRIP, &f, NULL), 0);
    double pts[6] = {0.2, 0.2, 0.5, 0.9, 0.7, 0.45}, val[3], g[6];
    dflw_eval(s, 3, pts, val, g);
    for (int i = 0; i < 3; i++) {
        double gr[2];
        double u = dfl_field_eval1(&f, pts + 2 * i, gr);
        cr_assert(u == val[i] && gr[0] == g[2 * i] && gr[1] == g[2 * i + 1]);
    }
    /* grid: cell centres, row 0 at the top; u as the batch eval gives it */
    float gu[16], gd[16], gn[16];
    dflw_grid(s, 4, 4, 0, 0, 1, 1, gu, gd, gn);
    double x[2] = {0.125, 0.875}, gx[2];
    double u = dfl_field_eval1(&f, x, gx);
    cr_assert_float_eq(gu[0], (float)u, 1e-6 * (1 + u));
    cr_assert_float_eq(gn[0], (float)hypot(gx[0], gx[1]), 1e-6);
    const double d0 = fmin(dfl_point_segment_dist(2, x, v, v + 2), dfl_point_segment_dist(2, x, v + 2, v + 4));
    cr_assert_float_eq(gd[0], (float)d0, 1e-6);
    /* a cell centre above the vertex, in its hatched sector: d = |x - vertex| */
    const double xt[2] = {0.625, 0.875};
    cr_assert_float_eq(gd[2], (float)hypot(xt[0] - v[2], xt[1] - v[3]), 1e-6);
    /* jets: d1 = 1 along a segment's normal, order p for R-equivalence */
    const double e[2] = {(v[2] - v[0]) / 0.4, (v[3] - v[1]) / 0.4};
    const double mid[2] = {(v[0] + v[2]) / 2, (v[1] + v[3]) / 2}, n[2] = {-e[1], e[0]};
    double d[13];
    cr_assert_eq(dflw_jet(s, mid, n, 13, d), 0);
    cr_assert_float_eq(d[0], 1.0, 1e-12);
    int kf = 0;
    cr_assert_eq(dflw_order(s, mid, n, 16, 0.4, 1e-9, &kf), 7);
    cr_assert_eq(kf, 8);
    cr_assert_neq(dflw_jet(s, mid, n, 99, d), 0); /* order outside [0, 24] */
    cr_assert_str_not_empty(dflw_scene_error(s));
    dfl_field_destroy(&f);
    dflw_scene_free(s);
}

Test(dflweb, bounds_ring_and_exact_bulge)
{
    double v[6];
    dflw_two_segments(90, v);
    dflw_scene *s = dflw_scene_new();
    for (int p = 1; p <= 12; p++) {
        cr_assert_eq(dflw_scene_exact(s, v, 3, DFL_RFUNC_REQUIV, p), 0);
        const double up[2] = {0, 1};
        double b = dflw_bulge(s, v + 2, up, 0.05, 0.35);
        cr_assert_float_eq(b, pow(2, 1.0 / p) - 1, 1e-9, "p = %d: bulge %.17g", p, b);
    }
    double lo[5], hi[5];
    cr_assert_eq(dflw_bounds(s, DFL_RFUNC_REQUIV, 2, 5, lo, hi), 0);
    cr_assert_float_eq(hi[2], pow(2, -0.5), 1e-14); /* phi = pi/4: F1 + F2 = 2^(-1/p) */
    cr_assert_float_eq(lo[2], 0.0, 1e-14);
    cr_assert_float_eq(hi[0], 1.0, 1e-14);
    cr_assert_neq(dflw_bounds(s, DFL_RFUNC_REQUIV_CORRECTED, 2, 5, lo, hi), 0);
    /* measured |grad u| on the ring lies in the eq. 13 band at its phi */
    double g[36], phi[36];
    cr_assert_eq(dflw_scene_exact(s, v, 3, DFL_RFUNC_REQUIV, 3), 0);
    dflw_ring(s, v + 2, 0.05, 36, g, phi);
    for (int i = 0; i < 36; i++) {
        cr_assert(isfinite(phi[i]) && phi[i] >= 0 && phi[i] <= DFL_PI / 2 + 1e-15);
        cr_assert(g[i] > 0 && g[i] <= 1 + 1e-12);
    }
    dflw_scene_free(s);
}

Test(dflweb, failures_leave_no_field_and_a_message)
{
    double v[6];
    dflw_two_segments(120, v);
    dflw_scene *s = dflw_scene_new();
    cr_assert_neq(dflw_scene_polyline(s, v, 3, DFL_RFUNC_RCONJ, 1, DFL_RFUNC_TRIM_DISK), 0);
    cr_assert_str_not_empty(dflw_scene_error(s));
    cr_assert_eq(dflw_scene_nvertices(s), 0);
    double x[2] = {0.5, 0.5}, u, g[2];
    dflw_eval(s, 1, x, &u, g);
    cr_assert(isnan(u) && isnan(g[0]));
    cr_assert_neq(dflw_scene_polyline(s, v, 3, 7, 2, DFL_RFUNC_TRIM_DISK), 0);
    cr_assert_neq(dflw_scene_polyline(s, v, 3, DFL_RFUNC_REQUIV, 2, -1), 0);
    cr_assert_neq(dflw_scene_polyline(s, v, 1, DFL_RFUNC_REQUIV, 2, DFL_RFUNC_TRIM_DISK), 0);
    double r[4];
    cr_assert_neq(dflw_curve_bulge(s, 0.05, 11, 4, r), 0);
    cr_assert(isnan(r[0]));
    dflw_scene_free(s);
    dflw_scene_free(NULL);
}

Test(dflweb, curve_scene_polygonizes_and_measures_the_bulge)
{
    /* configs/shapes/W.ini */
    const double cp[14] = {0.05, 0.95, 0.2, 0.05, 0.35, 0.05, 0.5, 0.75, 0.65, 0.05, 0.8, 0.05, 0.95, 0.95};
    dflw_scene *s = dflw_scene_new();
    cr_assert_eq(dflw_scene_curve(s, cp, 7, 4, 0.02, DFL_RFUNC_REQUIV, 3, DFL_RFUNC_TRIM_STRIP), 0,
                 "%s", dflw_scene_error(s));
    const int n = dflw_scene_nvertices(s);
    cr_assert_gt(n, 3);
    const double *pv = dflw_scene_vertices(s);
    cr_assert_float_eq(pv[0], 0.05, 1e-15); /* clamped: the polyline starts at the curve's start */
    cr_assert_float_eq(pv[2 * n - 1], 0.95, 1e-15);
    double r[4];
    cr_assert_eq(dflw_curve_bulge(s, 0.05, 101, 8, r), 0, "%s", dflw_scene_error(s));
    for (int i = 0; i < 4; i++) cr_assert(isfinite(r[i]));
    cr_assert_geq(r[0], r[1]);
    cr_assert_geq(r[0], r[2]);
    cr_assert_gt(r[1], 0); /* the joints bulge outwards */
    /* rebuilding replaces the curve (no leak under LSan) */
    cr_assert_eq(dflw_scene_curve(s, cp, 7, 4, 0.05, DFL_RFUNC_REQUIV, 2, DFL_RFUNC_TRIM_STRIP), 0);
    cr_assert_neq(dflw_scene_curve(s, cp, 7, 4, -1, DFL_RFUNC_REQUIV, 2, DFL_RFUNC_TRIM_STRIP), 0);
    cr_assert_eq(dflw_scene_nvertices(s), 0);
    dflw_scene_free(s);
}

/* The corrected join with exact parts (eq. 20 verbatim) removes the bulge
 * in the hatched sector only.  At alpha = 200 that sector is below the
 * joint (dflw_two_bisector); the upward ray runs on the convex side, where
 * h1 = h2 = d = t sin(80 deg) and q = t, so u = t (2 sin^-p(80) - 1)^(-1/p)
 * and t/c - 1 = (2 sin^-p(80) - 1)^(1/p) - 1 (0.0306 at p = 2) for every c:
 * the page's old upward measure was not a bulge, and no finite-radius effect. */
Test(dflweb, corrected_exact_bulge_is_zero_on_the_reflex_side_only)
{
    double v[6], dir[2], up[2] = {0, 1};
    dflw_two_bisector(120, dir);
    cr_assert(dir[0] == 0 && dir[1] == 1);
    dflw_two_bisector(180, dir);
    cr_assert(dir[1] == 1);
    dflw_two_segments(200, v);
    dflw_two_bisector(200, dir);
    cr_assert(dir[0] == 0 && dir[1] == -1);
    dflw_scene *s = dflw_scene_new();
    for (int p = 1; p <= 12; p++) {
        cr_assert_eq(dflw_scene_exact(s, v, 3, DFL_RFUNC_REQUIV_CORRECTED, p), 0);
        const double sb = sin(80 * DFL_PI / 180), conv = pow(2 * pow(sb, -p) - 1, 1.0 / p) - 1;
        for (double c = 0.01; c < 0.11; c += 0.03) {
            cr_assert_float_eq(dflw_bulge(s, v + 2, dir, c, 0.35), 0.0, 1e-9);
            cr_assert_float_eq(dflw_bulge(s, v + 2, up, c, 0.35), conv, 1e-9, "p %d c %g", p, c);
        }
        /* there u < d = t sin(80): the corrected join does bulge a little on the convex side */
        const double x[2] = {0.5, 0.65};
        double u, d;
        dflw_eval(s, 1, x, &u, NULL);
        dflw_dist(s, 1, x, &d);
        cr_assert_float_eq(d, 0.05 * sb, 1e-12);
        cr_assert_float_eq(u, 0.05 / (1 + conv), 1e-12);
        cr_assert_lt(u, d);
        cr_assert_eq(dflw_scene_exact(s, v, 3, DFL_RFUNC_REQUIV, p), 0);
        cr_assert_float_eq(dflw_bulge(s, v + 2, dir, 0.05, 0.35), pow(2, 1.0 / p) - 1, 1e-9);
    }
    dflw_scene_free(s);
    double d = 0;
    dflw_dist(s = dflw_scene_new(), 1, v, &d); /* no field: NAN */
    cr_assert(isnan(d));
    dflw_scene_free(s);
}
