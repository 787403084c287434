/* Every part kind of `[field] kind = rfunc` through the binary (`dflab
 * probe`), with derived values:
 *   - a point part: h = |x - c| exactly, gradient (x - c)/|x - c|;
 *   - a rectangle region: 0 inside, the distance to an edge's line off one
 *     edge, the exact corner distance off a corner (orthogonal edges);
 *   - two parallel triangles with the prism trim, at a point midway between
 *     them that projects inside both: equal distances h, u = 2^(-1/p) h;
 *   - a triangulated surface: 0 at its corner (a mesh vertex), positive and
 *     at most the distance to that corner above it;
 *   - a heterogeneous set (region, segment, point) joined by rconj and a
 *     space curve: equal (1e-15) to the field the library builds from the
 *     same parts in the same order. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "geom/polygonize.h"
#include "rfunc/rfield.h"
#include "util/e2e_util.h"

/* Writes f.ini and p.csv in dir, probes, and returns the output path in
 * out (exit status 0 asserted). */
static void probe(const char *dir, const char *ini, const char *pts, char *out, size_t size)
{
    char path[600], args[1400];
    e2e_write(dir, "f.ini", ini, path, sizeof path);
    e2e_write(dir, "p.csv", pts, path, sizeof path);
    snprintf(args, sizeof args, "probe %s/f.ini --points %s/p.csv", dir, dir);
    const int rc = e2e_dflab(dir, args);
    char *msg = e2e_err_text(dir);
    cr_assert_eq(rc, 0, "%s: %s", ini, msg);
    free(msg);
    snprintf(out, size, "%s/out.txt", dir);
}

Test(e2e_bs04_rfunc_parts, points_regions_triangles_exact, .timeout = 60)
{
    char dir[256], out[600];
    e2e_tmpdir(dir, sizeof dir);
    probe(dir, "[field]\nkind = rfunc\npoints = 1 2\n", "x,y\n4,6\n", out, sizeof out);
    cr_expect_eq(e2e_csv_get(out, 0, "value"), 5.0);
    cr_expect_float_eq(e2e_csv_get(out, 0, "gx"), 0.6, 1e-15);
    cr_expect_float_eq(e2e_csv_get(out, 0, "gy"), 0.8, 1e-15);

    probe(dir, "[field]\nkind = rfunc\nregion = 0 0; 1 0; 1 1; 0 1\n",
          "x,y\n0.5,0.5\n0.5,-0.25\n1.3,1.4\n", out, sizeof out);
    cr_expect_eq(e2e_csv_get(out, 0, "value"), 0.0);
    cr_expect_float_eq(e2e_csv_get(out, 1, "value"), 0.25, 1e-15);
    cr_expect_float_eq(e2e_csv_get(out, 2, "value"), 0.5, 1e-15);

    for (int p = 1; p <= 7; p += 3) {
        char ini[300];
        snprintf(ini, sizeof ini,
                 "[field]\nkind = rfunc\ntriangles = 0 0 0; 1 0 0; 0 1 0; 0 0 1; 1 0 1; 0 1 1\n"
                 "tri_trim = prism\np = %d\n",
                 p);
        probe(dir, ini, "x,y,z\n0.2,0.25,0.5\n0.2,0.25,0\n", out, sizeof out);
        cr_expect_float_eq(e2e_csv_get(out, 0, "value"), 0.5 * pow(2.0, -1.0 / p), 1e-14,
                           "p %d", p);
        cr_expect_eq(e2e_csv_get(out, 1, "value"), 0.0);
    }
    cr_expect_eq(e2e_rmtree(dir), 0);
}

/* The library's field at the probe's points, against the probe's output. */
static void expect_same(const dfl_field *f, const char *out, const double *x, size_t n, int dim)
{
    for (size_t i = 0; i < n; i++) {
        double g[3] = {0, 0, 0};
        const double u = dfl_field_eval1(f, x + i * (size_t)dim, g);
        cr_expect(fabs(e2e_csv_get(out, i, "value") - u) <= 1e-15 * fmax(1.0, u), "point %zu", i);
        cr_expect(fabs(e2e_csv_get(out, i, "gx") - g[0]) <= 1e-14, "point %zu", i);
        cr_expect(fabs(e2e_csv_get(out, i, "gy") - g[1]) <= 1e-14, "point %zu", i);
        if (dim == 3) cr_expect(fabs(e2e_csv_get(out, i, "gz") - g[2]) <= 1e-14, "point %zu", i);
    }
}

Test(e2e_bs04_rfunc_parts, hetero_surface_spacecurve_as_the_library, .timeout = 120)
{
    char dir[256], out[600], ini[1200];
    e2e_tmpdir(dir, sizeof dir);
    const double x2[6] = {0.5, 0.1, 0.6, 0.9, -0.2, 0.4};
    probe(dir,
          "[field]\nkind = rfunc\nregion = 0 0; 0.3 0; 0.3 0.3; 0 0.3\n"
          "vertices = 0.5 0.5; 0.9 0.6\npoints = 0.2 0.8\njoin = rconj\np = 3\n",
          "x,y\n0.5,0.1\n0.6,0.9\n-0.2,0.4\n", out, sizeof out);
    dfl_rfield *r;
    dfl_field f;
    const double reg[8] = {0, 0, 0.3, 0, 0.3, 0.3, 0, 0.3}, a[2] = {0.5, 0.5}, b[2] = {0.9, 0.6},
                 c[2] = {0.2, 0.8};
    cr_assert_eq(dfl_rfield_new(2, DFL_RFUNC_RCONJ, 3, &r, NULL), DFL_OK);
    cr_assert_eq(dfl_rfield_add_region(r, reg, 4, NULL), DFL_OK);
    cr_assert_eq(dfl_rfield_add_segment(r, a, b, DFL_RFUNC_TRIM_DISK, NULL), DFL_OK);
    cr_assert_eq(dfl_rfield_add_point(r, c, NULL), DFL_OK);
    cr_assert_eq(dfl_rfield_finish(&r, &f, NULL), DFL_OK);
    expect_same(&f, out, x2, 3, 2);
    dfl_field_destroy(&f);

    /* the space curve of configs/shapes/space1.ini, polygonized to 1e-2 */
    char cwd[400];
    cr_assert_not_null(getcwd(cwd, sizeof cwd));
    snprintf(ini, sizeof ini,
             "[field]\nkind = rfunc\ncurve = sc\neps = 1e-2\np = 4\n[sc]\ninclude = %s/"
             "configs/shapes/space1.ini\n",
             cwd);
    const double x3[6] = {0.2, 0.2, 0.5, 0.6, 0.4, 0.1};
    probe(dir, ini, "x,y,z\n0.2,0.2,0.5\n0.6,0.4,0.1\n", out, sizeof out);
    dfl_bspline sc;
    dfl_polyline pl;
    e2e_load_curve("configs/shapes/space1.ini", "shape", &sc);
    cr_assert_eq(dfl_polygonize_curve(&sc, 1e-2, 0, &pl, NULL), DFL_OK);
    cr_assert_eq(dfl_rfield_polyline(3, pl.pts, pl.n, false, DFL_RFUNC_REQUIV, 4,
                                     DFL_RFUNC_TRIM_DISK, &f, NULL),
                 DFL_OK);
    expect_same(&f, out, x3, 2, 3);
    dfl_field_destroy(&f);
    dfl_polyline_free(&pl);
    dfl_bspline_free(&sc);

    /* configs/shapes/surface.ini: its corner control point (0, 0, 0.4) is on
     * the surface and a vertex of every triangulation */
    snprintf(ini, sizeof ini,
             "[field]\nkind = rfunc\nsurface = s\neps = 0.05\n[s]\ninclude = %s/"
             "configs/shapes/surface.ini\n",
             cwd);
    probe(dir, ini, "x,y,z\n0,0,0.4\n0,0,0.7\n", out, sizeof out);
    cr_expect_eq(e2e_csv_get(out, 0, "value"), 0.0);
    const double up = e2e_csv_get(out, 1, "value");
    cr_expect(up > 0 && up <= 0.3 + 1e-12, "%g", up);
    cr_expect_eq(e2e_rmtree(dir), 0);
}
