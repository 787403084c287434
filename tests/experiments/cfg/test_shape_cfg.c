/* [shape] sections -> dfl_shape: every kind of the table has a parser, the
 * ellipse kind builds the library's ellipse, and messages name the key. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cfg/shape_cfg.h"
#include "geom/ellipse.h"
#include "io/config.h"

static dfl_status build(const char *text, dfl_shape *s, dfl_err *err)
{
    dfl_cfg *cfg;
    cr_assert_eq(dfl_cfg_parse_string("test.ini", text, &cfg, err), DFL_OK, "%s", err->msg);
    dfl_status st = dfl_shape_from_cfg(cfg, "shape", s, err);
    dfl_cfg_free(cfg);
    return st;
}

Test(shape_cfg, every_kind_has_a_parser)
{
    cr_assert_eq(DFL_SHAPE_KIND_COUNT, (int)(sizeof dfl_shape_kind_names / sizeof *dfl_shape_kind_names));
    for (int k = 0; k < DFL_SHAPE_KIND_COUNT; k++) {
        const char *name = dfl_shape_kind_name((dfl_shape_kind)k);
        cr_assert_not_null(name);
        dfl_shape_kind got = (dfl_shape_kind)DFL_SHAPE_KIND_COUNT;
        cr_assert_eq(dfl_shape_kind_parse(name, &got, NULL), DFL_OK);
        cr_assert_eq(got, k);
        /* a section with nothing but the kind: a missing key, never an
         * internal error */
        char text[128];
        snprintf(text, sizeof text, "[shape]\nkind = %s\n", name);
        dfl_shape s = {0};
        dfl_err err;
        cr_assert_eq(build(text, &s, &err), DFL_E_INPUT, "kind %s: %s", name, err.msg);
        cr_assert(strstr(err.msg, "test.ini"), "kind %s: %s", name, err.msg);
        cr_assert_null(s.impl);
    }
    cr_assert_str_eq(dfl_shape_kind_name((dfl_shape_kind)DFL_SHAPE_KIND_COUNT), "?");
    dfl_shape s = {0};
    dfl_err err;
    dfl_shape_kind k = DFL_SHAPE_CSG;
    cr_assert_eq(dfl_shape_kind_parse("blob", &k, &err), DFL_E_INPUT);
    cr_assert_eq(k, DFL_SHAPE_CSG);
    cr_assert(strstr(err.msg, "blob") && strstr(err.msg, "circle|sphere"), "%s", err.msg);
    cr_assert_eq(build("[shape]\nkind = blob\n", &s, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "[shape] kind"), "%s", err.msg);
    cr_assert(strstr(err.msg, "ellipse"), "%s", err.msg);
}

Test(shape_cfg, ellipse_is_the_library_ellipse)
{
    dfl_shape s;
    dfl_err err;
    cr_assert_eq(build("[shape]\nkind = ellipse\ncenter = 0.5 -0.25\na = 2\nb = 0.75\n", &s, &err),
                 DFL_OK, "%s", err.msg);
    cr_assert_eq(s.dim, 2);
    cr_assert_str_eq(s.ops->kind, "ellipse");
    for (int i = 0; i < 50; i++) {
        double x[2] = {-3 + 0.13 * i, 2 - 0.09 * i}, u[2] = {x[0] - 0.5, x[1] + 0.25}, g[2], h[2];
        cr_assert_eq(dfl_shape_eval1(&s, x, g), dfl_ellipse_sdist(2, 0.75, u, NULL, h));
        cr_assert_eq(g[0], h[0]);
        cr_assert_eq(g[1], h[1]);
    }
    dfl_shape_free(&s);
}

Test(shape_cfg, ellipse_errors_name_the_key)
{
    const struct {
        const char *text, *want;
    } cases[] = {
        {"[shape]\nkind = ellipse\na = 1\nb = 1\n", "[shape] center"},
        {"[shape]\nkind = ellipse\ncenter = 0 0\nb = 1\n", "[shape] a"},
        {"[shape]\nkind = ellipse\ncenter = 0 0\na = 1\nb = 0\n", "[shape] b"},
        {"[shape]\nkind = ellipse\ncenter = 0 0\na = -2\nb = 1\n", "[shape] a"},
        {"[shape]\nkind = ellipse\ncenter = 0 0 0\na = 1\nb = 1\n", "center"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        dfl_shape s = {0};
        dfl_err err;
        cr_assert_eq(build(cases[i].text, &s, &err), DFL_E_INPUT, "case %zu", i);
        cr_assert(strstr(err.msg, cases[i].want), "case %zu: %s", i, err.msg);
        cr_assert(strstr(err.msg, "test.ini:"), "case %zu: %s", i, err.msg);
    }
}
