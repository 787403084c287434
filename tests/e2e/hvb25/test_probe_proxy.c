/* The proxy probe contract through the binary: `dflab probe` on [field]
 * kind = proxy gives the exact distance where the proxies are exact
 * (order-2 sphere proxies with Hermite blending: value and gradient;
 * order-1 plane proxies with the nearest filter), and bad keys exit 2
 * naming the key. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/e2e_util.h"

static const char *const sphere_ini =
    "[field]\nkind = proxy\norder = 2\ninput = sdf\ncurvature = analytic\nres = 8\n"
    "filter = hermite\nsigned = true\n"
    "[shape]\nkind = sphere\ncenter = 0.01 -0.02 0.03\nradius = 0.5\n";

/* points at signed distance s from the sphere, directions (a, b, c) */
static const double pts[][4] = {{1, 0.2, 0.1, 0.05}, {-0.3, 1, 0.4, -0.08},
                                {0.2, -0.5, -1, 0.0}, {-1, -1, 1, 0.12}};

/* dflab probe dir/f.ini --points dir/p.csv must succeed; path receives
 * its output's path. */
static void probe_ok(const char *dir, char *path, size_t size)
{
    char args[1024];
    snprintf(args, sizeof args, "probe %s/f.ini --points %s/p.csv", dir, dir);
    int rc = e2e_dflab(dir, args);
    char *msg = e2e_err_text(dir);
    cr_assert_eq(rc, 0, "%s", msg);
    free(msg);
    snprintf(path, size, "%s/out.txt", dir);
}

Test(e2e_probe_proxy, order2_sphere_hermite_exact)
{
    char dir[256], path[600], csv[2048] = "x,y,z\n";
    e2e_tmpdir(dir, sizeof dir);
    e2e_write(dir, "f.ini", sphere_ini, path, sizeof path);
    const double c[3] = {0.01, -0.02, 0.03};
    double want[4][4];
    for (int i = 0; i < 4; i++) {
        const double l = sqrt(pts[i][0] * pts[i][0] + pts[i][1] * pts[i][1] + pts[i][2] * pts[i][2]);
        double x[3];
        for (int j = 0; j < 3; j++) {
            want[i][1 + j] = pts[i][j] / l;
            x[j] = c[j] + (0.5 + pts[i][3]) * pts[i][j] / l;
        }
        want[i][0] = pts[i][3];
        snprintf(csv + strlen(csv), sizeof csv - strlen(csv), "%.17g,%.17g,%.17g\n", x[0], x[1],
                 x[2]);
    }
    e2e_write(dir, "p.csv", csv, path, sizeof path);
    probe_ok(dir, path, sizeof path);
    cr_assert_eq(e2e_csv_rows(path), 4);
    static const char *const col[] = {"value", "gx", "gy", "gz"};
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 4; k++)
            cr_expect(fabs(e2e_csv_get(path, (size_t)i, col[k]) - want[i][k]) < 1e-10,
                      "row %d %s: %.17g vs %.17g", i, col[k], e2e_csv_get(path, (size_t)i, col[k]),
                      want[i][k]);
    e2e_rmtree(dir);
}

Test(e2e_probe_proxy, order1_plane_nearest_exact)
{
    char dir[256], path[600];
    e2e_tmpdir(dir, sizeof dir);
    e2e_write(dir, "f.ini",
              "[field]\nkind = proxy\nres = 5\n[shape]\nkind = plane\npoint = 0.1 0.2 0.3\n"
              "normal = 0 0.6 0.8\n",
              path, sizeof path);
    e2e_write(dir, "p.csv", "x,y,z\n0.3,-0.7,0.9\n-0.9,0.5,-0.4\n0.05,0.2,0.3\n", path,
              sizeof path);
    probe_ok(dir, path, sizeof path);
    const double x[3][3] = {{0.3, -0.7, 0.9}, {-0.9, 0.5, -0.4}, {0.05, 0.2, 0.3}};
    for (int i = 0; i < 3; i++) {
        /* unsigned (the default): |(x - q) . n| */
        const double d = fabs(0.6 * (x[i][1] - 0.2) + 0.8 * (x[i][2] - 0.3));
        cr_expect(fabs(e2e_csv_get(path, (size_t)i, "value") - d) < 1e-14, "row %d", i);
    }
    e2e_rmtree(dir);
}

Test(e2e_probe_proxy, bad_keys_exit_2)
{
    static const struct {
        const char *field, *shape, *key;
    } cases[] = {
        {"res = 0\n", "kind = sphere\nradius = 0.5\n", "res"},
        {"clip_radius = 0\n", "kind = sphere\nradius = 0.5\n", "clip_radius"},
        {"clip_radius = -2\n", "kind = sphere\nradius = 0.5\n", "clip_radius"},
        {"input = parametric\n", "kind = cylinder\ncenter = 0 0 0\naxis = 0 0 1\nradius = 0.3\n",
         "input"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        char dir[256], path[600], args[1024], text[512];
        e2e_tmpdir(dir, sizeof dir);
        snprintf(text, sizeof text, "[field]\nkind = proxy\n%s[shape]\n%s", cases[k].field,
                 cases[k].shape);
        e2e_write(dir, "f.ini", text, path, sizeof path);
        e2e_write(dir, "p.csv", "x,y,z\n0,0,0\n", path, sizeof path);
        snprintf(args, sizeof args, "probe %s/f.ini --points %s/p.csv", dir, dir);
        cr_expect_eq(e2e_dflab(dir, args), 2, "%s", cases[k].field);
        char *msg = e2e_err_text(dir);
        char want[64];
        snprintf(want, sizeof want, "] %s", cases[k].key);
        cr_expect(msg && strstr(msg, want) && strstr(msg, "f.ini:"), "%s: %s", cases[k].field,
                  msg ? msg : "(none)");
        free(msg);
        e2e_rmtree(dir);
    }
}
