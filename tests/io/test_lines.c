/* Tests for src/io/lines.c: the line rules shared by the INI and CSV
 * readers, and the escaping of messages. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/lines.h"

/* Reads all lines of text (len bytes, may hold NULs) with limit max;
 * returns the status of the first failure (DFL_OK at the end) and the
 * count of lines read. */
static dfl_status read_all(const char *text, size_t len, size_t max, long max_lines, long *nread,
                           dfl_err *err)
{
    FILE *fp = fmemopen((void *)text, len, "rb");
    cr_assert_not_null(fp);
    dfl_lines r;
    dfl_lines_open_file(&r, fp, "t.txt", max, max_lines);
    char *buf = malloc(max + 4);
    size_t n;
    dfl_status st;
    *nread = 0;
    while ((st = dfl_lines_next(&r, buf, max + 4, &n, err)) == DFL_OK && n != (size_t)-1)
        (*nread)++;
    free(buf);
    fclose(fp);
    return st;
}

Test(lines, limits_and_line_ends)
{
    dfl_err err;
    long n;
    cr_expect_eq(read_all("ab\ncd\r\nef", 9, 2, 10, &n, &err), DFL_OK);
    cr_expect_eq(n, 3);
    /* a final line of exactly max bytes without newline is accepted */
    cr_expect_eq(read_all("abc\nxyz", 7, 3, 10, &n, &err), DFL_OK);
    cr_expect_eq(n, 2);
    cr_expect_eq(read_all("abc\nwxyz", 8, 3, 10, &n, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "t.txt:2: line longer than 3 characters"), "%s", err.msg);
    cr_expect_eq(read_all("a\nb\nc\n", 6, 3, 2, &n, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "t.txt:3: more than 2 lines"), "%s", err.msg);
    cr_expect_eq(read_all("\xef\xbb\xbf" "abc", 6, 3, 10, &n, &err), DFL_OK, "BOM beyond max");
}

/* The reader stops at the first byte beyond the limit: an endless line
 * (here 64 MiB of 'a') costs max + 1 bytes, not the whole stream. */
Test(lines, endless_line_stops_early)
{
    const size_t big = 64u << 20;
    char *text = malloc(big);
    memset(text, 'a', big);
    FILE *fp = fmemopen(text, big, "rb");
    dfl_lines r;
    dfl_lines_open_file(&r, fp, "z", 100, 10);
    char buf[104];
    size_t n;
    dfl_err err;
    cr_expect_eq(dfl_lines_next(&r, buf, sizeof buf, &n, &err), DFL_E_INPUT);
    cr_expect_lt(ftell(fp), 1 << 16, "read on to %ld", ftell(fp));
    fclose(fp);
    free(text);
}

Test(lines, bytes_that_are_not_text)
{
    static const struct {
        const char *text;
        size_t len;
        const char *want;
    } cases[] = {
        {"ab\0c\n", 5, "t.txt:1: NUL byte at column 3"},
        {"ok\nab\x01\n", 7, "t.txt:2: control character 0x01 at column 3"},
        {"a\rb\n", 4, "control character 0x0d at column 2"},
        {"\x7f\n", 2, "0x7f"},
        {"a\xc2\x85\n", 4, "U+0085 at column 2"},
        {"a\xff\n", 3, "invalid UTF-8 at column 2 (byte 0xff"},
        {"\xc0\xaf\n", 3, "invalid UTF-8 at column 1"},
        {"\xed\xa0\x80\n", 4, "invalid UTF-8"},
        {"\xf4\x90\x80\x80\n", 5, "invalid UTF-8"},
        {"ab\xe2\x82\n", 5, "invalid UTF-8 at column 3"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        dfl_err err;
        long n;
        cr_expect_eq(read_all(cases[i].text, cases[i].len, 64, 10, &n, &err), DFL_E_INPUT,
                     "case %zu", i);
        cr_expect(strstr(err.msg, cases[i].want), "case %zu: %s", i, err.msg);
    }
    dfl_err err;
    long n;
    const char *ok = "tab\there \xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80\n";
    cr_expect_eq(read_all(ok, strlen(ok), 64, 10, &n, &err), DFL_OK, "%s", err.msg);
}

Test(lines, escape)
{
    char out[64];
    cr_expect_str_eq(dfl_text_escape("a\rb\x1b[2J\xff \xc3\xa9", out, sizeof out),
                     "a\\x0db\\x1b[2J\\xff \xc3\xa9");
    cr_expect_str_eq(dfl_text_escape("\xc2\x9b", out, sizeof out), "\\xc2\\x9b");
    /* truncation keeps whole escapes */
    cr_expect_str_eq(dfl_text_escape("ab\x01", out, 5), "ab");
    cr_expect_eq(dfl_text_utf8_bad("ab\xc3", 3), 2);
    cr_expect_eq(dfl_text_utf8_bad("ab", 2), 2);
}

/* The rules' edges, one assertion per sentence of lines.h: the BOM's three
 * bytes are allowed beyond max on the first line only and only as a BOM (a
 * BOM line of max + 1 characters is still too long); a BOM is skipped on the
 * first line and kept as text elsewhere; the C1 range ends at U+009F. */
Test(lines, rule_edges)
{
    dfl_err err;
    long n;
    cr_expect_eq(read_all("\xef\xbb\xbf" "abcd", 7, 3, 10, &n, &err), DFL_E_INPUT,
                 "a BOM line of max + 1 characters");
    cr_expect(strstr(err.msg, "t.txt:1: line longer than 3 characters"), "%s", err.msg);
    cr_expect_eq(read_all("\xef\xbb\xbf" "abcd\n", 8, 3, 10, &n, &err), DFL_E_INPUT);

    dfl_lines r;
    char buf[64];
    size_t len;
    dfl_lines_open_text(&r, "\xef\xbb\xbf" "a\n\xef\xbb\xbf" "b\n", "t.txt", 32, 10);
    cr_assert_eq(dfl_lines_next(&r, buf, sizeof buf, &len, &err), DFL_OK);
    cr_expect_eq(len, 1);
    cr_expect_str_eq(buf, "a");
    cr_assert_eq(dfl_lines_next(&r, buf, sizeof buf, &len, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(len, 4, "a BOM on line 2 is text, not skipped");
    cr_expect_str_eq(buf, "\xef\xbb\xbf" "b");

    cr_expect_eq(read_all("a\xc2\x9f", 3, 8, 10, &n, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "U+009F"), "%s", err.msg);
    cr_expect_eq(read_all("a\xc2\x80", 3, 8, 10, &n, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "U+0080"), "%s", err.msg);
    cr_expect_eq(read_all("a\xc2\xa0", 3, 8, 10, &n, &err), DFL_OK, "U+00A0 is text");
}
