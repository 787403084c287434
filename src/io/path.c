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

/* Components are copied one by one into buf; ".." pops the last one unless
 * it is itself ".." (or there is none, in a relative path). */
char *dfl_path_beside(const char *file, const char *rel, char *buf, size_t size)
{
    if (size < 2) return NULL; /* not even "." or "/" fits */
    const char *base = dfl_path_base(file);
    size_t dlen = rel[0] == '/' ? 0 : (size_t)(base - file);
    const int absolute = rel[0] == '/' || (dlen > 0 && file[0] == '/');
    size_t n = 0;
    if (absolute) buf[n++] = '/';
    size_t keep = n; /* length that ".." may not cut into */
    for (int part = 0; part < 2; part++) {
        const char *s = part == 0 ? file : rel;
        const char *end = part == 0 ? file + dlen : rel + strlen(rel);
        while (s < end) {
            while (s < end && *s == '/') s++;
            const char *e = s;
            while (e < end && *e != '/') e++;
            size_t len = (size_t)(e - s);
            if (len == 0 || (len == 1 && s[0] == '.')) {
                s = e;
                continue;
            }
            if (len == 2 && s[0] == '.' && s[1] == '.') {
                /* the last component starts after the last '/' beyond keep */
                size_t k = n;
                while (k > keep && buf[k - 1] != '/') k--;
                const int last_is_up = n - k == 2 && buf[k] == '.' && buf[k + 1] == '.';
                if (n > keep && !last_is_up) {
                    n = k > keep ? k - 1 : keep; /* drop the component and its '/' */
                    s = e;
                    continue;
                }
                if (absolute) { /* ".." above "/" stays at "/" */
                    s = e;
                    continue;
                }
            }
            if (n + (n > keep) + len >= size) return NULL;
            if (n > keep) buf[n++] = '/';
            memcpy(buf + n, s, len);
            n += len;
            s = e;
        }
    }
    if (n == 0) buf[n++] = '.';
    buf[n] = '\0';
    return buf;
}
