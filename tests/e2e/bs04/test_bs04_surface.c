/* End-to-end: the bs04_surface study (Fig. 12) at bs04's coarse eps = 0.5
 * on a small plane.  Expected values: the triangulation and the field from
 * the library run directly, the distance to the mesh by brute force, the
 * distance to the surface by dense parameter sampling (independent of the
 * footpoint solver), and the Hausdorff argument |d_M - d_S| <= bound. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cfg/curve_cfg.h"
#include "geom/polygonize.h"
#include "io/config.h"
#include "rfunc/rfield.h"
#include "rfunc/tri3d.h"
#include "util/e2e_util.h"

#define CFG "configs/paper/bs04/bs04_surface.ini"
#define NS 1000

Test(e2e_bs04_surface, coarse_mesh_metrics, .timeout = 60)
{
    char out[512], csv[700];
    e2e_run_table(CFG, "--set field.eps=0.5 --set field.p=2 --set study.slice_n=12",
                  "bs04_surface", 1, out, sizeof out, csv, sizeof csv);
    dfl_cfg *cfg;
    dfl_err err;
    dfl_surface_set S;
    cr_assert_eq(dfl_cfg_load("configs/shapes/surface.ini", &cfg, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_surface_from_cfg(cfg, "shape", "bspline_surface", &S, &err), DFL_OK, "%s",
                 err.msg);
    dfl_cfg_free(cfg);
    dfl_trimesh M;
    cr_assert_eq(dfl_polygonize_surface(&S, 0.5, 0, &M, NULL), DFL_OK);
    cr_expect_eq((long)e2e_csv_get(csv, 0, "triangles"), (long)M.ntris);
    cr_expect(fabs(e2e_csv_get(csv, 0, "bound") - M.bound) <= 1e-15);
    const double bound = M.bound;
    /* Hausdorff: the two distance functions differ by at most the bound */
    cr_expect(e2e_csv_get(csv, 0, "mesh_dev_max_s0") <= bound);

    /* the field of the mesh (conditional trim, a = 0.2, k = 2, eq. 4; p = 2) */
    dfl_rfield *rf;
    dfl_field f;
    const dfl_rfunc_tri_opts o = dfl_rfunc_tri_defaults();
    cr_assert_eq(dfl_rfield_new(3, DFL_RFUNC_REQUIV, 2, &rf, NULL), DFL_OK);
    for (size_t t = 0; t < M.ntris; t++) {
        const size_t *v = M.tris + 3 * t;
        cr_assert_eq(dfl_rfield_add_triangle(rf, M.verts + 3 * v[0], M.verts + 3 * v[1],
                                             M.verts + 3 * v[2], &o, NULL),
                     DFL_OK);
    }
    cr_assert_eq(dfl_rfield_finish(&rf, &f, NULL), DFL_OK);
    /* dense samples of the surface */
    double *sp = malloc(3 * NS * NS * sizeof *sp);
    const dfl_surface *pa = &S.patch[0];
    cr_assert_eq(S.npatch, 1);
    for (int j = 0; j < NS; j++)
        for (int i = 0; i < NS; i++)
            dfl_surface_eval(pa, pa->u0 + (pa->u1 - pa->u0) * i / (NS - 1.0),
                             pa->v0 + (pa->v1 - pa->v0) * j / (NS - 1.0), 0,
                             sp + 3 * ((size_t)j * NS + (size_t)i));
    /* slice y = 0.5, x in [0, 1], z in [-0.25, 0.85], 12 x 12 */
    double l1m = 0, l1s = 0, dev = 0;
    for (int j = 0; j < 12; j++)
        for (int i = 0; i < 12; i++) {
            const double x[3] = {i / 11.0, 0.5, -0.25 + 1.1 * j / 11.0};
            double dm = INFINITY, ds2 = INFINITY;
            for (size_t t = 0; t < M.ntris; t++) {
                const size_t *v = M.tris + 3 * t;
                dm = fmin(dm, dfl_point_triangle_dist(x, M.verts + 3 * v[0], M.verts + 3 * v[1],
                                                      M.verts + 3 * v[2]));
            }
            for (size_t k = 0; k < (size_t)NS * NS; k++) {
                const double a = x[0] - sp[3 * k], b = x[1] - sp[3 * k + 1],
                             c = x[2] - sp[3 * k + 2];
                ds2 = fmin(ds2, a * a + b * b + c * c);
            }
            const double u = dfl_field_eval1(&f, x, NULL), ds = sqrt(ds2);
            l1m += fabs(u - dm) / 144;
            l1s += fabs(u - ds) / 144;
            dev = fmax(dev, fabs(dm - ds));
        }
    cr_expect(fabs(e2e_csv_get(csv, 0, "l1_s0_mesh") - l1m) <= 1e-12, "l1 mesh %.15g vs %.15g",
              e2e_csv_get(csv, 0, "l1_s0_mesh"), l1m);
    /* sample spacing < 2e-3 on the surface: brute-force d_S is above the
     * true distance by at most ~1e-3 */
    cr_expect(fabs(e2e_csv_get(csv, 0, "l1_s0") - l1s) <= 1e-3, "l1 %.9g vs %.9g",
              e2e_csv_get(csv, 0, "l1_s0"), l1s);
    cr_expect(fabs(e2e_csv_get(csv, 0, "mesh_dev_max_s0") - dev) <= 1e-3);
    free(sp);
    dfl_field_destroy(&f);
    dfl_trimesh_free(&M);
    dfl_surface_set_free(&S);
    /* csv, config, manifest, the mesh, one slice (vti + exr) */
    cr_expect_eq(e2e_count_entries(out), 6);
}

Test(e2e_bs04_surface, bad_input)
{
    e2e_expect_bad_config("[study]\nname = bs04_surface\nslices = y 0.5\n[field]\nkind = rfunc\n"
                          "surface = nowhere\neps = 0.1\n",
                          "[field] surface", "no section [nowhere]");
    e2e_expect_bad_config("[study]\nname = bs04_surface\nslices = y 0.5\n[field]\nkind = rfunc\n"
                          "vertices = 0 0 0; 1 0 0\n",
                          "[field] of bs04_surface", NULL);
}
