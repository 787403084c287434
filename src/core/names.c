#include "core/names.h"

#include <stdio.h>
#include <string.h>

int dfl_names_find(const char *const *names, int count, const char *name)
{
    for (int i = 0; i < count; i++)
        if (strcmp(names[i], name) == 0) return i;
    return -1;
}

const char *dfl_names_at(const char *const *names, int count, int i)
{
    return i >= 0 && i < count ? names[i] : "?";
}

const char *dfl_names_list(const char *const *names, int count, char *buf, size_t size)
{
    if (size == 0) return buf;
    buf[0] = '\0';
    size_t k = 0;
    for (int i = 0; i < count && k + 1 < size; i++) {
        const int w = snprintf(buf + k, size - k, "%s%s", i ? "|" : "", names[i]);
        if (w < 0) break;
        k += (size_t)w;
    }
    return buf;
}

dfl_status dfl_names_parse(const char *what, const char *const *names, int count,
                           const char *name, int *out, dfl_err *err)
{
    const int i = dfl_names_find(names, count, name);
    if (i >= 0) {
        *out = i;
        return DFL_OK;
    }
    char list[512];
    return dfl_err_set(err, DFL_E_INPUT, "unknown %s '%.200s' (expected one of %s)", what, name,
                       dfl_names_list(names, count, list, sizeof list));
}
