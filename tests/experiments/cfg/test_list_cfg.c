/* cfg/list_cfg: section-name lists and fixed-count point lists; and
 * cfg/curve_cfg's curve-section reader. */
#include <criterion/criterion.h>
#include <string.h>

#include "cfg_util.h"
#include "cfg/curve_cfg.h"
#include "cfg/list_cfg.h"

Test(list_cfg, section_names)
{
    dfl_cfg *cfg = tu_cfg("l.ini", "[s]\na = S \t W  Q\nb = \nc = x y z\n"
                         "d = aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa\n"
                         "e = one\n");
    char names[3][DFL_SECTION_NAME_LEN];
    int n = -1;
    dfl_err err;
    cr_assert_eq(dfl_section_names_from_cfg(cfg, "s", "a", 3, names, &n, "thing", &err), DFL_OK,
                 "%s", err.msg);
    cr_assert_eq(n, 3);
    cr_expect_str_eq(names[0], "S");
    cr_expect_str_eq(names[1], "W");
    cr_expect_str_eq(names[2], "Q");
    cr_expect_eq(dfl_section_names_from_cfg(cfg, "s", "b", 3, names, &n, "thing", &err),
                 DFL_E_INPUT);
    cr_expect(strstr(err.msg, "l.ini:3"), "%s", err.msg); /* the reader refuses empty values */
    cr_expect_eq(dfl_section_names_from_cfg(cfg, "s", "c", 2, names, &n, "thing", &err),
                 DFL_E_INPUT);
    cr_expect(strstr(err.msg, "l.ini:4") && strstr(err.msg, "at most 2 section names"), "%s",
              err.msg);
    /* 64 characters: one more than the room */
    cr_expect_eq(dfl_section_names_from_cfg(cfg, "s", "d", 3, names, &n, "thing", &err),
                 DFL_E_INPUT);
    cr_expect(strstr(err.msg, "< 64 characters"), "%s", err.msg);
    cr_expect_eq(dfl_section_names_from_cfg(cfg, "s", "e", 1, names, &n, "thing", &err), DFL_OK);
    cr_expect_eq(n, 1);
    cr_expect_str_eq(names[0], "one");
    cr_expect_eq(dfl_section_names_from_cfg(cfg, "s", "none", 1, names, &n, "thing", &err),
                 DFL_E_INPUT);
    dfl_cfg_free(cfg);
}

Test(list_cfg, points_n)
{
    dfl_cfg *cfg = tu_cfg("l.ini", "[s]\nseg = 0 1; 2 3\ntri = 0 0 0; 1 0 0\nbad = 0 1; 2\n");
    double v[9] = {9, 9, 9, 9, 9, 9, 9, 9, 9};
    dfl_err err;
    cr_assert_eq(dfl_points_n_from_cfg(cfg, "s", "seg", 2, 2, v, "2 end points", &err), DFL_OK,
                 "%s", err.msg);
    const double want[4] = {0, 1, 2, 3};
    cr_expect_arr_eq(v, want, sizeof want);
    cr_expect_eq(v[4], 9.0, "no more than n * dim values written");
    cr_expect_eq(dfl_points_n_from_cfg(cfg, "s", "tri", 3, 3, v, "exactly 3 vertices", &err),
                 DFL_E_INPUT);
    cr_expect(strstr(err.msg, "l.ini:3") && strstr(err.msg, "tri"), "%s", err.msg);
    cr_expect_eq(v[0], 0.0, "untouched on failure");
    cr_expect_eq(dfl_points_n_from_cfg(cfg, "s", "seg", 2, 1, v, "1 point", &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "expected 1 point, got 2"), "%s", err.msg);
    cr_expect_eq(dfl_points_n_from_cfg(cfg, "s", "bad", 2, 2, v, "2 end points", &err),
                 DFL_E_INPUT);
    dfl_cfg_free(cfg);
}

Test(list_cfg, curve_section)
{
    dfl_cfg *cfg = tu_cfg("l.ini", "[c]\nkind = bspline_curve\norder = 2\ncontrol = 0 0; 1 1\n"
                         "[d]\nkind = circle\ncenter = 0 0\nradius = 1\n");
    dfl_bspline c;
    dfl_err err;
    cr_assert_eq(dfl_curve_section_from_cfg(cfg, "c", &c, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(c.dim, 2);
    cr_expect_eq(c.n, 2);
    dfl_bspline_free(&c);
    cr_expect_eq(dfl_curve_section_from_cfg(cfg, "d", &c, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "l.ini:6") && strstr(err.msg, "expected bspline_curve, got 'circle'"),
              "%s", err.msg);
    dfl_cfg_free(cfg);
}
