/* Exact segment distances and their R-function polylines (experiments/
 * segdist.h).  Expected values: brute-force minimization over the segment,
 * the join formulas evaluated directly with pow(), central differences, and
 * the closed forms of eq. 20 in the hatched sector. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "geom/segdist.h"

static double urand(uint64_t *s, double lo, double hi)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return lo + (hi - lo) * ((double)(z >> 11) * 0x1.0p-53);
}

/* min over t of |x - (a + t (b - a))|: dense scan, then ternary search
 * (the squared distance is convex in t). */
static double brute(int dim, const double *a, const double *b, const double *x)
{
    double best = INFINITY, tb = 0;
    for (int k = 0; k <= 2000; k++) {
        double t = k / 2000.0, s = 0;
        for (int j = 0; j < dim; j++) {
            double c = a[j] + t * (b[j] - a[j]) - x[j];
            s += c * c;
        }
        if (s < best) best = s, tb = t;
    }
    double lo = fmax(0, tb - 1e-3), hi = fmin(1, tb + 1e-3);
    for (int it = 0; it < 200; it++) {
        double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3, s1 = 0, s2 = 0;
        for (int j = 0; j < dim; j++) {
            double c1 = a[j] + m1 * (b[j] - a[j]) - x[j], c2 = a[j] + m2 * (b[j] - a[j]) - x[j];
            s1 += c1 * c1;
            s2 += c2 * c2;
        }
        if (s1 < s2) hi = m2;
        else lo = m1;
    }
    double t = 0.5 * (lo + hi), s = 0;
    for (int j = 0; j < dim; j++) {
        double c = a[j] + t * (b[j] - a[j]) - x[j];
        s += c * c;
    }
    return sqrt(fmin(s, best));
}

Test(segdist, distance_matches_brute_force_and_gradient_fd)
{
    uint64_t seed = 7;
    for (int dim = 2; dim <= 3; dim++)
        for (int it = 0; it < 300; it++) {
            double a[3], b[3], x[3], g[3];
            for (int j = 0; j < dim; j++) {
                a[j] = urand(&seed, -1, 1);
                b[j] = urand(&seed, -1, 1);
                x[j] = urand(&seed, -2, 2);
            }
            double d = dfl_segdist_eval(dim, a, b, x, g);
            cr_assert_float_eq(d, brute(dim, a, b, x), 1e-12, "dim %d it %d", dim, it);
            double gn = 0;
            for (int j = 0; j < dim; j++) {
                double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]};
                xp[j] += 1e-6;
                xm[j] -= 1e-6;
                double fd = (dfl_segdist_eval(dim, a, b, xp, NULL) -
                             dfl_segdist_eval(dim, a, b, xm, NULL)) / (xp[j] - xm[j]);
                cr_expect_float_eq(g[j], fd, 1e-7, "dim %d it %d comp %d", dim, it, j);
                gn += g[j] * g[j];
            }
            cr_expect_float_eq(sqrt(gn), 1.0, 1e-14);
        }
}

Test(segdist, end_point_branch_is_the_vertex_distance_bit_for_bit)
{
    const double a[2] = {0.3, -0.2}, b[2] = {1.1, 0.7};
    uint64_t seed = 3;
    int hits = 0;
    for (int it = 0; it < 1000; it++) {
        double x[2] = {urand(&seed, -2, 2), urand(&seed, -2, 2)};
        if (!dfl_segdist_closest_is_start(2, a, b, x)) continue;
        hits++;
        double w0 = x[0] - a[0], w1 = x[1] - a[1];
        cr_assert_eq(dfl_segdist_eval(2, a, b, x, NULL), sqrt(w0 * w0 + w1 * w1));
        /* and the test is the sign of (x - a) . (b - a) */
        cr_assert(w0 * (b[0] - a[0]) + w1 * (b[1] - a[1]) <= 0);
    }
    cr_assert(hits > 100);
    /* on the segment: distance and gradient 0 */
    double m[2] = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])}, g[2] = {1, 1};
    cr_expect(dfl_segdist_eval(2, a, b, m, g) < 1e-16);
    /* a degenerate segment is a point */
    double x[2] = {1, 1};
    cr_expect_float_eq(dfl_segdist_eval(2, a, a, x, NULL), hypot(0.7, 1.2), 1e-15);
}

static double fd_norm(const dfl_field *f, const double *x, double h)
{
    double g[2];
    for (int j = 0; j < 2; j++) {
        double xp[2] = {x[0], x[1]}, xm[2] = {x[0], x[1]};
        xp[j] += h;
        xm[j] -= h;
        g[j] = (dfl_field_eval1(f, xp, NULL) - dfl_field_eval1(f, xm, NULL)) / (xp[j] - xm[j]);
    }
    return hypot(g[0], g[1]);
}

Test(segdist, one_segment_polyline_is_the_segment_distance)
{
    const double v[4] = {0.2, 0.1, 0.9, -0.4};
    const dfl_rfunc_join joins[3] = {DFL_RFUNC_REQUIV, DFL_RFUNC_RCONJ, DFL_RFUNC_REQUIV_CORRECTED};
    uint64_t seed = 11;
    for (int j = 0; j < 3; j++) {
        dfl_field f;
        dfl_err err;
        cr_assert_eq(dfl_segdist_polyline_field(2, v, 2, joins[j], 3, &f, &err), DFL_OK, "%s",
                     err.msg);
        for (int it = 0; it < 100; it++) {
            double x[2] = {urand(&seed, -1, 2), urand(&seed, -1, 1)}, g[2], gs[2];
            double u = dfl_field_eval1(&f, x, g);
            double h = dfl_segdist_eval(2, v, v + 2, x, gs);
            cr_assert_eq(u, h);
            cr_assert_eq(g[0], gs[0]);
            cr_assert_eq(g[1], gs[1]);
        }
        dfl_field_destroy(&f);
    }
}

/* Two segments O-P1, O-P2 (polyline P1, O, P2) at 90 degrees. */
Test(segdist, joins_match_their_formulas_and_fd)
{
    const double v[6] = {1, 0, 0, 0, 0, 1};
    const int ps[3] = {2, 7, 12};
    uint64_t seed = 5;
    for (int ip = 0; ip < 3; ip++) {
        const int p = ps[ip];
        dfl_field fe, fc, fr;
        cr_assert_eq(dfl_segdist_polyline_field(2, v, 3, DFL_RFUNC_REQUIV, p, &fe, NULL), DFL_OK);
        cr_assert_eq(dfl_segdist_polyline_field(2, v, 3, DFL_RFUNC_REQUIV_CORRECTED, p, &fc, NULL),
                     DFL_OK);
        cr_assert_eq(dfl_segdist_polyline_field(2, v, 3, DFL_RFUNC_RCONJ, p, &fr, NULL), DFL_OK);
        for (int it = 0; it < 300; it++) {
            double x[2] = {urand(&seed, -1.5, 1.5), urand(&seed, -1.5, 1.5)}, g[2];
            double h1 = dfl_segdist_eval(2, v, v + 2, x, NULL);
            double h2 = dfl_segdist_eval(2, v + 2, v + 4, x, NULL);
            double q = hypot(x[0], x[1]);
            if (h1 < 1e-3 || h2 < 1e-3) continue;
            /* eq. 6 */
            double ue = pow(pow(h1, -p) + pow(h2, -p), -1.0 / p);
            cr_expect_float_eq(dfl_field_eval1(&fe, x, g), ue, 1e-13 * ue, "p %d", p);
            cr_expect_float_eq(hypot(g[0], g[1]), fd_norm(&fe, x, 1e-6), 1e-6);
            /* eq. 7 */
            double ur = h1 + h2 - pow(pow(h1, p) + pow(h2, p), 1.0 / p);
            cr_expect_float_eq(dfl_field_eval1(&fr, x, g), ur, 1e-12, "p %d", p);
            cr_expect_float_eq(hypot(g[0], g[1]), fd_norm(&fr, x, 1e-6), 1e-6);
            /* eq. 20 (exact distances: the guard never binds) */
            double uc = pow(pow(h1, -p) + pow(h2, -p) - pow(q, -p), -1.0 / p);
            double u = dfl_field_eval1(&fc, x, g);
            cr_expect_float_eq(u, uc, 1e-12 * uc, "p %d x %g %g", p, x[0], x[1]);
            /* hatched sector: u = q exactly, |grad u| = 1; where one
             * closest point is the vertex: u = the other distance */
            if (x[0] <= 0 && x[1] <= 0) {
                cr_expect_float_eq(u, q, 1e-15 * q);
                cr_expect_float_eq(hypot(g[0], g[1]), 1.0, 1e-14);
            } else if (x[0] <= 0 || x[1] <= 0) {
                cr_expect_float_eq(u, fmin(h1, h2), 1e-14 * u, "x %g %g", x[0], x[1]);
            }
        }
        dfl_field_destroy(&fe);
        dfl_field_destroy(&fc);
        dfl_field_destroy(&fr);
    }
}

Test(segdist, bad_input)
{
    dfl_field f;
    dfl_err err;
    const double v[6] = {0, 0, 1, 1, 1, 1};
    cr_expect_eq(dfl_segdist_polyline_field(2, v, 1, DFL_RFUNC_REQUIV, 2, &f, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_segdist_polyline_field(2, v, 3, DFL_RFUNC_REQUIV, 2, &f, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "coincide") != NULL, "%s", err.msg);
    cr_expect_eq(dfl_segdist_polyline_field(4, v, 2, DFL_RFUNC_REQUIV, 2, &f, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_segdist_polyline_field(2, v, 2, DFL_RFUNC_RCONJ, 1, &f, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_segdist_polyline_field(2, v, 2, DFL_RFUNC_REQUIV, 0, &f, &err), DFL_E_INPUT);
    const double w[4] = {0, NAN, 1, 1};
    cr_expect_eq(dfl_segdist_polyline_field(2, w, 2, DFL_RFUNC_REQUIV, 2, &f, &err), DFL_E_INPUT);
    /* no jets */
    const double s[4] = {0, 0, 1, 0};
    cr_assert_eq(dfl_segdist_polyline_field(2, s, 2, DFL_RFUNC_REQUIV, 2, &f, &err), DFL_OK);
    dfl_jet j;
    const double x[2] = {0.5, 0.5}, dir[2] = {0, 1};
    cr_expect_eq(dfl_field_jet(&f, x, dir, 2, &j, &err), DFL_E_INPUT);
    dfl_field_destroy(&f);
}
