#include "io/path.h"

#include <stdio.h>
#include <string.h>

const char *dfl_path_base(const char *path)
{
    const char *b = strrchr(path, '/');
    return b ? b + 1 : path;
}

char *dfl_path_stem(const char *path, char *buf, size_t size)
{
    if (size == 0) return buf;
    snprintf(buf, size, "%s", dfl_path_base(path));
    char *dot = strrchr(buf, '.');
    if (dot && dot != buf) *dot = '\0';
    return buf;
}
