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
    cr_assert_eq(dfl_table_prefix_string(t, "grid.n", "16"), DFL_OK);
    cr_assert_eq(dfl_table_row(t), DFL_OK);
    dfl_table_set_double(t, "l1", 0.1);
    dfl_table_set_string(t, "name", "a,b");
    dfl_table_prefix_clear(t);
    dfl_table_prefix_string(t, "grid.n", "32");
    dfl_table_row(t);
    dfl_table_set_int(t, "count", 7);
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
