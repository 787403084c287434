/* harness/nonfinite: the exit-status side of the non-finite rule, on CSV
 * tables written by hand (which column, row, point and count the message
 * names; allow per point), and through the real binary: allowed, the run
 * exits 0 with +inf metrics and the exact count. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/nonfinite.h"
#include "util/e2e_util.h"

Test(nonfinite, scan_names_table_row_column_count)
{
    char d[512], p[1024];
    e2e_tmpdir(d, sizeof d);
    e2e_write(d, "a.csv", "point,name,l1,nonfinite\n0,\"x, \"\"y\"\"\",0.5,0\n1,z,inf,12\n", p,
              sizeof p);
    e2e_write(d, "b.csv", "point,band_nonfinite\n0,0\n", p, sizeof p);
    e2e_write(d, "notes.txt", "nonfinite\n7\n", p, sizeof p);
    const bool none[2] = {false, false}, second[2] = {false, true};
    dfl_err err;
    cr_assert_eq(dfl_nonfinite_check(d, none, 2, &err), DFL_E_NUMERIC);
    cr_expect(strstr(err.msg, "a.csv: row 2 (point 1): nonfinite: 12 non-finite points") != NULL,
              "%s", err.msg);
    cr_expect(strstr(err.msg, "allow_nonfinite") != NULL, "%s", err.msg);
    /* point 1 allows them: nothing else holds one (notes.txt is no table) */
    cr_expect_eq(dfl_nonfinite_check(d, second, 2, &err), DFL_OK, "%s", err.msg);
    /* any column whose name holds "nonfinite", one point */
    e2e_write(d, "b.csv", "point,band_nonfinite,x\n0,1,\n", p, sizeof p);
    cr_assert_eq(dfl_nonfinite_check(d, second, 2, &err), DFL_E_NUMERIC);
    cr_expect(strstr(err.msg, "b.csv: row 1 (point 0): band_nonfinite: 1 non-finite point ") !=
                  NULL,
              "%s", err.msg);
    /* no point column: point 0 */
    e2e_write(d, "b.csv", "nonfinite_nodes\n3\n", p, sizeof p);
    cr_assert_eq(dfl_nonfinite_check(d, second, 2, &err), DFL_E_NUMERIC);
    cr_expect(strstr(err.msg, "(point 0): nonfinite_nodes: 3") != NULL, "%s", err.msg);
    e2e_rmtree(d);
    cr_expect_eq(dfl_nonfinite_check("/nonexistent/dflab", none, 2, &err), DFL_E_IO);
}

/* A double proxy with footpoints moved 1e300 (the decode's |x - p|^2
 * overflows; half storage would clamp, proxy/store.h): every one of the 9^3 = 729
 * evaluation points decodes to a non-finite value.  Allowed, the run exits 0
 * and the table holds +inf metrics and the count; not allowed, exit 1 with
 * the same table written. */
#define NF_INI                                                                                  \
    "[study]\nname = hvb25_accuracy\nband = 0.05\n%s"                                          \
    "[shape]\nkind = sphere\ncenter = 0 0 0\nradius = 0.5\n"                                   \
    "[field]\nkind = proxy\norder = 1\nres = 8\ninput = sdf\nstorage = double\nseed = 1\n"       \
    "noise = 1e300\n[eval]\nn = 9\n"

Test(nonfinite, allowed_run_exits_0_with_inf_metrics, .timeout = 120)
{
    char d[512], p[1024], ini[1024], args[2048], csv[1200];
    e2e_tmpdir(d, sizeof d);
    snprintf(ini, sizeof ini, NF_INI, "allow_nonfinite = true\n");
    e2e_write(d, "a.ini", ini, p, sizeof p);
    snprintf(args, sizeof args, "run %s --out %s/o --quiet", p, d);
    cr_assert_eq(e2e_dflab(d, args), 0, "%s", e2e_err_text(d));
    snprintf(csv, sizeof csv, "%s/o/hvb25_accuracy.csv", d);
    cr_expect_eq(e2e_csv_get(csv, 0, "count"), 729);
    cr_expect_eq(e2e_csv_get(csv, 0, "nonfinite"), 729);
    cr_expect(isinf(e2e_csv_get(csv, 0, "linf")) && isinf(e2e_csv_get(csv, 0, "l1")));
    /* the band count includes the points whose reference is in the band */
    const double cb = e2e_csv_get(csv, 0, "count_band");
    cr_expect(cb > 0 && e2e_csv_get(csv, 0, "nonfinite_band") == cb);
    snprintf(ini, sizeof ini, NF_INI, "");
    e2e_write(d, "b.ini", ini, p, sizeof p);
    snprintf(args, sizeof args, "run %s --out %s/q --quiet", p, d);
    cr_expect_eq(e2e_dflab(d, args), 1);
    char *msg = e2e_err_text(d);
    cr_expect(msg && strstr(msg, "row 1 (point 0): nonfinite: 729 non-finite points"), "%s", msg);
    free(msg);
    snprintf(csv, sizeof csv, "%s/q/hvb25_accuracy.csv", d);
    cr_expect_eq(e2e_csv_get(csv, 0, "nonfinite"), 729);
    e2e_rmtree(d);
}

/* The report marks a row holding an error of +inf in red (scripts/dflio.py
 * md_table), and only that row; nonfinite_count reads the count columns. */
Test(nonfinite, report_marks_the_row_red, .timeout = 60)
{
    char d[512];
    e2e_tmpdir(d, sizeof d);
    char *out = NULL;
    const int rc = e2e_python_run(
        d, &out,
        "-c \"import sys; sys.path.insert(0, 'scripts'); import dflio\n"
        "t = dflio.md_table(['a', 'linf'], [['x', 0.5], ['y', float('inf')], ['z', 'inf']])\n"
        "l = t.split(chr(10))\n"
        "assert 'color:red' not in l[2], l[2]\n"
        "assert l[3].count('color:red') == 2 and l[4].count('color:red') == 2, t\n"
        "assert dflio.nonfinite_count({'nonfinite': '0', 'band_nonfinite': '3', 'l1': '9'}) == 3\n"
        "assert dflio.nonfinite_count({'l1': 'inf'}) == 0\n"
        "print('ok')\"");
    cr_expect_eq(rc, 0, "%s", out ? out : "");
    cr_expect(out && strstr(out, "ok"), "%s", out ? out : "");
    free(out);
    e2e_rmtree(d);
}
