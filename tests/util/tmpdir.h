/* Temporary directories for tests (unit and end-to-end alike).
 *
 *   tmpdir_new(dir, size)                       a fresh empty directory under /tmp
 *   tmpdir_file(dir, dsize, name, path, psize)  tmpdir_new, and the path of name in it
 *   tmpdir_write(dir, name, text, path, psize)  writes text to <dir>/<name> (parents made)
 *   tmpdir_count(dir)                           its entries other than . and ..
 *   tmpdir_remove(dir)                          removes dir and everything below it
 *   tmpdir_expect_io_error(st, err, path, dir, left)
 *                                               a writer's failure left `left` entries
 *
 * Failures to create a directory are fatal Criterion assertions; the other
 * functions report through their return values and never assert, so they
 * can check what a failed call left behind.
 */
#ifndef DFL_TESTS_TMPDIR_H
#define DFL_TESTS_TMPDIR_H

#include <stddef.h>

#include "core/status.h"

/* Creates /tmp/dflab-test-XXXXXX and writes its path into dir (size >= 24);
 * asserts (fatal) that it exists. */
void tmpdir_new(char *dir, size_t dsize);
/* tmpdir_new(dir, dsize), then path = "<dir>/<name>" (asserted to fit). */
void tmpdir_file(char *dir, size_t dsize, const char *name, char *path, size_t psize);
/* Writes text to <dir>/<name>, making missing directories of name first;
 * the path goes to path (NULL: not wanted).  Asserts (fatal) success.
 * Returns path. */
const char *tmpdir_write(const char *dir, const char *name, const char *text, char *path,
                         size_t psize);
/* Number of entries of dir other than . and ..; -1 if dir cannot be opened
 * (e.g. it does not exist). */
int tmpdir_count(const char *dir);
/* Removes dir recursively (directories are not followed through links);
 * a missing dir is not an error. */
void tmpdir_remove(const char *dir);
/* For tests of file writers: asserts (fatal) st == DFL_E_IO, err->code ==
 * DFL_E_IO, a message naming path, and exactly `left` entries in dir (no
 * temporary file behind). */
void tmpdir_expect_io_error(dfl_status st, const dfl_err *err, const char *path,
                            const char *dir, int left);

#endif
