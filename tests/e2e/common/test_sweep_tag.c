/* The sweep tag has one rule on both sides: the runner's dfl_study_tag
 * (experiments/harness/experiment.h) and the report's dflio.sweep_tag /
 * sweep_name / sweep_split (scripts/dflio.py).  Checked on chosen (point,
 * npoints) pairs, including the widths past three digits, and on the files a
 * real one-point and two-point run write. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/experiment.h"
#include "util/e2e_util.h"

static const size_t pairs[][2] = {{0, 1},     {0, 2},      {1, 2},          {7, 12}, {99, 100},
                                  {999, 1000}, {1000, 1001}, {12345, 20000}, {0, 0}};

Test(e2e_sweep_tag, python_rule_equals_c_rule)
{
    char dir[256], args[1024], want[4096];
    e2e_tmpdir(dir, sizeof dir);
    size_t k = 0, w = 0;
    for (size_t i = 0; i < sizeof pairs / sizeof pairs[0]; i++) {
        const size_t pt = pairs[i][0], np = pairs[i][1];
        char tag[32], split[64];
        dfl_study_tag(pt, np, tag, sizeof tag);
        if (np > 1) snprintf(split, sizeof split, "('field', %zu, 'vti')", pt);
        else snprintf(split, sizeof split, "('field', None, 'vti')");
        k += (size_t)snprintf(args + k, sizeof args - k, " %zu,%zu", pt, np);
        w += (size_t)snprintf(want + w, sizeof want - w, "'%s' field%s.vti %s\n", tag, tag, split);
    }
    /* names the runner never writes are no tags */
    w += (size_t)snprintf(want + w, sizeof want - w,
                          "('field_pt7', None, 'vti')\n('field_pt0012', None, 'vti')\n");
    cr_assert(k < sizeof args && w < sizeof want);
    char *py;
    const int rc = e2e_python_run(dir, &py,
                                  "-c \"import sys; sys.path.insert(0, 'scripts'); import dflio\n"
                                  "for a in sys.argv[1:]:\n"
                                  "    if ',' not in a:\n"
                                  "        print(dflio.sweep_split(a)); continue\n"
                                  "    i, n = map(int, a.split(','))\n"
                                  "    f = dflio.sweep_name('field', i, n, 'vti')\n"
                                  "    print(repr(dflio.sweep_tag(i, n)), f, dflio.sweep_split(f))\""
                                  "%s field_pt7.vti field_pt0012.vti",
                                  args);
    cr_assert_eq(rc, 0, "python failed: %s", py);
    cr_expect_str_eq(py, want);
    free(py);
    cr_expect_eq(e2e_rmtree(dir), 0);
}

/* the report's names are exactly the files of a run, with one and two points */
Test(e2e_sweep_tag, run_files_follow_the_python_rule, .timeout = 60)
{
    const char *sets[2] = {"--set grid.n=16", "--set grid.n=16,24"};
    for (int np = 1; np <= 2; np++) {
        char out[512], dir[512], *py;
        e2e_run_ok("configs/smoke/smoke.ini", sets[np - 1], out, sizeof out);
        snprintf(dir, sizeof dir, "%s", out);
        *strrchr(dir, '/') = '\0'; /* out is <dir>/res */
        const int rc = e2e_python_run(dir, &py,
                                      "tests/e2e/common/check_sweep_names.py %s %d "
                                      "field.vti,field.exr smoke.csv config.ini manifest.json",
                                      out, np);
        cr_expect_eq(rc, 0, "%d point(s): %s", np, py);
        free(py);
        cr_expect_eq(e2e_rmtree(dir), 0);
    }
}
