/* Tests for src/io/config_set.c: --set overrides. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

#include "io/config.h"
#include "util/config_util.h"

Test(config, set_overrides_and_adds)
{
    dfl_cfg *c = cfgu_parse("[g]\nn = 4\n");
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

/* include is resolved when the file is read; --set cannot add one. */
Test(config, set_refuses_include)
{
    dfl_cfg *c = cfgu_parse("[S]\norder = 4\n");
    dfl_err err;
    cr_assert_eq(dfl_cfg_set(c, "S.include=configs/shapes/S.ini", &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "--set S.include=configs/shapes/S.ini: include is read with"),
              "%s", err.msg);
    cr_assert(!dfl_cfg_has(c, "S", "include"));
    /* a --set key gets the origin "--set" in messages */
    cr_assert_eq(dfl_cfg_set(c, "S.order=x", &err), DFL_OK);
    long o;
    cr_assert_eq(dfl_cfg_int(c, "S", "order", 1, 9, &o, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "--set S.order: expected an integer in [1, 9], got 'x'"), "%s",
              err.msg);
    dfl_cfg_free(c);
}

/* `--set perturb.offset=4e-320`: a subnormal set on the command line is the
 * value the getter returns, within [-1, 1]. */
Test(config, set_subnormal_is_a_value)
{
    dfl_cfg *c = cfgu_parse("[perturb]\nscale = 0\n");
    dfl_err err;
    cr_assert_eq(dfl_cfg_set(c, "perturb.offset=4e-320", &err), DFL_OK, "%s", err.msg);
    double d;
    cr_assert_eq(dfl_cfg_double(c, "perturb", "offset", -1, 1, &d, &err), DFL_OK, "%s", err.msg);
    cr_expect(d == 4e-320);
    dfl_cfg_free(c);
}

/* Reads what a study with cases would: [study] cases (a list of section
 * names) and each named section's x. */
static dfl_status read_cases(dfl_cfg *c, dfl_err *err)
{
    const char *cases;
    dfl_status st = dfl_cfg_string(c, "study", "cases", &cases, err);
    char buf[256];
    snprintf(buf, sizeof buf, "%s", st ? "" : cases);
    for (char *w = strtok(buf, " "); !st && w; w = strtok(NULL, " ")) {
        long x;
        st = dfl_cfg_int(c, w, "x", 0, 9, &x, err);
    }
    return st ? st : dfl_cfg_check_used(c, err);
}

/* A section the run did not select is the config's, not a typo: one that
 * a --set removed from a list key, or another item of a sweep over the
 * list; a section no read key ever named is still unknown, and so is an
 * unread key of a selected section. */
Test(config, unselected_sections_are_not_unused)
{
    const char *ini = "[study]\ncases = a b c\n[a]\nx = 1\n[b]\nx = 2\n[c]\nx = 3\n";
    dfl_err err;
    dfl_cfg *c = cfgu_parse(ini);
    cr_expect_eq(read_cases(c, &err), DFL_OK, "%s", err.msg); /* all selected */
    dfl_cfg_free(c);
    c = cfgu_parse(ini);
    cr_assert_eq(dfl_cfg_set(c, "study.cases=b", &err), DFL_OK);
    cr_expect_eq(read_cases(c, &err), DFL_OK, "--set narrowed the list: %s", err.msg);
    dfl_cfg_free(c);
    /* a sweep over the list: each point selects one */
    c = cfgu_parse("[study]\ncases = a, b\n[a]\nx = 1\n[b]\nx = 2\n");
    dfl_cfg *p;
    cr_assert_eq(dfl_cfg_sweep_point(c, 1, &p, &err), DFL_OK);
    cr_expect_eq(read_cases(p, &err), DFL_OK, "sweep point: %s", err.msg);
    dfl_cfg_free(p);
    dfl_cfg_free(c);
    /* never named: still a typo */
    c = cfgu_parse("[study]\ncases = a\n[a]\nx = 1\n[aa]\nx = 2\n");
    cr_expect_eq(read_cases(c, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "[aa] x"), "%s", err.msg);
    dfl_cfg_free(c);
    /* a selected section's unread key: still unknown */
    c = cfgu_parse(ini);
    cr_assert_eq(dfl_cfg_set(c, "study.cases=a", &err), DFL_OK);
    cr_assert_eq(dfl_cfg_set(c, "a.y=1", &err), DFL_OK);
    cr_expect_eq(read_cases(c, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "a.y: unknown key"), "%s", err.msg);
    dfl_cfg_free(c);
    /* named only by a key nobody read: not excused */
    c = cfgu_parse("[z]\nx = 2\n[study]\ncases = a\n[a]\nx = 1\n[w]\nother = z\n");
    cr_expect_eq(read_cases(c, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "[z] x"), "%s", err.msg);
    dfl_cfg_free(c);
}
