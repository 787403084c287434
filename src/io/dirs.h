/* Whole directories: staging names owned by a process, removal, swapping,
 * linking a file into another directory.
 *
 * Function index
 *   dfl_dir_owned_name      "<base>.<kind>.<host>.<pid>" of this process
 *   dfl_dir_owner_dead      whether such a name's process is gone
 *   dfl_dir_remove_tree     rm -r
 *   dfl_dir_replace         put a finished directory in place of another
 *   dfl_dir_link_or_copy    a file's bytes under a new name (a copy)
 *   dfl_dir_check_writable  whether a directory (or its nearest existing
 *                           ancestor) accepts new entries
 *   dfl_file_read_all       a whole (small) file as a string
 *   dfl_dir_check_replaceable  whether a folder may be replaced by a run
 *
 * Staging directories and files carry the host and process id of their
 * writer, so a later run can tell a dead run's leftovers (same host, no
 * such process) from a live one's, also when several hosts share the
 * results folder (a Slurm array): other hosts' leftovers are left alone.
 */
#ifndef DFL_IO_DIRS_H
#define DFL_IO_DIRS_H

#include <stdbool.h>
#include <stddef.h>

#include "core/status.h"

/* "<base>.<kind>.<host>.<pid>" into buf; returns buf. */
const char *dfl_dir_owned_name(const char *base, const char *kind, char *buf, size_t size);
/* True when name ends in ".<kind>.<host>.<pid>" with this host and a pid
 * that no longer runs (and is not this process). */
bool dfl_dir_owner_dead(const char *name, const char *kind);
/* Removes path and everything below it; a missing path is fine.  Returns
 * DFL_E_IO naming the first entry that could not be removed. */
dfl_status dfl_dir_remove_tree(const char *path, dfl_err *err);
/* Makes the directory fresh appear at dst: an existing dst is moved aside
 * (to "<dst>.old.<host>.<pid>") and removed after fresh took its name.
 * Readers see either the old or the new directory, never a mix. */
dfl_status dfl_dir_replace(const char *fresh, const char *dst, dfl_err *err);
/* A copy of the regular file src at dst (replacing dst through a
 * temporary file): never a hard link, so writing to one file leaves the
 * other as it was.  A reflink (FICLONE) where the file system has it,
 * else the bytes.  DFL_E_INPUT when src is not a regular file, DFL_E_IO
 * naming the file on a read or write failure (no dst is left then). */
dfl_status dfl_dir_link_or_copy(const char *src, const char *dst, dfl_err *err);
/* DFL_OK when dir exists and is a writable directory, or does not exist
 * and its nearest existing ancestor is a writable directory; else
 * DFL_E_INPUT "what DIR: not writable (...)". */
dfl_status dfl_dir_check_writable(const char *dir, const char *what, dfl_err *err);

/* DFL_OK when dir does not exist, is empty, or holds a file named marker
 * (a run's manifest.json: dflab made it); else DFL_E_INPUT "what DIR:
 * exists and is not ...", so that `--out results` cannot wipe a folder of
 * other things. */
dfl_status dfl_dir_check_replaceable(const char *dir, const char *marker, const char *what,
                                     dfl_err *err);

/* The bytes of path plus a terminating NUL, malloc'ed (caller frees);
 * *len (may be NULL) receives the byte count.  NULL when the file cannot
 * be read or memory runs out. */
char *dfl_file_read_all(const char *path, size_t *len);

#endif
