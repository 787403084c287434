/* `dflab probe` on the bs04 paper configs that name their figure's field
 * in [field] (through the binary): every one evaluates (one value per
 * sweep axis set), and for bs04_hetero and bs04_fields the probe equals,
 * bit for bit, the study's own image at its grid nodes -- the [field]
 * section is what the figure shows.  The configs whose figures come from
 * generated geometry (an angle sweep: bs04_corrected, bs04_gradbounds,
 * bs04_triedge), several fields per run (bs04_bulging, bs04_spacecurves) or
 * no field (bs04_polygonization) have no [field]: probe says so (exit 2). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/e2e_util.h"

#define DIR "configs/paper/bs04/"

typedef struct pc {
    const char *cfg, *sets, *pts;
} pc;

Test(e2e_bs04_probe_configs, every_field_config_probes, .timeout = 120)
{
    static const pc cases[] = {
        {"bs04_fields.ini", "--set field.trim=disk", "x,y\n0.3,0.5\n0.5,0.6\n"},
        {"bs04_hetero.ini", "--set field.p=2", "x,y\n0.2,0.2\n0.6,0.6\n"},
        {"bs04_normalization.ini", "--set field.join=rconj --set field.p=3 --set field.trim=strip",
         "x,y\n0.3,0.5\n0.5,0.6\n"},
        {"bs04_recursive.ini", "--set field.m=2 --set implicit.b=0.5", "x,y\n0.9,0.1\n1,0\n"},
        {"bs04_scurve.ini", "--set field.eps=1e-2 --set field.join=requiv",
         "x,y\n0.3,0.5\n0.5,0.6\n"},
        {"bs04_surface.ini", "--set field.eps=0.5 --set field.p=2", "x,y,z\n0.5,0.5,0.3\n0,0,0.4\n"},
        {"bs04_triangle.ini", "--set field.tri_trim=prism", "x,y,z\n0.3,0.2,0.1\n0.3,0.2,0\n"},
    };
    char dir[256], path[600], args[1600];
    e2e_tmpdir(dir, sizeof dir);
    e2e_write(dir, "p.csv", "", path, sizeof path);
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        e2e_write(dir, "p.csv", cases[i].pts, path, sizeof path);
        snprintf(args, sizeof args, "probe " DIR "%s --points %s/p.csv %s", cases[i].cfg, dir,
                 cases[i].sets);
        const int rc = e2e_dflab(dir, args);
        char *msg = e2e_err_text(dir);
        cr_expect_eq(rc, 0, "%s: %s", cases[i].cfg, msg);
        free(msg);
        snprintf(path, sizeof path, "%s/out.txt", dir);
        cr_expect_eq(e2e_csv_rows(path), 2, "%s", cases[i].cfg);
        for (size_t r = 0; r < 2; r++)
            cr_expect(isfinite(e2e_csv_get(path, r, "value")), "%s row %zu", cases[i].cfg, r);
    }
    static const char *const none[] = {"bs04_corrected.ini", "bs04_gradbounds.ini",
                                       "bs04_triedge.ini", "bs04_bulging.ini",
                                       "bs04_spacecurves.ini", "bs04_polygonization.ini"};
    e2e_write(dir, "p.csv", "x,y\n0,0\n", path, sizeof path);
    for (size_t i = 0; i < sizeof none / sizeof none[0]; i++) {
        snprintf(args, sizeof args, "probe " DIR "%s --points %s/p.csv", none[i], dir);
        cr_expect_eq(e2e_dflab(dir, args), 2, "%s", none[i]);
    }
    cr_expect_eq(e2e_rmtree(dir), 0);
}

/* The probe at every node of the study's own (small) grid equals the image. */
static void same_as_image(const char *cfg, const char *runsets, const char *probesets,
                          const char *vti)
{
    char dir[256], path[900], args[2400];
    e2e_tmpdir(dir, sizeof dir);
    snprintf(args, sizeof args, "run %s%s --out %s/res --quiet %s", DIR, cfg, dir, runsets);
    cr_assert_eq(e2e_dflab(dir, args), 0, "%s", args);
    static const char *const arrays[] = {"value"};
    e2e_vti img;
    snprintf(path, sizeof path, "%s/res/%s", dir, vti);
    e2e_vti_read(dir, path, arrays, 1, &img);
    /* the nodes as probe points */
    const size_t n = img.npoints;
    size_t cap = 32 + n * 64;
    char *pts = malloc(cap);
    size_t o = (size_t)snprintf(pts, cap, "x,y\n");
    for (size_t i = 0; i < n; i++)
        o += (size_t)snprintf(pts + o, cap - o, "%.17g,%.17g\n", img.pts[3 * i], img.pts[3 * i + 1]);
    e2e_write(dir, "p.csv", pts, path, sizeof path);
    free(pts);
    snprintf(args, sizeof args, "probe %s%s --points %s/p.csv %s", DIR, cfg, dir, probesets);
    cr_assert_eq(e2e_dflab(dir, args), 0, "%s", args);
    snprintf(path, sizeof path, "%s/out.txt", dir);
    size_t bad = 0;
    for (size_t i = 0; i < n; i++)
        bad += e2e_csv_get(path, i, "value") != img.val[i];
    cr_expect_eq(bad, 0u, "%s: %zu of %zu nodes differ", cfg, bad, n);
    e2e_vti_free(&img);
    cr_expect_eq(e2e_rmtree(dir), 0);
}

Test(e2e_bs04_probe_configs, probe_equals_the_figure, .timeout = 120)
{
    same_as_image("bs04_hetero.ini", "--set field.p=7 --set grid.n=9", "--set field.p=7",
                  "hetero.vti");
    same_as_image("bs04_fields.ini", "--set field.trim=strip --set grid.n=9",
                  "--set field.trim=strip", "field_join.vti");
}
