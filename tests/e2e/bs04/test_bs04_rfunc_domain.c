/* The rfunc fields' domain of validity through the real binary
 * (rfunc/domain.h): points and geometry beyond it, degenerate polylines and
 * bad jet directions exit 2 with one error line naming the point, vertex or
 * key and nothing on stdout; large finite coordinates inside it give
 * finite values equal, by homogeneity, to the scaled small case; and
 * `correction = eq20` is NaN exactly where bs04's radicand is <= 0. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/e2e_util.h"

static const char *const base =
    "[field]\nkind = rfunc\nvertices = 1 0; 0 0; 0 1\njoin = requiv_corrected\np = 2\n";

/* Runs probe on f.ini (base) with the points text and extra options;
 * returns the exit status, stdout into *out and stderr into *msg (malloc'ed). */
static int probe(const char *dir, const char *pts, const char *extra, char **out, char **msg)
{
    char path[600], args[2048];
    e2e_write(dir, "f.ini", base, path, sizeof path);
    e2e_write(dir, "p.csv", pts, path, sizeof path);
    snprintf(args, sizeof args, "probe %s/f.ini --points %s/p.csv %s", dir, dir, extra);
    const int rc = e2e_dflab(dir, args);
    snprintf(path, sizeof path, "%s/out.txt", dir);
    *out = e2e_slurp(path);
    *msg = e2e_err_text(dir);
    return rc;
}

typedef struct bad_case {
    const char *pts, *extra, *want;
} bad_case;

Test(e2e_bs04_rfunc_domain, bad_inputs_exit_2_naming_what, .timeout = 60)
{
    static const bad_case cases[] = {
        /* issue: --jet at 1e78 aborted (134), at 1e77 exited 1 */
        {"x,y,dx,dy\n1e78,0.5,1,0\n", "--jet 2", "point 1: point (1e+78"},
        {"x,y,dx,dy\n1e77,0.5,1,0\n", "--jet 2", "for exact derivatives"},
        {"x,y,dx,dy\n1e31,0.5,1,0\n", "--jet 1", "|x| <= 1e+30"},
        /* issue: x = 1e155 printed -nan (refused by dflab's coordinate
         * range, core/domain.h, before the rfunc domain) */
        {"x,y\n1e155,0\n", "", "point 1: coordinate x = 1e+155 is outside"},
        {"x,y\n0,0\n1,-1e101\n", "", "point 2: point (1, -9.99"},
        /* zero and non-finite jet directions */
        {"x,y,dx,dy\n0.5,0.5,0,0\n", "--jet 2", "jet direction is zero"},
        {"x,y,dx,dy\n0.5,0.5,1e-40,0\n", "--jet 2", "jet direction of size"},
        /* issue: -1e200 0; 1e200 0 gave 0 at (0.5, 0.5) */
        {"x,y\n0.5,0.5\n", "--set 'field.vertices=-1e200 0; 1e200 0'",
         "field.vertices: point 1: expected 2 numbers, got '-1e200 0'"},
        /* issue: a segment of length 1e-160 gave an infinite gradient */
        {"x,y\n0.5,0.5\n", "--set 'field.vertices=0 0; 1e-160 0'", "segment of length"},
        /* degenerate parts */
        {"x,y\n0.5,0.5\n", "--set 'field.vertices=0 0; 1 0; 0 0'",
         "at vertex 2 it turns back on itself"},
        {"x,y\n0.5,0.5\n", "--set 'field.vertices=0 0; 1 1; 0.5 0.5; 2 0'",
         "at vertex 2 it turns back on itself"},
        {"x,y\n0.5,0.5\n", "--set 'field.vertices=0 0; 1e-13 0; 1 1'",
         "segment 1 (vertices 1 and 2) has length 1e-13"},
        /* a closed polyline with no area turns back at its extreme vertices */
        {"x,y\n0.5,0.5\n", "--set 'field.vertices=0 0; 2 0; 1 1e-14' --set field.closed=true",
         "at vertex 1 it turns back on itself"},
        {"x,y\n0.5,0.5\n", "--set field.correction=eq21", "correction"},
    };
    char dir[256];
    e2e_tmpdir(dir, sizeof dir);
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char *out, *msg;
        const int rc = probe(dir, cases[i].pts, cases[i].extra, &out, &msg);
        cr_expect_eq(rc, 2, "case %zu (%s): exit %d, %s", i, cases[i].extra, rc, msg);
        cr_expect(out && out[0] == '\0', "case %zu: stdout not empty: %s", i, out);
        cr_expect(msg && strstr(msg, cases[i].want), "case %zu: '%s' not in '%s'", i,
                  cases[i].want, msg);
        cr_expect(msg && strchr(msg, '\n') == msg + strlen(msg) - 1, "case %zu: not one line: %s",
                  i, msg);
        free(out);
        free(msg);
    }
    cr_expect_eq(e2e_rmtree(dir), 0);
}

/* R-equivalence of eq. 4 (non-smooth) trims is homogeneous of degree 1:
 * u(l x; l V) = l u(x; V).  With l = 2^300 (exact scaling) the large case
 * must be finite and equal l times the unit case (the scaled forms near the
 * domain's edge round differently, so to 1e-13). */
Test(e2e_bs04_rfunc_domain, large_coordinates_are_scaled_copies, .timeout = 60)
{
    char dir[256], path[600], args[2048];
    e2e_tmpdir(dir, sizeof dir);
    const double l = ldexp(1.0, 300); /* 2e90 */
    static const char *const trims[] = {"disk", "strip"};
    static const char *const joins[] = {"requiv", "rconj", "requiv_corrected"};
    const double x[2] = {-0.3, 2.5};
    for (int t = 0; t < 2; t++)
        for (int j = 0; j < 3; j++) {
            double v[2], g[2][2];
            for (int s = 0; s < 2; s++) {
                const double k = s ? l : 1.0;
                char ini[512], pts[256];
                snprintf(ini, sizeof ini,
                         "[field]\nkind = rfunc\nvertices = %.17g 0; 0 0; 0 %.17g\njoin = %s\n"
                         "trim = %s\np = 3\n",
                         k, k, joins[j], trims[t]);
                e2e_write(dir, "f.ini", ini, path, sizeof path);
                snprintf(pts, sizeof pts, "x,y\n%.17g,%.17g\n", k * x[0], k * x[1]);
                e2e_write(dir, "p.csv", pts, path, sizeof path);
                snprintf(args, sizeof args, "probe %s/f.ini --points %s/p.csv", dir, dir);
                cr_assert_eq(e2e_dflab(dir, args), 0);
                snprintf(path, sizeof path, "%s/out.txt", dir);
                v[s] = e2e_csv_get(path, 0, "value");
                g[s][0] = e2e_csv_get(path, 0, "gx");
                g[s][1] = e2e_csv_get(path, 0, "gy");
            }
            cr_expect(isfinite(v[1]) && isfinite(g[1][0]) && isfinite(g[1][1]));
            cr_expect(fabs(v[1] / l - v[0]) <= 1e-13 * v[0], "%s %s: %.17g vs %.17g", trims[t],
                      joins[j], v[1] / l, v[0]);
            for (int c = 0; c < 2; c++)
                cr_expect(fabs(g[1][c] - g[0][c]) <= 1e-13 * (fabs(g[0][0]) + fabs(g[0][1])),
                          "%s %s: gradient %d %.17g vs %.17g", trims[t], joins[j], c, g[1][c],
                          g[0][c]);
        }
    cr_expect_eq(e2e_rmtree(dir), 0);
}

/* correction = eq20 through the binary: at points of the hatched sector of
 * the right-angle vertex (x, y < 0) the disk trim gives, in closed form
 * (rfunc/join.h), h_i = q sqrt(1 + 2 a_i r + r^2) with r = q/L, a_i the
 * cosines of the angles from -e_i; on the bisector the radicand is 0 at
 * r* = sqrt(cos^2 45 + 2^(2/p) - 1) - cos 45 (0.517638 for p = 2): the value
 * there is u = q (2 (1 + 2 a r + r^2)^(-1) - 1)^(-1/2) inside and NaN
 * beyond, and guarded is finite everywhere. */
Test(e2e_bs04_rfunc_domain, eq20_nan_exactly_beyond_onset, .timeout = 60)
{
    char dir[256];
    e2e_tmpdir(dir, sizeof dir);
    const double a = sqrt(0.5), rs = sqrt(0.5 + 1.0) - a;
    const double rr[4] = {0.3, 0.5, 0.54, 0.9};
    char pts[512];
    int o = snprintf(pts, sizeof pts, "x,y\n");
    for (int i = 0; i < 4; i++)
        o += snprintf(pts + o, sizeof pts - (size_t)o, "%.17g,%.17g\n", -rr[i] * a, -rr[i] * a);
    for (int c = 0; c < 2; c++) {
        char *out, *msg;
        const int rc = probe(dir, pts, c ? "--set field.correction=eq20" : "", &out, &msg);
        cr_assert_eq(rc, 0, "%s", msg);
        char path[600];
        snprintf(path, sizeof path, "%s/out.txt", dir);
        for (int i = 0; i < 4; i++) {
            const double u = e2e_csv_get(path, (size_t)i, "value");
            if (!c) {
                cr_expect(isfinite(u));
                continue;
            }
            const double r = rr[i], H = 1.0 + 2.0 * a * r + r * r, R = 2.0 / H - 1.0;
            if (r < rs) cr_expect(fabs(u - r / sqrt(R)) <= 1e-13 * u, "r %g: %.17g", r, u);
            else cr_expect(isnan(u), "r %g beyond r* = %g: %.17g", r, rs, u);
        }
        free(out);
        free(msg);
    }
    cr_expect_eq(e2e_rmtree(dir), 0);
}
