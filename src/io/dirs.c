/* Leftovers are recognised by name rather than by lock files: a killed
 * process cannot clean up, but its name still says who it was. */
#include "io/dirs.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <linux/fs.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/atomic.h"
#include "io/rfile.h"

static void host_name(char *buf, size_t size)
{
    if (gethostname(buf, size) != 0 || !buf[0]) snprintf(buf, size, "localhost");
    buf[size - 1] = '\0';
    for (char *s = buf; *s; s++)
        if (*s == '.' || *s == '/') *s = '_'; /* the name's separators */
}

const char *dfl_dir_owned_name(const char *base, const char *kind, char *buf, size_t size)
{
    char host[256];
    host_name(host, sizeof host);
    snprintf(buf, size, "%s.%s.%s.%ld", base, kind, host, (long)getpid());
    return buf;
}

bool dfl_dir_owner_dead(const char *name, const char *kind)
{
    char host[256], pat[300];
    host_name(host, sizeof host);
    snprintf(pat, sizeof pat, ".%s.%s.", kind, host);
    const char *p = strstr(name, pat);
    if (!p) return false;
    p += strlen(pat);
    char *end;
    long pid = strtol(p, &end, 10);
    if (end == p || *end != '\0' || pid <= 0) return false;
    if (pid == (long)getpid()) return false;
    return kill((pid_t)pid, 0) != 0 && errno == ESRCH;
}

dfl_status dfl_dir_remove_tree(const char *path, dfl_err *err)
{
    struct stat sb;
    if (lstat(path, &sb) != 0) return DFL_OK;
    if (S_ISDIR(sb.st_mode)) {
        DIR *d = opendir(path);
        if (d) {
            struct dirent *de;
            dfl_status st = DFL_OK;
            while ((de = readdir(d)) && st == DFL_OK) {
                if (strcmp(de->d_name, ".") == 0 || strcmp(de->d_name, "..") == 0) continue;
                char p[8192];
                snprintf(p, sizeof p, "%s/%s", path, de->d_name);
                st = dfl_dir_remove_tree(p, err);
            }
            closedir(d);
            if (st != DFL_OK) return st;
        }
        if (rmdir(path) != 0)
            return dfl_err_set(err, DFL_E_IO, "%s: cannot remove: %s", path, strerror(errno));
        return DFL_OK;
    }
    if (unlink(path) != 0)
        return dfl_err_set(err, DFL_E_IO, "%s: cannot remove: %s", path, strerror(errno));
    return DFL_OK;
}

dfl_status dfl_dir_replace(const char *fresh, const char *dst, dfl_err *err)
{
    char old[4400];
    dfl_dir_owned_name(dst, "old", old, sizeof old);
    struct stat sb;
    const bool had = stat(dst, &sb) == 0;
    if (had && rename(dst, old) != 0)
        return dfl_err_set(err, DFL_E_IO, "%s: cannot move aside: %s", dst, strerror(errno));
    if (rename(fresh, dst) != 0) {
        int e = errno;
        if (had) rename(old, dst);
        return dfl_err_set(err, DFL_E_IO, "%s: cannot move into place: %s", dst, strerror(e));
    }
    return had ? dfl_dir_remove_tree(old, err) : DFL_OK;
}

/* Not link(2): a hard link shares the inode, so an edit of the merged
 * file in place would change the committed point too (and its sha256
 * would then refuse it).  A reflink shares the blocks copy-on-write where
 * the file system can (Btrfs, XFS); elsewhere the bytes are copied. */
dfl_status dfl_dir_link_or_copy(const char *src, const char *dst, dfl_err *err)
{
    FILE *in;
    dfl_status st = dfl_rfile_open(src, "", &in, err);
    if (st != DFL_OK) return st;
    dfl_atomic_file af;
    st = dfl_atomic_open(dst, &af, err);
    if (st != DFL_OK) {
        fclose(in);
        return st;
    }
    fflush(af.fp);
    if (ioctl(fileno(af.fp), FICLONE, fileno(in)) == 0) {
        fclose(in);
        return dfl_atomic_commit(&af, err);
    }
    char buf[65536];
    size_t n;
    int wbad = 0;
    while ((n = fread(buf, 1, sizeof buf, in)) > 0)
        if (fwrite(buf, 1, n, af.fp) != n) {
            wbad = 1;
            break;
        }
    const int bad = ferror(in);
    fclose(in);
    if (bad || wbad) {
        dfl_atomic_abort(&af);
        return dfl_err_set(err, DFL_E_IO, "%s: %s error", bad ? src : dst, bad ? "read" : "write");
    }
    return dfl_atomic_commit(&af, err);
}

dfl_status dfl_dir_check_writable(const char *dir, const char *what, dfl_err *err)
{
    char p[4096];
    snprintf(p, sizeof p, "%s", dir);
    for (;;) {
        struct stat sb;
        if (stat(p, &sb) == 0) {
            if (!S_ISDIR(sb.st_mode))
                return dfl_err_set(err, DFL_E_INPUT, "%s %s: not writable (%s is not a directory)",
                                   what, dir, p);
            /* a real create: access() says yes to root on /proc or a
             * read-only mount */
            char probe[4200];
            snprintf(probe, sizeof probe, "%s/.dflab-probe.%ld", p, (long)getpid());
            int fd = open(probe, O_WRONLY | O_CREAT | O_EXCL, 0600);
            if (fd < 0)
                return dfl_err_set(err, DFL_E_INPUT, "%s %s: not writable (%s: %s)", what, dir, p,
                                   strerror(errno));
            close(fd);
            unlink(probe);
            return DFL_OK;
        }
        char *slash = strrchr(p, '/');
        if (!slash) {
            snprintf(p, sizeof p, ".");
            continue;
        }
        if (slash == p) {
            p[1] = '\0';
            continue;
        }
        *slash = '\0';
    }
}

char *dfl_file_read_all(const char *path, size_t *len)
{
    FILE *fp = fopen(path, "rb");
    if (!fp) return NULL;
    char *buf = NULL;
    size_t cap = 0, n = 0, k;
    do {
        if (n + 65536 > cap) {
            char *b = realloc(buf, cap = 2 * cap + 65536);
            if (!b) {
                free(buf), fclose(fp);
                return NULL;
            }
            buf = b;
        }
        k = fread(buf + n, 1, cap - n - 1, fp);
        n += k;
    } while (k > 0);
    const int bad = ferror(fp);
    fclose(fp);
    if (bad) {
        free(buf);
        return NULL;
    }
    buf[n] = '\0';
    if (len) *len = n;
    return buf;
}

dfl_status dfl_dir_check_replaceable(const char *dir, const char *marker, const char *what,
                                     dfl_err *err)
{
    DIR *d = opendir(dir);
    if (!d) return DFL_OK;
    int entries = 0;
    struct dirent *de;
    while ((de = readdir(d)))
        if (strcmp(de->d_name, ".") != 0 && strcmp(de->d_name, "..") != 0) entries++;
    closedir(d);
    char p[8192];
    snprintf(p, sizeof p, "%s/%s", dir, marker);
    if (entries == 0 || access(p, F_OK) == 0) return DFL_OK;
    return dfl_err_set(err, DFL_E_INPUT,
                       "%s %s: exists and is not a dflab results folder (no %s); a run replaces "
                       "its folder as a whole, so give a new or a results folder",
                       what, dir, marker);
}
