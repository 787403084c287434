/* rfunc/domain.h: the bounds, the messages, and every part kind of an
 * rfield rejecting geometry beyond them. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "rfunc/domain.h"
#include "rfunc/rfield.h"

Test(rfunc_domain, bounds_and_messages)
{
    dfl_err err;
    const double ok[3] = {1e100, -1e100, 0.0}, big[3] = {0.0, 1.0000000000000002e100, 0.0};
    const double nanp[2] = {NAN, 0.0};
    cr_expect_eq(dfl_rfunc_domain_coords(3, ok, "corner", &err), DFL_OK);
    cr_expect_eq(dfl_rfunc_domain_coords(3, big, "corner", &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "corner (0, 1.0000000000000002e+100, 0)"), "%s", err.msg);
    cr_expect_eq(dfl_rfunc_domain_point(2, nanp, false, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_rfunc_domain_point(2, ok, false, &err), DFL_OK);
    cr_expect_eq(dfl_rfunc_domain_point(2, ok, true, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "jets"), "%s", err.msg);
    const double j[2] = {1e30, -1e30};
    cr_expect_eq(dfl_rfunc_domain_point(2, j, true, &err), DFL_OK);
}

Test(rfunc_domain, every_part_kind_rejects_far_geometry)
{
    dfl_err err;
    dfl_rfield *r;
    const double far[3] = {2e100, 0, 0}, o[3] = {0, 0, 0}, e1[3] = {1, 0, 0}, e2[3] = {0, 1, 0};
    cr_assert_eq(dfl_rfield_new(3, DFL_RFUNC_REQUIV, 2, &r, &err), DFL_OK);
    cr_expect_eq(dfl_rfield_add_segment(r, o, far, DFL_RFUNC_TRIM_DISK, &err), DFL_E_INPUT);
    const dfl_rfunc_tri_opts to = dfl_rfunc_tri_defaults();
    cr_expect_eq(dfl_rfield_add_triangle(r, o, e1, far, &to, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "triangle corner"), "%s", err.msg);
    cr_expect_eq(dfl_rfield_add_point(r, far, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_rfield_add_segment(r, o, e1, DFL_RFUNC_TRIM_DISK, &err), DFL_OK);
    cr_expect_eq(dfl_rfield_add_triangle(r, o, e1, e2, &to, &err), DFL_OK);
    cr_expect_eq(dfl_rfield_count(r), 2u);
    dfl_rfield_free(r);
    cr_assert_eq(dfl_rfield_new(2, DFL_RFUNC_REQUIV, 2, &r, &err), DFL_OK);
    const double sq[8] = {0, 0, 1, 0, 1, 1, 0, 2e100};
    cr_expect_eq(dfl_rfield_add_region(r, sq, 4, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "region vertex"), "%s", err.msg);
    const double tiny[4] = {0, 0, 1e-101, 0};
    cr_expect_eq(dfl_rfield_add_segment(r, tiny, tiny + 2, DFL_RFUNC_TRIM_DISK, &err),
                 DFL_E_INPUT);
    dfl_rfield_free(r);
}

/* Inside the domain an rfield's values and gradients are finite, and the
 * point check accepts exactly the domain. */
Test(rfunc_domain, finite_inside_checked_outside)
{
    const double v[6] = {-1e99, 3e98, 0, 0, 1e99, 1e99};
    for (int t = 0; t < DFL_RFUNC_TRIM_COUNT; t++)
        for (int j = 0; j < DFL_RFUNC_JOIN_COUNT; j++) {
            dfl_field f;
            cr_assert_eq(dfl_rfield_polyline(2, v, 3, false, (dfl_rfunc_join)j, 3,
                                             (dfl_rfunc_trim)t, &f, NULL),
                         DFL_OK);
            const double pts[5][2] = {{1e100, -1e100}, {-1e100, -1e100}, {0.5, 0.5}, {1e99, 0},
                                      {-3e50, 2e-300}};
            for (int i = 0; i < 5; i++) {
                double g[2];
                const double u = dfl_field_eval1(&f, pts[i], g);
                cr_expect(isfinite(u) && isfinite(g[0]) && isfinite(g[1]),
                          "trim %d join %d point %d: %g (%g, %g)", t, j, i, u, g[0], g[1]);
                cr_expect_eq(dfl_rfield_check_point(&f, pts[i], false, NULL), DFL_OK);
            }
            const double out[2] = {0, 1.1e100};
            cr_expect_eq(dfl_rfield_check_point(&f, out, false, NULL), DFL_E_INPUT);
            /* the geometry reaches 1e99: beyond the jets' domain */
            cr_expect_eq(dfl_rfield_check_point(&f, pts[2], true, NULL), DFL_E_INPUT);
            dfl_field_destroy(&f);
        }
}
