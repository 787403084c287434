/* A results place that cannot hold files is the user's choice, not the
 * machine's failure: a read-only mount at <out>.points is exit 2 with one
 * `dflab: error:` line naming the folder and "Read-only file system", and
 * nothing is left in the working folder but the inputs and that mount.
 * Needs a read-only bind mount (root and a kernel that allows it); the
 * test is skipped where mount(8) refuses. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "util/e2e_util.h"

Test(readonly_place, points_on_a_read_only_mount_exit_2, .timeout = 60)
{
    char dir[256], cfg[512], pts[600], cmd[2000], args[1400];
    e2e_tmpdir(dir, sizeof dir);
    e2e_write(dir, "s.ini",
              "[study]\nname = smoke\n[shape]\nkind = circle\ncenter = 0.5 0.5\nradius = 0.3\n"
              "[field]\nkind = exact\n[grid]\nn = 8\n",
              cfg, sizeof cfg);
    snprintf(pts, sizeof pts, "%s/o.points", dir);
    cr_assert_eq(mkdir(pts, 0777), 0);
    snprintf(cmd, sizeof cmd,
             "mount --bind '%s' '%s' 2>/dev/null && mount -o remount,ro,bind '%s' 2>/dev/null",
             pts, pts, pts);
    if (system(cmd) != 0) {
        snprintf(cmd, sizeof cmd, "umount '%s' 2>/dev/null", pts);
        (void)system(cmd);
        e2e_rmtree(dir);
        cr_skip_test("no read-only bind mount here (needs root)");
    }
    snprintf(args, sizeof args, "run '%s' --out '%s/o' --quiet", cfg, dir);
    const int rc = e2e_dflab(dir, args);
    snprintf(cmd, sizeof cmd, "umount '%s'", pts);
    cr_assert_eq(system(cmd), 0, "umount %s", pts);
    char ep[700];
    snprintf(ep, sizeof ep, "%s/err.txt", dir);
    char *e = e2e_slurp(ep);
    cr_assert_not_null(e);
    cr_expect_eq(rc, 2, "exit %d: %s", rc, e);
    cr_expect(strstr(e, "dflab: error: ") != NULL && strstr(e, "o.points") != NULL &&
                  strstr(e, "Read-only file system") != NULL,
              "%s", e);
    free(e);
    /* the inputs, the captured output and the (empty) mount point only */
    cr_expect_eq(e2e_count_entries(dir), 4, "%d entries", e2e_count_entries(dir));
    cr_expect_eq(e2e_count_entries(pts), 0);
    e2e_rmtree(dir);
}
