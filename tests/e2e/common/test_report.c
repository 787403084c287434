/* scripts/report.py finds a paper's sections by folder, gives a study
 * without a section its CSV as a table, and shows a broken section or
 * folder as a failure (check_report.py builds the trees and checks). */
#include <criterion/criterion.h>
#include <stdlib.h>

#include "util/e2e_util.h"

Test(e2e_report, sections_by_folder_generic_table_and_failures, .timeout = 60)
{
    char dir[256], *py;
    e2e_tmpdir(dir, sizeof dir);
    cr_assert(dir[0], "no temporary directory");
    const int rc = e2e_python_run(dir, &py, "tests/e2e/common/check_report.py %s", dir);
    cr_expect_eq(rc, 0, "%s", py);
    free(py);
    cr_expect_eq(e2e_rmtree(dir), 0);
}

/* The reading of hvb25's "L2": printed intervals and the bounds of MSE, RMS
 * and norm/N, on hand-derived cells (check_l2_reading.py). */
Test(e2e_report, hvb25_l2_reading_bounds, .timeout = 60)
{
    char dir[256], *py;
    e2e_tmpdir(dir, sizeof dir);
    cr_assert(dir[0], "no temporary directory");
    const int rc = e2e_python_run(dir, &py, "tests/e2e/common/check_l2_reading.py");
    cr_expect_eq(rc, 0, "%s", py);
    free(py);
    cr_expect_eq(e2e_rmtree(dir), 0);
}

/* The report's figure rules (axis labels and colour bars on field images,
 * no label over a neighbouring panel, legible legends), each broken once
 * and kept once (check_figures.py); report.py refuses to save a figure that
 * breaks one. */
Test(e2e_report, figure_rules_fail_when_broken, .timeout = 60)
{
    char dir[256], *py;
    e2e_tmpdir(dir, sizeof dir);
    cr_assert(dir[0], "no temporary directory");
    const int rc = e2e_python_run(dir, &py, "tests/e2e/common/check_figures.py");
    cr_expect_eq(rc, 0, "%s", py);
    free(py);
    cr_expect_eq(e2e_rmtree(dir), 0);
}
