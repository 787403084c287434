/* field/metrics dfl_metrics_put: the metric columns, their order and their values
 * as the table formats doubles (shortest round-trip form). */
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
                           .gdef_max = 3.5,
                           .nonfinite = 4};
    dfl_err err = {0};
    cr_assert_eq(dfl_table_row(t, &err), DFL_OK);
    cr_assert_eq(dfl_metrics_put(t, "", &m, &err), DFL_OK);
    cr_assert_eq(dfl_metrics_put(t, "_band", &m, &err), DFL_OK);
    const char *names[] = {"count", "l1", "mse", "rms", "linf", "graddefect_mean",
                           "graddefect_max", "nonfinite"};
    const char *values[] = {"12", "0.5", "0.25", "0.125", "2", "0.1", "3.5", "4"};
    cr_assert_eq(dfl_table_cols(t), 16);
    for (size_t j = 0; j < 8; j++) {
        char band[64];
        snprintf(band, sizeof band, "%s_band", names[j]);
        cr_expect_str_eq(dfl_table_col_name(t, j), names[j]);
        cr_expect_str_eq(dfl_table_col_name(t, 8 + j), band);
        cr_expect_str_eq(dfl_table_get(t, 0, names[j]), values[j], "%s", names[j]);
        cr_expect_str_eq(dfl_table_get(t, 0, band), values[j], "%s", band);
    }
    dfl_table_free(t);
}

/* dfl_metrics_put_gradstat: three columns with the suffix, in order, the
 * values in the shortest round-trip form, and the table's error when there is no row. */
Test(metrics_put, gradstat_columns)
{
    dfl_table *t = dfl_table_new();
    cr_assert_not_null(t);
    const dfl_gradstat g = {.count = 9, .min = 0.25, .mean = 0.1, .max = 7.0};
    dfl_err err = {0};
    cr_assert_eq(dfl_table_row(t, &err), DFL_OK);
    cr_assert_eq(dfl_metrics_put_gradstat(t, "_s1_band", &g, &err), DFL_OK);
    cr_assert_eq(dfl_metrics_put_gradstat(t, "", &g, &err), DFL_OK);
    const char *cols[6] = {"grad_min_s1_band", "grad_mean_s1_band", "grad_max_s1_band",
                           "grad_min", "grad_mean", "grad_max"};
    const char *vals[3] = {"0.25", "0.1", "7"};
    cr_assert_eq(dfl_table_cols(t), 6);
    for (size_t j = 0; j < 6; j++) {
        cr_expect_str_eq(dfl_table_col_name(t, j), cols[j]);
        cr_expect_str_eq(dfl_table_get(t, 0, cols[j]), vals[j % 3], "%s", cols[j]);
    }
    dfl_table_free(t);
    t = dfl_table_new();
    cr_expect_eq(dfl_metrics_put_gradstat(t, "_x", &g, &err), DFL_E_INTERNAL);
    cr_expect(strstr(err.msg, "grad_min_x") != NULL, "%s", err.msg);
    dfl_table_free(t);
}
