/* io/meshfile.h: reading through Assimp, welding by position, writing OBJ
 * and PLY, and refusing bad files with the file's name and the reason. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "io/meshfile.h"
#include "util/tmpdir.h"

static const char *const QUAD_OBJ = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";

Test(meshfile, polygons_are_triangulated)
{
    char dir[64], path[256];
    tmpdir_new(dir, sizeof dir);
    tmpdir_write(dir, "q.obj", QUAD_OBJ, path, sizeof path);
    dfl_meshfile m;
    dfl_err err;
    cr_assert_eq(dfl_meshfile_read(path, &m, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(m.ntris, 2);
    cr_expect_eq(m.nverts, 4);
    cr_expect_eq(m.nskipped, 0);
    dfl_meshfile_free(&m);
    tmpdir_remove(dir);
}

Test(meshfile, equal_positions_are_welded)
{
    /* two triangles sharing an edge, written with separate vertices (as
     * STL always does) */
    char dir[64], path[256];
    tmpdir_new(dir, sizeof dir);
    tmpdir_write(dir, "w.obj",
                 "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 5 5 5\n"
                 "f 1 2 3\nf 4 5 6\n",
                 path, sizeof path);
    dfl_meshfile m;
    dfl_err err;
    cr_assert_eq(dfl_meshfile_read(path, &m, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(m.nverts, 4, "6 written, 2 pairs equal, the unused one dropped: %zu", m.nverts);
    cr_expect_eq(m.ntris, 2);
    /* the shared edge uses the same indices in both triangles */
    int shared = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) shared += m.tris[i] == m.tris[3 + j];
    cr_expect_eq(shared, 2);
    dfl_meshfile_free(&m);
    tmpdir_remove(dir);
}

Test(meshfile, write_and_read_back_obj_and_ply)
{
    const double v[] = {0.1, 0.25, -3, 1.5, 0, 0, 0, 2, 0.125, 7, 7, 7};
    const size_t t[] = {0, 1, 2, 0, 2, 3};
    const char *names[] = {"m.obj", "m.PLY"};
    char dir[64], path[256];
    tmpdir_new(dir, sizeof dir);
    for (int k = 0; k < 2; k++) {
        snprintf(path, sizeof path, "%s/%s", dir, names[k]);
        dfl_err err;
        cr_assert_eq(dfl_meshfile_write(path, 4, v, 2, t, &err), DFL_OK, "%s", err.msg);
        dfl_meshfile m;
        cr_assert_eq(dfl_meshfile_read(path, &m, &err), DFL_OK, "%s: %s", names[k], err.msg);
        cr_expect_eq(m.nverts, 4);
        cr_assert_eq(m.ntris, 2);
        for (size_t i = 0; i < 6; i++)
            cr_expect_eq(m.verts[3 * m.tris[i] + 0], (double)(float)v[3 * t[i] + 0], "%s", names[k]);
        for (size_t i = 0; i < 6; i++)
            cr_expect_eq(m.verts[3 * m.tris[i] + 2], (double)(float)v[3 * t[i] + 2], "%s", names[k]);
        dfl_meshfile_free(&m);
    }
    dfl_err err;
    snprintf(path, sizeof path, "%s/m.stl", dir);
    cr_expect_eq(dfl_meshfile_write(path, 4, v, 2, t, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, ".obj or .ply"), "%s", err.msg);
    cr_expect_eq(tmpdir_count(dir), 2, "nothing left by the refused write");
    tmpdir_remove(dir);
}

Test(meshfile, bad_files_name_the_file_and_the_reason)
{
    struct {
        const char *name, *text, *want;
    } cs[] = {
        {"e.obj", "", "empty file"},
        {"junk.stl", "solid x\n garbage\n", "not a mesh"},
        {"nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "non-finite"},
        {"inf.obj", "v 1e300 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "non-finite"},
        {"l.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n", "no triangles"},
    };
    char dir[64], path[256];
    tmpdir_new(dir, sizeof dir);
    for (size_t i = 0; i < sizeof cs / sizeof *cs; i++) {
        tmpdir_write(dir, cs[i].name, cs[i].text, path, sizeof path);
        dfl_meshfile m;
        dfl_err err;
        cr_expect_eq(dfl_meshfile_read(path, &m, &err), DFL_E_INPUT, "%s", cs[i].name);
        cr_expect(strstr(err.msg, path) && strstr(err.msg, cs[i].want), "%s: %s", cs[i].name,
                  err.msg);
        cr_expect_null(m.verts, "zeroed on failure");
    }
    dfl_meshfile m;
    dfl_err err;
    snprintf(path, sizeof path, "%s/missing.obj", dir);
    cr_expect_eq(dfl_meshfile_read(path, &m, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "missing.obj") && strstr(err.msg, "cannot open"), "%s", err.msg);
    cr_expect_eq(dfl_meshfile_read(dir, &m, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "a directory"), "%s", err.msg);
    tmpdir_remove(dir);
}
