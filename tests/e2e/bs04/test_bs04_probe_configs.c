/* `dflab probe` on every bs04 paper config (through the binary): each one
 * evaluates (one value per sweep axis set), and for bs04_hetero and
 * bs04_fields the probe equals, bit for bit, the study's own image at its
 * grid nodes -- the [field] section is what the figure shows.  The configs
 * whose figures come from generated geometry (an angle sweep:
 * bs04_corrected, bs04_gradbounds, bs04_triedge), several fields per run
 * (bs04_bulging, bs04_spacecurves) or the polygonized curves
 * (bs04_polygonization) carry probe-only [field] / [field_NAME] sections
 * (experiments/harness/probe.h); their values are checked against closed
 * forms: 0 on the parts, and on the line of a disk-trimmed segment of
 * length d at distance s beyond its end h = s (d + s) / d (eq. 4,
 * h = sqrt(f^2 + max(-t, 0)^2), with f = 0, t = -s (d + s) / d), joined by R-equivalence p = 2 as (sum h_i^-2)^-1/2. */
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
    cr_expect_eq(e2e_rmtree(dir), 0);
}

/* A probe-only section: config, --field (NULL: the default [field]), sets,
 * points and the value expected at each (derived, see the top). */
typedef struct pf {
    const char *cfg, *field, *sets, *pts;
    int n;
    double want[3];
} pf;

Test(e2e_bs04_probe_configs, probe_only_sections, .timeout = 120)
{
    /* two disk-trimmed unit segments at alpha = 90 (O, (1,0), (0,1)) at
     * (2, 0): h1 = 2; for (0,0)-(0,1): f^2 = 4, t = -((x - a).(x - b)) = -4,
     * so by eq. 4 h2^2 = f^2 + max(-t, 0)^2 = 20 */
    const double g90 = 1.0 / sqrt(0.25 + 1.0 / 20.0);
    /* collinear (-1,0)-(0,0)-(1,0) at (2, 0): h = 2 and 2 * 3 = 6 */
    const double col = 1.0 / sqrt(0.25 + 1.0 / 36.0);
    const pf cases[] = {
        {"bs04_corrected.ini", NULL, "--set study.alpha=90 --set study.p=2 --set study.parts=disk",
         "x,y\n0.5,0\n0,0.25\n", 2, {0, 0}},
        {"bs04_corrected.ini", "field_eq20",
         "--set study.alpha=90 --set study.p=2 --set study.parts=disk", "x,y\n0.5,0\n", 1, {0}},
        {"bs04_gradbounds.ini", NULL,
         "--set study.alpha=90 --set study.p=2 --set study.parts=disk --set study.join=requiv",
         "x,y\n0.5,0\n2,0\n", 2, {0, g90}},
        {"bs04_gradbounds.ini", "field_alpha270",
         "--set study.alpha=90 --set study.p=2 --set study.parts=disk --set study.join=requiv",
         "x,y\n0,-0.5\n", 1, {0}},
        {"bs04_triedge.ini", NULL, "--set study.dihedral=90 --set study.p=2",
         "x,y,z\n0.3,0,0.5\n0,0,0.4\n", 2, {0, 0}},
        {"bs04_bulging.ini", NULL, "--set study.p=2", "x,y\n0.5,0\n2,0\n", 2, {0, col}},
        {"bs04_bulging.ini", "field_W_fig2", "--set study.p=2", "x,y\n0.05,0.95\n", 1, {0}},
        {"bs04_spacecurves.ini", NULL, "--set study.trim=disk", "x,y,z\n0.9,0.5,0\n", 1, {0}},
        /* closed uniform cubic: starts at (P14 + 4 P0 + P1) / 6 */
        {"bs04_spacecurves.ini", "field_space2", "--set study.trim=disk",
         "x,y,z\n0.5,0.36526666666666667,0.5\n", 1, {0}},
        {"bs04_polygonization.ini", NULL, "--set study.eps=1e-3", "x,y\n0.85,0.85\n", 1, {0}},
        {"bs04_polygonization.ini", "field_W", "--set study.eps=1e-3", "x,y\n0.05,0.95\n", 1,
         {0}},
    };
    char dir[256], path[600], args[1600];
    e2e_tmpdir(dir, sizeof dir);
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const pf *c = &cases[i];
        e2e_write(dir, "p.csv", c->pts, path, sizeof path);
        char fl[128] = "";
        if (c->field) snprintf(fl, sizeof fl, "--field %s", c->field);
        snprintf(args, sizeof args, "probe " DIR "%s --points %s/p.csv %s %s", c->cfg, dir, fl,
                 c->sets);
        const int rc = e2e_dflab(dir, args);
        char *msg = e2e_err_text(dir);
        cr_expect_eq(rc, 0, "%s %s: %s", c->cfg, fl, msg);
        free(msg);
        snprintf(path, sizeof path, "%s/out.txt", dir);
        cr_expect_eq(e2e_csv_rows(path), (long)c->n, "%s %s", c->cfg, fl);
        for (int r = 0; r < c->n; r++) {
            const double v = e2e_csv_get(path, (size_t)r, "value");
            cr_expect(fabs(v - c->want[r]) <= 1e-12 * (1.0 + c->want[r]),
                      "%s %s row %d: %.17g, expected %.17g", c->cfg, fl, r, v, c->want[r]);
        }
    }
    /* a section the config does not have: exit 2, named */
    e2e_write(dir, "p.csv", "x,y\n0,0\n", path, sizeof path);
    snprintf(args, sizeof args,
             "probe " DIR "bs04_polygonization.ini --points %s/p.csv --field field_nope "
             "--set study.eps=1e-3", dir);
    cr_expect_eq(e2e_dflab(dir, args), 2);
    char *msg = e2e_err_text(dir);
    cr_expect(msg && strstr(msg, "[field_nope]"), "%s", msg ? msg : "(none)");
    free(msg);
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

/* The runner checks the probe's sections (experiments/harness/probe.h):
 * a valid [field_NAME] the study never reads runs; a typo in one, or a
 * field it cannot build, is exit 2 naming the key. */
Test(e2e_bs04_probe_configs, runner_checks_probe_sections, .timeout = 120)
{
    char dir[256], args[1600];
    e2e_tmpdir(dir, sizeof dir);
    static const char *const base =
        "run configs/smoke/smoke.ini --quiet --set grid.n=9 --set field_extra.kind=rfunc "
        "--set 'field_extra.vertices=0 0; 1 0'";
    snprintf(args, sizeof args, "%s --out %s/a", base, dir);
    cr_expect_eq(e2e_dflab(dir, args), 0, "%s", args);
    snprintf(args, sizeof args, "%s --out %s/b --set field_extra.typo=1", base, dir);
    cr_expect_eq(e2e_dflab(dir, args), 2, "%s", args);
    char *msg = e2e_err_text(dir);
    cr_expect(msg && strstr(msg, "typo") && strstr(msg, "field_extra"), "%s", msg ? msg : "");
    free(msg);
    snprintf(args, sizeof args, "%s --out %s/c --set field_extra.join=nope", base, dir);
    cr_expect_eq(e2e_dflab(dir, args), 2, "%s", args);
    cr_expect_eq(e2e_rmtree(dir), 0);
}
