/* The point-segment distances of geom/segdist.h.  Expected values:
 * brute-force minimization over the segment, central differences, the
 * closed forms at the end points, and the formulas of the other callers
 * written out (the shape kind, the polygonization's checks). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "core/rng.h"
#include "geom/segdist.h"


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
                a[j] = dfl_rng_splitmix(&seed, -1, 1);
                b[j] = dfl_rng_splitmix(&seed, -1, 1);
                x[j] = dfl_rng_splitmix(&seed, -2, 2);
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
        double x[2] = {dfl_rng_splitmix(&seed, -2, 2), dfl_rng_splitmix(&seed, -2, 2)};
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

/* The clamped-projection member: brute force, the residual's meaning, and
 * the formula written out as the shape kind and the polygonization used it
 * before they called it (bit for bit). */
Test(segdist, residual_matches_brute_force_and_its_formula)
{
    uint64_t seed = 19;
    for (int dim = 1; dim <= 3; dim++)
        for (int it = 0; it < 300; it++) {
            double a[3] = {0, 0, 0}, b[3] = {0, 0, 0}, x[3] = {0, 0, 0}, e[3], r[3], ee = 0;
            for (int j = 0; j < dim; j++) {
                a[j] = dfl_rng_splitmix(&seed, -1, 1);
                b[j] = it % 10 == 0 ? a[j] : dfl_rng_splitmix(&seed, -1, 1);
                x[j] = dfl_rng_splitmix(&seed, -2, 2);
                e[j] = b[j] - a[j];
                ee += e[j] * e[j];
            }
            double d = dfl_segdist_residual(dim, a, e, ee, x, r);
            if (dim >= 2) cr_assert_float_eq(d, brute(dim, a, b, x), 1e-12, "dim %d it %d", dim, it);
            cr_assert_eq(dfl_point_segment_dist(dim, x, a, b), d);
            /* the formula: s = clamp((x - a).e / ee), r = (x - a) - s e */
            double we = 0, s, rr = 0;
            for (int j = 0; j < dim; j++) we += (x[j] - a[j]) * e[j];
            s = ee > 0 ? we / ee : 0;
            s = s < 0 ? 0 : (s > 1 ? 1 : s);
            for (int j = 0; j < dim; j++) {
                double w = (x[j] - a[j]) - s * e[j];
                cr_assert_eq(r[j], w, "dim %d it %d comp %d", dim, it, j);
                rr += w * w;
            }
            cr_assert_eq(d, sqrt(rr));
            /* x - r is on the segment */
            if (ee > 0 && dim >= 2) {
                double c[3];
                for (int j = 0; j < dim; j++) c[j] = x[j] - r[j];
                cr_assert(dfl_segdist_eval(dim, a, b, c, NULL) < 1e-15);
            }
        }
}

/* The two members differ only in rounding (end points, norm). */
Test(segdist, members_agree_to_rounding)
{
    uint64_t seed = 23;
    for (int dim = 2; dim <= 3; dim++)
        for (int it = 0; it < 500; it++) {
            double a[3], b[3], x[3];
            for (int j = 0; j < dim; j++) {
                a[j] = dfl_rng_splitmix(&seed, -1, 1);
                b[j] = dfl_rng_splitmix(&seed, -1, 1);
                x[j] = dfl_rng_splitmix(&seed, -2, 2);
            }
            double d1 = dfl_segdist_eval(dim, a, b, x, NULL);
            double d2 = dfl_point_segment_dist(dim, x, a, b);
            cr_assert(fabs(d1 - d2) <= 4e-16 * (1 + d1), "dim %d it %d: %.17g vs %.17g", dim, it,
                      d1, d2);
        }
}

/* The hypot member: bs04_fields' own formula written out (clamped
 * projection, hypot of x - a - l e) bit for bit, the brute force to
 * rounding, and a degenerate segment as the distance to its point. */
static double fields_formula(const double *a, const double *b, const double *x)
{
    const double ex = b[0] - a[0], ey = b[1] - a[1];
    double l = ((x[0] - a[0]) * ex + (x[1] - a[1]) * ey) / (ex * ex + ey * ey);
    l = l < 0 ? 0 : l > 1 ? 1 : l;
    return hypot(x[0] - a[0] - l * ex, x[1] - a[1] - l * ey);
}

Test(segdist, hypot_member_is_the_formula_bit_for_bit)
{
    uint64_t seed = 91;
    int differs = 0;
    for (int it = 0; it < 2000; it++) {
        double a[2], b[2], x[2];
        for (int j = 0; j < 2; j++) {
            a[j] = dfl_rng_splitmix(&seed, -1, 1);
            b[j] = dfl_rng_splitmix(&seed, -1, 1);
            x[j] = dfl_rng_splitmix(&seed, -2, 2);
        }
        const double d = dfl_point_segment_dist_hypot(x, a, b);
        cr_assert_eq(d, fields_formula(a, b, x), "it %d: %.17g vs %.17g", it, d,
                     fields_formula(a, b, x));
        cr_assert(fabs(d - brute(2, a, b, x)) <= 1e-12, "it %d", it);
        differs += d != dfl_point_segment_dist(2, x, a, b);
    }
    /* it is a rounding of its own, not another name for the sqrt member */
    cr_expect(differs > 0);
    /* exact cases: beyond each end, across the middle */
    const double a[2] = {0, 0}, b[2] = {4, 0};
    const double p1[2] = {-3, 4}, p2[2] = {7, -4}, p3[2] = {1.5, -2};
    cr_expect_eq(dfl_point_segment_dist_hypot(p1, a, b), 5.0);
    cr_expect_eq(dfl_point_segment_dist_hypot(p2, a, b), 5.0);
    cr_expect_eq(dfl_point_segment_dist_hypot(p3, a, b), 2.0);
    /* far beyond double range of squares: hypot does not overflow */
    const double big[2] = {1e200, 1e200}, o[2] = {0, 0}, e[2] = {1, 0};
    cr_expect_float_eq(dfl_point_segment_dist_hypot(big, o, e), sqrt(2.0) * 1e200, 1e186);
    /* a == b: the distance to the point */
    const double q[2] = {3, 4};
    cr_expect_eq(dfl_point_segment_dist_hypot(q, o, o), 5.0);
}

/* The header's rule is (x - a) . (b - a) <= 0: a point on the line through
 * a perpendicular to the segment (the dot product is exactly 0) and a
 * itself have a as their closest point, and so does the eval branch. */
Test(segdist, closest_is_start_includes_the_perpendicular_through_a)
{
    const double a2[2] = {1, 2}, b2[2] = {4, 2};
    const double perp2[2] = {1, 7}, on_a[2] = {1, 2}, past[2] = {1.5, -3};
    cr_expect(dfl_segdist_closest_is_start(2, a2, b2, perp2));
    cr_expect(dfl_segdist_closest_is_start(2, a2, b2, on_a));
    cr_expect(!dfl_segdist_closest_is_start(2, a2, b2, past));
    const double a3[3] = {0, 0, 0}, b3[3] = {0, 0, 2}, perp3[3] = {3, -4, 0};
    cr_expect(dfl_segdist_closest_is_start(3, a3, b3, perp3));
    cr_expect_eq(dfl_segdist_eval(3, a3, b3, perp3, NULL), 5.0);
}
