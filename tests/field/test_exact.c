/* Tests for field/exact and the [shape] config section (experiments/
 * shape_cfg).  The field must forward the shape exactly (same value,
 * gradient and jet, bit for bit); a config-built shape must equal the one
 * built by the constructor from the same numbers; bad input must be
 * DFL_E_INPUT naming file:line and key. */
#include <criterion/criterion.h>

#include <math.h>
#include <string.h>

#include "field/exact.h"
#include "geom/implicit.h"
#include "geom/shape.h"
#include "io/config.h"
#include "cfg/shape_cfg.h"

Test(exact, forwards_the_shape)
{
    double c[3] = {0.1, 0.2, -0.3};
    dfl_shape s, ref;
    cr_assert_eq(dfl_shape_sphere(c, 0.5, &s, NULL), DFL_OK);
    cr_assert_eq(dfl_shape_sphere(c, 0.5, &ref, NULL), DFL_OK);
    dfl_field f;
    cr_assert_eq(dfl_field_exact_new(&s, &f, NULL), DFL_OK);
    cr_assert_null(s.impl, "ownership moved into the field");
    cr_assert_eq(f.dim, 3);
    cr_assert_not_null(dfl_field_exact_shape(&f));
    double pts[12] = {0, 0, 0, 1, 1, 1, 0.1, 0.2, 0.2, -1, 0.5, 0.25}, v[4], g[12];
    f.ops->eval(f.ctx, 4, pts, v, g);
    for (int i = 0; i < 4; i++) {
        double gr[3];
        double want = dfl_shape_eval1(&ref, pts + 3 * i, gr);
        cr_assert(v[i] == want);
        cr_assert(memcmp(gr, g + 3 * i, sizeof gr) == 0);
        /* and the closed form |x - c| - r */
        double u[3] = {pts[3 * i] - c[0], pts[3 * i + 1] - c[1], pts[3 * i + 2] - c[2]};
        cr_assert(fabs(v[i] - (sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]) - 0.5)) < 1e-15);
    }
    double x[3] = {0.7, -0.1, 0.2}, dir[3] = {0.3, 0.4, -0.5};
    dfl_jet a, b;
    cr_assert_eq(dfl_field_jet(&f, x, dir, 8, &a, NULL), DFL_OK);
    cr_assert_eq(dfl_shape_jet(&ref, x, dir, 8, &b, NULL), DFL_OK);
    for (int k = 0; k <= 8; k++) cr_assert(dfl_jet_coeff(&a, k) == dfl_jet_coeff(&b, k));
    dfl_field_destroy(&f);
    dfl_shape_free(&ref);
    cr_assert_eq(dfl_field_exact_new(&s, &f, NULL), DFL_E_INPUT, "empty shape");
}

static dfl_cfg *parse(const char *text)
{
    dfl_cfg *cfg = NULL;
    dfl_err err;
    cr_assert_eq(dfl_cfg_parse_string("test.ini", text, &cfg, &err), DFL_OK, "%s", err.msg);
    return cfg;
}

static void expect_same(const dfl_shape *a, const dfl_shape *b, double lo, double hi)
{
    cr_assert_eq(a->dim, b->dim);
    for (int t = 0; t < 50; t++) {
        double x[3];
        for (int j = 0; j < 3; j++) x[j] = lo + (hi - lo) * fmod(0.6180339887 * (t * 3 + j + 1), 1.0);
        double ga[3], gb[3];
        double va = dfl_shape_eval1(a, x, ga), vb = dfl_shape_eval1(b, x, gb);
        cr_assert(fabs(va - vb) <= 1e-12 * (1 + fabs(vb)), "%.17g vs %.17g", va, vb);
    }
}

/* [sec] of cfg is the same shape as r (freed here). */
static void expect_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_shape *r)
{
    dfl_shape s;
    dfl_err err;
    cr_assert_eq(dfl_shape_from_cfg(cfg, sec, &s, &err), DFL_OK, "[%s]: %s", sec, err.msg);
    expect_same(&s, r, -1, 1);
    dfl_shape_free(&s);
    dfl_shape_free(r);
}

Test(exact, shapes_from_config)
{
    dfl_cfg *cfg = parse("[shape]\nkind = torus\ncenter = 0 0 0\naxis = 0 0 1\nmajor = 0.5\n"
                         "minor = 0.2\n"
                         "[c]\nkind = circle\ncenter = 0.5 0.5\nradius = 0.3\n"
                         "[s]\nkind = sphere\ncenter = 0 0 0\nradius = 0.5\n"
                         "[cyl]\nkind = cylinder\ncenter = 0 0 0\naxis = 1 1 0\nradius = 0.2\n"
                         "[pl]\nkind = plane\npoint = 0 0 0.1\nnormal = 0 0 2\n"
                         "[co]\nkind = cone\na = 0 0 0\nb = 0 0 1\nra = 0.5\nrb = 0.1\n"
                         "[bx]\nkind = box\ndim = 2\ncenter = 0 0\nhalf = 0.3 0.2\n"
                         "[sg]\nkind = segment\na = 0 0\nb = 1 0\n"
                         "[u]\nkind = csg\nop = smooth_union\na = s\nb = cyl\nk = 0.1\n");
    dfl_err err;
    dfl_shape r;
    double o[3] = {0, 0, 0}, z[3] = {0, 0, 1}, c2[2] = {0.5, 0.5}, ax[3] = {1, 1, 0},
           pp[3] = {0, 0, 0.1}, top[3] = {0, 0, 1}, h2[2] = {0.3, 0.2}, e2[2] = {1, 0};
    dfl_shape_torus(o, z, 0.5, 0.2, &r, NULL);
    expect_from_cfg(cfg, "shape", &r);
    dfl_shape_circle(c2, 0.3, &r, NULL);
    expect_from_cfg(cfg, "c", &r);
    dfl_shape_cylinder(o, ax, 0.2, &r, NULL);
    expect_from_cfg(cfg, "cyl", &r);
    dfl_shape_plane(3, pp, z, &r, NULL);
    expect_from_cfg(cfg, "pl", &r);
    dfl_shape_cone(o, top, 0.5, 0.1, &r, NULL);
    expect_from_cfg(cfg, "co", &r);
    dfl_shape_box(2, o, h2, &r, NULL);
    expect_from_cfg(cfg, "bx", &r);
    dfl_shape_segment(2, o, e2, &r, NULL);
    expect_from_cfg(cfg, "sg", &r);
    dfl_shape a, b;
    dfl_shape_sphere(o, 0.5, &a, NULL);
    dfl_shape_cylinder(o, ax, 0.2, &b, NULL);
    dfl_shape_csg(DFL_CSG_SMOOTH_UNION, 0.1, &a, &b, &r, NULL);
    expect_from_cfg(cfg, "u", &r);
    /* every key above was read */
    cr_assert_eq(dfl_cfg_check_used(cfg, &err), DFL_OK, "%s", err.msg);
    dfl_cfg_free(cfg);
}

Test(exact, implicit_from_config_is_the_torus)
{
    dfl_cfg *cfg = parse("[shape]\nkind = implicit\nsurface = torus\nsolver = ceres\n"
                         "center = 0 0 0\naxis = 0 1 1\nmajor = 0.5\nminor = 0.2\n");
    dfl_shape s, r;
    dfl_err err;
    cr_assert_eq(dfl_shape_from_cfg(cfg, "shape", &s, &err), DFL_OK, "%s", err.msg);
    double o[3] = {0, 0, 0}, ax[3] = {0, 1, 1};
    dfl_shape_torus(o, ax, 0.5, 0.2, &r, NULL);
    expect_same(&s, &r, -1, 1);
    dfl_field f;
    cr_assert_eq(dfl_field_exact_new(&s, &f, NULL), DFL_OK);
    double x[3] = {0.3, 0.1, 0.2}, dir[3] = {1, 0, 0};
    dfl_jet a, b;
    cr_assert_eq(dfl_field_jet(&f, x, dir, 3, &a, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_shape_jet(&r, x, dir, 3, &b, NULL), DFL_OK);
    for (int k = 0; k <= 3; k++)
        cr_assert(fabs(dfl_jet_deriv(&a, k) - dfl_jet_deriv(&b, k)) < 1e-8 * (1 + fabs(dfl_jet_deriv(&b, k))));
    dfl_field_destroy(&f);
    dfl_shape_free(&r);
    cr_assert_eq(dfl_cfg_check_used(cfg, &err), DFL_OK, "%s", err.msg);
    dfl_cfg_free(cfg);
}

/* Each bad config must fail with DFL_E_INPUT, "test.ini:<line>" and the key. */
static void expect_bad(const char *text, const char *line, const char *key)
{
    dfl_cfg *cfg = parse(text);
    dfl_shape s = {0};
    dfl_err err;
    dfl_status st = dfl_shape_from_cfg(cfg, "shape", &s, &err);
    cr_assert_eq(st, DFL_E_INPUT, "status %d for:\n%s", st, text);
    cr_assert(strstr(err.msg, line), "'%s' lacks '%s'", err.msg, line);
    cr_assert(strstr(err.msg, key), "'%s' lacks '%s'", err.msg, key);
    cr_assert_null(s.impl);
    dfl_cfg_free(cfg);
}

Test(exact, bad_config_names_file_line_and_key)
{
    expect_bad("[shape]\nkind = circle\ncenter = 0 0\nradius = 0\n", "test.ini:4", "radius");
    expect_bad("[shape]\nkind = circle\ncenter = 0 0\nradius = -1\n", "test.ini:4", "radius");
    expect_bad("[shape]\nkind = sphere\ncenter = 0 0\nradius = 1\n", "test.ini:3", "center");
    expect_bad("[shape]\nkind = blob\n", "test.ini:2", "kind");
    expect_bad("[shape]\nkind = torus\ncenter = 0 0 0\naxis = 0 0 0\nmajor = 1\nminor = 0.2\n",
               "test.ini:4", "axis");
    expect_bad("[shape]\nkind = torus\ncenter = 0 0 0\naxis = 0 0 1\nmajor = 1\nminor = 2\n",
               "test.ini:6", "minor");
    expect_bad("[shape]\nkind = box\ncenter = 0 0 0\nhalf = 1 0 1\n", "test.ini:4", "half");
    expect_bad("[shape]\nkind = cone\na = 0 0 0\nb = 0 0 0\nra = 1\nrb = 0\n", "test.ini:4", "b");
    expect_bad("[shape]\nkind = csg\nop = union\na = x\nb = shape\n", "test.ini:4", "a");
    expect_bad("[shape]\nkind = csg\nop = smooth_union\nk = 0\na = shape\nb = shape\n",
               "test.ini:4", "k");
    /* a cycle of sections */
    expect_bad("[shape]\nkind = csg\nop = union\na = shape\nb = shape\n", "test.ini", "csg");
    expect_bad("[shape]\nkind = implicit\nsurface = genus2\neps = 0.3\n", "test.ini:4", "eps");
    expect_bad("[shape]\nkind = implicit\nsurface = torus\nsolver = gauss\n", "test.ini:4",
               "solver");
    /* missing key */
    expect_bad("[shape]\nkind = circle\ncenter = 0 0\n", "test.ini", "radius");
}

/* The view gives the shape's values and gradients and leaves the shape to
 * its owner: destroying the view and then using and freeing the shape is
 * clean (ASan would see a double free or a use after free). */
Test(exact, view_borrows_the_shape)
{
    dfl_shape s;
    dfl_err err = {0};
    const double c[3] = {0.1, -0.2, 0.3};
    cr_assert_eq(dfl_shape_sphere(c, 0.5, &s, &err), DFL_OK);
    dfl_field f;
    dfl_field_exact_view(&s, &f);
    cr_expect_eq(f.dim, 3);
    cr_expect_eq(dfl_field_exact_shape(&f), &s);
    const double x[3] = {1.1, -0.2, 0.3};
    double g[3];
    /* |x - c| - r = 1 - 0.5, gradient (x - c)/|x - c| = (1, 0, 0) */
    cr_expect_float_eq(dfl_field_eval1(&f, x, g), 0.5, 1e-15);
    cr_expect_float_eq(g[0], 1.0, 1e-15);
    cr_expect_float_eq(g[1], 0.0, 1e-15);
    dfl_field_destroy(&f);
    cr_expect_null(f.ops);
    cr_expect_float_eq(dfl_shape_eval1(&s, x, NULL), 0.5, 1e-15);
    dfl_shape_free(&s);
}

/* dfl_field_bytes: a kind without a bytes op says "unknown" (0) and leaves
 * the output alone; the exact field is one (its shape is the reference). */
Test(exact, bytes_unknown)
{
    double c[3] = {0, 0, 0};
    dfl_shape s;
    cr_assert_eq(dfl_shape_sphere(c, 0.5, &s, NULL), DFL_OK);
    dfl_field f;
    cr_assert_eq(dfl_field_exact_new(&s, &f, NULL), DFL_OK);
    size_t b = 12345;
    cr_expect_eq(dfl_field_bytes(&f, &b), 0);
    cr_expect_eq(b, 12345);
    dfl_field_destroy(&f);
}
