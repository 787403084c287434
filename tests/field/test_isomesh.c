/* field/isomesh.h: the marching-cubes mesh of a field's zero set.
 * Invariants: a closed surface inside the grid gives a watertight,
 * manifold mesh whose Euler characteristic V - E + F is 2 - 2 genus
 * (sphere 2, genus-2 surface -2); vertices lie on the level set after
 * refinement; the orientation makes the winding number 1 inside; written
 * as OBJ and read back it is the same mesh up to float rounding. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "field/exact.h"
#include "field/isomesh.h"
#include "geom/implicit.h"
#include "geom/mesh.h"
#include "geom/trimesh.h"
#include "geom/winding.h"
#include "io/meshfile.h"
#include "util/tmpdir.h"

static void euler(const dfl_trimesh *m, long *chi)
{
    size_t nb, nn;
    dfl_err err;
    cr_assert_eq(dfl_trimesh_edges(m, &nb, &nn, &err), DFL_OK);
    cr_expect_eq(nb, 0, "watertight: %zu boundary edges", nb);
    cr_expect_eq(nn, 0, "manifold");
    cr_assert_eq(m->ntris % 2, 0);
    *chi = (long)m->nverts - (long)(3 * m->ntris / 2) + (long)m->ntris;
}

Test(isomesh, sphere_closed_on_the_surface_oriented)
{
    dfl_shape s;
    dfl_err err;
    const double c[3] = {0.01, -0.02, 0.03};
    cr_assert_eq(dfl_shape_sphere(c, 0.7, &s, &err), DFL_OK);
    dfl_field f;
    cr_assert_eq(dfl_field_exact_new(&s, &f, &err), DFL_OK);
    const dfl_grid g = {3, {25, 25, 25}, {-1, -1, -1}, {1, 1, 1}};
    dfl_trimesh m;
    size_t dropped = 99;
    cr_assert_eq(dfl_field_isomesh(&f, &g, 20, 1, &m, &dropped, &err), DFL_OK, "%s", err.msg);
    cr_expect_lt(dropped, m.ntris);
    long chi;
    euler(&m, &chi);
    cr_expect_eq(chi, 2, "a sphere: chi = %ld", chi);
    for (size_t i = 0; i < m.nverts; i++)
        cr_expect(fabs(dfl_field_eval1(&f, m.verts + 3 * i, NULL)) < 1e-12, "vertex %zu on the sphere", i);
    cr_expect_eq(dfl_trimesh_check(&m, &err), DFL_OK, "no degenerate triangle left: %s", err.msg);
    cr_expect_float_eq(dfl_winding_brute(m.verts, m.tris, m.ntris, c), 1.0, 1e-12);
    const double out[3] = {0.9, 0.9, 0.9};
    cr_expect(fabs(dfl_winding_brute(m.verts, m.tris, m.ntris, out)) < 1e-12);
    dfl_trimesh_free(&m);
    dfl_field_destroy(&f);
}

Test(isomesh, genus2_euler_characteristic_and_obj_round_trip, .timeout = 120)
{
    dfl_implicit_options opt;
    dfl_implicit_options_default(&opt);
    dfl_implicit *imp;
    dfl_err err;
    const double o[3] = {0, 0, 0};
    cr_assert_eq(dfl_implicit_genus2(o, 0.1, &opt, &imp, &err), DFL_OK, "%s", err.msg);
    dfl_shape s;
    cr_assert_eq(dfl_implicit_shape(&imp, &s, &err), DFL_OK, "%s", err.msg);
    /* the surface reaches |x|, |y| = 1.07 and |z| = 0.105 */
    const dfl_grid g = {3, {65, 65, 17}, {-1.2, -1.2, -0.3}, {1.2, 1.2, 0.3}};
    dfl_trimesh m;
    cr_assert_eq(dfl_shape_isomesh(&s, &g, 30, 2, &m, NULL, &err), DFL_OK, "%s", err.msg);
    const dfl_implicit *gi = dfl_implicit_of_shape(&s);
    for (size_t i = 0; i < m.nverts; i++)
        {
            double G[3], gv = dfl_implicit_g(gi, m.verts + 3 * i, G, NULL);
            cr_assert(fabs(gv) < 1e-10 * (1 + sqrt(G[0] * G[0] + G[1] * G[1] + G[2] * G[2])), "vertex %zu on g = 0: %g", i, gv);
        }
    long chi;
    euler(&m, &chi);
    cr_expect_eq(chi, -2, "genus 2: chi = %ld", chi);
    char dir[64], path[256];
    tmpdir_new(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/g2.obj", dir);
    cr_assert_eq(dfl_meshfile_write(path, m.nverts, m.verts, m.ntris, m.tris, &err), DFL_OK);
    dfl_trimesh r;
    cr_assert_eq(dfl_trimesh_read(path, &r, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(r.ntris, m.ntris);
    cr_expect_eq(r.nverts, m.nverts);
    for (size_t i = 0; i < 3 * r.ntris; i++)
        for (int j = 0; j < 3; j++)
            cr_assert(fabs(r.verts[3 * r.tris[i] + j] - m.verts[3 * m.tris[i] + j]) <=
                          0x1p-23 * fabs(m.verts[3 * m.tris[i] + j]),
                      "read back to float precision (Assimp's parser)");
    /* the reloaded mesh as a shape: negative where the implicit is */
    dfl_shape ms;
    cr_assert_eq(dfl_shape_mesh(&r, DFL_MESH_SIGNED, &ms, &err), DFL_OK, "%s", err.msg);
    int agree = 0, n = 0;
    for (int i = 0; i < 200; i++) {
        double x[3] = {-0.9 + 1.8 * ((i * 37) % 200) / 200.0, -0.9 + 1.8 * ((i * 91) % 200) / 200.0,
                       -0.3 + 0.6 * ((i * 53) % 200) / 200.0};
        double di = dfl_shape_eval1(&s, x, NULL), dm = dfl_shape_eval1(&ms, x, NULL);
        if (fabs(di) < 0.05) continue; /* the mesh is within a cell of the surface */
        n++;
        agree += (di < 0) == (dm < 0);
    }
    cr_expect_eq(agree, n, "signs agree off the surface: %d of %d", agree, n);
    dfl_shape_free(&ms);
    tmpdir_remove(dir);
    cr_expect_gt(n, 100);
    dfl_trimesh_free(&m);
    dfl_shape_free(&s);
}

Test(isomesh, refusals)
{
    dfl_shape s;
    dfl_err err;
    const double c[3] = {5, 5, 5};
    cr_assert_eq(dfl_shape_sphere(c, 0.5, &s, &err), DFL_OK);
    dfl_field f;
    cr_assert_eq(dfl_field_exact_new(&s, &f, &err), DFL_OK);
    const dfl_grid g = {3, {8, 8, 8}, {-1, -1, -1}, {1, 1, 1}};
    dfl_trimesh m;
    cr_expect_eq(dfl_field_isomesh(&f, &g, 0, 1, &m, NULL, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "does not cross"), "%s", err.msg);
    cr_expect_null(m.verts);
    dfl_field_destroy(&f);
    const double c2[2] = {0, 0};
    cr_assert_eq(dfl_shape_circle(c2, 0.5, &s, &err), DFL_OK);
    cr_assert_eq(dfl_field_exact_new(&s, &f, &err), DFL_OK);
    cr_expect_eq(dfl_field_isomesh(&f, &g, 0, 1, &m, NULL, &err), DFL_E_INPUT);
    dfl_field_destroy(&f);
}
