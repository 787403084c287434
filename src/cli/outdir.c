/* Checks are made on the real file system, once, before any study code
 * runs; the probe (an unnamed file where the file system has them) is the
 * only thing ever created here. */
#include "outdir.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/dirs.h"

static int is_dir(const char *p)
{
    struct stat sb;
    return stat(p, &sb) == 0 && S_ISDIR(sb.st_mode);
}

dfl_status dfl_outdir_check(const char *dir, dfl_outdir_guard *g, dfl_err *err)
{
    size_t n = strlen(dir);
    if (n == 0) return dfl_err_set(err, DFL_E_INPUT, "--out: empty directory name");
    if (n >= sizeof g->dir - 64)
        return dfl_err_set(err, DFL_E_INPUT, "--out %.80s...: name too long", dir);
    memcpy(g->dir, dir, n + 1);
    while (n > 1 && g->dir[n - 1] == '/') g->dir[--n] = '\0';
    if (strcmp(g->dir, "/") == 0)
        return dfl_err_set(err, DFL_E_INPUT,
                           "--out /: the root directory cannot hold a run's results");
    if (dfl_dir_check_name(g->dir, "--out", err) != DFL_OK) return DFL_E_INPUT;
    struct stat sb;
    if (stat(g->dir, &sb) == 0 && !S_ISDIR(sb.st_mode))
        return dfl_err_set(err, DFL_E_INPUT, "--out %s: exists and is not a directory", g->dir);
    /* the deepest existing ancestor (or dir itself) */
    char a[4096];
    memcpy(a, g->dir, n + 1);
    size_t k = n;
    while (!is_dir(a)) {
        while (k > 0 && a[k - 1] != '/') k--;   /* drop the last component */
        while (k > 1 && a[k - 1] == '/') k--;   /* and the slashes before it */
        if (k == 0) {
            snprintf(a, sizeof a, ".");
            break;
        }
        a[k] = '\0';
        if (stat(a, &sb) == 0 && !S_ISDIR(sb.st_mode))
            return dfl_err_set(err, DFL_E_INPUT, "--out %s: %s is not a directory", g->dir, a);
    }
    g->exist_len = strcmp(a, ".") == 0 && g->dir[0] != '.' ? 0 : strlen(a);
    const int e = dfl_dir_probe(a);
    if (e)
        return dfl_err_set(err, DFL_E_INPUT, "--out %s: cannot create directories in %s: %s",
                           g->dir, a, strerror(e));
    return DFL_OK;
}

void dfl_outdir_undo(const dfl_outdir_guard *g)
{
    char p[4096];
    snprintf(p, sizeof p, "%s", g->dir);
    size_t k = strlen(p);
    /* rmdir every component below the existing ancestor, deepest first;
     * rmdir refuses non-empty directories, so nothing else is touched */
    while (k > g->exist_len) {
        rmdir(p);
        while (k > 0 && p[k - 1] != '/') k--;
        while (k > 1 && p[k - 1] == '/') k--;
        if (k == 0 || k <= g->exist_len) break;
        p[k] = '\0';
    }
}
