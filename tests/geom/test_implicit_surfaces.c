/* The named implicit surfaces (implicit_surfaces.c): Goursat's and the
 * genus-2 surface against a dense brute-force sampling of the zero set made
 * here by bisection on sign changes along grid lines (independent of the
 * solver's own projected samples), and their parameter checks. */
#include <stdlib.h>
#include <string.h>

#include "geom/implicit_fixtures.h"

/* ---- brute force over the zero set ----------------------------------- */

typedef struct cloud {
    size_t n, cap;
    double *p;
} cloud;

static void cloud_add(cloud *c, const double p[3])
{
    if (c->n == c->cap) {
        c->cap = c->cap ? 2 * c->cap : 4096;
        c->p = realloc(c->p, c->cap * 3 * sizeof *c->p);
        cr_assert_not_null(c->p);
    }
    memcpy(c->p + 3 * c->n++, p, 3 * sizeof *p);
}

/* Roots of g along all grid lines (three directions) of a grid of spacing
 * about hb over [lo, hi], by bisection to 1e-13. */
static cloud zero_set(const dfl_implicit *s, const double lo[3], const double hi[3], double hb)
{
    cloud c = {0, 0, NULL};
    int n[3];
    for (int a = 0; a < 3; a++) n[a] = (int)ceil((hi[a] - lo[a]) / hb);
    for (int ax = 0; ax < 3; ax++) {
        int a1 = (ax + 1) % 3, a2 = (ax + 2) % 3;
        double step = (hi[ax] - lo[ax]) / n[ax];
        for (int i = 0; i <= n[a1]; i++)
            for (int j = 0; j <= n[a2]; j++) {
                double p[3];
                p[a1] = lo[a1] + (hi[a1] - lo[a1]) * i / n[a1];
                p[a2] = lo[a2] + (hi[a2] - lo[a2]) * j / n[a2];
                p[ax] = lo[ax];
                double gprev = dfl_implicit_g(s, p, NULL, NULL);
                for (int k = 1; k <= n[ax]; k++) {
                    double q[3] = {p[0], p[1], p[2]};
                    q[ax] = lo[ax] + step * k;
                    double g = dfl_implicit_g(s, q, NULL, NULL);
                    if ((g < 0) != (gprev < 0)) {
                        double a = q[ax] - step, b = q[ax], ga = gprev;
                        while (b - a > 1e-13) {
                            double m = 0.5 * (a + b);
                            q[ax] = m;
                            double gm = dfl_implicit_g(s, q, NULL, NULL);
                            if ((gm < 0) == (ga < 0)) { a = m; ga = gm; } else b = m;
                        }
                        q[ax] = 0.5 * (a + b);
                        cloud_add(&c, q);
                    }
                    gprev = g;
                }
            }
    }
    return c;
}

static void check_against_cloud(const dfl_implicit *s, const double lo[3], const double hi[3],
                                double hb, int npts)
{
    cloud c = zero_set(s, lo, hi, hb);
    cr_assert(c.n > 1000);
    double worst_excess = 0;
    for (int t = 0; t < npts; t++) {
        double x[3];
        for (int a = 0; a < 3; a++) {
            double m = 0.5 * (lo[a] + hi[a]), r = 0.75 * (hi[a] - lo[a]);
            x[a] = urand(m - r, m + r);
        }
        dfl_footpoint f;
        dfl_err err;
        cr_assert_eq(dfl_implicit_footpoint(s, x, &f, &err), DFL_OK, "%s", err.msg);
        double best = HUGE_VAL;
        for (size_t i = 0; i < c.n; i++) {
            double u[3] = {x[0] - c.p[3 * i], x[1] - c.p[3 * i + 1], x[2] - c.p[3 * i + 2]};
            best = fmin(best, dfl_vec3_dot(u, u));
        }
        best = sqrt(best);
        /* the solver's footpoint is on the surface, so no sample can be
         * closer; and the true footpoint has a sample within ~hb */
        cr_assert(best >= fabs(f.d) - 1e-12, "x (%g %g %g): sample closer (%.17g) than solver (%.17g)",
                  x[0], x[1], x[2], best, fabs(f.d));
        cr_assert(best - fabs(f.d) <= 2 * hb, "x (%g %g %g): solver %.17g, samples %.17g",
                  x[0], x[1], x[2], fabs(f.d), best);
        worst_excess = fmax(worst_excess, best - fabs(f.d));
        double g = dfl_implicit_g(s, x, NULL, NULL);
        cr_assert(g == 0 || (g < 0) == (f.d < 0));
        cr_assert(fabs(dfl_implicit_g(s, f.p, NULL, NULL)) < 1e-10);
    }
    cr_log_info("cloud of %zu points, spacing %.3g: max sample excess %.3g", c.n, hb, worst_excess);
    free(c.p);
}

Test(implicit_surfaces, goursat_distance_matches_brute_force)
{
    const double c[3] = {0, 0, 0};
    dfl_implicit *s = NULL;
    dfl_err err;
    cr_assert_eq(dfl_implicit_goursat(c, 0, -5, 11.8, NULL, &s, &err), DFL_OK, "%s", err.msg);
    double lo[3] = {-2.5, -2.5, -2.5}, hi[3] = {2.5, 2.5, 2.5};
    check_against_cloud(s, lo, hi, 0.02, 100);
    dfl_implicit_free(s);
}

Test(implicit_surfaces, genus2_distance_matches_brute_force)
{
    const double c[3] = {0.1, 0, -0.1};
    dfl_implicit *s = NULL;
    dfl_err err;
    cr_assert_eq(dfl_implicit_genus2(c, 0.1, NULL, &s, &err), DFL_OK, "%s", err.msg);
    double lo[3] = {-1.2 + 0.1, -0.6, -0.12 - 0.1}, hi[3] = {1.2 + 0.1, 0.6, 0.12 - 0.1};
    check_against_cloud(s, lo, hi, 0.006, 100);
    dfl_implicit_free(s);
}

Test(implicit_surfaces, bad_input)
{
    dfl_implicit *s = NULL;
    dfl_err err;
    double c[3] = {0, 0, 0}, z[3] = {0, 0, 0};
    cr_assert_eq(dfl_implicit_torus(c, z, 1, 0.2, NULL, &s, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_implicit_torus(c, TAX, 0.2, 0.3, NULL, &s, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_implicit_genus2(c, 0.3, NULL, &s, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_implicit_goursat(c, -0.5, 0, -1, NULL, &s, &err), DFL_E_INPUT);
}

/* The sphere polynomial and the scrambled ellipsoid: the zero sets are the
 * closed forms', g < 0 inside, and neither g is a distance. */
Test(implicit_surfaces, sphere_and_scrambled_ellipsoid)
{
    const double c[3] = {0.1, 0, 0}, semi[3] = {0.7, 0.5, 0.35};
    dfl_implicit *s, *e;
    cr_assert_eq(dfl_implicit_sphere(c, 0.5, NULL, &s, NULL), DFL_OK);
    cr_assert_eq(dfl_implicit_ellipsoid(c, semi, 4, NULL, &e, NULL), DFL_OK);
    double G[3];
    double on[3] = {0.1 + 0.3, 0.4, 0};
    cr_assert(fabs(dfl_implicit_g(s, on, G, NULL)) < 1e-15);
    cr_assert(fabs(dfl_vec3_norm(G) - 1.0) < 1e-14); /* 2 |q| = 1 */
    double in[3] = {0.1, 0.1, 0.1};
    cr_assert(dfl_implicit_g(s, in, NULL, NULL) < 0 && dfl_implicit_g(e, in, NULL, NULL) < 0);
    double ex[3] = {0.1 + 0.7 * 0.6, 0.5 * 0.8, 0};
    cr_assert(fabs(dfl_implicit_g(e, ex, G, NULL)) < 1e-14);
    /* E's gradient at ex times the factor 1 + 4 (x^2 + y^4) */
    double qx = 0.42, qy = 0.4, phi = 1 + 4 * (qx * qx + qy * qy * qy * qy);
    cr_assert(fabs(G[0] - phi * 2 * qx / 0.49) < 1e-12 && fabs(G[1] - phi * 2 * qy / 0.25) < 1e-12);
    dfl_implicit_free(s);
    dfl_implicit_free(e);
    dfl_err err;
    dfl_implicit *t = NULL;
    cr_assert_eq(dfl_implicit_sphere(c, 0, NULL, &t, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_implicit_ellipsoid(c, semi, -1, NULL, &t, &err), DFL_E_INPUT);
    cr_assert_null(t);
}
