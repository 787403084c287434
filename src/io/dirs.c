/* Leftovers are recognised by name rather than by lock files: a killed
 * process cannot clean up, but its name still says who it was. */
#define _GNU_SOURCE /* O_TMPFILE, syscall() */
#include "io/dirs.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <linux/fs.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "io/atomic.h"
#include "io/rfile.h"
#include "io/manifest.h"

#ifndef RENAME_EXCHANGE
#define RENAME_EXCHANGE (1 << 1)
#endif
#ifndef RENAME_NOREPLACE
#define RENAME_NOREPLACE (1 << 0)
#endif

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

/* renameat2 through syscall(): older glibc lacks the wrapper, and the
 * flags are what makes the swap atomic.  -1 with errno on failure. */
static int rename2(const char *from, const char *to, unsigned flags)
{
#ifdef SYS_renameat2
    return (int)syscall(SYS_renameat2, AT_FDCWD, from, AT_FDCWD, to, flags);
#else
    (void)from, (void)to, (void)flags;
    errno = ENOSYS;
    return -1;
#endif
}

dfl_status dfl_dir_replace(const char *fresh, const char *dst, dfl_err *err)
{
    struct stat sb;
    if (lstat(dst, &sb) != 0) {
        if (rename(fresh, dst) != 0)
            return dfl_err_set(err, DFL_E_IO, "%s: cannot move into place: %s", dst,
                               strerror(errno));
        return DFL_OK;
    }
    /* One system call swaps the two names: at every moment dst is either
     * the old or the new folder, and fresh's name then holds the old one. */
    if (rename2(fresh, dst, RENAME_EXCHANGE) == 0) return dfl_dir_remove_tree(fresh, err);
    if (errno != EINVAL && errno != ENOSYS)
        return dfl_err_set(err, DFL_E_IO, "%s: cannot swap in %s: %s", dst, fresh,
                           strerror(errno));
    /* A file system without the exchange: two renames.  A kill between them
     * leaves dst missing and the backup the only copy; the next run's
     * dfl_dir_restore_stale puts it back (see dirs.h). */
    char old[4400];
    dfl_dir_owned_name(dst, "old", old, sizeof old);
    if (rename(dst, old) != 0)
        return dfl_err_set(err, DFL_E_IO, "%s: cannot move aside: %s", dst, strerror(errno));
    if (rename(fresh, dst) != 0) {
        int e = errno;
        if (rename(old, dst) != 0)
            return dfl_err_set(err, DFL_E_IO,
                               "%s: cannot move into place (%s), and the old folder stays at %s",
                               dst, strerror(e), old);
        return dfl_err_set(err, DFL_E_IO, "%s: cannot move into place: %s", dst, strerror(e));
    }
    return dfl_dir_remove_tree(old, err);
}

bool dfl_dir_restore_stale(const char *backup, const char *dst)
{
    struct stat sb;
    if (!dfl_dir_owner_dead(backup, "old") || lstat(dst, &sb) == 0 || errno != ENOENT)
        return false;
    /* RENAME_NOREPLACE: a run that made dst meanwhile keeps it */
    if (rename2(backup, dst, RENAME_NOREPLACE) == 0) return true;
    if (errno != EINVAL && errno != ENOSYS) return false;
    return lstat(dst, &sb) != 0 && rename(backup, dst) == 0;
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

/* Removes the probes of dead processes of this host from dir (a kill
 * between creating and removing one leaves it). */
static void clean_probes(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return;
    struct dirent *de;
    while ((de = readdir(d))) {
        if (strncmp(de->d_name, ".dflab.probe.", 13) != 0 || !dfl_dir_owner_dead(de->d_name, "probe"))
            continue;
        char p[8192];
        snprintf(p, sizeof p, "%s/%s", dir, de->d_name);
        if (unlink(p) != 0) rmdir(p);
    }
    closedir(d);
}

int dfl_dir_probe(const char *dir)
{
    /* an unnamed file: nothing is left behind whenever the process dies */
    int fd = open(dir, O_TMPFILE | O_WRONLY | O_CLOEXEC, 0600);
    if (fd >= 0) {
        close(fd);
        return 0;
    }
    if (errno != EOPNOTSUPP && errno != EISDIR && errno != EINVAL && errno != ENOENT)
        return errno;
    /* a file system without O_TMPFILE: a named probe of this process */
    clean_probes(dir);
    char base[4200], probe[4700];
    snprintf(base, sizeof base, "%s/.dflab", dir);
    dfl_dir_owned_name(base, "probe", probe, sizeof probe);
    if (mkdir(probe, 0700) != 0) return errno;
    rmdir(probe);
    return 0;
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
            const int e = dfl_dir_probe(p);
            if (e)
                return dfl_err_set(err, DFL_E_INPUT, "%s %s: not writable (%s: %s)", what, dir, p,
                                   strerror(e));
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

dfl_status dfl_dir_check_name(const char *dir, const char *what, dfl_err *err)
{
    size_t n = strlen(dir);
    while (n > 1 && dir[n - 1] == '/') n--;
    size_t b = n;
    while (b > 0 && dir[b - 1] != '/') b--;
    const size_t bl = n - b;
    if ((bl == 1 && dir[b] == '.') || (bl == 2 && dir[b] == '.' && dir[b + 1] == '.'))
        return dfl_err_set(err, DFL_E_INPUT,
                           "%s %s: a results folder cannot be named '.' or '..' (it would be a "
                           "folder that holds other things); name a new folder",
                           what, dir);
    /* a ".." after a missing folder: the kernel would need that folder,
     * and making it would leave it behind */
    char pre[4096];
    for (size_t i = 0; i + 2 <= n && i < sizeof pre; i++) {
        if (!(dir[i] == '.' && dir[i + 1] == '.' && (i == 0 || dir[i - 1] == '/') &&
              (i + 2 == n || dir[i + 2] == '/')))
            continue;
        if (i == 0) continue;
        memcpy(pre, dir, i);
        pre[i] = '\0';
        struct stat sb;
        if (stat(pre, &sb) != 0 || !S_ISDIR(sb.st_mode))
            return dfl_err_set(err, DFL_E_INPUT,
                               "%s %s: '..' follows %s, which is not an existing folder", what, dir,
                               pre);
    }
    return DFL_OK;
}

/* One reader of whole files: io/rfile.h's (regular files only, so a FIFO
 * named like a manifest cannot block a run). */
char *dfl_file_read_all(const char *path, size_t *len)
{
    char *text;
    dfl_err e;
    if (dfl_rfile_read(path, "", SIZE_MAX - 1, &text, len, &e) != DFL_OK) return NULL;
    return text;
}

static int cmp_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static void free_names(char **v, size_t n)
{
    for (size_t i = 0; i < n; i++) free(v[i]);
    free(v);
}

/* The entries of dir but . and .., sorted; -1 when dir cannot be read,
 * -2 when memory runs out. */
static long list_dir(const char *dir, char ***out)
{
    *out = NULL;
    DIR *d = opendir(dir);
    if (!d) return -1;
    char **v = NULL;
    size_t n = 0;
    struct dirent *de;
    while ((de = readdir(d))) {
        if (strcmp(de->d_name, ".") == 0 || strcmp(de->d_name, "..") == 0) continue;
        char **nv = realloc(v, (n + 1) * sizeof *nv);
        char *s = nv ? strdup(de->d_name) : NULL;
        if (nv) v = nv;
        if (!s) {
            closedir(d);
            free_names(v, n);
            return -2;
        }
        v[n++] = s;
    }
    closedir(d);
    if (n) qsort(v, n, sizeof *v, cmp_name);
    *out = v;
    return (long)n;
}

static bool listed(char *const *names, size_t n, const char *s)
{
    for (size_t i = 0; i < n; i++)
        if (strcmp(names[i], s) == 0) return true;
    return false;
}

dfl_status dfl_dir_check_replaceable(const char *dir, const char *marker, const char *what,
                                     dfl_err *err)
{
    struct stat sb;
    if (lstat(dir, &sb) != 0) return DFL_OK;
    /* a link would be replaced by the folder, not followed */
    if (S_ISLNK(sb.st_mode))
        return dfl_err_set(err, DFL_E_INPUT,
                           "%s %s: is a symbolic link (a run would replace the link); give the "
                           "folder it points to",
                           what, dir);
    if (!S_ISDIR(sb.st_mode))
        return dfl_err_set(err, DFL_E_INPUT, "%s %s: exists and is not a directory", what, dir);
    char **ents;
    const long ne = list_dir(dir, &ents);
    if (ne == -2) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    if (ne < 0)
        return dfl_err_set(err, DFL_E_INPUT, "%s %s: cannot list: %s", what, dir, strerror(errno));
    if (ne == 0) return DFL_OK;
    static const char tail[] = "; a run replaces its folder as a whole, so give a new folder or "
                               "one that dflab wrote";
    char p[8192];
    snprintf(p, sizeof p, "%s/%s", dir, marker);
    dfl_status st = DFL_OK;
    char *json = NULL;
    if (lstat(p, &sb) != 0 || !S_ISREG(sb.st_mode)) {
        st = dfl_err_set(err, DFL_E_INPUT,
                         "%s %s: exists and is not a dflab results folder (no %s; it holds %s)%s",
                         what, dir, marker, ents[0], tail);
    } else if (sb.st_size > (64 << 20) || !(json = dfl_file_read_all(p, NULL))) {
        st = dfl_err_set(err, DFL_E_INPUT, "%s %s: %s cannot be read as a dflab manifest%s",
                         what, dir, marker, tail);
    }
    char **files = NULL;
    size_t nf = 0;
    if (st == DFL_OK) {
        const int kind = dfl_manifest_results_files(json, &files, &nf);
        if (kind == -2) st = dfl_err_set(err, DFL_E_NOMEM, "out of memory");
        else if (kind < 0)
            st = dfl_err_set(err, DFL_E_INPUT,
                             "%s %s: %s is not a dflab results manifest (format \"%s\" version "
                             "%d)%s",
                             what, dir, marker, DFL_RESULTS_FORMAT, DFL_RESULTS_FORMAT_VERSION,
                             tail);
    }
    /* every entry is the manifest or a regular file it lists */
    for (long i = 0; i < ne && st == DFL_OK; i++) {
        if (strcmp(ents[i], marker) == 0) continue;
        snprintf(p, sizeof p, "%s/%s", dir, ents[i]);
        if (!listed(files, nf, ents[i]) || lstat(p, &sb) != 0 || !S_ISREG(sb.st_mode))
            st = dfl_err_set(err, DFL_E_INPUT,
                             "%s %s: holds %s, which its %s does not list as a file dflab wrote%s",
                             what, dir, ents[i], marker, tail);
    }
    free(json);
    free_names(files, nf);
    free_names(ents, (size_t)ne);
    return st;
}

/* Provenance must not depend on how a user spelled the path (a merged
 * sweep launched with absolute paths and a one-process run with relative
 * ones must stamp the same bytes), nor on where the checkout lives: the
 * path below the repository root is what another clone reproduces. */
dfl_status dfl_path_stamp(const char *path, char *buf, size_t size, dfl_err *err)
{
    char *real = realpath(path, NULL);
    if (!real)
        return dfl_err_set(err, DFL_E_INPUT, "%s: cannot resolve: %s", path, strerror(errno));
    const size_t n = strlen(real);
    size_t root = 0; /* length of the root prefix; 0: none found */
    char *probe = malloc(n + 8);
    if (!probe) {
        free(real);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    }
    /* the ancestors of real, nearest first: its directory [0, d), then
     * each shorter prefix ending before a '/'; d == 0 is "/" itself */
    size_t d = (size_t)(strrchr(real, '/') - real);
    for (;;) {
        memcpy(probe, real, d);
        memcpy(probe + d, "/.git", 6);
        struct stat sb;
        if (lstat(probe, &sb) == 0) {
            root = d + 1;
            break;
        }
        if (d == 0) break;
        while (d > 0 && real[--d] != '/') {}
    }
    free(probe);
    const char *out = root ? real + root : real;
    dfl_status st = DFL_OK;
    if (strlen(out) + 1 > size)
        st = dfl_err_set(err, DFL_E_INPUT, "%s: its path is longer than %zu characters", path,
                         size - 1);
    else
        memcpy(buf, out, strlen(out) + 1);
    free(real);
    return st;
}
