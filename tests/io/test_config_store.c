/* Tests for src/io/config_store.c: the entry list and the resolved INI. */
#define _DEFAULT_SOURCE /* realpath */
#include <criterion/criterion.h>
#include <limits.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>
#include <stdlib.h>
#include <string.h>

#include "io/config.h"
#include "util/config_util.h"
#include "util/e2e_util.h"
#include "util/tmpdir.h"

/* The written file holds every key once, in entry order, --set values
 * included, and parses back to the same values. */
Test(config, write_reads_back)
{
    dfl_cfg *c = cfgu_parse("[s]\nname = x\nlist = 1, 2\n[g]\nn = 3\n  4\n");
    dfl_err err;
    cr_assert_eq(dfl_cfg_set(c, "g.n=5", &err), DFL_OK);
    cr_assert_eq(dfl_cfg_set(c, "h.k=on", &err), DFL_OK);
    /* a key new to an earlier section: written there, the header once */
    cr_assert_eq(dfl_cfg_set(c, "s.extra=7", &err), DFL_OK);
    cr_assert(dfl_cfg_has_section(c, "h") && !dfl_cfg_has_section(c, "x"));
    char dir[64], path[128];
    tmpdir_file(dir, sizeof dir, "config.ini", path, sizeof path);
    cr_assert_eq(dfl_cfg_write(c, NULL, path, &err), DFL_OK, "%s", err.msg);
    char *text = e2e_slurp(path);
    cr_assert_str_eq(text, "# resolved configuration of t.ini\n"
                           "[s]\nname = x\nlist = 1, 2\nextra = 7\n\n[g]\nn = 5\n\n[h]\nk = on\n");
    free(text);
    dfl_cfg *r = cfgu_load(path);
    cr_assert_str_eq(dfl_cfg_path(r), path);
    cr_assert_eq(dfl_cfg_sweep_points(r), 2);
    cr_assert_str_eq(cfgu_string(r, "g", "n"), "5");
    cr_assert_str_eq(cfgu_string(r, "h", "k"), "on");
    cr_assert_str_eq(cfgu_string(r, "s", "extra"), "7");
    dfl_cfg_free(r);
    /* an origin names the file instead of the load path */
    cr_assert_eq(dfl_cfg_write(c, "configs/x.ini", path, &err), DFL_OK, "%s", err.msg);
    text = e2e_slurp(path);
    cr_assert(strncmp(text, "# resolved configuration of configs/x.ini\n[s]\n", 46) == 0, "%s",
              text);
    free(text);
    /* an origin holding a newline (a hostile folder name) stays one comment
     * line: escaped, and the file still loads with the same keys */
    cr_assert_eq(dfl_cfg_write(c, "a\nb = 1\r\x7f.ini", path, &err), DFL_OK, "%s", err.msg);
    text = e2e_slurp(path);
    cr_assert(strncmp(text, "# resolved configuration of a\\x0ab = 1\\x0d\\x7f.ini\n[s]\n", 55) == 0,
              "%s", text);
    free(text);
    r = cfgu_load(path);
    cr_assert_str_eq(cfgu_string(r, "g", "n"), "5");
    dfl_cfg_free(r);
    dfl_cfg_free(c);
    tmpdir_remove(dir);
}

/* A file-name key (DFL_CFG_PATH_KEYS) is written resolved and absolute, so
 * config.ini names the same file from its own folder: written relative to
 * the config's folder, a --set value relative to the working directory, a
 * sweep list item by item; a file that does not exist is made absolute
 * against the working directory.  The written config, loaded from another
 * folder, resolves to the same file. */
Test(config, write_resolves_file_names)
{
    char dir[64], p[600], real[PATH_MAX], cwd[PATH_MAX];
    tmpdir_new(dir, sizeof dir);
    cr_assert_not_null(realpath(dir, real));
    tmpdir_write(dir, "m/x.obj", "v 0 0 0\n", p, sizeof p);
    tmpdir_write(dir, "m/y.obj", "v 0 0 0\n", p, sizeof p);
    char cfgp[700];
    tmpdir_write(dir, "a/c.ini", "[shape]\nkind = mesh\nfile = ../m/x.obj, ../m/y.obj\n[s2]\n"
                 "file = ../m/none.obj\n", cfgp, sizeof cfgp);
    dfl_cfg *c = cfgu_load(cfgp);
    dfl_err err;
    cr_assert_not_null(getcwd(cwd, sizeof cwd));
    char d2[700];
    snprintf(d2, sizeof d2, "%s/m", dir);
    cr_assert_eq(chdir(d2), 0);
    cr_assert_eq(dfl_cfg_set(c, "s3.file=y.obj", &err), DFL_OK, "%s", err.msg);
    char out[700];
    snprintf(out, sizeof out, "%s/out/config.ini", dir);
    snprintf(d2, sizeof d2, "%s/out", dir);
    mkdir(d2, 0755);
    dfl_status st = dfl_cfg_write(c, NULL, out, &err);
    cr_assert_eq(chdir(cwd), 0);
    cr_assert_eq(st, DFL_OK, "%s", err.msg);
    char *text = e2e_slurp(out);
    char want[3 * PATH_MAX];
    snprintf(want, sizeof want, "file = %s/m/x.obj, %s/m/y.obj\n", real, real);
    cr_expect(strstr(text, want), "want %s in %s", want, text);
    snprintf(want, sizeof want, "file = %s/m/none.obj\n", real);
    cr_expect(strstr(text, want), "missing file: want %s in %s", want, text);
    snprintf(want, sizeof want, "[s3]\nfile = %s/m/y.obj\n", real);
    cr_expect(strstr(text, want), "--set: want %s in %s", want, text);
    free(text);
    /* reread from its own folder: the same files */
    dfl_cfg *r = cfgu_load(out), *pt = NULL;
    cr_assert_eq(dfl_cfg_sweep_point(r, 1, &pt, &err), DFL_OK);
    char got[PATH_MAX];
    cr_assert_eq(dfl_cfg_path_value(pt, "shape", "file", got, sizeof got, &err), DFL_OK);
    snprintf(want, sizeof want, "%s/m/y.obj", real);
    cr_expect_str_eq(got, want);
    dfl_cfg_free(pt);
    dfl_cfg_free(r);
    dfl_cfg_free(c);
    tmpdir_remove(dir);
}
