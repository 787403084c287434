/* Tests for src/io/config_set.c: --set overrides. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

#include "io/config.h"
#include "util/config_util.h"
#include "util/tmpdir.h"

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
    /* named by a key of an unselected section (a case's shape), to any
     * depth: excused too; a typo in a selected case's shape is not */
    const char *deep = "[study]\ncases = a b\n[a]\nx = 1\n[b]\nx = 2\nshape = sb\n"
                       "[sb]\ninner = sbb\n[sbb]\nr = 1\n";
    c = cfgu_parse(deep);
    cr_assert_eq(dfl_cfg_set(c, "study.cases=a", &err), DFL_OK);
    cr_expect_eq(read_cases(c, &err), DFL_OK, "b's shape and its part: %s", err.msg);
    dfl_cfg_free(c);
    c = cfgu_parse(deep);
    cr_assert_eq(dfl_cfg_set(c, "study.cases=b", &err), DFL_OK);
    cr_expect_eq(read_cases(c, &err), DFL_E_INPUT, "b is selected: its shape key is unread");
    cr_expect(strstr(err.msg, "[b] shape"), "%s", err.msg);
    dfl_cfg_free(c);
    /* named only by a key nobody read: not excused */
    c = cfgu_parse("[z]\nx = 2\n[study]\ncases = a\n[a]\nx = 1\n[w]\nother = z\n");
    cr_expect_eq(read_cases(c, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "[z] x"), "%s", err.msg);
    dfl_cfg_free(c);
    /* the sections an unselected section names (a CSG case's operands, and
     * theirs; a cycle ends) are unselected too; one nothing names is not */
    c = cfgu_parse("[study]\ncases = a b\n[a]\nx = 1\n[b]\nop = b1\n[b1]\nop = b2\n"
                   "[b2]\nop = b1\n[q]\nx = 5\n");
    cr_assert_eq(dfl_cfg_set(c, "study.cases=a", &err), DFL_OK);
    cr_expect_eq(read_cases(c, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "[q] x"), "only [q] is unknown: %s", err.msg);
    dfl_cfg_free(c);
    c = cfgu_parse("[study]\ncases = a b\n[a]\nx = 1\n[b]\nop = b1\n[b1]\nop = b2\n"
                   "[b2]\nop = b1\n");
    cr_assert_eq(dfl_cfg_set(c, "study.cases=a", &err), DFL_OK);
    cr_expect_eq(read_cases(c, &err), DFL_OK, "%s", err.msg);
    dfl_cfg_free(c);
}

/* Reads what a field factory would: [f] kind, then kind a's key `order`
 * or kind b's key `res`, kind csg's sub-sections `x`, `y` (their key n). */
static dfl_status read_kind(dfl_cfg *c, long *val, dfl_err *err)
{
    static const char *const kinds[] = {"a", "b", "csg"};
    int k;
    dfl_status st = dfl_cfg_enum(c, "f", "kind", kinds, 3, &k, err);
    if (st == DFL_OK && k == 0) st = dfl_cfg_int(c, "f", "order", 0, 9, val, err);
    if (st == DFL_OK && k == 1) st = dfl_cfg_int(c, "f", "res", 0, 99, val, err);
    if (st == DFL_OK && k == 2) {
        const char *x, *y;
        long n1, n2;
        st = dfl_cfg_string(c, "f", "x", &x, err);
        if (st == DFL_OK) st = dfl_cfg_string(c, "f", "y", &y, err);
        if (st == DFL_OK) st = dfl_cfg_int(c, x, "n", 0, 9, &n1, err);
        if (st == DFL_OK) st = dfl_cfg_int(c, y, "n", 0, 9, &n2, err);
        *val = 10 * n1 + n2;
    }
    return st ? st : dfl_cfg_check_used(c, err);
}

/* A --set of kind to a value sharing no item with the file's is a switch:
 * the file's other keys of that section (the old kind's) are dropped, keys
 * --set before the switch stay; narrowing a kind sweep is no switch. */
Test(config, set_kind_switch_drops_the_old_kinds_keys)
{
    dfl_err err;
    long v = -1;
    dfl_cfg *c = cfgu_parse("[f]\nkind = a\norder = 3\n");
    cr_expect_eq(read_kind(c, &v, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(v, 3);
    dfl_cfg_free(c);
    /* the switch: order (kind a's) goes, res is --set after it */
    c = cfgu_parse("[f]\nkind = a\norder = 3\n");
    cr_assert_eq(dfl_cfg_set(c, "f.kind=b", &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_cfg_set(c, "f.res=42", &err), DFL_OK, "%s", err.msg);
    cr_expect(!dfl_cfg_has(c, "f", "order"));
    cr_expect_eq(read_kind(c, &v, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(v, 42);
    dfl_cfg_free(c);
    /* a key --set before the switch stays */
    c = cfgu_parse("[f]\nkind = a\norder = 3\n");
    cr_assert_eq(dfl_cfg_set(c, "f.res=7", &err), DFL_OK);
    cr_assert_eq(dfl_cfg_set(c, "f.kind=b", &err), DFL_OK);
    cr_expect_eq(read_kind(c, &v, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(v, 7);
    dfl_cfg_free(c);
    /* the same value, or a narrowed sweep of kinds: no switch, keys stay */
    c = cfgu_parse("[f]\nkind = a\norder = 3\n");
    cr_assert_eq(dfl_cfg_set(c, "f.kind=a", &err), DFL_OK);
    cr_expect(dfl_cfg_has(c, "f", "order"));
    dfl_cfg_free(c);
    c = cfgu_parse("[f]\nkind = a, b\norder = 3\nres = 5\n");
    cr_assert_eq(dfl_cfg_set(c, "f.kind=b", &err), DFL_OK);
    cr_expect(dfl_cfg_has(c, "f", "order") && dfl_cfg_has(c, "f", "res"));
    dfl_cfg_free(c);
    /* only kind switches: another key's new value drops nothing */
    c = cfgu_parse("[f]\nkind = a\norder = 3\nmode = p\n");
    cr_assert_eq(dfl_cfg_set(c, "f.mode=q", &err), DFL_OK);
    cr_expect(dfl_cfg_has(c, "f", "order"));
    dfl_cfg_free(c);
    /* the old kind's sub-sections are unselected, not typos; a section
     * nothing ever named still is one */
    c = cfgu_parse("[f]\nkind = csg\nx = p\ny = q\n[p]\nn = 1\n[q]\nn = 2\n");
    cr_expect_eq(read_kind(c, &v, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(v, 12);
    dfl_cfg_free(c);
    c = cfgu_parse("[f]\nkind = csg\nx = p\ny = q\n[p]\nn = 1\n[q]\nn = 2\n[r]\nn = 3\n");
    cr_assert_eq(dfl_cfg_set(c, "f.kind=a", &err), DFL_OK);
    cr_assert_eq(dfl_cfg_set(c, "f.order=4", &err), DFL_OK);
    cr_expect_eq(read_kind(c, &v, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "[r] n"), "only [r] is unknown: %s", err.msg);
    dfl_cfg_free(c);
}

/* --set S=@FILE replaces every key of [S] by FILE's [S] (its includes
 * read), in place, with FILE's origins; FILE's other sections are not
 * taken; a FILE without [S], a missing FILE, an empty name: refused. */
Test(config, set_section_from_a_file)
{
    char dir[64], grp[600], inc[600], other[600];
    tmpdir_new(dir, sizeof dir);
    tmpdir_write(dir, "inc.ini", "[shape]\nres = 9\n", inc, sizeof inc);
    tmpdir_write(dir, "b.ini", "# a field group\n[f]\nkind = b\ninclude = inc.ini\n[g]\nn = 5\n",
                 grp, sizeof grp);
    tmpdir_write(dir, "other.ini", "[h]\nk = 1\n", other, sizeof other);
    dfl_err err;
    long v = -1;
    dfl_cfg *c = cfgu_parse("[g]\nn = 1\n[f]\nkind = a\norder = 3\n[z]\nm = 2\n");
    char set[700];
    snprintf(set, sizeof set, "f=@%s", grp);
    cr_assert_eq(dfl_cfg_set(c, set, &err), DFL_OK, "%s", err.msg);
    cr_expect(!dfl_cfg_has(c, "f", "order"));
    cr_expect_str_eq(cfgu_string(c, "f", "kind"), "b");
    cr_expect_str_eq(cfgu_string(c, "f", "res"), "9");
    cr_expect_str_eq(cfgu_string(c, "g", "n"), "1", "FILE's [g] is not taken");
    char w[1024];
    cr_expect(strstr(dfl_cfg_where(c, "f", "kind", w, sizeof w), "b.ini:3"), "%s", w);
    long n, m;
    cr_assert_eq(dfl_cfg_int(c, "g", "n", 0, 9, &n, &err), DFL_OK);
    cr_assert_eq(dfl_cfg_int(c, "z", "m", 0, 9, &m, &err), DFL_OK);
    cr_expect_eq(read_kind(c, &v, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(v, 9);
    /* written back in place: [g], then [f], then [z] */
    char path[700];
    snprintf(path, sizeof path, "%s/out.ini", dir);
    cr_assert_eq(dfl_cfg_write(c, NULL, path, &err), DFL_OK, "%s", err.msg);
    FILE *fp = fopen(path, "r");
    cr_assert_not_null(fp);
    char text[512] = "";
    size_t got = fread(text, 1, sizeof text - 1, fp);
    fclose(fp);
    text[got] = '\0';
    cr_expect(strstr(text, "[g]\nn = 1\n\n[f]\nkind = b\nres = 9\n\n[z]\nm = 2\n"), "%s", text);
    dfl_cfg_free(c);
    /* refusals */
    c = cfgu_parse("[f]\nkind = a\norder = 3\n");
    snprintf(set, sizeof set, "f=@%s", other);
    cr_expect_eq(dfl_cfg_set(c, set, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "has no [f] section"), "%s", err.msg);
    snprintf(set, sizeof set, "f=@%s/none.ini", dir);
    cr_expect_eq(dfl_cfg_set(c, set, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "none.ini"), "%s", err.msg);
    cr_expect_eq(dfl_cfg_set(c, "f=@", &err), DFL_E_INPUT);
    cr_expect_eq(dfl_cfg_set(c, "=@x.ini", &err), DFL_E_INPUT);
    cr_expect_eq(dfl_cfg_set(c, "f=x.ini", &err), DFL_E_INPUT, "no @: not a group");
    cr_expect_str_eq(cfgu_string(c, "f", "order"), "3", "a refused --set changes nothing");
    dfl_cfg_free(c);
    tmpdir_remove(dir);
}
