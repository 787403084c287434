/* Tests for src/io/config_where.c: every message names where the key was
 * written; unknown keys are reported. */
#include <criterion/criterion.h>
#include <string.h>

#include "io/config.h"
#include "util/config_util.h"

Test(config, errors_name_line_and_key)
{
    dfl_cfg *c = cfgu_parse("[a]\nx = 1\ny = 2.5\nz = 1 2\n");
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
    c = cfgu_parse("[a]\nx = 1\nw = 3\n");
    cr_assert_eq(dfl_cfg_int(c, "a", "x", 0, 9, &i, &err), DFL_OK);
    cr_expect_eq(dfl_cfg_check_used(c, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "t.ini:3: [a] w") != NULL, "%s", err.msg);
    dfl_cfg_free(c);
}

Test(config, where_and_err_at)
{
    dfl_cfg *c = cfgu_parse("[a]\nx = 1\n\n[b]\ny = 2\n");
    char w[256];
    cr_assert_str_eq(dfl_cfg_where(c, "b", "y", w, sizeof w), "t.ini:5: [b] y");
    cr_assert_str_eq(dfl_cfg_where(c, "b", "nope", w, sizeof w), "t.ini: [b] nope");
    dfl_err err;
    cr_assert_eq(dfl_cfg_set(c, "a.x=3", &err), DFL_OK);
    cr_assert_str_eq(dfl_cfg_where(c, "a", "x", w, sizeof w), "--set a.x");
    dfl_err_set(&err, DFL_E_INPUT, "degenerate");
    cr_assert_eq(dfl_cfg_err_at(c, "b", "y", DFL_E_INPUT, &err), DFL_E_INPUT);
    cr_assert_str_eq(err.msg, "t.ini:5: [b] y: degenerate");
    /* check_used_in looks at one section only */
    long v;
    cr_assert_eq(dfl_cfg_int(c, "a", "x", 0, 9, &v, &err), DFL_OK);
    cr_assert_eq(dfl_cfg_check_used_in(c, "a", &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_cfg_check_used_in(c, "b", &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "t.ini:5: [b] y: unknown key"), "%s", err.msg);
    dfl_cfg_free(c);
}

/* Deferred sections: NAME and NAME_* are skipped by dfl_cfg_check_used
 * (not NAMEx), and dfl_cfg_unused_deferred names the first with an unread
 * key. */
Test(config, deferred_sections)
{
    dfl_cfg *c = cfgu_parse("[a]\nx = 1\n[field]\nk = 1\n[field_b]\nk = 2\n");
    dfl_err err;
    long i;
    cr_assert_eq(dfl_cfg_int(c, "a", "x", 0, 9, &i, &err), DFL_OK);
    cr_expect_eq(dfl_cfg_check_used(c, &err), DFL_E_INPUT);
    dfl_cfg_defer_sections(c, "field");
    cr_expect_eq(dfl_cfg_check_used(c, &err), DFL_OK, "%s", err.msg);
    cr_expect_str_eq(dfl_cfg_unused_deferred(c), "field");
    cr_assert_eq(dfl_cfg_int(c, "field", "k", 0, 9, &i, &err), DFL_OK);
    cr_expect_str_eq(dfl_cfg_unused_deferred(c), "field_b");
    cr_assert_eq(dfl_cfg_int(c, "field_b", "k", 0, 9, &i, &err), DFL_OK);
    cr_expect_null(dfl_cfg_unused_deferred(c));
    dfl_cfg_free(c);
    c = cfgu_parse("[fieldx]\nk = 1\n");
    dfl_cfg_defer_sections(c, "field");
    cr_expect_eq(dfl_cfg_check_used(c, &err), DFL_E_INPUT);
    cr_expect_null(dfl_cfg_unused_deferred(c));
    dfl_cfg_defer_sections(c, NULL);
    dfl_cfg_free(c);
}

/* claim_section marks exactly the keys of one section read, and records
 * nothing in the read record. */
Test(config, claim_section_marks_one_section)
{
    dfl_cfg *c = cfgu_parse("[a]\nx = 1\ny = 2\n[b]\nz = 3\n");
    dfl_err err;
    const size_t reads = dfl_cfg_reads(c);
    dfl_cfg_claim_section(c, "a");
    dfl_cfg_claim_section(c, "nosuch");
    cr_expect_eq(dfl_cfg_reads(c), reads);
    cr_expect_eq(dfl_cfg_check_used_in(c, "a", &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(dfl_cfg_check_used(c, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "t.ini:5: [b] z") != NULL, "%s", err.msg);
    dfl_cfg_free(c);
}

/* dfl_cfg_used: present and read; absent is false; marks nothing */
Test(config, used_is_present_and_read)
{
    dfl_cfg *cfg = cfgu_parse("[a]\nk = 1\nj = 2\n");
    cr_expect_not(dfl_cfg_used(cfg, "a", "k"));
    cr_expect_not(dfl_cfg_used(cfg, "a", "nope"));
    long v;
    dfl_err err;
    cr_assert_eq(dfl_cfg_int(cfg, "a", "k", 0, 9, &v, &err), DFL_OK, "%s", err.msg);
    cr_expect(dfl_cfg_used(cfg, "a", "k"));
    cr_expect_not(dfl_cfg_used(cfg, "a", "j"));
    cr_expect_not(dfl_cfg_used(cfg, "b", "k"));
    cr_expect_eq(dfl_cfg_check_used_in(cfg, "a", &err), DFL_E_INPUT, "j stays unread");
    cr_expect(strstr(err.msg, "j"), "%s", err.msg);
    dfl_cfg_free(cfg);
}

/* claim_read marks in the original exactly the keys read in a sweep point
 * of it (sections a reader followed included), not those of a key the
 * point added, and appends the point's read records of c's keys and of
 * defaults (not of the added key) to c's record. */
Test(config, claim_read_marks_what_the_point_read)
{
    dfl_cfg *c = cfgu_parse("[a]\nx = 1\nnext = b\n[b]\nz = 3\n[c]\nw = 4\n");
    dfl_cfg *p;
    dfl_err err;
    cr_assert_eq(dfl_cfg_sweep_point(c, 0, &p, &err), DFL_OK);
    cr_assert_eq(dfl_cfg_set(p, "c.extra=5", &err), DFL_OK, "%s", err.msg);
    const char *v;
    long z;
    cr_assert_eq(dfl_cfg_string(p, "a", "x", &v, &err), DFL_OK);
    cr_assert_eq(dfl_cfg_string(p, "a", "next", &v, &err), DFL_OK);
    cr_assert_eq(dfl_cfg_int(p, "b", "z", 0, 9, &z, &err), DFL_OK);
    cr_assert_eq(dfl_cfg_string(p, "c", "extra", &v, &err), DFL_OK);
    long dflt;
    cr_assert_eq(dfl_cfg_int_opt(p, "b", "absent", 7, 0, 9, &dflt, &err), DFL_OK);
    const size_t reads = dfl_cfg_reads(c);
    dfl_cfg_claim_read(c, p);
    cr_expect_eq(dfl_cfg_reads(c), reads + 4, "a.x, a.next, b.z, b.absent (not c.extra)");
    dfl_cfg_read r;
    cr_assert(dfl_cfg_read_at(c, reads + 2, &r));
    cr_expect_str_eq(r.sec, "b");
    cr_expect_str_eq(r.key, "z");
    cr_expect_str_eq(r.value, "3");
    cr_expect(!r.is_default);
    cr_expect(strstr(r.expect, "[0, 9]") != NULL, "%s", r.expect);
    cr_assert(dfl_cfg_read_at(c, reads + 3, &r));
    cr_expect_str_eq(r.key, "absent");
    cr_expect(r.is_default);
    cr_expect_str_eq(r.value, "7");
    for (size_t i = 0; dfl_cfg_read_at(c, i, &r); i++)
        cr_expect(strcmp(r.key, "extra") != 0, "the point's own key was recorded");
    dfl_cfg_claim_read(c, p);
    cr_expect_eq(dfl_cfg_reads(c), reads + 4, "a second claim records nothing new");
    cr_expect_eq(dfl_cfg_check_used_in(c, "a", &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(dfl_cfg_check_used_in(c, "b", &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(dfl_cfg_check_used(c, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "t.ini:7: [c] w") != NULL, "%s", err.msg);
    dfl_cfg_free(p);
    dfl_cfg_free(c);
}
