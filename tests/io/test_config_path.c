/* io/config.h's dfl_cfg_path_value: a relative file name resolves against
 * the folder of the file the key was written in (the config or the
 * included shape file), a --set value against the working directory, an
 * absolute name is kept; empty values are refused naming the key. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

#include "io/config.h"
#include "util/tmpdir.h"

Test(config_path, relative_to_the_file_of_the_key)
{
    char dir[64], path[256], want[512], buf[512];
    tmpdir_new(dir, sizeof dir);
    tmpdir_write(dir, "shapes/m.ini", "[shape]\nkind = mesh\nfile = meshes/a.obj\n", NULL, 0);
    tmpdir_write(dir, "cfg/c.ini",
                 "[shape]\ninclude = ../shapes/m.ini\n[other]\nfile = b.obj\n[abs]\nfile = /x/y.obj\n"
                 "[empty]\nfile =\n",
                 path, sizeof path);
    dfl_cfg *c;
    dfl_err err;
    cr_assert_eq(dfl_cfg_load(path, &c, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_cfg_path_value(c, "shape", "file", buf, sizeof buf, &err), DFL_OK, "%s", err.msg);
    snprintf(want, sizeof want, "%s/shapes/meshes/a.obj", dir);
    cr_expect_str_eq(buf, want, "an included key: beside the shape file");
    cr_assert_eq(dfl_cfg_path_value(c, "other", "file", buf, sizeof buf, &err), DFL_OK);
    snprintf(want, sizeof want, "%s/cfg/b.obj", dir);
    cr_expect_str_eq(buf, want, "beside the config");
    cr_assert_eq(dfl_cfg_path_value(c, "abs", "file", buf, sizeof buf, &err), DFL_OK);
    cr_expect_str_eq(buf, "/x/y.obj");
    cr_expect_eq(dfl_cfg_path_value(c, "empty", "file", buf, sizeof buf, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "[empty] file"), "%s", err.msg);
    cr_expect_eq(dfl_cfg_path_value(c, "other", "file", buf, 8, &err), DFL_E_INPUT, "too long for buf");
    cr_assert_eq(dfl_cfg_set(c, "shape.file=rel/c.obj", &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_cfg_path_value(c, "shape", "file", buf, sizeof buf, &err), DFL_OK);
    cr_expect_str_eq(buf, "rel/c.obj", "--set: the working directory");
    dfl_cfg_free(c);
    tmpdir_remove(dir);
}
