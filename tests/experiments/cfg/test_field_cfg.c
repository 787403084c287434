/* The field-kind table: every row is reachable by its name, an unknown
 * kind is refused with the accepted names, and dfl_field_from_cfg hands
 * the section to the row's factory. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cfg_util.h"
#include "cfg/field_cfg.h"
#include "cfg/rfunc_cfg.h"
#include "io/config.h"
#include "proxy/proxy_field.h"

Test(field_cfg, table_rows)
{
    size_t n;
    const dfl_field_kind *kinds = dfl_field_kinds(&n);
    cr_assert_geq(n, 2); /* other modules add rows (tests/experiments/cfg/test_<kind>_cfg.c check theirs) */
    cr_expect_str_eq(kinds[0].name, "exact");
    cr_expect_str_eq(kinds[1].name, "rfunc");
    cr_expect_eq(kinds[1].build, dfl_rfunc_field_from_cfg);
    cr_expect_str_eq(kinds[2].name, "normalized");
    cr_expect_eq(kinds[2].build, dfl_rfunc_normalized_from_cfg);
    int have_pht = 0;
    for (size_t i = 0; i < n; i++)
        if (strcmp(kinds[i].name, "pht") == 0) have_pht = 1;
    cr_expect(have_pht, "the pht row");
    for (size_t i = 0; i < n; i++) {
        char text[64];
        snprintf(text, sizeof text, "[field]\nkind = %s\n", kinds[i].name);
        dfl_cfg *cfg = tu_cfg("f.ini", text);
        const dfl_field_kind *k = NULL;
        cr_expect_eq(dfl_field_kind_from_cfg(cfg, "field", &k, NULL), DFL_OK);
        cr_expect_eq(k, &kinds[i]);
        dfl_cfg_free(cfg);
    }
}

Test(field_cfg, unknown_kind_lists_the_rows)
{
    dfl_cfg *cfg = tu_cfg("f.ini", "[field]\nkind = magic\n");
    const dfl_field_kind *k = NULL;
    dfl_err err;
    cr_expect_eq(dfl_field_kind_from_cfg(cfg, "field", &k, &err), DFL_E_INPUT);
    cr_expect_null(k);
    cr_expect(strstr(err.msg, "f.ini:2") && strstr(err.msg, "exact|rfunc") &&
                  strstr(err.msg, "magic"),
              "%s", err.msg);
    dfl_field f;
    cr_expect_eq(dfl_field_from_cfg(cfg, "field", &f, &err), DFL_E_INPUT);
    dfl_cfg_free(cfg);
    cfg = tu_cfg("f.ini", "[field]\njoin = requiv\n");
    cr_expect_eq(dfl_field_kind_from_cfg(cfg, "field", &k, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "kind"), "%s", err.msg);
    dfl_cfg_free(cfg);
}

/* Each kind's factory builds the field: exact from [shape], rfunc from
 * its own keys. */
Test(field_cfg, factories_build)
{
    dfl_cfg *cfg = tu_cfg("f.ini", "[field]\nkind = exact\n"
                                   "[shape]\nkind = circle\ncenter = 0 0\nradius = 1\n");
    dfl_field f;
    dfl_err err;
    cr_assert_eq(dfl_field_from_cfg(cfg, "field", &f, &err), DFL_OK, "%s", err.msg);
    const double x[2] = {2.0, 0.0};
    cr_expect_float_eq(dfl_field_eval1(&f, x, NULL), 1.0, 1e-15);
    dfl_field_destroy(&f);
    dfl_cfg_free(cfg);
    cfg = tu_cfg("f.ini", "[field]\nkind = rfunc\nvertices = 0 0; 1 0\n");
    cr_assert_eq(dfl_field_from_cfg(cfg, "field", &f, &err), DFL_OK, "%s", err.msg);
    const double y[2] = {0.5, 0.0};
    cr_expect_eq(dfl_field_eval1(&f, y, NULL), 0.0);
    dfl_field_destroy(&f);
    dfl_cfg_free(cfg);
}

/* dfl_field_from_cfg_target: a kind without build_target (exact) builds
 * its field with the no-target record (NaN, -1, 0); a failure (unknown
 * kind) leaves *out and *target untouched. */
Test(field_cfg, a_kind_without_a_target_says_none)
{
    dfl_field_target tg = {7.0, 5, 9};
    dfl_field_target_none(&tg);
    cr_expect(isnan(tg.value));
    cr_expect_eq(tg.met, -1);
    cr_expect_eq(tg.over, 0);
    size_t n;
    const dfl_field_kind *kinds = dfl_field_kinds(&n);
    cr_expect_null(kinds[0].build_target, "exact has no target");
    dfl_cfg *cfg = tu_cfg("f.ini", "[field]\nkind = exact\n"
                                   "[shape]\nkind = circle\ncenter = 0 0\nradius = 1\n");
    dfl_field f;
    dfl_err err;
    tg = (dfl_field_target){7.0, 5, 9};
    cr_assert_eq(dfl_field_from_cfg_target(cfg, "field", &f, &tg, &err), DFL_OK, "%s", err.msg);
    cr_expect(isnan(tg.value));
    cr_expect_eq(tg.met, -1);
    cr_expect_eq(tg.over, 0);
    dfl_field_destroy(&f);
    dfl_cfg_free(cfg);
    cfg = tu_cfg("f.ini", "[field]\nkind = magic\n");
    tg = (dfl_field_target){7.0, 5, 9};
    memset(&f, 0xab, sizeof f);
    const dfl_field before = f;
    cr_expect_eq(dfl_field_from_cfg_target(cfg, "field", &f, &tg, &err), DFL_E_INPUT);
    cr_expect_eq(memcmp(&f, &before, sizeof f), 0);
    cr_expect_eq(tg.value, 7.0);
    cr_expect_eq(tg.met, 5);
    cr_expect_eq(tg.over, 9);
    dfl_cfg_free(cfg);
}

/* A validation pass (io/config.h dfl_cfg_validating) builds nothing:
 * the factories of pht, gridpeer and openvdb fields read and check their
 * keys and return a placeholder of the field's dimension; a proxy field
 * is a grid of the configured shape with zeroed proxies (the studies read
 * its shape before they stop).  Each config here is refused by its build
 * or would build something that is not a placeholder, so a factory that
 * built in a validation pass fails the test; each bad key is still named. */
static dfl_status build_in_pass(const char *text, int pass, dfl_field *f, dfl_err *err)
{
    dfl_cfg *cfg = tu_cfg("v.ini", text);
    if (pass) dfl_cfg_validate_only(cfg);
    memset(f, 0, sizeof *f);
    dfl_status st = dfl_field_from_cfg(cfg, "field", f, err);
    if (!st) st = dfl_cfg_check_used_in(cfg, "field", err);
    dfl_cfg_free(cfg);
    return st;
}

#define SPHERE_BIG "[shape]\nkind = sphere\ncenter = 0 0 0\nradius = 1e5\n"
#define CIRCLE "[shape]\nkind = circle\ncenter = 0.5 0.5\nradius = 0.3\n"
#define SPHERE "[shape]\nkind = sphere\ncenter = 0 0 0\nradius = 0.5\n"

Test(field_cfg, a_validation_pass_builds_no_field)
{
    static const struct {
        const char *text;
        int dim;
        int build_fails; /* the build (not the keys) refuses it */
    } cases[] = {
        /* a half overflows at every sample: the build refuses it */
        {"[field]\nkind = gridpeer\nmethod = trilinear0\nstorage = float16\nres = 4\n" SPHERE_BIG,
         3, 1},
        {"[field]\nkind = pht\neps = 1e-3\nmax_level = 3\nlo = 0 0\nhi = 1 1\n" CIRCLE, 2, 0},
        {"[field]\nkind = openvdb\nvoxel = 0.1\nband = 3\n" SPHERE, 3, 0},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        dfl_field f;
        dfl_err err;
        if (build_in_pass(cases[i].text, 1, &f, &err) != DFL_OK) {
            cr_expect_fail("case %zu: the pass built and failed: %s", i, err.msg);
            continue;
        }
        cr_expect_str_eq(f.ops->name, "placeholder", "case %zu", i);
        cr_expect_eq(f.dim, cases[i].dim, "case %zu", i);
        dfl_field_destroy(&f);
        dfl_status st = build_in_pass(cases[i].text, 0, &f, &err);
        if (cases[i].build_fails) {
            cr_expect_eq(st, DFL_E_INPUT, "case %zu: the run builds, and refuses", i);
        } else {
            cr_assert_eq(st, DFL_OK, "case %zu: %s", i, err.msg);
            cr_expect_str_neq(f.ops->name, "placeholder", "case %zu: the run builds", i);
        }
        dfl_field_destroy(&f);
    }
}

Test(field_cfg, a_validation_pass_still_checks_every_key)
{
    static const struct {
        const char *text, *key;
    } cases[] = {
        {"[field]\nkind = gridpeer\nres = 0\n" SPHERE, "res"},
        {"[field]\nkind = gridpeer\nresolution = 8\n" SPHERE, "resolution"},
        {"[field]\nkind = pht\neps = 1e-3\nmax_level = -3\nlo = 0 0\nhi = 1 1\n" CIRCLE,
         "max_level"},
        {"[field]\nkind = pht\neps = 1e-3\nmaxlevel = 3\nlo = 0 0\nhi = 1 1\n" CIRCLE, "maxlevel"},
        {"[field]\nkind = openvdb\nvoxel = 0.1\nsampler = cubic\n" SPHERE, "sampler"},
        {"[field]\nkind = openvdb\nvoxel = 0.1\nbnd = 3\n" SPHERE, "bnd"},
        {"[field]\nkind = proxy\norder = 3\nres = 4\n" SPHERE, "order"},
        {"[field]\nkind = proxy\norder = 2\nres = 4\nstorag = half\n" SPHERE, "storag"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        dfl_field f;
        dfl_err err;
        cr_expect_eq(build_in_pass(cases[i].text, 1, &f, &err), DFL_E_INPUT, "case %zu", i);
        cr_expect(strstr(err.msg, cases[i].key) != NULL, "case %zu: %s", i, err.msg);
        dfl_field_destroy(&f);
    }
}

/* A proxy field in a pass: the grid as configured, no proxy computed. */
Test(field_cfg, a_validation_pass_gives_a_proxy_grid_of_zeros)
{
    const char *text = "[field]\nkind = proxy\norder = 2\nres = 6\nstorage = double\n" SPHERE;
    dfl_field f;
    dfl_err err;
    cr_assert_eq(build_in_pass(text, 1, &f, &err), DFL_OK, "%s", err.msg);
    const dfl_proxy_grid *g = dfl_proxy_field_grid(&f);
    cr_assert_not_null(g);
    cr_expect_eq(g->res, 6);
    cr_expect_eq(g->order, 2);
    const double *d = g->data;
    size_t nonzero = 0;
    for (size_t c = 0; c < g->ncells * (size_t)g->nscalar; c++) nonzero += d[c] != 0.0;
    cr_expect_eq(nonzero, 0, "no proxy computed");
    dfl_field_destroy(&f);
    cr_assert_eq(build_in_pass(text, 0, &f, &err), DFL_OK, "%s", err.msg);
    g = dfl_proxy_field_grid(&f);
    d = g->data;
    nonzero = 0;
    for (size_t c = 0; c < g->ncells * (size_t)g->nscalar; c++) nonzero += d[c] != 0.0;
    cr_expect_gt(nonzero, 0, "the run computes the proxies");
    dfl_field_destroy(&f);
}
