/* Tests for src/io/points.c: the points CSV reader. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/points.h"

static dfl_status read_text(const char *text, size_t len, int dim, bool dir, dfl_points *p,
                            dfl_err *err)
{
    FILE *fp = fmemopen((void *)text, len, "rb");
    cr_assert_not_null(fp);
    dfl_status st = dfl_points_read(fp, "p.csv", dim, dir, p, err);
    fclose(fp);
    return st;
}

Test(points, columns_any_order_bom_crlf)
{
    const char *t = "\xef\xbb\xbfy, x ,dy,dx\r\n\r\n1,2,0,1\r\n-3e-2 , 4,1,0";
    dfl_points p;
    dfl_err err;
    cr_assert_eq(read_text(t, strlen(t), 2, true, &p, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(p.n, 2);
    cr_expect_eq(p.v[0], 2);
    cr_expect_eq(p.v[1], 1);
    cr_expect_eq(p.v[3], 1);
    cr_expect_eq(p.v[6 + 1], -3e-2);
    cr_expect_eq(p.v[6 + 4], 1);
    dfl_points_free(&p);
}

/* A final line of DFL_POINTS_LINE_MAX characters without a newline is a
 * valid line; one more character is refused. */
Test(points, final_line_at_the_limit)
{
    const size_t L = DFL_POINTS_LINE_MAX;
    char *t = malloc(L + 16);
    size_t k = (size_t)snprintf(t, 16, "x,y\n");
    memset(t + k, ' ', L - 4);
    memcpy(t + k + L - 4, "1,2", 3);
    t[k + L - 1] = '5';
    dfl_points p;
    dfl_err err;
    cr_assert_eq(read_text(t, k + L, 2, false, &p, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(p.n, 1);
    cr_expect_eq(p.v[1], 25);
    dfl_points_free(&p);
    t[k + L] = '5';
    cr_expect_eq(read_text(t, k + L + 1, 2, false, &p, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "p.csv:2: line longer than 4095"), "%s", err.msg);
    free(t);
}

Test(points, refused)
{
    static const struct {
        const char *text;
        size_t len;
        const char *want;
    } cases[] = {
        {"x,y\n1,2\0junk\n", 13, "p.csv:2: NUL byte at column 4"},
        {"x,y\n1,\xff\n", 7, "p.csv:2: invalid UTF-8"},
        {"x,y\n1,2,3\n", 10, "p.csv:2: expected 2 fields, got 3"},
        {"x,y\n1,1e999\n", 12, "column 'y': expected a finite number"},
        {"x,y\n1,nan\n", 10, "column 'y'"},
        {"x,x\n", 4, "duplicate column 'x'"},
        {"x,q\n", 4, "unknown column 'q'"},
        {"", 0, "empty file"},
        {"x,y\n\n", 5, "no points"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        dfl_points p = {(double *)1, 5, 5};
        dfl_err err;
        cr_expect_eq(read_text(cases[i].text, cases[i].len, 2, false, &p, &err), DFL_E_INPUT,
                     "case %zu", i);
        cr_expect(strstr(err.msg, cases[i].want), "case %zu: %s", i, err.msg);
        cr_expect(p.v == NULL && p.n == 0, "case %zu: points left", i);
    }
}

/* points.h: the header names x,y[,z] and, with want_dir, dx,dy[,dz], "no
 * other column": a z column for a 2D field, or a direction without
 * --jet, is refused naming the column. */
Test(points, refuses_columns_the_field_does_not_take)
{
    static const struct {
        const char *text;
        int dim;
        bool dir;
        const char *want;
    } cases[] = {
        {"x,y,z\n1,2,3\n", 2, false, "column 'z' not expected for a 2D field"},
        {"x,y,dx,dy\n1,2,0,1\n", 2, false, "column 'dx' not expected"},
        {"x,y,z,dz\n1,2,3,1\n", 3, false, "column 'dz' not expected"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        dfl_points p = {0};
        dfl_err err;
        const size_t len = strlen(cases[i].text);
        cr_expect_eq(read_text(cases[i].text, len, cases[i].dim, cases[i].dir, &p, &err),
                     DFL_E_INPUT, "case %zu", i);
        cr_expect(strstr(err.msg, cases[i].want), "case %zu: %s", i, err.msg);
        cr_expect(p.v == NULL && p.n == 0, "case %zu: points left", i);
    }
}
