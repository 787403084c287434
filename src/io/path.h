/* Path-name helpers (string work only; nothing touches the file system).
 *
 *   dfl_path_base(path)              the part after the last '/'
 *   dfl_path_stem(path, buf, size)   base name without its last extension
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

#endif
