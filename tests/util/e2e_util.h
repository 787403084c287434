/* Helpers for end-to-end tests that run the dflab binary.
 *
 * DFL_DFLAB names the binary (the Makefile sets it; default build/dflab);
 * tests run from the repository root. */
#ifndef DFL_TESTS_E2E_UTIL_H
#define DFL_TESTS_E2E_UTIL_H

#include <math.h>
#include <stddef.h>

#include "geom/bspline.h"

/* tmpdir_new (util/tmpdir.h): a fresh empty directory under /tmp, path into
 * buf; fatal assertion when it cannot be made. */
void e2e_tmpdir(char *buf, size_t size);
/* tmpdir_write: writes text to dir/name (fatal assertion on failure);
 * returns the path in buf. */
const char *e2e_write(const char *dir, const char *name, const char *text, char *buf, size_t size);
/* Runs `dflab <args>` with stdout and stderr captured into dir/out.txt and
 * dir/err.txt; returns the exit status (or -1). */
int e2e_dflab(const char *dir, const char *args);
/* Reads a whole file into a malloc'ed string (NULL if unreadable). */
char *e2e_slurp(const char *path);
/* tmpdir_count: number of directory entries (excluding . and ..); -1 if
 * dir is absent. */
int e2e_count_entries(const char *dir);
/* Path of the python interpreter with numpy/vtk. */
const char *e2e_python(void);
/* Value of column col in data row `row` (0-based) of a CSV file, as double
 * (NAN when the cell is absent or empty). */
double e2e_csv_get(const char *path, size_t row, const char *col);
/* Number of data rows of a CSV file (-1 when it cannot be read). */
long e2e_csv_rows(const char *path);
/* Text of column col in data row `row` (0-based) of a CSV file without
 * quoting (malloc'ed, caller frees; NULL when the file, column or row is
 * absent, "" for an empty cell). */
char *e2e_csv_cell(const char *path, long row, const char *col);

/* Removes a directory made by e2e_tmpdir and everything in it; 0 on
 * success, -1 on failure or for any other path (nothing is removed). */
int e2e_rmtree(const char *dir);
/* Runs `<python> <args>` (args printf-style; tests run from the repository
 * root) with stdout and stderr captured in dir/py.txt.  Returns the exit
 * status (-1 if the interpreter did not run); *out (when out is not NULL)
 * receives the captured text (malloc'ed, caller frees; "" when none). */
int e2e_python_run(const char *dir, char **out, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Runs `<python> <script> <dflab binary> <extra>` (extra may be NULL) in a
 * fresh directory and expects (non-fatal) exit status 0, reporting the
 * script's output under `what` otherwise: for checks kept as scripts
 * (tests/cli/bad_input_table.py, scripts/check_threads.py). */
void e2e_expect_binary_script(const char *script, const char *extra, const char *what);

/* A .vti as VTK's own reader sees it (through tests/e2e/common/vtk_dump.py). */
typedef struct e2e_vti {
    int dims[3];
    double origin[3], spacing[3];
    size_t npoints;   /* dims[0] dims[1] dims[2], x fastest */
    int narrays;
    double *pts;      /* pts[3 i + k]: coordinate k of point i (VTK's GetPoint) */
    double *val;      /* val[i narrays + a]: array a at point i */
} e2e_vti;
/* Reads the scalar point arrays names[0..nnames-1] of path, exactly (17
 * digits each way), using dir for the dump.  Asserts (Criterion, fatal) that
 * the file reads and has every array.  Free with e2e_vti_free. */
void e2e_vti_read(const char *dir, const char *path, const char *const *names, int nnames,
                  e2e_vti *v);
void e2e_vti_free(e2e_vti *v);
/* Larger / smaller of a and b, NaN if either is NaN (as numpy's max and min:
 * a NaN in the data then fails every comparison that follows). */
static inline double e2e_max(double a, double b)
{
    return isnan(a) || isnan(b) ? NAN : a > b ? a : b;
}
static inline double e2e_min(double a, double b)
{
    return isnan(a) || isnan(b) ? NAN : a < b ? a : b;
}

/* Contents of dir/err.txt as left by e2e_dflab (malloc'ed; NULL if absent). */
char *e2e_err_text(const char *dir);
/* Runs `dflab run <cfg> --out <dir>/res --quiet <extra>` (extra may be NULL)
 * in dir; out receives <dir>/res.  Returns the exit status (see e2e_dflab). */
int e2e_run_cfg(const char *dir, const char *cfg, const char *extra, char *out, size_t size);
/* e2e_run_cfg in a fresh temporary directory; asserts (Criterion, fatal)
 * exit status 0, reporting stderr.  out receives the results directory. */
void e2e_run_ok(const char *cfg, const char *extra, char *out, size_t size);
/* e2e_run_ok, then the path of the study's table <out>/<study>.csv into csv;
 * asserts (fatal) that it has nrows data rows unless nrows < 0.  Returns the
 * number of data rows. */
long e2e_run_table(const char *cfg, const char *extra, const char *study, long nrows, char *out,
                   size_t nout, char *csv, size_t ncsv);
/* A study run from config text, as most end-to-end tests start: the
 * directory the config is written to, the config's path, the results
 * directory and the study's table. */
typedef struct e2e_table {
    char dir[256], cfg[512], out[512], csv[700];
} e2e_table;
/* Writes ini as t->dir/name (a fresh t->dir when it is empty: zero t
 * first; later calls write beside the first config) and runs it with
 * e2e_run_table (nrows < 0: any number of rows).  Returns the rows. */
long e2e_ini_table(e2e_table *t, const char *name, const char *ini, const char *study,
                   long nrows);
/* The counts every row of an sjp10 fit table (sjp10_3d, sjp10_cells) obeys,
 * as (non-fatal) expectations: 2^dim dofs per base vertex (a vertex's
 * Hermite data) and, for a uniform fit at level k, (2^k)^dim cells on
 * (2^k + 1)^dim base vertices.  Returns k, -1 for an adaptive row. */
int e2e_sjp10_counts(const char *csv, long r, int dim);
/* e2e_run_expect_fail for each row {args, want} of a table of bad input:
 * the run gets `<fixed> <args>` (fixed may be NULL). */
void e2e_expect_bad_runs(const char *cfg, const char *fixed, const char *const rows[][2],
                         size_t n);
/* A config given as text that must be rejected: written to a fresh
 * directory and run; expects (non-fatal) exit status 2, want1 and want2 (NULL:
 * none) in stderr and no results directory left behind. */
void e2e_expect_bad_config(const char *ini_text, const char *want1, const char *want2);
/* e2e_run_cfg in a fresh temporary directory for input that must be
 * rejected; expects (Criterion, non-fatal) exit status 2, `want` in stderr
 * and no results directory left behind. */
void e2e_run_expect_fail(const char *cfg, const char *extra, const char *want);

/* The curve of [sec] in the config file path, built as the studies build it
 * (dfl_curve_from_cfg, cfg/curve_cfg.h); fatal assertions on failure.  The
 * caller frees it with dfl_bspline_free. */
void e2e_load_curve(const char *path, const char *sec, dfl_bspline *c);
#endif
