#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/table.h"

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
    cr_expect_str_eq(buf, "grid.n,l1,name,count\n16,0.10000000000000001,\"a,b\",\n32,,,7\n");
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
