/* Tests for src/io/config_parse.c: INI syntax through libinih. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/config.h"
#include "util/config_util.h"

/* Long values (beyond libinih's default 200-character line) and indented
 * continuation lines are kept whole. */
Test(config, long_and_continued_values)
{
    char text[8192];
    size_t k = (size_t)snprintf(text, sizeof text, "[c]\ncontrol = ");
    for (int i = 0; i < 300; i++) k += (size_t)snprintf(text + k, sizeof text - k, "%d %d; ", i, i);
    k += (size_t)snprintf(text + k, sizeof text - k, "\nknots = 0 0\n  1 1\n  2 2\n");
    dfl_cfg *c = cfgu_parse(text);
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

/* Input the parser rejects: each message names the file and line. */
Test(config, parse_errors_name_file_and_line)
{
    static const struct {
        const char *text, *want;
    } cases[] = {
        {"x = 1\n[a]\n", "t.ini:1: key 'x' outside any [section]"},
        {"[a]\nx = 1\ny = 2\nx = 3\n", "t.ini:4: [a] x: duplicate key (first at line 2)"},
        {"[a]\nx = 1\nthis line has no equals sign\n", "t.ini:3: syntax error"},
        {"[a\nx = 1\n", "t.ini:1: syntax error"},
        /* sections are never merged (config.h, "Duplicates") */
        {"[a]\nx = 1\n[b]\ny = 2\n[a]\nz = 3\n", "t.ini:5: [a]: duplicate section (first at line 1"},
        {"[a]\n[a]\n", "t.ini:2: [a]: duplicate section"},
        /* names libinih would cut are refused */
        {"[aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa]\n", "t.ini:1: section name longer than 49"},
        {"[a]\nkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkk = 1\n", "t.ini:2: key name longer than 49"},
        {"[a]\nx = 1\x01\n", "t.ini:2: control character 0x01 at column 6"},
        {"[a]\nx = \xe9\n", "t.ini:2: invalid UTF-8 at column 5"},
        {"[a]\nx = 1\ry\n", "t.ini:2: control character 0x0d"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        dfl_cfg *c = (dfl_cfg *)&c;
        dfl_err err;
        cr_assert_eq(dfl_cfg_parse_string("t.ini", cases[i].text, &c, &err), DFL_E_INPUT,
                     "case %zu", i);
        cr_assert_null(c, "case %zu", i);
        cr_assert(strstr(err.msg, cases[i].want), "case %zu: '%s'", i, err.msg);
    }
    /* a line beyond the limit is refused, not cut */
    size_t n = 70000;
    char *text = malloc(n + 16);
    cr_assert_not_null(text);
    size_t k = (size_t)snprintf(text, n, "[a]\nv = ");
    memset(text + k, '1', n - k);
    text[n] = '\0';
    dfl_cfg *c;
    dfl_err err;
    cr_assert_eq(dfl_cfg_parse_string("t.ini", text, &c, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "t.ini:2: line longer than"), "%s", err.msg);
    free(text);
    const char *want[] = {"no/such/file.ini: cannot open config"};
    cfgu_expect_fail("no/such/file.ini", want, 1, NULL);
}

/* A BOM is skipped and CRLF line ends are accepted, as in the points CSV
 * (io/lines.h); a 49-character name is the longest accepted. */
Test(config, bom_crlf_and_longest_names)
{
    dfl_cfg *c = cfgu_parse("\xef\xbb\xbf[a]\r\nx = 1\r\n"
                            "[sssssssssssssssssssssssssssssssssssssssssssssssss]\r\n"
                            "kkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkk = 2\n");
    long v;
    dfl_err err;
    cr_assert_eq(dfl_cfg_int(c, "a", "x", 0, 9, &v, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(v, 1);
    cr_assert_eq(dfl_cfg_int(c, "sssssssssssssssssssssssssssssssssssssssssssssssss",
                             "kkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkk", 0, 9, &v, &err),
                 DFL_OK, "%s", err.msg);
    cr_expect_eq(v, 2);
    dfl_cfg_free(c);
}
