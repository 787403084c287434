/* Whole directories: staging names owned by a process, removal, swapping,
 * linking a file into another directory.
 *
 * Function index
 *   dfl_dir_owned_name      "<base>.<kind>.<host>.<pid>" of this process
 *   dfl_dir_owner_dead      whether such a name's process is gone
 *   dfl_dir_remove_tree     rm -r
 *   dfl_dir_replace         put a finished directory in place of another
 *   dfl_dir_restore_stale   put back a dead run's backup of a missing folder
 *   dfl_dir_probe           whether a file can be created in a directory
 *   dfl_dir_check_name      whether a name can be a results folder
 *   dfl_dir_link_or_copy    a file's bytes under a new name (a copy)
 *   dfl_dir_check_writable  whether a directory (or its nearest existing
 *                           ancestor) accepts new entries
 *   dfl_file_read_all       a whole (small) file as a string
 *   dfl_dir_check_replaceable  whether a folder may be replaced by a run
 *   dfl_path_stamp          a file's path as provenance: relative to the
 *                           repository holding it, else absolute
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
/* Makes the directory fresh appear at dst.  An existing dst is swapped
 * with fresh in one renameat2(RENAME_EXCHANGE) and the old folder (now
 * under fresh's name) removed: a kill at any moment leaves either the old
 * or the new folder at dst.  Only when the file system has no exchange
 * (EINVAL, ENOSYS) dst is moved aside to "<dst>.old.<host>.<pid>" and fresh
 * renamed to dst; a kill between the two leaves no dst and the backup,
 * which is never deleted then: dfl_dir_restore_stale puts it back.
 * DFL_E_IO naming dst on failure (the old folder then stays at dst, or
 * the message names where it is). */
dfl_status dfl_dir_replace(const char *fresh, const char *dst, dfl_err *err);
/* When backup is "<dst>.old.<host>.<pid>" of a dead process of this host
 * and dst does not exist: renames backup to dst and returns true (the one
 * copy of a folder whose replacement was cut off).  Else false, nothing
 * touched. */
bool dfl_dir_restore_stale(const char *backup, const char *dst);
/* A copy of the regular file src at dst (replacing dst through a
 * temporary file): never a hard link, so writing to one file leaves the
 * other as it was.  A reflink (FICLONE) where the file system has it,
 * else the bytes.  DFL_E_INPUT when src is not a regular file, DFL_E_IO
 * naming the file on a read or write failure (no dst is left then). */
dfl_status dfl_dir_link_or_copy(const char *src, const char *dst, dfl_err *err);
/* DFL_OK when dir exists and is a writable directory, or does not exist
 * and its nearest existing ancestor is a writable directory; else
 * DFL_E_INPUT "what DIR: not writable (...)".  Probes with dfl_dir_probe,
 * so nothing is left in any directory. */
dfl_status dfl_dir_check_writable(const char *dir, const char *what, dfl_err *err);
/* 0 when a file can be created in the existing directory dir, else the
 * errno of the attempt.  An unnamed O_TMPFILE file where the file system
 * has them (a kill leaves nothing); else a directory
 * "dir/.dflab.probe.<host>.<pid>" made and removed at once, after removing
 * such probes of dead processes of this host. */
int dfl_dir_probe(const char *dir);
/* DFL_E_INPUT "what DIR: ..." when dir's last component is "." or ".."
 * (the folder would be one that holds other things: the working
 * directory, its parent) or a ".." follows a prefix that is not an
 * existing directory ("nonexist/../y": resolving it would need nonexist);
 * else DFL_OK.  Only stat()s. */
dfl_status dfl_dir_check_name(const char *dir, const char *what, dfl_err *err);

/* Whether a run or merge may replace the folder dir as a whole.  DFL_OK
 * when dir does not exist, is empty, or is a dflab results folder: its
 * file marker (manifest.json) is a results manifest that
 * dfl_manifest_results_files reads (this format version, or the shape of
 * dflab before the magic existed), and every other entry is a regular
 * file that manifest lists.  Else DFL_E_INPUT "what DIR: ..." naming the
 * first foreign entry in name order (or the manifest; a symbolic link at
 * dir is refused too: the swap would replace the link), so that `--out
 * webapp` or `dflab merge notes` never deletes anything dflab did not
 * write.  DFL_E_NOMEM when memory runs out. */
dfl_status dfl_dir_check_replaceable(const char *dir, const char *marker, const char *what,
                                     dfl_err *err);

/* The bytes of path plus a terminating NUL, malloc'ed (caller frees);
 * *len (may be NULL) receives the byte count.  NULL when the file cannot
 * be read, is not a regular file (dfl_rfile_read) or memory runs out. */
char *dfl_file_read_all(const char *path, size_t *len);

/* The path by which provenance names a file (a config), the same whatever
 * spelling reached it: path's symbolic links and "."/".." are resolved
 * (realpath), then the nearest ancestor directory holding an entry named
 * ".git" (a repository or a git worktree) is the root and the result is
 * the path below it ("configs/paper/x.ini" whether reached as
 * "./configs/paper/x.ini", "/abs/repo/configs/../configs/paper/x.ini" or
 * from a sub-folder); without such an ancestor it is the absolute resolved
 * path.  DFL_E_INPUT when path cannot be resolved (missing: named with
 * the system's reason); DFL_E_INPUT when the result needs more than
 * size - 1 characters. */
dfl_status dfl_path_stamp(const char *path, char *buf, size_t size, dfl_err *err);

#endif
