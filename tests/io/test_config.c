#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/config.h"

static dfl_cfg *parse(const char *text)
{
    dfl_cfg *c = NULL;
    dfl_err err;
    dfl_status st = dfl_cfg_parse_string("t.ini", text, &c, &err);
    cr_assert_eq(st, DFL_OK, "%s", err.msg);
    return c;
}

Test(config, typed_getters)
{
    dfl_cfg *c = parse("[a]\ni = 42\nd = -1.5e-3\nb = yes\ne = strip\n"
                       "v = 1 2 3\np = 0 0; 1 0.5; 2 1;\nl = 0 0 0 1 1 1\n");
    dfl_err err;
    long i;
    double d, v[3];
    bool b;
    int e;
    static const char *const names[] = {"disk", "strip"};
    cr_assert_eq(dfl_cfg_int(c, "a", "i", 0, 100, &i, &err), DFL_OK);
    cr_expect_eq(i, 42);
    cr_assert_eq(dfl_cfg_double(c, "a", "d", -1, 1, &d, &err), DFL_OK);
    cr_expect_eq(d, -1.5e-3);
    cr_assert_eq(dfl_cfg_bool(c, "a", "b", &b, &err), DFL_OK);
    cr_expect(b);
    cr_assert_eq(dfl_cfg_enum(c, "a", "e", names, 2, &e, &err), DFL_OK);
    cr_expect_eq(e, 1);
    cr_assert_eq(dfl_cfg_vec(c, "a", "v", 3, v, &err), DFL_OK);
    cr_expect(v[0] == 1 && v[1] == 2 && v[2] == 3);
    double *pts;
    size_t n;
    cr_assert_eq(dfl_cfg_points(c, "a", "p", 2, 2, &pts, &n, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(n, 3);
    cr_expect(pts[2] == 1 && pts[3] == 0.5 && pts[5] == 1);
    free(pts);
    double *l;
    cr_assert_eq(dfl_cfg_doubles(c, "a", "l", 2, &l, &n, &err), DFL_OK);
    cr_expect_eq(n, 6);
    free(l);
    cr_expect_eq(dfl_cfg_check_used(c, &err), DFL_OK, "%s", err.msg);
    /* defaults do not invent keys */
    cr_assert_eq(dfl_cfg_int_opt(c, "a", "zz", 7, 0, 9, &i, &err), DFL_OK);
    cr_expect_eq(i, 7);
    dfl_cfg_free(c);
}

Test(config, errors_name_line_and_key)
{
    dfl_cfg *c = parse("[a]\nx = 1\ny = 2.5\nz = 1 2\n");
    dfl_err err;
    long i;
    double v[3];
    cr_expect_eq(dfl_cfg_int(c, "a", "y", 0, 9, &i, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "t.ini:3: [a] y") != NULL, "%s", err.msg);
    cr_expect_eq(dfl_cfg_int(c, "a", "x", 2, 9, &i, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "[2, 9]") != NULL, "%s", err.msg);
    cr_expect_eq(dfl_cfg_vec(c, "a", "z", 3, v, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "t.ini:4") != NULL, "%s", err.msg);
    cr_expect_eq(dfl_cfg_int(c, "a", "missing", 0, 9, &i, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "missing") != NULL, "%s", err.msg);
    /* x, y, z were read (even if rejected); nothing else exists */
    cr_expect_eq(dfl_cfg_check_used(c, &err), DFL_OK, "%s", err.msg);
    dfl_cfg_free(c);
    c = parse("[a]\nx = 1\nw = 3\n");
    cr_assert_eq(dfl_cfg_int(c, "a", "x", 0, 9, &i, &err), DFL_OK);
    cr_expect_eq(dfl_cfg_check_used(c, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "t.ini:3: [a] w") != NULL, "%s", err.msg);
    dfl_cfg_free(c);
}

/* Sweep expansion: cartesian product, file order, last axis fastest. */
Test(config, sweep_cartesian_product)
{
    dfl_cfg *c = parse("[s]\nname = x\n[g]\nn = 1, 2, 3\nm = 10\n[h]\np = a,b\n");
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

Test(config, set_overrides_and_adds)
{
    dfl_cfg *c = parse("[g]\nn = 4\n");
    dfl_err err;
    cr_assert_eq(dfl_cfg_set(c, "g.n=16,32", &err), DFL_OK);
    cr_assert_eq(dfl_cfg_set(c, "h.k = 3", &err), DFL_OK);
    cr_expect_eq(dfl_cfg_sweep_points(c), 2);
    dfl_cfg *p;
    cr_assert_eq(dfl_cfg_sweep_point(c, 1, &p, &err), DFL_OK);
    long n, k;
    cr_assert_eq(dfl_cfg_int(p, "g", "n", 0, 99, &n, &err), DFL_OK);
    cr_assert_eq(dfl_cfg_int(p, "h", "k", 0, 99, &k, &err), DFL_OK);
    cr_expect_eq(n, 32);
    cr_expect_eq(k, 3);
    dfl_cfg_free(p);
    cr_expect_eq(dfl_cfg_set(c, "nodot=1", &err), DFL_E_INPUT);
    cr_expect_eq(dfl_cfg_set(c, "g.n=", &err), DFL_E_INPUT);
    dfl_cfg_free(c);
}

/* Long values (beyond libinih's default 200-character line) and indented
 * continuation lines are kept whole. */
Test(config, long_and_continued_values)
{
    char text[8192];
    size_t k = (size_t)snprintf(text, sizeof text, "[c]\ncontrol = ");
    for (int i = 0; i < 300; i++) k += (size_t)snprintf(text + k, sizeof text - k, "%d %d; ", i, i);
    k += (size_t)snprintf(text + k, sizeof text - k, "\nknots = 0 0\n  1 1\n  2 2\n");
    dfl_cfg *c = parse(text);
    dfl_err err;
    double *p;
    size_t n;
    cr_assert_eq(dfl_cfg_points(c, "c", "control", 2, 1, &p, &n, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(n, 300);
    cr_expect_eq(p[2 * 299], 299);
    free(p);
    cr_assert_eq(dfl_cfg_doubles(c, "c", "knots", 1, &p, &n, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(n, 6);
    cr_expect_eq(p[5], 2);
    free(p);
    dfl_cfg_free(c);
}

Test(config, rejects_non_finite)
{
    dfl_cfg *c = parse("[a]\nx = nan\ny = inf\nz = 1e999\nv = 1 nan\n");
    dfl_err err;
    double d, v[2];
    cr_expect_eq(dfl_cfg_double(c, "a", "x", -1e300, 1e300, &d, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_cfg_double(c, "a", "y", -HUGE_VAL, HUGE_VAL, &d, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_cfg_double(c, "a", "z", -HUGE_VAL, HUGE_VAL, &d, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_cfg_vec(c, "a", "v", 2, v, &err), DFL_E_INPUT);
    dfl_cfg_free(c);
}
