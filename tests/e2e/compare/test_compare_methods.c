/* End-to-end: compare_methods on configs/compare/quick.ini (every method on
 * the circle, the sjp10 convex curve, the torus and the Wuson mesh; on
 * Wuson every method runs (order-2 proxies with the fitted curvature) and
 * every number is finite).  Expected values are
 * derived, not copied from a run:
 *   - rows: per shape one row per (applicable method, value) and one
 *     skipped row per method that does not apply (dims, shape_kinds);
 *   - the exact field has error 0 in every region and a gradient equal to
 *     the reference's; its pair jumps are those of a C1 function at the
 *     pair separation 2 delta = 2e-9 box lengths: c0 <= 2 delta |grad d|,
 *     c1 <= 2 delta |Hess d| with |Hess d| <= 1 / 0.02 off the medial band;
 *   - bytes: a proxy grid holds res^3 cells x DFL_PROXY_NSCALAR(order)
 *     doubles, plus one sign byte per cell for order 1 with an inside
 *     (proxy/proxy.h); a grid peer res^3 x its scalars (1, 4, 10; tricubic
 *     1) doubles;
 *   - trilinear interpolation of the torus SDF on the centre grid of
 *     h = 2/32: |e| <= h^2/8 (|d_xx| + |d_yy| + |d_zz|) over the cell, and
 *     the cell's centres lie within sqrt(3) h of a band point, where |d| <=
 *     0.05 + sqrt(3) h; there the Hessian's eigenvalues are 0, 1/(r + d) and
 *     cos(theta) / rho with rho >= R - r - |d|: |d_aa| <= 1 / (r - 0.05 -
 *     sqrt(3) h) (R = 0.6, r = 0.25);
 *   - continuity pairs also straddle each grid method's own faces (faces =
 *     count): a trilinear grid is C0 (c0 <= 20 delta) and kinked (c1 > 1e-2);
 *   - a PHT spline is C1: c1_jump is 2 delta |Hess u|, under 1e-4 unless
 *     |Hess u| > 2.5e4; a trilinear grid is C0 and kinked across its faces;
 *     the tricubic spline is C2: its pair jumps are 2 delta |grad u| and
 *     2 delta |Hess u|, |Hess u| <= 4 sqrt(3) max|c| / h^2 (the second
 *     derivative weights of a cubic B-spline sum to <= 4 in absolute value,
 *     the first to <= 1): under 1e-3 unless max|c| > 2e3 at h = 1/16;
 *   - the protocol's point counts: 101^2 and 25^3 grid nodes, 4000 surface
 *     points (all stay in the boxes: the shapes lie 0.15 inside them),
 *     count = grid + surface + medial, no non-finite value anywhere;
 *   - targets: a PHT row's target is its eps, target_met is 1 exactly when
 *     target_over is 0 (pht/fit.h: capped is 0 iff converged),
 *     target_linf_met is 1 exactly when the row's linf is <= eps; every
 *     other row (no kind but pht has a target) has the four cells empty.  On
 *     Wuson the fit cannot meet eps: where the winding-number sign flips
 *     off the mesh (|d| > 0 on a sheet closing an open edge) the SDF jumps
 *     by 2|d|, and a continuous f errs by at least |d| on one side of the
 *     sheet, as close to it as one likes; near the surface at x = 0 such
 *     sheets lie at |d| of about 0.014 (d = -0.0174 at x = -0.02, +0.0100 at
 *     x = -0.01 on the line y = -0.1696, z = 0.1599 of the box: a step of
 *     0.0274 over 0.01, more than the 0.01 a distance can change), above
 *     both eps (1e-2, 1e-3), so cells there stay above eps at max_level:
 *     target_met = 0 and target_over > 0 at both.  On the circle (radius
 *     0.3) at eps = 1e-2 the fit meets it by max_level 6: away from the
 *     centre bicubic Hermite interpolation errs by about h^4 |d''''| / 384
 *     per axis with |d''''| ~ 4! / rho^3 at distance rho from the centre,
 *     below 1e-2 for h <= 1/16 once rho >= 1/64; the centre (the SDF's cone
 *     point, a vertex of every level >= 1, error O(h)) is the estimator's
 *     to judge from its sample points, not a bound the test derives: the
 *     row says what the fit's estimate reached, and the protocol's own
 *     error points may find more there (linf is not the estimate). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "proxy/decode.h"
#include "util/e2e_util.h"

static int is(const char *csv, long r, const char *col, const char *want)
{
    char *v = e2e_csv_cell(csv, r, col);
    const int eq = v && strcmp(v, want) == 0;
    free(v);
    return eq;
}

static double ipow3(double x) { return x * x * x; }

Test(e2e_compare, quick_config_derived, .timeout = 300)
{
    char out[512], csv[700];
    e2e_run_table("configs/compare/quick.ini", NULL, "compare_methods", 63, out, sizeof out, csv,
                  sizeof csv);
    int exact = 0, proxies = 0, peers = 0, skipped = 0, trilinear32 = 0, vdb = 0;
    int pht_wuson = 0, pht_circle = 0;
    for (long r = 0; r < 63; r++) {
        char *m = e2e_csv_cell(csv, r, "method"), *sk = e2e_csv_cell(csv, r, "skipped");
        char *set = e2e_csv_cell(csv, r, "setting");
        cr_assert(m && sk && set);
        const int torus = is(csv, r, "shape", "s_torus");
        const int space = torus || is(csv, r, "shape", "s_wuson");
        const int dim = (int)e2e_csv_get(csv, (size_t)r, "dim");
        cr_expect_eq(dim, space ? 3 : 2, "row %ld", r);
        if (!is(csv, r, "method", "m_pht")) {
            static const char *const tcol[] = {"target", "target_met", "target_over",
                                               "target_linf_met"};
            for (size_t k = 0; k < 4; k++)
                cr_expect(is(csv, r, tcol[k], ""), "row %ld %s: no target, an empty cell", r,
                          tcol[k]);
        }
        if (sk[0]) {
            skipped++;
            const int rf = strcmp(m, "m_rfunc") == 0;
            /* m_proxy2 skips meshes (skip_kinds: order 2 needs a curvature
             * a mesh's edges do not have), m_proxy2_fit takes only them */
            const int p2mesh = strcmp(m, "m_proxy2") == 0 && is(csv, r, "shape", "s_wuson");
            const int p2fit = strcmp(m, "m_proxy2_fit") == 0 && !is(csv, r, "shape", "s_wuson");
            cr_expect(rf ? !is(csv, r, "shape", "s_convex") : p2mesh || p2fit || dim == 2,
                      "row %ld %s skipped", r, m);
            free(m), free(sk), free(set);
            continue;
        }
        const double len = space ? 2.0 : 1.0, delta = 1e-9 * len;
        cr_expect_eq(e2e_csv_get(csv, (size_t)r, "nonfinite"), 0, "row %ld", r);
        const double ng = e2e_csv_get(csv, (size_t)r, "n_grid");
        cr_expect_eq(ng, space ? 25 * 25 * 25 : 101 * 101, "row %ld", r);
        cr_expect_eq(e2e_csv_get(csv, (size_t)r, "n_surface"), 4000, "row %ld", r);
        cr_expect_eq(e2e_csv_get(csv, (size_t)r, "count"),
                     ng + 4000 + e2e_csv_get(csv, (size_t)r, "n_medial"), "row %ld", r);
        const double c0 = e2e_csv_get(csv, (size_t)r, "c0_jump");
        const double c1 = e2e_csv_get(csv, (size_t)r, "c1_jump");
        const double bytes = e2e_csv_get(csv, (size_t)r, "bytes");
        if (strcmp(m, "m_exact") == 0) {
            exact++;
            static const char *const zero[] = {"l1", "rms", "linf", "band_linf", "off_linf",
                                               "grad_linf"};
            for (size_t k = 0; k < sizeof zero / sizeof zero[0]; k++)
                cr_expect_eq(e2e_csv_get(csv, (size_t)r, zero[k]), 0.0, "row %ld %s", r, zero[k]);
            cr_expect_lt(e2e_csv_get(csv, (size_t)r, "eikonal_max"), 1e-14, "row %ld", r);
            cr_expect_leq(c0, 2 * delta * (1 + 1e-6), "row %ld", r);
            /* smooth shapes only: a mesh's SDF bends around its edges and
             * vertices with curvature 1 / |d|, unbounded near the surface */
            if (!is(csv, r, "shape", "s_wuson"))
                cr_expect_leq(c1, 2 * delta / 0.02, "row %ld", r);
            cr_expect(isnan(bytes), "row %ld: exact bytes are not known", r);
        } else if (strncmp(m, "m_proxy", 7) == 0) {
            proxies++;
            const int order = m[7] - '0';
            const double res = atof(set + strlen("res="));
            const double cells = ipow3(res);
            cr_expect_eq(bytes, cells * DFL_PROXY_NSCALAR(order) * 8 + (order == 1 ? cells : 0),
                         "row %ld", r);
        } else if (strncmp(m, "m_gp_", 5) == 0) {
            peers++;
            const double res = atof(set + strlen("res="));
            const int cubic = strcmp(m, "m_gp_tricubic") == 0;
            const int k = strcmp(m, "m_gp_tri") == 0 || cubic ? 1
                          : strcmp(m, "m_gp_t1") == 0    ? 4
                                                         : 10;
            cr_expect_eq(bytes, ipow3(res) * k * 8, "row %ld", r);
            if (cubic) {
                cr_expect_leq(c0, 2 * delta * 10, "row %ld: tricubic is continuous", r);
                cr_expect_lt(c1, 1e-3, "row %ld: tricubic is C2", r);
            }
            if (k == 1 && !cubic) {
                cr_expect_leq(c0, 2 * delta * 10, "row %ld: trilinear is C0", r);
                cr_expect_gt(c1, 1e-2, "row %ld: trilinear is kinked across faces", r);
            }
            if (k == 1 && !cubic && res == 32 && torus) {
                trilinear32++;
                const double h = 2.0 / 32, dmax = 0.05 + sqrt(3.0) * h;
                const double hmax = 1.0 / (0.25 - dmax);
                cr_assert_gt(0.25 - dmax, 0);
                cr_assert_gt(0.6 - 0.25 - dmax, 1.0 / hmax);
                cr_expect_leq(e2e_csv_get(csv, (size_t)r, "band_linf"), h * h / 8 * 3 * hmax,
                              "row %ld", r);
            }
        } else if (strcmp(m, "m_pht") == 0) {
            cr_expect_lt(c1, 1e-4, "row %ld: PHT is C1", r);
            cr_expect_gt(bytes, 0, "row %ld", r);
            const double eps = atof(set + strlen("eps="));
            const double met = e2e_csv_get(csv, (size_t)r, "target_met");
            const double over = e2e_csv_get(csv, (size_t)r, "target_over");
            cr_expect_eq(e2e_csv_get(csv, (size_t)r, "target"), eps, "row %ld", r);
            cr_expect(met == 0 || met == 1, "row %ld: target_met %g", r, met);
            cr_expect_eq(met == 1, over == 0, "row %ld: met %g, over %g", r, met, over);
            /* the study's own verdict: its linf over every error point <= eps */
            const double lm = e2e_csv_get(csv, (size_t)r, "target_linf_met");
            const double linf = e2e_csv_get(csv, (size_t)r, "linf");
            cr_expect_eq(lm, linf <= eps ? 1.0 : 0.0, "row %ld: target_linf_met %g, linf %g, "
                         "eps %g", r, lm, linf, eps);
            if (is(csv, r, "shape", "s_wuson")) {
                pht_wuson++;
                cr_expect_eq(met, 0, "row %ld: eps not reachable across Wuson's jumps", r);
                cr_expect_gt(over, 0, "row %ld", r);
            }
            if (is(csv, r, "shape", "s_circle") && eps == 1e-2) {
                pht_circle++;
                cr_expect_eq(met, 1, "row %ld: the circle meets eps = 1e-2", r);
            }
        } else if (strcmp(m, "m_vdb") == 0) {
            vdb++;
            cr_expect_gt(bytes, 0, "row %ld: OpenVDB's memUsage", r);
            cr_expect(space, "row %ld", r);
        } else {
            cr_expect_str_eq(m, "m_rfunc", "row %ld", r);
            cr_expect_gt(bytes, 0, "row %ld", r);
        }
        free(m), free(sk), free(set);
    }
    cr_expect_eq(exact, 4);
    cr_expect_eq(proxies, 8);
    cr_expect_eq(peers, 16);
    cr_expect_eq(trilinear32, 1);
    cr_expect_eq(vdb, 4);
    cr_expect_eq(pht_wuson, 2);
    cr_expect_eq(pht_circle, 1);
    /* circle: rfunc, 3 proxies, 4 peers, vdb; convex: 8; torus: rfunc,
     * m_proxy2_fit; Wuson: rfunc, m_proxy2 */
    cr_expect_eq(skipped, 9 + 8 + 2 + 2);
}

/* A config around the quick one's keys, with one method and one shape. */
#define BASE                                                                                  \
    "[study]\nname = compare_methods\nmethods = m\nshapes = s\n"                               \
    "[compare]\ngrid3d = 5\nsurface = 10\nmedial_draws = 10\npairs = 10\n"                      \
    "[s]\nkind = sphere\ncenter = 0 0 0\nradius = 0.5\nlo = -1 -1 -1\nhi = 1 1 1\n"

Test(e2e_compare, bad_method_sections_exit_2, .timeout = 60)
{
    /* a typo in a method section is the factory's unknown key, in the copy */
    e2e_expect_bad_config(BASE "[m]\nkind = gridpeer\nresolution = res\nvalues = 4\nmethd = x\n",
                          "[m] methd", "unknown key");
    e2e_expect_bad_config(BASE "[m]\nkind = exact\nresolution = none\nvalues = 4\n",
                          "[m] values", "not with resolution = none");
    e2e_expect_bad_config(BASE "[m]\nkind = gridpeer\nresolution = res\nvalues = 0\n",
                          "[m] values (value 0)", "expected an integer in [1, 1024]");
    e2e_expect_bad_config(BASE "[m]\nkind = gridpeer\nresolution = res\nvalues = 4\ndims = 4\n",
                          "[m] dims", NULL);
    e2e_expect_bad_config(BASE "[m]\nkind = nosuch\nresolution = res\nvalues = 4\n",
                          "[m] kind", NULL);
    /* the box keys the study sets must be keys the kind reads */
    e2e_expect_bad_config(BASE "[m]\nkind = exact\nresolution = none\n", "[m] box",
                          "kind = exact reads no key 'lo' for the box (set box = none");
    /* the last method's typo is named before the first method is built */
    e2e_expect_bad_config("[study]\nname = compare_methods\nmethods = e m\nshapes = s\n"
                          "[s]\nkind = sphere\ncenter = 0 0 0\nradius = 0.5\nlo = -1 -1 -1\n"
                          "hi = 1 1 1\n[e]\nkind = exact\nresolution = none\nbox = none\n"
                          "[m]\nkind = openvdb\nresolution = voxel\nvalues = 0.5\n"
                          "faces = size\nsamplr = box\n",
                          "[m] samplr", "unknown key");
}

Test(e2e_compare, bad_shape_sections_exit_2, .timeout = 60)
{
    e2e_expect_bad_config("[study]\nname = compare_methods\nmethods = m\nshapes = s\n"
                          "[s]\nkind = sphere\ncenter = 0 0 0\nradius = 0.5\nlo = 1 1 1\n"
                          "hi = -1 -1 -1\n[m]\nkind = exact\nresolution = none\nbox = none\n",
                          "[s] hi", "hi > lo");
    e2e_expect_bad_config("[study]\nname = compare_methods\nmethods = m\nshapes = s nos\n"
                          "[s]\nkind = sphere\ncenter = 0 0 0\nradius = 0.5\nlo = -1 -1 -1\n"
                          "hi = 1 1 1\n[m]\nkind = exact\nresolution = none\nbox = none\n",
                          "[study] shapes", "no section [nos]");
    e2e_expect_bad_config("[study]\nname = compare_methods\nmethods = m\nshapes = s\n"
                          "[s]\nkind = sphere\ncenter = 0 0 0\nradius = 0.5\nlo = -1 -1 -1\n"
                          "hi = 1 1 1\ncolour = red\n[m]\nkind = exact\nresolution = none\nbox = none\n",
                          "[s] colour", "unknown key");
}

/* A CSG shape follows sections the study does not name (its operands, and
 * theirs): they count as read, so it runs; a typo in a nested operand is
 * still an unknown key.  The union of two disjoint spheres: the exact
 * field has error 0, one row per method value. */
#define CSG_S "[s]\nkind = csg\nop = union\na = left\nb = pair\nlo = -1 -1 -1\nhi = 1 1 1\n"
#define CSG_SHAPE CSG_S CSG_OPS
#define CSG_OPS                                                                               \
    "[pair]\nkind = csg\nop = union\na = right\nb = top\n"                                   \
    "[left]\nkind = sphere\ncenter = -0.5 0 0\nradius = 0.3\n"                               \
    "[right]\nkind = sphere\ncenter = 0.5 0 0\nradius = 0.3\n"                               \
    "[top]\nkind = sphere\ncenter = 0 0.5 0.3\nradius = 0.2\n"
#define CSG_STUDY                                                                             \
    "[study]\nname = compare_methods\nmethods = m g\nshapes = s\n"                             \
    "[compare]\ngrid3d = 5\nsurface = 10\nmedial_draws = 10\npairs = 10\n"                     \
    "[m]\nkind = exact\nresolution = none\nbox = none\n"                                      \
    "[g]\nkind = gridpeer\nmethod = tricubic\nresolution = res\nvalues = 4 8\ndims = 3\n"

Test(e2e_compare, nested_csg_shape_runs, .timeout = 60)
{
    e2e_table t = {0};
    cr_assert_eq(e2e_ini_table(&t, "csg.ini", CSG_STUDY CSG_SHAPE, "compare_methods", 3), 3);
    for (long r = 0; r < 3; r++) {
        char *sk = e2e_csv_cell(t.csv, r, "skipped");
        cr_expect(sk && !sk[0], "row %ld skipped: %s", r, sk ? sk : "?");
        free(sk);
    }
    cr_expect_eq(e2e_csv_get(t.csv, 0, "linf"), 0.0);
    e2e_rmtree(t.dir);
    e2e_expect_bad_config(CSG_STUDY CSG_SHAPE "colour = red\n", "[top] colour", "unknown key");
}

/* max_values = 1 on a shape: each method's first value runs, the others
 * are skipped rows naming the key (and the exact field's single row runs);
 * out of [1, 32] it is bad input at the key. */
Test(e2e_compare, max_values_reduces_a_shapes_sweep, .timeout = 60)
{
    e2e_table t = {0};
    cr_assert_eq(e2e_ini_table(&t, "mv.ini", CSG_STUDY CSG_S "max_values = 1\n" CSG_OPS,
                               "compare_methods", 3), 3);
    static const char *const want_set[] = {"", "res=4", "res=8"};
    for (long r = 0; r < 3; r++) {
        char *sk = e2e_csv_cell(t.csv, r, "skipped"), *set = e2e_csv_cell(t.csv, r, "setting");
        cr_assert(sk && set);
        cr_expect_str_eq(set, want_set[r], "row %ld", r);
        if (r < 2) cr_expect_str_eq(sk, "", "row %ld", r);
        else cr_expect(strstr(sk, "[s] max_values = 1"), "row %ld: %s", r, sk);
        free(sk), free(set);
    }
    e2e_rmtree(t.dir);
    e2e_expect_bad_config(CSG_STUDY CSG_S "max_values = 0\n" CSG_OPS, "[s] max_values", NULL);
}

/* skip_kinds: a method skips shapes of the kinds listed, one row saying
 * so; other methods still run on the shape. */
Test(e2e_compare, skip_kinds_skips_with_the_reason, .timeout = 60)
{
    e2e_table t = {0};
    cr_assert_eq(e2e_ini_table(&t, "sk.ini", CSG_STUDY "skip_kinds = sphere csg\n" CSG_SHAPE,
                               "compare_methods", 2), 2);
    char *sk0 = e2e_csv_cell(t.csv, 0, "skipped"), *sk1 = e2e_csv_cell(t.csv, 1, "skipped");
    cr_assert(sk0 && sk1);
    cr_expect_str_eq(sk0, "", "the exact field runs");
    cr_expect_str_eq(sk1, "shape kind csg is in skip_kinds");
    free(sk0), free(sk1);
    e2e_rmtree(t.dir);
}

/* The report's marks of a row's target: not met by the build, met by the
 * build's estimate but not by the study's L∞, met both ways, none
 * (check_targets.py, on made-up rows). */
Test(e2e_compare, report_marks_targets_the_build_or_the_study_missed, .timeout = 60)
{
    char dir[256], *py;
    e2e_tmpdir(dir, sizeof dir);
    cr_assert(dir[0], "no temporary directory");
    const int rc = e2e_python_run(dir, &py, "tests/e2e/compare/check_targets.py");
    cr_expect_eq(rc, 0, "%s", py);
    free(py);
    cr_expect_eq(e2e_rmtree(dir), 0);
}
