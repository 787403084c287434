/* [field] kind = proxy: the keys build the grid the library calls build,
 * bad keys are rejected naming the key. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "cfg/field_cfg.h"
#include "cfg/proxy_cfg.h"
#include "cfg/shape_cfg.h"
#include "cfg_util.h"
#include "proxy/input_sdf.h"
#include "proxy/proxy_field.h"

static const char *const sphere =
    "[shape]\nkind = sphere\ncenter = 0.01 0.02 -0.03\nradius = 0.5\n";

static dfl_cfg *with_field(const char *field)
{
    char text[1024];
    snprintf(text, sizeof text, "[field]\nkind = proxy\n%s%s", field, sphere);
    return tu_cfg("p.ini", text);
}

Test(proxy_cfg, row_in_field_table)
{
    size_t n;
    const dfl_field_kind *k = dfl_field_kinds(&n);
    int found = 0;
    for (size_t i = 0; i < n; i++)
        if (strcmp(k[i].name, "proxy") == 0) found = k[i].build == dfl_proxy_field_from_cfg;
    cr_expect(found);
}

/* What dfl_proxy_cfg_read makes of a [field] text: every key it reads. */
typedef struct keys_case {
    const char *field;
    int order, res;
    double lo[3], hi[3];
    dfl_proxy_filter filter;
    dfl_proxy_storage storage;
    dfl_proxy_position position;
    double clip_cells;
    int is_signed;
    double noise;
    unsigned long seed;
} keys_case;

static const keys_case KEYS[] = {
    /* the defaults */
    {"", 1, 16, {-1, -1, -1}, {1, 1, 1}, DFL_PROXY_NEAREST, DFL_PROXY_DOUBLE,
     DFL_PROXY_DISPLACEMENT, 0.0, 0, 0.0, 1},
    /* every key given; one number for hi is every axis */
    {"order = 2\nres = 8\nlo = -1 -2 -0.5\nhi = 2\nfilter = hermite\nstorage = half\n"
     "position = absolute\nclip_radius = 1.5\nsigned = true\nnoise = 0.01\nseed = 7\n",
     2, 8, {-1, -2, -0.5}, {2, 2, 2}, DFL_PROXY_HERMITE, DFL_PROXY_HALF, DFL_PROXY_ABSOLUTE, 1.5,
     1, 0.01, 7},
};

Test(proxy_cfg, defaults_and_keys)
{
    for (size_t i = 0; i < sizeof KEYS / sizeof KEYS[0]; i++) {
        const keys_case *w = &KEYS[i];
        dfl_cfg *cfg = with_field(w->field);
        dfl_proxy_cfg c;
        cr_assert_eq(dfl_proxy_cfg_read(cfg, "field", &c, NULL), DFL_OK, "case %zu", i);
        cr_expect_eq(c.build.order, w->order, "case %zu", i);
        cr_expect_eq(c.build.res, w->res, "case %zu", i);
        for (int j = 0; j < 3; j++) {
            cr_expect_eq(c.build.lo[j], w->lo[j], "case %zu lo[%d]", i, j);
            cr_expect_eq(c.build.hi[j], w->hi[j], "case %zu hi[%d]", i, j);
        }
        cr_expect_eq(c.filter, w->filter, "case %zu", i);
        cr_expect_eq(c.build.storage, w->storage, "case %zu", i);
        cr_expect_eq(c.build.position, w->position, "case %zu", i);
        cr_expect_eq(c.clip_cells, w->clip_cells, "case %zu", i);
        cr_expect_eq(c.is_signed, w->is_signed, "case %zu", i);
        cr_expect_eq(c.build.noise, w->noise, "case %zu", i);
        cr_expect_eq(c.build.seed, w->seed, "case %zu", i);
        dfl_cfg_free(cfg);
    }
}

/* The field of the config is the field of the library calls. */
Test(proxy_cfg, same_as_library)
{
    dfl_cfg *cfg = with_field("order = 2\nres = 6\nfilter = trilinear\nsigned = true\n"
                              "clip_radius = 2\ninput = sdf\ncurvature = analytic\n");
    dfl_field f;
    dfl_err err;
    cr_assert_eq(dfl_field_from_cfg(cfg, "field", &f, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(dfl_cfg_check_used(cfg, &err), DFL_OK, "%s", err.msg);
    dfl_shape s;
    cr_assert_eq(dfl_shape_from_cfg(cfg, "shape", &s, NULL), DFL_OK);
    dfl_proxy_input in;
    cr_assert_eq(dfl_proxy_input_sdf(&s, DFL_PROXY_CURV_ANALYTIC, NULL, &in, NULL), DFL_OK);
    dfl_proxy_build_opts o;
    dfl_proxy_build_opts_default(&o);
    o.order = 2;
    o.res = 6;
    dfl_proxy_grid g;
    cr_assert_eq(dfl_proxy_grid_build(&in, &o, &g, NULL), DFL_OK);
    const dfl_proxy_grid *fg = dfl_proxy_field_grid(&f);
    cr_assert_not_null(fg);
    cr_expect_eq(memcmp(g.data, fg->data, dfl_proxy_grid_scalars(&g) * 8), 0);
    const dfl_proxy_filter_opts *fo = dfl_proxy_field_opts(&f);
    cr_expect_eq(fo->filter, DFL_PROXY_TRILINEAR);
    cr_expect_float_eq(fo->clip, 2.0 * 2.0 / 6.0, 1e-15);
    cr_expect_eq(fo->is_signed, 1);
    const double x[3] = {0.3, -0.2, 0.25};
    cr_expect_lt(dfl_field_eval1(&f, x, NULL), 0);
    dfl_proxy_grid_free(&g);
    dfl_proxy_input_free(&in);
    dfl_field_destroy(&f);
    dfl_cfg_free(cfg);
}

static void expect_reject(const char *field, const char *key)
{
    dfl_cfg *cfg = with_field(field);
    dfl_field f;
    dfl_err err;
    cr_expect_eq(dfl_field_from_cfg(cfg, "field", &f, &err), DFL_E_INPUT, "%s", field);
    char want[64];
    snprintf(want, sizeof want, "] %s", key);
    cr_expect(strstr(err.msg, want) != NULL, "%s: %s", field, err.msg);
    cr_expect(strstr(err.msg, "p.ini:") != NULL, "%s", err.msg);
    dfl_cfg_free(cfg);
}

Test(proxy_cfg, bad_keys_name_the_key)
{
    expect_reject("res = 0\n", "res");
    expect_reject("res = -3\n", "res");
    expect_reject("clip_radius = 0\n", "clip_radius");
    expect_reject("clip_radius = -0.5\n", "clip_radius");
    expect_reject("order = 3\n", "order");
    expect_reject("filter = cubic\n", "filter");
    expect_reject("storage = int8\n", "storage");
    expect_reject("lo = 0.5\nhi = 0.5\n", "hi");
    expect_reject("noise = -1\n", "noise");
    expect_reject("input = magic\n", "input");
}

/* noise_at names the cell that holds the point: box [-1, 2] x [-2, 2] x
 * [-0.5, 2] at res 8 has cell sizes 3/8, 1/2, 5/16; (0.2, 1.9, -0.5) lies in
 * cell (3, 7, 0) (the face at -0.5 belongs to cell 0), index 3 + 8 * 7 = 59.
 * The default is every cell (-1); a point outside the box is refused. */
Test(proxy_cfg, noise_at_names_its_cell)
{
    dfl_cfg *cfg = with_field("");
    dfl_proxy_cfg c;
    cr_assert_eq(dfl_proxy_cfg_read(cfg, "field", &c, NULL), DFL_OK);
    cr_expect_eq(c.build.noise_cell, -1);
    dfl_cfg_free(cfg);
    cfg = with_field("res = 8\nlo = -1 -2 -0.5\nhi = 2\nnoise = 0.01\nnoise_at = 0.2 1.9 -0.5\n");
    cr_assert_eq(dfl_proxy_cfg_read(cfg, "field", &c, NULL), DFL_OK);
    cr_expect_eq(c.build.noise_cell, 59);
    dfl_cfg_free(cfg);
    cfg = with_field("res = 8\nnoise_at = 0 0 1\n");
    dfl_err err;
    cr_expect_eq(dfl_proxy_cfg_read(cfg, "field", &c, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "noise_at") && strstr(err.msg, "inside the box"), "%s", err.msg);
    dfl_cfg_free(cfg);
}
