#include "util/tmpdir.h"

#include <criterion/criterion.h>
#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

void tmpdir_new(char *dir, size_t dsize)
{
    int n = snprintf(dir, dsize, "/tmp/dflab-test-XXXXXX");
    cr_assert(n > 0 && (size_t)n < dsize, "temporary directory name does not fit");
    cr_assert_not_null(mkdtemp(dir), "cannot create a temporary directory");
}

void tmpdir_file(char *dir, size_t dsize, const char *name, char *path, size_t psize)
{
    tmpdir_new(dir, dsize);
    int n = snprintf(path, psize, "%s/%s", dir, name);
    cr_assert(n > 0 && (size_t)n < psize, "%s/%s does not fit", dir, name);
}

const char *tmpdir_write(const char *dir, const char *name, const char *text, char *path,
                         size_t psize)
{
    char p[4096];
    int n = snprintf(p, sizeof p, "%s/%s", dir, name);
    cr_assert(n > 0 && (size_t)n < sizeof p, "%s/%s does not fit", dir, name);
    for (char *s = p + strlen(dir) + 1; (s = strchr(s, '/')); s++) {
        *s = '\0';
        cr_assert(mkdir(p, 0700) == 0 || errno == EEXIST, "mkdir %s: %s", p, strerror(errno));
        *s = '/';
    }
    FILE *fp = fopen(p, "w");
    cr_assert_not_null(fp, "cannot write %s", p);
    fputs(text, fp);
    cr_assert_eq(fclose(fp), 0, "cannot write %s", p);
    if (path) {
        cr_assert_lt((size_t)n, psize, "%s does not fit", p);
        memcpy(path, p, (size_t)n + 1);
    }
    return path;
}

int tmpdir_count(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)))
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) n++;
    closedir(d);
    return n;
}

void tmpdir_remove(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return;
    struct dirent *e;
    char p[4096];
    while ((e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
        struct stat st;
        /* lstat: a link to a directory is removed, not followed */
        if (lstat(p, &st) == 0 && S_ISDIR(st.st_mode))
            tmpdir_remove(p);
        else
            remove(p);
    }
    closedir(d);
    rmdir(dir);
}

void tmpdir_expect_io_error(dfl_status st, const dfl_err *err, const char *path,
                            const char *dir, int left)
{
    cr_assert_eq(st, DFL_E_IO, "%s: status %d (%s)", path, (int)st, err->msg);
    cr_assert_eq(err->code, DFL_E_IO);
    cr_assert_not_null(strstr(err->msg, path), "message '%s' does not name the path", err->msg);
    cr_assert_eq(tmpdir_count(dir), left, "%s: %d entries left, expected %d", dir,
                 tmpdir_count(dir), left);
}
