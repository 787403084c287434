/* Tests for src/io/config_sweep.c: sweep axes and points. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

#include "io/config.h"
#include "util/config_util.h"

/* Sweep expansion: cartesian product, file order, last axis fastest. */
Test(config, sweep_cartesian_product)
{
    dfl_cfg *c = cfgu_parse("[s]\nname = x\n[g]\nn = 1, 2, 3\nm = 10\n[h]\np = a,b\n");
    dfl_err err;
    cr_assert_eq(dfl_cfg_sweep_axes(c), 2);
    cr_assert_eq(dfl_cfg_sweep_points(c), 6);
    cr_expect_str_eq(dfl_cfg_sweep_axis_name(c, 0), "g.n");
    cr_expect_str_eq(dfl_cfg_sweep_axis_name(c, 1), "h.p");
    const char *want_n[6] = {"1", "1", "2", "2", "3", "3"};
    const char *want_p[6] = {"a", "b", "a", "b", "a", "b"};
    for (size_t i = 0; i < 6; i++) {
        dfl_cfg *p = NULL;
        cr_assert_eq(dfl_cfg_sweep_point(c, i, &p, &err), DFL_OK);
        const char *s;
        cr_assert_eq(dfl_cfg_string(p, "g", "n", &s, &err), DFL_OK);
        cr_expect_str_eq(s, want_n[i]);
        cr_assert_eq(dfl_cfg_string(p, "h", "p", &s, &err), DFL_OK);
        cr_expect_str_eq(s, want_p[i]);
        cr_expect_str_eq(dfl_cfg_axis_value(p, 1), want_p[i]);
        dfl_cfg_free(p);
    }
    /* a getter refuses an unexpanded list */
    long n;
    cr_expect_eq(dfl_cfg_int(c, "g", "n", 0, 9, &n, &err), DFL_E_INPUT);
    dfl_cfg_free(c);
}

Test(config, sweep_rejects_empty_items)
{
    dfl_cfg *c = (dfl_cfg *)&c;
    dfl_err err;
    cr_assert_eq(dfl_cfg_parse_string("t.ini", "[g]\nn = 1,,2\n", &c, &err), DFL_E_INPUT);
    cr_assert_null(c);
    cr_assert(strstr(err.msg, "t.ini:2: [g] n: empty item in list '1,,2'"), "%s", err.msg);
    /* a single-valued point reports no axes of its own */
    c = cfgu_parse("[g]\nn = 1, 2\n");
    dfl_cfg *p;
    cr_assert_eq(dfl_cfg_sweep_point(c, 1, &p, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_cfg_sweep_axes(p), 0);
    cr_assert_eq(dfl_cfg_sweep_points(p), 1);
    cr_assert_str_eq(dfl_cfg_axis_value(p, 0), "2");
    cr_assert_eq(dfl_cfg_sweep_point(c, 2, &p, &err), DFL_E_INTERNAL);
    dfl_cfg_free(p);
    dfl_cfg_free(c);
}

/* The product of the list lengths is bounded when the axes are found
 * (10^8), so the point count cannot overflow: 9 axes of 10 items are
 * refused naming the axis that crosses the bound, 8 are accepted. */
Test(config_sweep, point_count_is_bounded)
{
    char text[1024];
    size_t k = (size_t)snprintf(text, sizeof text, "[a]\n");
    for (int i = 0; i < 9; i++)
        k += (size_t)snprintf(text + k, sizeof text - k, "k%d = 0,1,2,3,4,5,6,7,8,9\n", i);
    dfl_cfg *c = NULL;
    dfl_err err;
    cr_assert_eq(dfl_cfg_parse_string("t.ini", text, &c, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "t.ini:10: [a] k8: the sweep would have more than 100000000 points"),
              "%s", err.msg);
    text[strlen(text) - strlen("k8 = 0,1,2,3,4,5,6,7,8,9\n")] = '\0';
    cr_assert_eq(dfl_cfg_parse_string("t.ini", text, &c, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(dfl_cfg_sweep_points(c), 100000000u);
    dfl_cfg_free(c);
}
