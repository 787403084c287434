/* Two segments at a vertex (experiments/bs04/vjoin.h).  Expected values: the
 * geometry written out here (angles, normals), brute-force distances, and
 * the join formulas evaluated from the parts. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "core/vec.h"
#include "io/config.h"
#include "geom/segdist.h"
#include "bs04/vjoin.h"

Test(vjoin, geometry_bisector_and_hatched_range)
{
    const double alphas[7] = {10, 60, 90, 135, 180, 250, 350};
    for (int ia = 0; ia < 7; ia++) {
        dfl_vjoin vj;
        dfl_err err;
        cr_assert_eq(dfl_vjoin_init(alphas[ia], 2.0, 0, &vj, &err), DFL_OK, "%s", err.msg);
        const double a = alphas[ia] * DFL_PI / 180, ap = fmin(a, 2 * DFL_PI - a);
        /* alpha in radians is rounded differently here (a few ulps of 6):
         * 2 |d cos| <= 2 * 2 ulp(6.1) ~ 3.6e-15 */
        cr_expect_float_eq(vj.v[4], 2 * cos(a), 5e-15, "alpha %g", alphas[ia]);
        cr_expect_float_eq(vj.v[5], 2 * sin(a), 5e-15, "alpha %g", alphas[ia]);
        /* bisector: equidistant, both closest points interior */
        const double tb = dfl_vjoin_bisector(&vj), x[2] = {0.1 * cos(tb), 0.1 * sin(tb)};
        double h[2];
        dfl_vjoin_parts(&vj, x, h, NULL);
        cr_expect_float_eq(h[0], h[1], 1e-15, "alpha %g", alphas[ia]);
        cr_expect_float_eq(h[0], 0.1 * sin(ap / 2), 1e-15, "alpha %g", alphas[ia]);
        /* hatched range: width pi - alpha'; inside hatched, outside not */
        double t0, t1;
        int nr;
        dfl_vjoin_hatched_range(&vj, &t0, &t1, &nr);
        cr_expect_float_eq(t1 - t0, DFL_PI - ap, 1e-14, "alpha %g", alphas[ia]);
        cr_expect_eq(nr, alphas[ia] == 180 ? 2 : 1);
        for (int k = 1; k < 10; k++) {
            double t = t0 + (t1 - t0) * k / 10, y[2] = {cos(t), sin(t)};
            cr_expect(dfl_vjoin_hatched(&vj, y) || alphas[ia] == 180, "alpha %g t %g", alphas[ia], t);
            /* hatched: the closest point of both segments is O */
            if (alphas[ia] != 180) {
                dfl_vjoin_parts(&vj, y, h, NULL);
                cr_expect_float_eq(h[0], 1.0, 1e-15);
                cr_expect_float_eq(h[1], 1.0, 1e-15);
            }
        }
        const double out[2] = {t0 - 0.01, t1 + 0.01};
        for (int k = 0; k < 2; k++) {
            double y[2] = {cos(out[k]), sin(out[k])};
            cr_expect(!dfl_vjoin_hatched(&vj, y), "alpha %g t %g", alphas[ia], out[k]);
        }
    }
    /* collinear: the perpendicular line through O, exactly */
    dfl_vjoin vj;
    cr_assert_eq(dfl_vjoin_init(180, 1.0, 0, &vj, NULL), DFL_OK);
    const double up[2] = {0, 0.3}, dn[2] = {0, -0.3}, off[2] = {1e-300, 0.3};
    cr_expect(dfl_vjoin_hatched(&vj, up) && dfl_vjoin_hatched(&vj, dn));
    cr_expect(!dfl_vjoin_hatched(&vj, off));
}

Test(vjoin, field_is_the_join_of_the_parts)
{
    const int ps[2] = {2, 7};
    for (int parts = 0; parts < DFL_VJOIN_NPARTS; parts++) {
        dfl_vjoin vj;
        cr_assert_eq(dfl_vjoin_init(120, 1.0, parts, &vj, NULL), DFL_OK);
        for (int ip = 0; ip < 2; ip++) {
            dfl_field fe, fc;
            dfl_err err;
            cr_assert_eq(dfl_vjoin_field(&vj, DFL_RFUNC_REQUIV, ps[ip], &fe, &err), DFL_OK, "%s",
                         err.msg);
            cr_assert_eq(dfl_vjoin_field(&vj, DFL_RFUNC_RCONJ, ps[ip], &fc, &err), DFL_OK, "%s",
                         err.msg);
            for (int k = 0; k < 50; k++) {
                const double t = 0.3 + 2 * DFL_PI * k / 50, r = 0.05 + 0.01 * k;
                const double x[2] = {r * cos(t), r * sin(t)};
                double h[2], gh[4], g[2], F1, F2;
                dfl_vjoin_parts(&vj, x, h, gh);
                if (h[0] == 0 || h[1] == 0) continue;
                double u = dfl_rfunc_requiv2(h[0], h[1], ps[ip], &F1, &F2);
                cr_expect_float_eq(dfl_field_eval1(&fe, x, g), u, 1e-14 * u, "parts %d", parts);
                cr_expect_float_eq(g[0], F1 * gh[0] + F2 * gh[2], 1e-13);
                cr_expect_float_eq(g[1], F1 * gh[1] + F2 * gh[3], 1e-13);
                u = dfl_rfunc_rconj2(h[0], h[1], ps[ip], &F1, &F2);
                cr_expect_float_eq(dfl_field_eval1(&fc, x, g), u, 1e-14 * u, "parts %d", parts);
                cr_expect_float_eq(g[0], F1 * gh[0] + F2 * gh[2], 1e-13);
            }
            dfl_field_destroy(&fe);
            dfl_field_destroy(&fc);
        }
    }
}

Test(vjoin, union_distance)
{
    dfl_vjoin vj;
    cr_assert_eq(dfl_vjoin_init(90, 1.0, 1, &vj, NULL), DFL_OK);
    const double x[2] = {0.5, 0.2}, y[2] = {-0.3, -0.4}, z[2] = {2.0, 0.5};
    double g[2];
    cr_expect_float_eq(dfl_vjoin_dist(&vj, x, g), 0.2, 1e-15);
    cr_expect_float_eq(dfl_vjoin_dist(&vj, y, g), 0.5, 1e-15);
    cr_expect_float_eq(g[0], -0.6, 1e-15);
    cr_expect_float_eq(dfl_vjoin_dist(&vj, z, NULL), hypot(1.0, 0.5), 1e-15);
}

Test(vjoin, bad_input_names_the_key)
{
    dfl_vjoin vj;
    dfl_err err;
    cr_expect_eq(dfl_vjoin_init(0, 1, 0, &vj, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_vjoin_init(360, 1, 0, &vj, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_vjoin_init(90, 0, 0, &vj, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_vjoin_init(90, 1, 5, &vj, &err), DFL_E_INPUT);
    dfl_cfg *cfg;
    cr_assert_eq(dfl_cfg_parse_string("v.ini", "[s]\nalpha = 360\n", &cfg, &err), DFL_OK);
    cr_expect_eq(dfl_vjoin_from_cfg(cfg, "s", &vj, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "v.ini:2") && strstr(err.msg, "alpha"), "%s", err.msg);
    dfl_cfg_free(cfg);
    cr_assert_eq(dfl_cfg_parse_string("v.ini", "[s]\nalpha = 30\nparts = round\n", &cfg, &err),
                 DFL_OK);
    cr_expect_eq(dfl_vjoin_from_cfg(cfg, "s", &vj, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "v.ini:3") && strstr(err.msg, "strip_smooth"), "%s", err.msg);
    dfl_cfg_free(cfg);
}

/* The part kinds are "exact" and then the trims, by their library names. */
Test(vjoin, part_names_follow_the_trim_list)
{
    cr_assert_eq(DFL_VJOIN_NPARTS, 1 + DFL_RFUNC_TRIM_COUNT);
    cr_expect_str_eq(dfl_vjoin_part_names[0], "exact");
    for (int t = 0; t < DFL_RFUNC_TRIM_COUNT; t++) {
        cr_expect_str_eq(dfl_vjoin_part_names[1 + t], dfl_rfunc_trim_name((dfl_rfunc_trim)t));
        dfl_vjoin vj;
        cr_assert_eq(dfl_vjoin_init(90, 1.0, 1 + t, &vj, NULL), DFL_OK);
        cr_expect_eq(vj.seg[0].trim, (dfl_rfunc_trim)t);
        cr_expect_eq(vj.seg[1].trim, (dfl_rfunc_trim)t);
    }
}
