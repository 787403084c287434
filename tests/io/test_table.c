#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/table.h"
#include "core/rng.h"

Test(table, long_format_with_prefix)
{
    dfl_table *t = dfl_table_new();
    dfl_err err;
    cr_assert_eq(dfl_table_prefix_string(t, "grid.n", "16", &err), DFL_OK);
    cr_assert_eq(dfl_table_row(t, &err), DFL_OK);
    dfl_table_set_double(t, "l1", 0.1, &err);
    dfl_table_set_string(t, "name", "a,b", &err);
    dfl_table_prefix_clear(t);
    dfl_table_prefix_string(t, "grid.n", "32", &err);
    dfl_table_row(t, &err);
    dfl_table_set_int(t, "count", 7, &err);
    cr_expect_eq(dfl_table_rows(t), 2);
    cr_expect_eq(dfl_table_cols(t), 4);
    char path[] = "/tmp/dflab-table-XXXXXX";
    int fd = mkstemp(path);
    cr_assert(fd >= 0);
    close(fd);
    cr_assert_eq(dfl_table_write_csv(t, path, &err), DFL_OK);
    FILE *fp = fopen(path, "r");
    char buf[512] = "";
    size_t n = fread(buf, 1, sizeof buf - 1, fp);
    buf[n] = '\0';
    fclose(fp);
    cr_expect_str_eq(buf, "grid.n,l1,name,count\n16,0.1,\"a,b\",\n32,,,7\n");
    remove(path);
    dfl_table_free(t);
}

Test(table, cell_before_row_is_an_error_naming_the_column)
{
    dfl_table *t = dfl_table_new();
    dfl_err err;
    dfl_err_clear(&err);
    cr_assert_eq(dfl_table_set_double(t, "l1", 0.5, &err), DFL_E_INTERNAL);
    cr_expect_eq(err.code, DFL_E_INTERNAL);
    cr_expect(strstr(err.msg, "table") != NULL, "%s", err.msg);
    cr_expect(strstr(err.msg, "l1") != NULL, "%s", err.msg);
    /* a NULL err drops the message, not the status */
    cr_expect_eq(dfl_table_set_int(t, "n", 1, NULL), DFL_E_INTERNAL);
    cr_expect_eq(dfl_table_set_string(t, "s", "x", NULL), DFL_E_INTERNAL);
    /* the table is still usable */
    cr_expect_eq(dfl_table_rows(t), 0);
    cr_assert_eq(dfl_table_row(t, &err), DFL_OK);
    cr_assert_eq(dfl_table_set_string(t, "s", "x", &err), DFL_OK);
    cr_expect_str_eq(dfl_table_get(t, 0, "s"), "x");
    dfl_table_free(t);
}

Test(table, setting_a_cell_again_replaces_it)
{
    dfl_table *t = dfl_table_new();
    cr_assert_eq(dfl_table_row(t, NULL), DFL_OK);
    cr_assert_eq(dfl_table_set_int(t, "n", 1, NULL), DFL_OK);
    cr_assert_eq(dfl_table_set_int(t, "n", 2, NULL), DFL_OK);
    cr_expect_eq(dfl_table_cols(t), 1);
    cr_expect_str_eq(dfl_table_get(t, 0, "n"), "2");
    dfl_table_free(t);
}

/* Shortest form: fewer digits never read back, the printed ones always do. */
static void check_shortest(double v)
{
    char buf[64], shorter[64];
    dfl_table_format_double(v, buf, sizeof buf);
    cr_assert_eq(strtod(buf, NULL), v, "%s does not read back to %.17g", buf, v);
    shorter[0] = '\0';
    for (int prec = 1; prec <= 17; prec++) {
        char t[64];
        snprintf(t, sizeof t, "%.*g", prec, v);
        if (strtod(t, NULL) == v && (!shorter[0] || strlen(t) < strlen(shorter))) strcpy(shorter, t);
    }
    cr_assert_str_eq(buf, shorter, "%.17g: got %s, shortest is %s", v, buf, shorter);
}

Test(table, doubles_print_in_the_shortest_form_that_reads_back)
{
    char buf[64];
    cr_expect_str_eq(dfl_table_format_double(0.1, buf, sizeof buf), "0.1");
    cr_expect_str_eq(dfl_table_format_double(1.0 / 3.0, buf, sizeof buf), "0.3333333333333333");
    cr_expect_str_eq(dfl_table_format_double(0.1 + 0.2, buf, sizeof buf), "0.30000000000000004");
    cr_expect_str_eq(dfl_table_format_double(1e300, buf, sizeof buf), "1e+300");
    cr_expect_str_eq(dfl_table_format_double(-0.0, buf, sizeof buf), "-0");
    cr_expect_str_eq(dfl_table_format_double(5e-324, buf, sizeof buf), "5e-324");
    cr_expect_str_eq(dfl_table_format_double(10.0, buf, sizeof buf), "10");
    cr_expect_str_eq(dfl_table_format_double(1e16, buf, sizeof buf), "1e+16");
    cr_expect_str_eq(dfl_table_format_double(123456.0, buf, sizeof buf), "123456");
    uint64_t r = 12;
    for (int i = 0; i < 20000; i++) {
        double v = dfl_rng_splitmix(&r, -0.5, 0.5) * pow(10.0, (double)(i % 40 - 20));
        check_shortest(v);
        check_shortest(floor(v)); /* integers: plain or exponent form */
    }
}

static char *read_all(const char *path)
{
    static char buf[4096];
    FILE *fp = fopen(path, "rb");
    size_t n = fp ? fread(buf, 1, sizeof buf - 1, fp) : 0;
    if (fp) fclose(fp);
    buf[n] = '\0';
    return buf;
}

/* Quoted newlines stay inside their record; a second call adds nothing. */
Test(table, csv_prepend_adds_leading_columns_once)
{
    char path[] = "/tmp/dflab-prep-XXXXXX";
    int fd = mkstemp(path);
    cr_assert(fd >= 0);
    const char *text = "a,b\n1,\"x\ny\"\n2,\"q,\"\"r\"\n";
    cr_assert_eq(write(fd, text, strlen(text)), (ssize_t)strlen(text));
    close(fd);
    const char *cols[] = {"point", "study.p"}, *vals[] = {"3", "2,5"};
    dfl_err err;
    cr_assert_eq(dfl_table_csv_prepend(path, 2, cols, vals, &err), DFL_OK);
    const char *want = "point,study.p,a,b\n3,\"2,5\",1,\"x\ny\"\n3,\"2,5\",2,\"q,\"\"r\"\n";
    cr_expect_str_eq(read_all(path), want);
    cr_assert_eq(dfl_table_csv_prepend(path, 2, cols, vals, &err), DFL_OK);
    cr_expect_str_eq(read_all(path), want);
    remove(path);
    cr_expect_eq(dfl_table_csv_prepend(path, 2, cols, vals, &err), DFL_E_IO);
    cr_expect(strstr(err.msg, path) != NULL);
}

/* What dfl_table_write_csv writes, dfl_table_append_csv reads back cell for
 * cell: quotes, commas and newlines inside cells, empty cells absent; a
 * second file adds rows under the same columns; a missing file is
 * DFL_E_IO naming it. */
Test(table, append_csv_reads_back_what_write_csv_wrote)
{
    dfl_table *t = dfl_table_new();
    dfl_err err;
    static const char *const cells[3][3] = {
        {"1", "x\ny", "q,\"r\""}, {"", "plain", ""}, {"-0.5", "", "\"\""}};
    for (int i = 0; i < 3; i++) {
        cr_assert_eq(dfl_table_row(t, &err), DFL_OK);
        static const char *const cols[3] = {"a", "b", "c"};
        for (int j = 0; j < 3; j++)
            if (cells[i][j][0]) dfl_table_set_string(t, cols[j], cells[i][j], &err);
    }
    char path[] = "/tmp/dflab-tread-XXXXXX";
    int fd = mkstemp(path);
    cr_assert(fd >= 0);
    close(fd);
    cr_assert_eq(dfl_table_write_csv(t, path, &err), DFL_OK);
    dfl_table *r = dfl_table_new();
    cr_assert_eq(dfl_table_append_csv(r, path, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_table_append_csv(r, path, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_table_cols(r), 3);
    cr_assert_eq(dfl_table_rows(r), 6);
    for (size_t i = 0; i < 6; i++)
        for (int j = 0; j < 3; j++) {
            static const char *const cols[3] = {"a", "b", "c"};
            cr_expect_str_eq(dfl_table_get(r, i, cols[j]), cells[i % 3][j], "row %zu col %s", i,
                             cols[j]);
        }
    remove(path);
    cr_expect_eq(dfl_table_append_csv(r, path, &err), DFL_E_IO);
    cr_expect(strstr(err.msg, path) != NULL);
    dfl_table_free(r);
    dfl_table_free(t);
}
