/* Helpers for end-to-end tests that run the dflab binary.
 *
 * DFL_DFLAB names the binary (the Makefile sets it; default build/dflab);
 * tests run from the repository root. */
#ifndef DFL_TESTS_E2E_UTIL_H
#define DFL_TESTS_E2E_UTIL_H

#include <stddef.h>

/* A fresh empty directory under /tmp; path into buf. */
void e2e_tmpdir(char *buf, size_t size);
/* Writes text to dir/name; returns the path in buf. */
const char *e2e_write(const char *dir, const char *name, const char *text, char *buf, size_t size);
/* Runs `dflab <args>` with stdout and stderr captured into dir/out.txt and
 * dir/err.txt; returns the exit status (or -1). */
int e2e_dflab(const char *dir, const char *args);
/* Reads a whole file into a malloc'ed string (NULL if unreadable). */
char *e2e_slurp(const char *path);
/* Number of directory entries (excluding . and ..); -1 if dir is absent. */
int e2e_count_entries(const char *dir);
/* Path of the python interpreter with numpy/vtk. */
const char *e2e_python(void);
/* Value of column col in data row `row` (0-based) of a CSV file, as double
 * (NAN when absent). */
double e2e_csv_get(const char *path, size_t row, const char *col);
/* Number of data rows of a CSV file. */
long e2e_csv_rows(const char *path);

#endif
