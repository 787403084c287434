/* Opening and reading files that must be regular files (records dflab
 * wrote, included configs): a FIFO, a device, a socket or a directory in
 * their place is refused at once instead of blocking or reading forever.
 *
 * Function index
 *   dfl_rfile_open   a regular file for reading, as a FILE
 *   dfl_rfile_read   a whole regular file of at most max bytes
 *
 * The file is opened with O_NONBLOCK (so opening a FIFO with no writer
 * returns at once) and checked with fstat on the open descriptor (so the
 * check and the read are about the same file); O_NONBLOCK is then cleared.
 */
#ifndef DFL_IO_RFILE_H
#define DFL_IO_RFILE_H

#include <stddef.h>
#include <stdio.h>

#include "core/status.h"

/* *fp open for reading (caller fcloses).  DFL_E_INPUT "PATH: cannot open
 * WHAT: <strerror>" (what: "config", ...; "" or NULL: "PATH: cannot open:
 * ...") or "PATH: not a regular file (a FIFO|a directory|a device|a
 * socket)".  *fp is NULL on failure. */
dfl_status dfl_rfile_open(const char *path, const char *what, FILE **fp, dfl_err *err);

/* The bytes of the regular file path plus a terminating NUL, malloc'ed
 * (caller frees) into *text, the byte count into *len (may be NULL).
 * Errors as dfl_rfile_open, plus DFL_E_INPUT "PATH: larger than MAX bytes"
 * and DFL_E_IO on a read error, DFL_E_NOMEM; *text is NULL then. */
dfl_status dfl_rfile_read(const char *path, const char *what, size_t max, char **text,
                          size_t *len, dfl_err *err);

#endif
