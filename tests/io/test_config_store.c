/* Tests for src/io/config_store.c: the entry list and the resolved INI. */
#include <criterion/criterion.h>
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
    cr_assert(dfl_cfg_has_section(c, "h") && !dfl_cfg_has_section(c, "x"));
    char dir[64], path[128];
    tmpdir_file(dir, sizeof dir, "config.ini", path, sizeof path);
    cr_assert_eq(dfl_cfg_write(c, NULL, path, &err), DFL_OK, "%s", err.msg);
    char *text = e2e_slurp(path);
    cr_assert_str_eq(text, "# resolved configuration of t.ini\n"
                           "[s]\nname = x\nlist = 1, 2\n\n[g]\nn = 5\n\n[h]\nk = on\n");
    free(text);
    dfl_cfg *r = cfgu_load(path);
    cr_assert_str_eq(dfl_cfg_path(r), path);
    cr_assert_eq(dfl_cfg_sweep_points(r), 2);
    cr_assert_str_eq(cfgu_string(r, "g", "n"), "5");
    cr_assert_str_eq(cfgu_string(r, "h", "k"), "on");
    dfl_cfg_free(r);
    /* an origin names the file instead of the load path */
    cr_assert_eq(dfl_cfg_write(c, "configs/x.ini", path, &err), DFL_OK, "%s", err.msg);
    text = e2e_slurp(path);
    cr_assert(strncmp(text, "# resolved configuration of configs/x.ini\n[s]\n", 46) == 0, "%s",
              text);
    free(text);
    dfl_cfg_free(c);
    tmpdir_remove(dir);
}
