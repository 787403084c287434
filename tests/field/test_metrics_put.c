/* field/metrics dfl_metrics_put: the metric columns, their order and their values
 * as the table formats doubles (%.17g). */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

#include "field/metrics.h"
#include "io/table.h"

Test(metrics_put, columns_in_order_with_suffix)
{
    dfl_table *t = dfl_table_new();
    cr_assert_not_null(t);
    const dfl_metrics m = {.count = 12,
                           .l1 = 0.5,
                           .mse = 0.25,
                           .rms = 0.125,
                           .linf = 2.0,
                           .gdef_mean = 0.1,
                           .gdef_max = 3.5};
    dfl_err err = {0};
    cr_assert_eq(dfl_table_row(t, &err), DFL_OK);
    cr_assert_eq(dfl_metrics_put(t, "", &m, &err), DFL_OK);
    cr_assert_eq(dfl_metrics_put(t, "_band", &m, &err), DFL_OK);
    const char *names[] = {"count", "l1", "mse", "rms", "linf", "graddefect_mean",
                           "graddefect_max"};
    const char *values[] = {"12", "0.5", "0.25", "0.125", "2", "0.10000000000000001", "3.5"};
    cr_assert_eq(dfl_table_cols(t), 14);
    for (size_t j = 0; j < 7; j++) {
        char band[64];
        snprintf(band, sizeof band, "%s_band", names[j]);
        cr_expect_str_eq(dfl_table_col_name(t, j), names[j]);
        cr_expect_str_eq(dfl_table_col_name(t, 7 + j), band);
        cr_expect_str_eq(dfl_table_get(t, 0, names[j]), values[j], "%s", names[j]);
        cr_expect_str_eq(dfl_table_get(t, 0, band), values[j], "%s", band);
    }
    dfl_table_free(t);
}
