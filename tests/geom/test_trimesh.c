/* geom/trimesh.h: the validity rules (each one broken once), edge counts
 * of closed and open meshes, the fit into a box, and Wuson's counts. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "geom/trimesh.h"
#include "mesh_fixtures.h"
#include "util/tmpdir.h"

Test(trimesh, check_rules)
{
    dfl_trimesh m;
    dfl_err err;
    mf_octahedron(&m);
    cr_expect_eq(dfl_trimesh_check(&m, &err), DFL_OK);
    m.verts[4] = NAN;
    cr_expect_eq(dfl_trimesh_check(&m, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "vertex 1"), "%s", err.msg);
    m.verts[4] = 2e150;
    cr_expect_eq(dfl_trimesh_check(&m, &err), DFL_E_INPUT, "beyond the coordinate domain");
    m.verts[4] = 0;
    m.tris[7] = 6;
    cr_expect_eq(dfl_trimesh_check(&m, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "triangle 2") && strstr(err.msg, "index"), "%s", err.msg);
    m.tris[7] = 1;
    m.tris[5] = m.tris[4]; /* triangle 1 repeats a vertex: zero area */
    cr_expect_eq(dfl_trimesh_check(&m, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "triangle 1 is degenerate"), "%s", err.msg);
    m.ntris = 0;
    cr_expect_eq(dfl_trimesh_check(&m, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "no triangles"), "%s", err.msg);
    dfl_trimesh_free(&m);
}

Test(trimesh, collinear_triangle_is_degenerate)
{
    const double v[] = {0, 0, 0, 1, 1, 1, 2, 2, 2};
    const size_t t[] = {0, 1, 2};
    dfl_trimesh m;
    dfl_err err;
    mf_take(v, 3, t, 1, &m);
    cr_expect_eq(dfl_trimesh_check(&m, &err), DFL_E_INPUT);
    dfl_trimesh_free(&m);
}

Test(trimesh, edges_closed_and_open)
{
    dfl_trimesh m;
    dfl_err err;
    size_t nb, nn;
    mf_cube(&m);
    cr_assert_eq(dfl_trimesh_edges(&m, &nb, &nn, &err), DFL_OK);
    cr_expect_eq(nb, 0);
    cr_expect_eq(nn, 0);
    m.ntris -= 2; /* remove the x = 1 face: its 4 outer edges become boundary */
    cr_assert_eq(dfl_trimesh_edges(&m, &nb, &nn, &err), DFL_OK);
    cr_expect_eq(nb, 4);
    dfl_trimesh_free(&m);
}

Test(trimesh, fit_moves_the_box)
{
    dfl_trimesh m;
    mf_cube(&m);
    const double c[3] = {0.5, -1, 2};
    dfl_trimesh_fit(&m, c, 0.5);
    double lo[3], hi[3];
    dfl_trimesh_bbox(&m, lo, hi);
    for (int j = 0; j < 3; j++) {
        cr_expect_float_eq(lo[j], c[j] - 0.25, 1e-15);
        cr_expect_float_eq(hi[j], c[j] + 0.25, 1e-15);
    }
    dfl_trimesh_free(&m);
}

Test(trimesh, wuson_counts)
{
    dfl_trimesh m;
    dfl_err err;
    cr_assert_eq(dfl_trimesh_read(WUSON, &m, &err), DFL_OK, "%s", err.msg);
    size_t nb, nn;
    cr_assert_eq(dfl_trimesh_edges(&m, &nb, &nn, &err), DFL_OK);
    cr_expect_eq(m.ntris, 3732);
    /* the file indexes 3,205 vertices and has 2,338 edges used once by those
     * indices; most are seams between copies of one position, and welding
     * by position (io/meshfile.h) leaves the 412 edges of its real holes */
    cr_expect_eq(nb, 412, "boundary edges: %zu", nb);
    cr_expect_eq(nn, 0);
    cr_expect_eq(m.nverts, 2117);
    cr_expect_null(m.uv);
    dfl_trimesh_free(&m);
}

Test(trimesh, read_refuses_degenerate_triangles)
{
    char dir[64], path[256];
    tmpdir_new(dir, sizeof dir);
    tmpdir_write(dir, "d.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 4\nf 1 2 3\n", path,
                 sizeof path);
    dfl_trimesh m;
    dfl_err err;
    cr_expect_eq(dfl_trimesh_read(path, &m, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, path) && strstr(err.msg, "triangle 1 is degenerate"), "%s", err.msg);
    cr_expect_null(m.verts);
    tmpdir_remove(dir);
}
