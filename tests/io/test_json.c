/* Tests for src/io/json.c: the strict reader of point records. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/json.h"

static dfl_status check(const char *t, dfl_err *err)
{
    return dfl_json_check(t, strlen(t), "p.json", err);
}

Test(json, accepts_what_dflab_writes)
{
    const char *ok[] = {
        "{}", " {\n  \"a\": 1,\n  \"b\": [\"x\", {\"c\": null}],\n  \"d\": true\n}\n",
        "{\"s\": \"\\u00e9\\n\\\"\\\\\\/\\ud83d\\ude00\"}", "{\"n\": -0.5e+10, \"m\": 0, \"k\": []}",
        "{\"u\": \"\xc3\xa9\xe2\x82\xac\xf0\x9f\x98\x80\"}",
    };
    for (size_t i = 0; i < sizeof ok / sizeof *ok; i++) {
        dfl_err err = {0};
        cr_expect_eq(check(ok[i], &err), DFL_OK, "case %zu: %s", i, err.msg);
    }
}

Test(json, refuses_each_malformed_text_naming_the_byte)
{
    struct {
        const char *text, *want;
    } bad[] = {
        {"{\"a\": 1} x", "byte 9: expected nothing after the object"},
        {"{\"a\": 1}}", "byte 8: expected nothing after the object"},
        {"{\"a\": 1,}", "byte 8: expected '\"'"},
        {"{\"a\": [1, 2,]}", "byte 12:"},
        {"[1]", "byte 0: expected '{'"},
        {"", "byte 0: expected '{'"},
        {"{\"a\": 01}", "byte 7: expected ',' or '}'"},
        {"{\"a\": 1.}", "byte 8: expected a digit"},
        {"{\"a\": NaN}", "byte 6: expected a JSON value"},
        {"{\"a\": \"x\ny\"}", "byte 8: expected no control character"},
        {"{\"a\": \"\\x\"}", "byte 8: expected an escape"},
        {"{\"a\": \"\\u12\"}", "byte 11: expected a hex digit"},
        {"{\"a\": \"\\u", "byte 9: expected a hex digit"},
        {"{\"a\": \"\\udc00\"}", "byte 7: expected no lone low surrogate"},
        {"{\"a\": \"\\ud800x\"}", "expected a \\u low surrogate"},
        {"{\"a\": \"\xc0\xaf\"}", "byte 7: expected valid UTF-8"},
        {"{\"a\": \"\xed\xa0\x80\"}", "byte 7: expected valid UTF-8"},
        {"{\"a\": \"\xe2\x82\"}", "byte 7: expected valid UTF-8"},
        {"{\"a\": 1, \"a\": 2}", "byte 9: expected each top-level key once"},
        {"{\"a\" 1}", "byte 5: expected ':'"},
        {"{\"a\": tru}", "byte 6: expected a JSON value"},
        {"{\"a\": \"x", "byte 8: expected '\"' closing the string, got the end"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        dfl_err err = {0};
        cr_expect_eq(check(bad[i].text, &err), DFL_E_INPUT, "case %zu", i);
        cr_expect(strstr(err.msg, "p.json: ") == err.msg, "case %zu: %s", i, err.msg);
        cr_expect(strstr(err.msg, bad[i].want), "case %zu: %s", i, err.msg);
    }
}

Test(json, nul_byte_is_refused_where_it_stands)
{
    dfl_err err = {0};
    cr_assert_eq(dfl_json_check("{}\0x", 4, "p.json", &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "byte 2: expected nothing after the object, got a NUL byte"), "%s",
              err.msg);
    cr_assert_eq(dfl_json_check("{\"a\": \"\0\"}", 10, "p.json", &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "byte 7:") && strstr(err.msg, "NUL"), "%s", err.msg);
}

/* {"a": [[...[]...]]} with levels arrays: depth levels + 1. */
static char *nested(int levels)
{
    char *t = malloc(2 * (size_t)levels + 16);
    cr_assert_not_null(t);
    size_t n = (size_t)sprintf(t, "{\"a\": ");
    for (int d = 0; d < levels; d++) t[n++] = '[';
    for (int d = 0; d < levels; d++) t[n++] = ']';
    strcpy(t + n, "}");
    return t;
}

Test(json, nesting_is_bounded)
{
    dfl_err err = {0};
    char *t = nested(DFL_JSON_DEPTH_MAX - 1);
    cr_expect_eq(check(t, &err), DFL_OK, "%s", err.msg);
    free(t);
    t = nested(DFL_JSON_DEPTH_MAX);
    cr_expect_eq(check(t, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "levels of nesting"), "%s", err.msg);
    free(t);
}

static const char *REC =
    "{\n  \"index\": 3,\n  \"npoints\": 8,\n  \"resolved\": {\"index\": 99, \"s\": \"}\"},\n"
    "  \"study\": \"a\\u00e9\\ud83d\\ude00\\n\",\n  \"big\": 1e300,\n  \"neg\": -5,\n"
    "  \"frac\": 2.5,\n  \"str\": \"3\",\n  \"huge\": 1e400,\n  \"nul\": \"x\\u0000\"\n}\n";

Test(json, getters_read_top_level_members_only)
{
    dfl_err err = {0};
    cr_assert_eq(check(REC, &err), DFL_OK, "%s", err.msg);
    long v = -1;
    cr_assert_eq(dfl_json_get_long(REC, "index", "p.json", 0, 100, &v, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(v, 3); /* not the nested 99 */
    char buf[32];
    cr_assert_eq(dfl_json_get_string(REC, "study", "p.json", buf, sizeof buf, &err), DFL_OK);
    cr_expect_str_eq(buf, "a\xc3\xa9\xf0\x9f\x98\x80\n");
    double d = 0;
    cr_assert_eq(dfl_json_get_double(REC, "frac", "p.json", &d, &err), DFL_OK);
    cr_expect_eq(d, 2.5);
    const char *val;
    size_t vl;
    cr_assert(dfl_json_member(REC, "resolved", &val, &vl));
    cr_expect_eq(vl, strlen("{\"index\": 99, \"s\": \"}\"}"));
    cr_expect_eq(strncmp(val, "{\"index\": 99", 12), 0);
    cr_expect_not(dfl_json_member(REC, "s", &val, &vl));
}

Test(json, getters_refuse_wrong_types_and_ranges)
{
    struct {
        const char *key, *want;
    } longs[] = {
        {"big", "big: expected an integer in 0..100"}, {"neg", "neg: expected an integer"},
        {"frac", "frac: expected an integer"},         {"str", "str: expected an integer"},
        {"missing", "p.json: missing: missing"},
    };
    dfl_err err = {0};
    for (size_t i = 0; i < sizeof longs / sizeof *longs; i++) {
        long v = 7;
        cr_expect_eq(dfl_json_get_long(REC, longs[i].key, "p.json", 0, 100, &v, &err), DFL_E_INPUT);
        cr_expect(strstr(err.msg, longs[i].want), "%s: %s", longs[i].key, err.msg);
        cr_expect_eq(v, 7);
    }
    /* "big": 1e300 stands at the byte its message names */
    cr_expect_eq(dfl_json_get_long(REC, "big", "p.json", 0, 100, &(long){0}, &err), DFL_E_INPUT);
    char want[48];
    snprintf(want, sizeof want, "p.json: byte %zu: big", (size_t)(strstr(REC, "1e300") - REC));
    cr_expect(strstr(err.msg, want), "%s (want %s)", err.msg, want);
    double d;
    cr_expect_eq(dfl_json_get_double(REC, "huge", "p.json", &d, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "range of a double"), "%s", err.msg);
    cr_expect_eq(dfl_json_get_double(REC, "study", "p.json", &d, &err), DFL_E_INPUT);
    char buf[8];
    cr_expect_eq(dfl_json_get_string(REC, "nul", "p.json", buf, sizeof buf, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "\\u0000"), "%s", err.msg);
    cr_expect_eq(dfl_json_get_string(REC, "index", "p.json", buf, sizeof buf, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "expected a string"), "%s", err.msg);
    char small[4]; /* "a" + 2 + 4 + 1 bytes do not fit in 3 */
    cr_expect_eq(dfl_json_get_string(REC, "study", "p.json", small, sizeof small, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "at most 3 bytes"), "%s", err.msg);
    cr_expect_str_eq(small, "");
}

/* json.h: strings are valid UTF-8 without control characters.  The
 * controls are U+0000..U+001F (RFC 8259), the last of them 0x1F included;
 * UTF-8 ends at U+10FFFF = F4 8F BF BF, so F4 90 80 80 (U+110000) is
 * invalid while F4 8F BF BF is valid. */
Test(json, refuses_the_last_control_and_code_points_above_u10ffff)
{
    dfl_err err = {0};
    cr_expect_eq(check("{\"a\": \"x\x1fy\"}", &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "byte 8: expected no control character"), "%s", err.msg);
    cr_expect_eq(check("{\"a\": \"x\x20y\"}", &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(check("{\"a\": \"\xf4\x90\x80\x80\"}", &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "byte 7: expected valid UTF-8"), "%s", err.msg);
    cr_expect_eq(check("{\"a\": \"\xf4\x8f\xbf\xbf\"}", &err), DFL_OK, "%s", err.msg);
}
