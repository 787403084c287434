/* Tests for field/vdb's mesh build and field/isomesh: the marching-cubes
 * mesh of a sphere is closed with its vertices on the sphere; OpenVDB's
 * meshToLevelSet of it gives, at its active voxels, the brute-force
 * distance to the mesh (float rounding) and the sphere's SDF within the
 * mesh's derived deviation; the signs; memory within the bound. */
#include <criterion/criterion.h>

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "field/exact.h"
#include "field/isomesh.h"
#include "field/meshdist.h"
#include "field/vdb.h"

static const double C[3] = {0.01, -0.02, 0.03}, R = 0.5;

static double sdf(const double x[3])
{
    const double d[3] = {x[0] - C[0], x[1] - C[1], x[2] - C[2]};
    return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) - R;
}

/* The sphere's mesh on the lattice of spacing h over [-1, 1]^3. */
static dfl_trimesh sphere_mesh(double h)
{
    dfl_shape s;
    dfl_field f;
    cr_assert_eq(dfl_shape_sphere(C, R, &s, NULL), DFL_OK);
    cr_assert_eq(dfl_field_exact_new(&s, &f, NULL), DFL_OK);
    const int n = (int)lround(2 / h) + 1;
    dfl_grid g = {3, {n, n, n}, {-1, -1, -1}, {1, 1, 1}};
    dfl_trimesh m;
    dfl_err err;
    cr_assert_eq(dfl_field_isomesh(&f, &g, 30, 1, &m, NULL, &err), DFL_OK, "%s", err.msg);
    dfl_field_destroy(&f);
    return m;
}

static int cmp_edge(const void *a, const void *b)
{
    const size_t *x = a, *y = b;
    return x[0] != y[0] ? (x[0] < y[0] ? -1 : 1) : (x[1] < y[1] ? -1 : x[1] > y[1]);
}

Test(vdb_mesh, iso_mesh_of_a_sphere_is_closed_and_on_the_sphere)
{
    const double h = 0.05;
    dfl_trimesh m = sphere_mesh(h);
    cr_assert_gt(m.ntris, 100);
    cr_assert_eq(m.bound, 0); /* field/isomesh.h: no certified bound */
    for (size_t i = 0; i < m.nverts; i++)
        cr_assert_lt(fabs(sdf(m.verts + 3 * i)), 1e-12, "vertex %zu: %g", i, sdf(m.verts + 3 * i));
    /* closed: every undirected edge in exactly two triangles */
    size_t *e = malloc(6 * m.ntris * sizeof *e);
    for (size_t t = 0; t < m.ntris; t++)
        for (int k = 0; k < 3; k++) {
            size_t a = m.tris[3 * t + k], b = m.tris[3 * t + (k + 1) % 3];
            e[2 * (3 * t + k)] = a < b ? a : b;
            e[2 * (3 * t + k) + 1] = a < b ? b : a;
        }
    qsort(e, 3 * m.ntris, 2 * sizeof *e, cmp_edge);
    for (size_t i = 0; i < 3 * m.ntris;) {
        size_t j = i;
        while (j < 3 * m.ntris && !cmp_edge(e + 2 * i, e + 2 * j)) j++;
        cr_assert_eq(j - i, 2, "edge %zu-%zu in %zu triangles", e[2 * i], e[2 * i + 1], j - i);
        i = j;
    }
    /* Euler characteristic of a sphere: V - E + F = 2 */
    cr_assert_eq((long)m.nverts - (long)(3 * m.ntris / 2) + (long)m.ntris, 2);
    free(e);
    dfl_trimesh_free(&m);
}

Test(vdb_mesh, mesh_to_level_set_is_the_mesh_distance_and_close_to_the_sdf)
{
    const double h = 0.05;
    dfl_trimesh m = sphere_mesh(h);
    dfl_vdb_opts o;
    dfl_vdb_opts_default(&o);
    o.voxel = h;
    o.band = 3;
    dfl_vdb *g = NULL;
    dfl_err err;
    cr_assert_eq(dfl_vdb_from_mesh(&m, &o, &g, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_vdb_background(g), (double)(float)(3 * h));
    cr_assert_eq(dfl_vdb_evals(g), 0);
    cr_assert_leq((double)dfl_vdb_bytes(g), dfl_vdb_bytes_bound(&o, NULL));
    /* Mesh deviation (isomesh.h): triangle edges <= the cube diagonal
     * sqrt(3) h, so every mesh point is within dev = R - sqrt(R^2 - h^2)
     * inside the sphere, and every sphere point within dev of the mesh
     * (the ray from the centre crosses the closed mesh): the distance
     * functions differ by at most dev. */
    const double dev = R - sqrt(R * R - h * h);
    const size_t n = dfl_vdb_active_count(g);
    cr_assert_gt(n, 1000);
    int *ijk = malloc(3 * n * sizeof *ijk);
    float *v = malloc(n * sizeof *v);
    dfl_vdb_active_voxels(g, n, ijk, v);
    size_t checked = 0;
    double worst_mesh = 0, worst_sdf = 0;
    for (size_t i = 0; i < n; i++) {
        double x[3];
        dfl_vdb_voxel_centre(g, ijk + 3 * i, x);
        const double d = sdf(x);
        /* the sign: OpenVDB's flood fill of the closed mesh */
        if (fabs(d) > dev) cr_assert_eq(v[i] < 0, d < 0, "voxel %zu: %g vs d %g", i, v[i], d);
        const double dm = dfl_meshdist_eval(&m, x), b = dfl_vdb_background(g);
        if (dm < b - h) {
            /* the inner layers: the exact mesh distance, up to float
             * vertices and arithmetic (a few float epsilons of the
             * coordinates' size, 1), so the SDF within dev */
            worst_mesh = fmax(worst_mesh, fabs(fabs(v[i]) - dm));
            worst_sdf = fmax(worst_sdf, fabs(v[i] - d));
            checked++;
        } else {
            /* the outermost layer: OpenVDB's approximate extension of the
             * band (field/vdb.h), only bounded by the background */
            cr_assert_leq(fabs(v[i]), b);
        }
    }
    cr_assert_gt(checked, n / 2);
    cr_assert_leq(worst_mesh, 8 * FLT_EPSILON, "mesh distance error %g", worst_mesh);
    cr_assert_leq(worst_sdf, dev + 8 * FLT_EPSILON, "SDF error %g > dev %g", worst_sdf, dev);
    /* outside the band: the signed background */
    const double in[3] = {C[0], C[1], C[2]}, out[3] = {0.95, 0.95, 0.95};
    double u;
    dfl_vdb_sample(g, DFL_VDB_BOX, 1, in, &u, NULL);
    cr_assert_eq(u, -dfl_vdb_background(g));
    dfl_vdb_sample(g, DFL_VDB_BOX, 1, out, &u, NULL);
    cr_assert_eq(u, dfl_vdb_background(g));
    free(ijk);
    free(v);
    dfl_vdb_free(g);
    dfl_trimesh_free(&m);
}
