/* The openvdb probe contract through the binary: `dflab probe` on
 * `[field] kind = openvdb` gives, for a plane (an affine SDF, which both
 * samplers reproduce), the signed distance and the unit normal inside the
 * band and the signed background +-band*voxel with a zero gradient outside
 * it; for a sphere built through meshToLevelSet, at voxel centres, the SDF
 * within the marching-cubes mesh's derived deviation; bad keys exit 2
 * naming the key. */
#include <criterion/criterion.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/e2e_util.h"

/* plane through p = (0.1, -0.2, 0.05) with normal (1, 2, 2) / 3; voxel 1/16,
 * band 6: b = 0.375 */
#define PLANE                                                                              \
    "[field]\nkind = openvdb\nvoxel = 0.0625\nband = 6\nsampler = %s\n"                   \
    "[shape]\nkind = plane\npoint = 0.1 -0.2 0.05\nnormal = 1 2 2\n"

static void probe(const char *dir, const char *ini, const char *csv, char *out, size_t size)
{
    char path[600], args[1024];
    e2e_write(dir, "f.ini", ini, path, sizeof path);
    e2e_write(dir, "p.csv", csv, path, sizeof path);
    snprintf(args, sizeof args, "probe %s/f.ini --points %s/p.csv", dir, dir);
    int rc = e2e_dflab(dir, args);
    char *msg = e2e_err_text(dir);
    cr_assert_eq(rc, 0, "%s", msg);
    free(msg);
    snprintf(out, size, "%s/out.txt", dir);
}

Test(e2e_probe_vdb, plane_in_and_out_of_the_band, .timeout = 60)
{
    static const char *const samplers[] = {"box", "quadratic", "staggered"};
    const double p[3] = {0.1, -0.2, 0.05}, n[3] = {1.0 / 3, 2.0 / 3, 2.0 / 3}, b = 0.375,
                 h = 0.0625;
    /* Reach: the samplers read voxels less than 2 h from x per axis, the
     * gradient's half steps 2.5 h, i.e. at most 2.5 h (1 + 2 + 2) / 3 = 0.26
     * along n.  So for |s| < b - 0.26 every voxel read is active (the SDF,
     * affine, reproduced: value s, gradient n), and for |s| >= b + 0.26 none
     * is (+-b, gradient 0).  Points at signed distance s, off the lattice. */
    static const double s[] = {0.01, -0.03, 0.1, 0.7, -0.75};
    static const double t[][3] = {{0.3, -0.1, 0.17}, {-0.4, 0.2, 0.11}, {0.05, 0.33, -0.2},
                                  {0.2, 0.1, 0.0}, {-0.1, -0.3, 0.1}};
    const int np = 5;
    char csv[1024] = "x,y,z\n";
    for (int i = 0; i < np; i++) {
        /* x = p + t_perp + s n, t_perp the part of t along the plane */
        const double tn = t[i][0] * n[0] + t[i][1] * n[1] + t[i][2] * n[2];
        double x[3];
        for (int a = 0; a < 3; a++) x[a] = p[a] + t[i][a] - tn * n[a] + s[i] * n[a];
        snprintf(csv + strlen(csv), sizeof csv - strlen(csv), "%.17g,%.17g,%.17g\n", x[0], x[1],
                 x[2]);
    }
    char dir[256], ini[1024], out[600];
    e2e_tmpdir(dir, sizeof dir);
    for (int k = 0; k < 3; k++) {
        snprintf(ini, sizeof ini, PLANE, samplers[k]);
        probe(dir, ini, csv, out, sizeof out);
        cr_assert_eq(e2e_csv_rows(out), np);
        for (int i = 0; i < np; i++) {
            const double v = e2e_csv_get(out, (size_t)i, "value");
            const double g[3] = {e2e_csv_get(out, (size_t)i, "gx"),
                                 e2e_csv_get(out, (size_t)i, "gy"),
                                 e2e_csv_get(out, (size_t)i, "gz")};
            if (fabs(s[i]) < b - 0.26) {
                /* float storage and arithmetic (test_vdb.c's bound: 32
                 * float epsilons of the largest |d| read, <= b); central
                 * differences are exact on affine data up to that, / h */
                const double tol = 32 * FLT_EPSILON * b;
                cr_expect(fabs(v - s[i]) <= tol, "%s row %d: %.9g vs %g", samplers[k], i, v, s[i]);
                for (int a = 0; a < 3; a++)
                    cr_expect(fabs(g[a] - n[a]) <= 2 * tol / h, "%s row %d: g%d %.9g", samplers[k],
                              i, a, g[a]);
            } else {
                cr_expect_eq(v, s[i] < 0 ? -b : b, "%s row %d: %.9g", samplers[k], i, v);
                for (int a = 0; a < 3; a++) cr_expect_eq(g[a], 0);
            }
        }
    }
    /* bad keys: exit 2, the key named */
    static const char *const bad[][2] = {{"field.voxel=0", "voxel"},
                                         {"field.band=0", "band"},
                                         {"field.sampler=cubic", "sampler"}};
    for (int i = 0; i < 3; i++) {
        char args[1024];
        snprintf(args, sizeof args, "probe %s/f.ini --points %s/p.csv --set %s", dir, dir,
                 bad[i][0]);
        const int rc = e2e_dflab(dir, args);
        char *msg = e2e_err_text(dir);
        cr_expect_eq(rc, 2, "%s", bad[i][0]);
        cr_expect(strstr(msg, bad[i][1]), "%s", msg);
        free(msg);
    }
    cr_expect_eq(e2e_rmtree(dir), 0);
}

/* build = mesh, sphere radius 0.5 at c: at a voxel centre (voxel 1/16, so
 * the sampler's index point is the voxel) the box sampler gives the voxel,
 * OpenVDB's distance to the marching-cubes mesh, within dev = R -
 * sqrt(R^2 - h^2) of the SDF (field/iso_mesh.h: triangle edges <= the cube
 * diagonal) in the inner band |d| < b - h. */
Test(e2e_probe_vdb, mesh_build_sphere_at_voxel_centres, .timeout = 60)
{
    static const char ini[] = "[field]\nkind = openvdb\nvoxel = 0.0625\nband = 3\nbuild = mesh\n"
                              "[shape]\nkind = sphere\ncenter = 0.01 -0.02 0.03\nradius = 0.5\n";
    const double c[3] = {0.01, -0.02, 0.03}, R = 0.5, h = 0.0625, b = 3 * h;
    const double dev = R - sqrt(R * R - h * h);
    char csv[4096] = "x,y,z\n";
    double want[64];
    int np = 0;
    for (int i = -12; i <= 12 && np < 64; i += 3)
        for (int j = -12; j <= 12 && np < 64; j += 4) {
            for (int k = -12; k <= 12; k++) {
                const double x[3] = {i * h, j * h, k * h};
                const double d = sqrt((x[0] - c[0]) * (x[0] - c[0]) + (x[1] - c[1]) * (x[1] - c[1]) +
                                      (x[2] - c[2]) * (x[2] - c[2])) - R;
                if (fabs(d) >= b - h - dev) continue;
                want[np++] = d;
                snprintf(csv + strlen(csv), sizeof csv - strlen(csv), "%.17g,%.17g,%.17g\n", x[0],
                         x[1], x[2]);
                break;
            }
        }
    cr_assert_gt(np, 20);
    char dir[256], out[600];
    e2e_tmpdir(dir, sizeof dir);
    probe(dir, ini, csv, out, sizeof out);
    cr_assert_eq(e2e_csv_rows(out), np);
    for (int i = 0; i < np; i++) {
        const double v = e2e_csv_get(out, (size_t)i, "value");
        cr_expect(fabs(v - want[i]) <= dev + 8 * FLT_EPSILON, "row %d: %.9g vs %.9g (dev %g)", i,
                  v, want[i], dev);
    }
    cr_expect_eq(e2e_rmtree(dir), 0);
}
