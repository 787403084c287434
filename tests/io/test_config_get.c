/* Tests for src/io/config_get.c: typed getters, their ranges and defaults. */
#include <criterion/criterion.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/config.h"
#include "util/config_util.h"

Test(config, typed_getters)
{
    dfl_cfg *c = cfgu_parse("[a]\ni = 42\nd = -1.5e-3\nb = yes\ne = strip\n"
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

Test(config, rejects_non_finite)
{
    dfl_cfg *c = cfgu_parse("[a]\nx = nan\ny = inf\nz = 1e999\nv = 1 nan\n");
    dfl_err err;
    double d, v[2];
    cr_expect_eq(dfl_cfg_double(c, "a", "x", -1e300, 1e300, &d, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_cfg_double(c, "a", "y", -HUGE_VAL, HUGE_VAL, &d, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_cfg_double(c, "a", "z", -HUGE_VAL, HUGE_VAL, &d, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_cfg_vec(c, "a", "v", 2, v, &err), DFL_E_INPUT);
    dfl_cfg_free(c);
}

/* strtod's ERANGE: a subnormal is a finite double and the value; overflow
 * (inf) and a non-zero number that rounds to zero are out of range, and a
 * finite value outside the key's range names the end it misses. */
Test(config, subnormals_are_values)
{
    dfl_cfg *c = cfgu_parse("[a]\ns = 4e-320\nt = -5e-324\nu = 0x1p-1074\nz = 1e-400\n"
                            "o = 1e400\nw = 5e-324\nh = 2\n");
    dfl_err err;
    double d;
    cr_assert_eq(dfl_cfg_double(c, "a", "s", -1, 1, &d, &err), DFL_OK, "%s", err.msg);
    cr_expect(d == 4e-320 && d > 0 && !isnormal(d) && isfinite(d));
    cr_assert_eq(dfl_cfg_double(c, "a", "t", -1, 1, &d, &err), DFL_OK, "%s", err.msg);
    cr_expect(d == -0x1p-1074);
    cr_assert_eq(dfl_cfg_double(c, "a", "u", -1, 1, &d, &err), DFL_OK, "%s", err.msg);
    cr_expect(d == 0x1p-1074);
    cr_expect_eq(dfl_cfg_double(c, "a", "z", -1, 1, &d, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "got '1e-400' (out of range") != NULL, "%s", err.msg);
    cr_expect(strstr(err.msg, "below the smallest double") != NULL, "%s", err.msg);
    cr_expect_eq(dfl_cfg_double(c, "a", "o", -HUGE_VAL, HUGE_VAL, &d, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "out of range: beyond the largest double") != NULL, "%s", err.msg);
    /* below a key's smallest value: said so, naming it (not "not finite") */
    cr_expect_eq(dfl_cfg_double(c, "a", "w", 1e-300, HUGE_VAL, &d, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "got '5e-324' (below the smallest value accepted, 1e-300)") != NULL,
              "%s", err.msg);
    cr_expect_eq(dfl_cfg_double(c, "a", "h", -1, 1, &d, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "(above the largest value accepted, 1)") != NULL, "%s", err.msg);
    /* vectors (coordinates) take subnormals too */
    dfl_cfg *v = cfgu_parse("[a]\nv = 4e-320 1\n");
    double x[2];
    cr_assert_eq(dfl_cfg_vec(v, "a", "v", 2, x, &err), DFL_OK, "%s", err.msg);
    cr_expect(x[0] == 4e-320);
    dfl_cfg_free(v);
    dfl_cfg_free(c);
}

/* _opt getters: the default when absent, the full check when present. */
Test(config, optional_getters)
{
    dfl_cfg *c = cfgu_parse("[a]\ni = 12\nd = x\nb = maybe\ne = ring\nv = 1 2\ns =\n");
    dfl_err err;
    long i;
    double d, v[2];
    const double dv[2] = {7, 8};
    bool b;
    int e;
    const char *s;
    static const char *const names[] = {"disk", "strip"};
    cr_assert_eq(dfl_cfg_int_opt(c, "a", "i", 0, 0, 9, &i, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "t.ini:2: [a] i: expected an integer in [0, 9], got '12'"), "%s",
              err.msg);
    cr_assert_eq(dfl_cfg_double_opt(c, "a", "d", 0, -1, 1, &d, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_cfg_double_opt(c, "a", "zz", 0.5, -1, 1, &d, &err), DFL_OK);
    cr_assert_eq(d, 0.5);
    cr_assert_eq(dfl_cfg_bool_opt(c, "a", "b", true, &b, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_cfg_bool_opt(c, "a", "zz", true, &b, &err), DFL_OK);
    cr_assert(b);
    cr_assert_eq(dfl_cfg_enum_opt(c, "a", "e", names, 2, 0, &e, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "one of disk|strip"), "%s", err.msg);
    cr_assert_eq(dfl_cfg_enum_opt(c, "a", "zz", names, 2, 1, &e, &err), DFL_OK);
    cr_assert_eq(e, 1);
    cr_assert_eq(dfl_cfg_vec_opt(c, "a", "v", 2, dv, v, &err), DFL_OK);
    cr_assert(v[0] == 1 && v[1] == 2);
    cr_assert_eq(dfl_cfg_vec_opt(c, "a", "zz", 2, dv, v, &err), DFL_OK);
    cr_assert(v[0] == 7 && v[1] == 8);
    cr_assert_eq(dfl_cfg_string_opt(c, "a", "s", "def", &s, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "expected a non-empty value"), "%s", err.msg);
    cr_assert_eq(dfl_cfg_string_opt(c, "a", "zz", "def", &s, &err), DFL_OK);
    cr_assert_str_eq(s, "def");
    cr_assert(!dfl_cfg_has(c, "a", "zz"));
    dfl_cfg_free(c);
}

Test(config, point_lists)
{
    dfl_cfg *c = cfgu_parse("[a]\np = 0 0; 1 2 3; 4 4\nq = 0 0 1; 1 1 1\nr = 1 2\n");
    dfl_err err;
    double *pts;
    size_t n;
    cr_assert_eq(dfl_cfg_points(c, "a", "p", 2, 1, &pts, &n, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "t.ini:2: [a] p: point 2: expected 2 numbers, got ' 1 2 3'"), "%s",
              err.msg);
    cr_assert(pts == NULL && n == 0);
    cr_assert_eq(dfl_cfg_points(c, "a", "q", 3, 3, &pts, &n, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "at least 3 points of 3 numbers each"), "%s", err.msg);
    cr_assert_eq(dfl_cfg_point_dim("0 0 1; 1 1 1"), 3);
    cr_assert_eq(dfl_cfg_point_dim("  0   1 ;"), 2);
    cr_assert_eq(dfl_cfg_point_dim(""), 0);
    cr_assert_eq(dfl_cfg_doubles(c, "a", "r", 3, &pts, &n, &err), DFL_E_INPUT);
    dfl_cfg_free(c);
}

/* config.h: an integer is a long within [lo, hi]; a text beyond the range
 * of a long is refused even for the widest range [LONG_MIN, LONG_MAX]
 * (strtol's clamp to LONG_MAX / LONG_MIN with ERANGE is not the value
 * written), while LONG_MAX itself, written out, is a value. */
Test(config, int_beyond_long_is_refused)
{
    char text[160];
    snprintf(text, sizeof text, "[a]\nbig = 99999999999999999999\nneg = -99999999999999999999\n"
                                "max = %ld\n", LONG_MAX);
    dfl_cfg *c = cfgu_parse(text);
    dfl_err err;
    long v = 7;
    cr_expect_eq(dfl_cfg_int(c, "a", "big", LONG_MIN, LONG_MAX, &v, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_cfg_int(c, "a", "neg", LONG_MIN, LONG_MAX, &v, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_cfg_int(c, "a", "max", LONG_MIN, LONG_MAX, &v, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(v, LONG_MAX);
    dfl_cfg_free(c);
}
