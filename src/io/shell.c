/* Single quotes rather than backslashes: inside them no byte is special,
 * so the rule has no exceptions to get wrong (a backslash before a newline
 * is a line continuation, not a newline). */
#include "io/shell.h"

#include <stdlib.h>
#include <string.h>

static const char plain[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_./=,:+-@%";

static int is_plain(const char *s) { return *s && strspn(s, plain) == strlen(s); }

char *dfl_shell_quote(const char *s)
{
    size_t n = 3;
    for (const char *c = s; *c; c++) n += *c == '\'' ? 4 : 1;
    char *q = malloc(n), *o = q;
    if (!q) return NULL;
    if (is_plain(s)) {
        memcpy(q, s, strlen(s) + 1);
        return q;
    }
    *o++ = '\'';
    for (; *s; s++) {
        if (*s == '\'') memcpy(o, "'\\''", 4), o += 4;
        else *o++ = *s;
    }
    *o++ = '\'';
    *o = '\0';
    return q;
}

void dfl_shell_put(FILE *fp, const char *s)
{
    if (is_plain(s)) {
        fputs(s, fp);
        return;
    }
    fputc('\'', fp);
    for (; *s; s++) {
        if (*s == '\'') fputs("'\\''", fp);
        else fputc(*s, fp);
    }
    fputc('\'', fp);
}
