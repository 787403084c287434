/* Words for a POSIX shell: what `printf %q` does for bash, in the one form
 * every POSIX shell reads the same way.
 *
 *   dfl_shell_quote(s)        s as one shell word, malloc'ed
 *   dfl_shell_put(fp, s)      the same, written to a stream
 *
 * The word is s itself when s is not empty and every byte is one of
 * A-Z a-z 0-9 _ . / = , : + - @ % (none of them is special to a shell in
 * any position); otherwise s inside single quotes, each ' written as
 * '\'' .  sh, bash, dash and zsh read the word back as exactly the bytes of
 * s, whatever they are (newlines, $, `, \, ", spaces, non-UTF-8): nothing
 * in single quotes is expanded.  The empty string is ''.
 */
#ifndef DFL_IO_SHELL_H
#define DFL_IO_SHELL_H

#include <stdio.h>

/* NULL when out of memory; the caller frees. */
char *dfl_shell_quote(const char *s);
/* Writes the word of dfl_shell_quote(s) to fp (no allocation). */
void dfl_shell_put(FILE *fp, const char *s);

#endif
