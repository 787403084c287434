/* Helpers for end-to-end tests that run the dflab binary.
 *
 * DFL_DFLAB names the binary (the Makefile sets it; default build/dflab);
 * tests run from the repository root. */
#ifndef DFL_TESTS_E2E_UTIL_H
#define DFL_TESTS_E2E_UTIL_H

#include <stddef.h>

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
 * (NAN when absent). */
double e2e_csv_get(const char *path, size_t row, const char *col);
/* Number of data rows of a CSV file. */
long e2e_csv_rows(const char *path);
/* Text of column col in data row `row` (0-based) of a CSV file without
 * quoting (malloc'ed, caller frees; NULL when the file, column or row is
 * absent). */
char *e2e_csv_cell(const char *path, long row, const char *col);

/* Contents of dir/err.txt as left by e2e_dflab (malloc'ed; NULL if absent). */
char *e2e_err_text(const char *dir);
/* Runs `dflab run <cfg> --out <dir>/res --quiet <extra>` (extra may be NULL)
 * in dir; out receives <dir>/res.  Returns the exit status (see e2e_dflab). */
int e2e_run_cfg(const char *dir, const char *cfg, const char *extra, char *out, size_t size);
/* e2e_run_cfg in a fresh temporary directory; asserts (Criterion, fatal)
 * exit status 0, reporting stderr.  out receives the results directory. */
void e2e_run_ok(const char *cfg, const char *extra, char *out, size_t size);
/* e2e_run_cfg in a fresh temporary directory for input that must be
 * rejected; expects (Criterion, non-fatal) exit status 2, `want` in stderr
 * and no results directory left behind. */
void e2e_run_expect_fail(const char *cfg, const char *extra, const char *want);
#endif
