/* Path-name helpers (string work only; nothing touches the file system).
 *
 *   dfl_path_base(path)              the part after the last '/'
 *   dfl_path_stem(path, buf, size)   base name without its last extension
 *   dfl_path_beside(file, rel, buf, size)  rel resolved against file's directory
 */
#ifndef DFL_IO_PATH_H
#define DFL_IO_PATH_H

#include <stddef.h>

/* Pointer into path just after its last '/', or path itself without one
 * ("a/b.ini" -> "b.ini", "b" -> "b", "a/" -> ""). */
const char *dfl_path_base(const char *path);

/* The base name without its last ".ext" into buf (truncated to size - 1
 * characters, always terminated when size > 0); a leading dot is kept
 * (".ini" -> ".ini", "a/b.c.ini" -> "b.c").  Returns buf. */
char *dfl_path_stem(const char *path, char *buf, size_t size);

/* rel resolved against the directory of file, cleaned lexically, into buf:
 * an absolute rel is taken as is; otherwise dir(file) + "/" + rel, or rel
 * alone when file has no '/'.  Cleaning drops empty and "." components and
 * cancels "name/.." pairs ("configs/paper/a.ini" with "../shapes/S.ini" ->
 * "configs/shapes/S.ini"); a leading ".." of a relative result stays, one
 * above "/" is dropped; an empty result is ".".  Symbolic links are not
 * looked at (the file system is never touched).  Returns buf, or NULL when
 * the result needs more than size - 1 characters (buf then undefined). */
char *dfl_path_beside(const char *file, const char *rel, char *buf, size_t size);

#endif
