#include "io/atomic.h"

#include <errno.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

dfl_status dfl_io_errno_status(int e)
{
    switch (e) {
    case EROFS: case EACCES: case EPERM: case ENOTDIR: case ENAMETOOLONG: case ELOOP:
        return DFL_E_INPUT;
    default:
        return DFL_E_IO;
    }
}

void dfl_atomic_tmpname(const char *path, char *buf, size_t size)
{
    snprintf(buf, size, "%s.tmp.%ld", path, (long)getpid());
}

dfl_status dfl_atomic_open(const char *path, dfl_atomic_file *af, dfl_err *err)
{
    memset(af, 0, sizeof *af);
    if (strlen(path) >= sizeof af->path)
        return dfl_err_set(err, DFL_E_IO, "%s: path too long", path);
    strcpy(af->path, path);
    dfl_atomic_tmpname(path, af->tmp, sizeof af->tmp);
    af->fp = fopen(af->tmp, "wb");
    if (!af->fp) {
        const int e = errno;
        return dfl_err_set(err, dfl_io_errno_status(e), "%s: cannot create: %s", af->tmp,
                           strerror(e));
    }
    return DFL_OK;
}

dfl_status dfl_atomic_commit(dfl_atomic_file *af, dfl_err *err)
{
    if (!af->fp) return dfl_err_set(err, DFL_E_INTERNAL, "%s: file not open", af->path);
    int bad = ferror(af->fp);
    if (fclose(af->fp) != 0) bad = 1;
    af->fp = NULL;
    if (bad) {
        remove(af->tmp);
        return dfl_err_set(err, DFL_E_IO, "%s: write failed", af->path);
    }
    if (rename(af->tmp, af->path) != 0) {
        int e = errno;
        remove(af->tmp);
        return dfl_err_set(err, DFL_E_IO, "%s: cannot rename from %s: %s", af->path, af->tmp,
                           strerror(e));
    }
    return DFL_OK;
}

void dfl_atomic_abort(dfl_atomic_file *af)
{
    if (af->fp) {
        fclose(af->fp);
        af->fp = NULL;
    }
    if (af->tmp[0]) remove(af->tmp);
}

dfl_status dfl_mkdir_p(const char *path, dfl_err *err)
{
    char buf[4096];
    size_t len = strlen(path);
    if (len == 0 || len >= sizeof buf)
        return dfl_err_set(err, DFL_E_IO, "invalid directory name '%s'", path);
    memcpy(buf, path, len + 1);
    for (size_t i = 1; i <= len; i++) {
        if (buf[i] == '/' || buf[i] == '\0') {
            char saved = buf[i];
            buf[i] = '\0';
            if (mkdir(buf, 0777) != 0 && errno != EEXIST) {
                const int e = errno;
                return dfl_err_set(err, dfl_io_errno_status(e),
                                   "%s: cannot create directory: %s", buf, strerror(e));
            }
            buf[i] = saved;
        }
    }
    struct stat st;
    if (stat(path, &st) != 0 || !S_ISDIR(st.st_mode))
        return dfl_err_set(err, DFL_E_INPUT, "%s: not a directory", path);
    return DFL_OK;
}
