/* `[shape] kind = mesh` through the binary: `dflab probe` on a mesh file
 * written beside a shape file that a config includes (the relative `file`
 * resolves against the shape file's folder), the octahedron's closed form
 * (inside: -(1 - |x|_1)/sqrt 3), --set shape.distance=unsigned, and the
 * repository's Wuson config: every value and gradient finite, |grad| = 1. */
#include <criterion/criterion.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "util/e2e_util.h"

static const char *const OCT =
    "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n"
    "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n";

Test(e2e_probe_mesh, octahedron_file_beside_an_included_shape, .timeout = 120)
{
    char dir[256], path[600], args[2048];
    e2e_tmpdir(dir, sizeof dir);
    e2e_write(dir, "shapes/oct.obj", OCT, path, sizeof path);
    e2e_write(dir, "shapes/oct.ini", "[shape]\nkind = mesh\nfile = oct.obj\n", path, sizeof path);
    e2e_write(dir, "cfg/p.ini",
              "[study]\nname = smoke\n[shape]\ninclude = ../shapes/oct.ini\n[field]\nkind = exact\n",
              path, sizeof path);
    e2e_write(dir, "p.csv", "x,y,z\n0.1,0.2,0.3\n-0.2,0.1,-0.05\n2,0,0\n", path, sizeof path);
    const double want[3] = {-(1 - 0.6) / sqrt(3.0), -(1 - 0.35) / sqrt(3.0), 1.0};
    for (int u = 0; u < 2; u++) {
        snprintf(args, sizeof args, "probe %s/cfg/p.ini --points %s/p.csv%s", dir, dir,
                 u ? " --set shape.distance=unsigned" : "");
        int rc = e2e_dflab(dir, args);
        snprintf(path, sizeof path, "%s/err.txt", dir);
        char *msg = e2e_slurp(path);
        cr_assert_eq(rc, 0, "%s: %s", args, msg);
        free(msg);
        snprintf(path, sizeof path, "%s/out.txt", dir);
        cr_assert_eq(e2e_csv_rows(path), 3);
        for (size_t r = 0; r < 3; r++) {
            double v = e2e_csv_get(path, r, "value");
            cr_expect_float_eq(v, u ? fabs(want[r]) : want[r], 1e-14, "row %zu: %.17g", r, v);
        }
    }
    e2e_rmtree(dir);
}

Test(e2e_probe_mesh, wuson_values_finite, .timeout = 120)
{
    char dir[256], path[600], args[2048], cwd[PATH_MAX];
    cr_assert_not_null(getcwd(cwd, sizeof cwd));
    e2e_tmpdir(dir, sizeof dir);
    char ini[PATH_MAX + 200];
    snprintf(ini, sizeof ini,
             "[study]\nname = smoke\n[shape]\ninclude = %s/configs/shapes/wuson.ini\n[field]\nkind = "
             "exact\n",
             cwd);
    e2e_write(dir, "w.ini", ini, path, sizeof path);
    char pts[8192] = "x,y,z\n";
    for (int i = 0; i < 64; i++) {
        char row[96];
        snprintf(row, sizeof row, "%.3f,%.3f,%.3f\n", -1 + 2 * ((i * 7) % 64) / 63.0,
                 -1 + 2 * ((i * 13) % 64) / 63.0, -1 + 2 * i / 63.0);
        strcat(pts, row);
    }
    e2e_write(dir, "p.csv", pts, path, sizeof path);
    snprintf(args, sizeof args, "probe %s/w.ini --points %s/p.csv", dir, dir);
    int rc = e2e_dflab(dir, args);
    snprintf(path, sizeof path, "%s/err.txt", dir);
    char *msg = e2e_slurp(path);
    cr_assert_eq(rc, 0, "%s", msg);
    free(msg);
    snprintf(path, sizeof path, "%s/out.txt", dir);
    cr_assert_eq(e2e_csv_rows(path), 64);
    for (size_t r = 0; r < 64; r++) {
        double v = e2e_csv_get(path, r, "value"), gx = e2e_csv_get(path, r, "gx"),
               gy = e2e_csv_get(path, r, "gy"), gz = e2e_csv_get(path, r, "gz");
        cr_expect(isfinite(v), "row %zu", r);
        cr_expect_float_eq(gx * gx + gy * gy + gz * gz, 1.0, 1e-12, "row %zu", r);
    }
    e2e_rmtree(dir);
}
