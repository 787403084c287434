/* Why O_NONBLOCK and fstat: open(2) of a FIFO for reading waits for a
 * writer, and stat-then-open would check another file than the one read
 * when the name changes in between. */
#include "io/rfile.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static const char *kind(mode_t m)
{
    return S_ISFIFO(m) ? "a FIFO" : S_ISDIR(m) ? "a directory" : S_ISSOCK(m) ? "a socket"
         : S_ISCHR(m) || S_ISBLK(m) ? "a device" : "not a plain file";
}

dfl_status dfl_rfile_open(const char *path, const char *what, FILE **fp, dfl_err *err)
{
    *fp = NULL;
    const char *sp = what && *what ? " " : "";
    if (!what) what = "";
    /* "PATH: cannot open config: ..." reads as the callers' other messages */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0)
        return dfl_err_set(err, DFL_E_INPUT, "%s: cannot open%s%s: %s", path, sp, what,
                           strerror(errno));
    struct stat sb;
    if (fstat(fd, &sb) != 0) {
        const int e = errno;
        close(fd);
        return dfl_err_set(err, DFL_E_IO, "%s: cannot stat: %s", path, strerror(e));
    }
    if (!S_ISREG(sb.st_mode)) {
        close(fd);
        return dfl_err_set(err, DFL_E_INPUT, "%s: not a regular file (%s)", path,
                           kind(sb.st_mode));
    }
    const int fl = fcntl(fd, F_GETFL);
    if (fl >= 0) fcntl(fd, F_SETFL, fl & ~O_NONBLOCK);
    *fp = fdopen(fd, "rb");
    if (!*fp) {
        close(fd);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    }
    return DFL_OK;
}

dfl_status dfl_rfile_read(const char *path, const char *what, size_t max, char **text,
                          size_t *len, dfl_err *err)
{
    *text = NULL;
    if (len) *len = 0;
    FILE *fp;
    dfl_status st = dfl_rfile_open(path, what, &fp, err);
    if (st != DFL_OK) return st;
    char *buf = NULL;
    size_t cap = 0, n = 0, k;
    do {
        if (n + 65536 > cap) {
            char *b = realloc(buf, cap = 2 * cap + 65536);
            if (!b) {
                free(buf), fclose(fp);
                return dfl_err_set(err, DFL_E_NOMEM, "%s: out of memory", path);
            }
            buf = b;
        }
        k = fread(buf + n, 1, cap - n - 1, fp);
        n += k;
    } while (k > 0 && n <= max);
    const int bad = ferror(fp);
    fclose(fp);
    if (bad) st = dfl_err_set(err, DFL_E_IO, "%s: read error", path);
    else if (n > max) st = dfl_err_set(err, DFL_E_INPUT, "%s: larger than %zu bytes", path, max);
    if (st != DFL_OK) {
        free(buf);
        return st;
    }
    buf[n] = '\0';
    *text = buf;
    if (len) *len = n;
    return DFL_OK;
}
