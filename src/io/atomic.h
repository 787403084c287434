/* Files that appear whole or not at all.
 *
 * dfl_atomic_open creates "<path>.tmp.<pid>" for writing; dfl_atomic_commit
 * closes it, checks for write errors and renames it over path;
 * dfl_atomic_abort closes and removes it.  A reader therefore never sees a
 * half-written output, and a failed run leaves nothing behind.
 */
#ifndef DFL_IO_ATOMIC_H
#define DFL_IO_ATOMIC_H

#include <stdio.h>

#include "core/status.h"

typedef struct dfl_atomic_file {
    FILE *fp;
    char path[4096];
    char tmp[4200];
} dfl_atomic_file;

dfl_status dfl_atomic_open(const char *path, dfl_atomic_file *af, dfl_err *err);
dfl_status dfl_atomic_commit(dfl_atomic_file *af, dfl_err *err);
void dfl_atomic_abort(dfl_atomic_file *af);

/* Temporary name dfl_atomic_open would use for path (for libraries such as
 * OpenEXR that open files themselves). */
void dfl_atomic_tmpname(const char *path, char *buf, size_t size);

/* Creates directory path and its parents (mode 0777 & ~umask). */
dfl_status dfl_mkdir_p(const char *path, dfl_err *err);

/* The status of a failed create or write with errno e: DFL_E_INPUT when
 * the place is the user's choice and cannot hold dflab's files there
 * (EROFS read-only file system, EACCES, EPERM, ENOTDIR, ENAMETOOLONG,
 * ELOOP: exit 2, another folder fixes it), DFL_E_IO otherwise (ENOSPC,
 * EIO, ...: the machine, exit 1).  dfl_atomic_open and dfl_mkdir_p use it. */
dfl_status dfl_io_errno_status(int e);

#endif
