/* Hermite data of SDFs (pht/hermite.c) against central finite differences of
 * the exact SDF: circle and a closed B-spline curve in 2D; sphere, the
 * analytic torus and the implicit torus (robust footpoints) in 3D; plus the
 * rejection of shapes without derivatives or without a sign. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "geom/curve_fixtures.h"
#include "geom/ellipse.h"
#include "geom/implicit.h"
#include "geom/param_shape.h"
#include "pht/hermite.h"

static double sd(const dfl_shape *s, const double *x) { return dfl_shape_eval1(s, x, NULL); }

/* Central differences of d for mask b at x with step h:
 * sum over the 2^|b| sign patterns of the signed stencil / (2h)^|b|. */
static double fd(const dfl_shape *s, const double *x, int b, double h)
{
    int axes[3], n = 0;
    for (int j = 0; j < s->dim; j++)
        if (b >> j & 1) axes[n++] = j;
    if (n == 0) return sd(s, x);
    double acc = 0.0;
    for (int p = 0; p < (1 << n); p++) {
        double y[3] = {x[0], x[1], s->dim == 3 ? x[2] : 0}, sign = 1.0;
        for (int i = 0; i < n; i++) {
            int plus = (p >> i) & 1;
            y[axes[i]] += plus ? h : -h;
            if (!plus) sign = -sign;
        }
        acc += sign * sd(s, y);
    }
    return acc / pow(2 * h, n);
}

/* Data at m random points of [lo, hi]^dim whose |d| is in [dmin, dmax] and
 * which are farther than rmin from the point avoid (a medial point), against
 * finite differences; tolerance tol per derivative order. */
static void check_shape(const dfl_shape *s, double lo, double hi, double dmin, double dmax,
                        const double *avoid, double rmin, int m, const double *tol)
{
    dfl_pht_source *src;
    dfl_err err;
    cr_assert_eq(dfl_pht_source_new(s, &src, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_pht_source_dim(src), s->dim);
    int nd = DFL_PHT_NDATA(s->dim), got = 0;
    uint64_t seed = 99;
    /* bounded: a bug that rejects every point fails below, not hangs */
    for (long tries = 0; got < m; tries++) {
        cr_assert_lt(tries, 100000L * m, "%s: only %d of %d points accepted", s->ops->kind, got, m);
        double x[3];
        for (int j = 0; j < s->dim; j++) x[j] = dfl_rng_splitmix(&seed, lo, hi);
        double d = sd(s, x), r = 0;
        for (int j = 0; avoid && j < s->dim; j++) r += (x[j] - avoid[j]) * (x[j] - avoid[j]);
        if (fabs(d) < dmin || fabs(d) > dmax || (avoid && sqrt(r) < rmin)) continue;
        got++;
        double data[8];
        int flags;
        cr_assert_eq(dfl_pht_hermite(src, x, data, &flags, &err), DFL_OK, "%s", err.msg);
        for (int b = 0; b < nd; b++) {
            int order = __builtin_popcount((unsigned)b);
            double h = order <= 1 ? 1e-5 : order == 2 ? 1e-4 : 1e-3;
            /* Richardson: the O(h^2) error of the central stencil cancels */
            double ref = order >= 2 ? (4 * fd(s, x, b, h / 2) - fd(s, x, b, h)) / 3 : fd(s, x, b, h);
            cr_assert(fabs(data[b] - ref) <= tol[order] * (1 + fabs(ref)),
                      "%s at (%g %g %g) mask %d: %.12g vs fd %.12g", s->ops->kind, x[0], x[1],
                      s->dim == 3 ? x[2] : 0.0, b, data[b], ref);
        }
    }
    dfl_pht_source_free(src);
}

static const double TOL[4] = {1e-14, 1e-8, 1e-5, 1e-4};

Test(pht_hermite, circle_matches_finite_differences)
{
    dfl_shape s;
    const double c[2] = {0.5, 0.5};
    cr_assert_eq(dfl_shape_circle(c, 0.3, &s, NULL), DFL_OK);
    check_shape(&s, 0, 1, 0.01, 1, c, 0.1, 40, TOL);
    /* dflab sign: negative inside, the paper's is positive */
    dfl_pht_source *src;
    cr_assert_eq(dfl_pht_source_new(&s, &src, NULL), DFL_OK);
    double data[4], x[2] = {0.6, 0.5};
    cr_assert_eq(dfl_pht_hermite(src, x, data, NULL, NULL), DFL_OK);
    cr_assert(fabs(data[0] + 0.2) < 1e-15 && fabs(data[1] - 1) < 1e-15 && fabs(data[3]) < 1e-15);
    dfl_pht_source_free(src);
    dfl_shape_free(&s);
}

Test(pht_hermite, closed_bspline_curve_matches_finite_differences)
{
    dfl_bspline c;
    cf_make_blob(&c);
    dfl_shape s;
    cr_assert_eq(dfl_shape_param_curve(&c, NULL, 1, &s, NULL), DFL_OK);
    /* the blob's medial axis is on the x axis inside: stay off it by |y| > 0.1 */
    dfl_pht_source *src;
    cr_assert_eq(dfl_pht_source_new(&s, &src, NULL), DFL_OK);
    int got = 0;
    uint64_t seed = 3;
    /* bounded: a bug that rejects every point fails, not hangs */
    for (long tries = 0; got < 25; tries++) {
        cr_assert_lt(tries, 100000L, "blob: only %d of 25 points accepted", got);
        double x[2] = {dfl_rng_splitmix(&seed, -2, 2), dfl_rng_splitmix(&seed, -2, 2)};
        double d = sd(&s, x);
        if (fabs(x[1]) < 0.15 || fabs(d) < 0.02 || d < -0.5 || d > 0.3) continue;
        double data[4];
        cr_assert_eq(dfl_pht_hermite(src, x, data, NULL, NULL), DFL_OK);
        for (int b = 0; b < 4; b++) {
            double ref = fd(&s, x, b, b == 3 ? 1e-4 : 1e-6);
            cr_assert(fabs(data[b] - ref) <= (b == 3 ? 1e-5 : 1e-8) * (1 + fabs(ref)),
                      "blob at (%g, %g) mask %d: %.12g vs %.12g", x[0], x[1], b, data[b], ref);
        }
        got++;
    }
    dfl_pht_source_free(src);
    dfl_shape_free(&s);
}

Test(pht_hermite, sphere_and_analytic_torus_match_finite_differences)
{
    dfl_shape s;
    const double c[3] = {0.5, 0.5, 0.5}, ax[3] = {0, 0, 1};
    cr_assert_eq(dfl_shape_sphere(c, 0.3, &s, NULL), DFL_OK);
    check_shape(&s, 0, 1, 0.01, 1, c, 0.1, 20, TOL);
    dfl_shape_free(&s);
    cr_assert_eq(dfl_shape_torus(c, ax, 0.3, 0.1, &s, NULL), DFL_OK);
    /* off the torus' core circle (medial) and axis: |d| in [0.02, 0.08] */
    check_shape(&s, 0, 1, 0.02, 0.08, NULL, 0, 20, TOL);
    dfl_shape_free(&s);
}

Test(pht_hermite, implicit_torus_matches_finite_differences)
{
    dfl_implicit *imp;
    const double c[3] = {0.5, 0.5, 0.5}, ax[3] = {0, 0, 1};
    cr_assert_eq(dfl_implicit_torus(c, ax, 0.3, 0.1, NULL, &imp, NULL), DFL_OK);
    dfl_shape s;
    cr_assert_eq(dfl_implicit_shape(&imp, &s, NULL), DFL_OK);
    const double tol[4] = {1e-12, 1e-7, 1e-5, 1e-4};
    check_shape(&s, 0, 1, 0.02, 0.08, NULL, 0, 10, tol);
    dfl_shape_free(&s);
}

Test(pht_hermite, rejects_shapes_without_derivatives_or_sign)
{
    dfl_shape s;
    dfl_pht_source *src = NULL;
    dfl_err err;
    const double a[2] = {0, 0}, b[2] = {1, 0};
    cr_assert_eq(dfl_shape_segment(2, a, b, &s, NULL), DFL_OK);
    cr_assert_eq(dfl_pht_source_new(&s, &src, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "unsigned"), "%s", err.msg);
    dfl_shape_free(&s);
    cr_assert_eq(dfl_shape_ellipse(a, 2.0, 1.0, &s, NULL), DFL_OK);
    cr_assert_eq(dfl_pht_source_new(&s, &src, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "no SDF derivatives"), "%s", err.msg);
    dfl_shape_free(&s);
    cr_assert_null(src);
}

/* hermite.h: where the footpoint ties (a point of the torus' axis: the
 * whole circle of the tube's nearest points is a footpoint; the implicit
 * surface reports the tie) dfl_pht_hermite still returns DFL_OK with the
 * FALLBACK data and flags the point MEDIAL (it is on the medial axis):
 * value d = sqrt(R^2 + z^2) - r at height z above the centre, the mixed
 * derivatives 0. */
Test(pht_hermite, torus_axis_is_flagged_medial_fallback)
{
    dfl_implicit *imp;
    const double c[3] = {0.5, 0.5, 0.5}, ax[3] = {0, 0, 1};
    cr_assert_eq(dfl_implicit_torus(c, ax, 0.3, 0.1, NULL, &imp, NULL), DFL_OK);
    dfl_shape s;
    cr_assert_eq(dfl_implicit_shape(&imp, &s, NULL), DFL_OK);
    dfl_pht_source *src;
    dfl_err err;
    cr_assert_eq(dfl_pht_source_new(&s, &src, &err), DFL_OK, "%s", err.msg);
    const double z = 0.05, x[3] = {c[0], c[1], c[2] + z};
    double data[8];
    int flags = 0;
    cr_assert_eq(dfl_pht_hermite(src, x, data, &flags, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(flags, DFL_PHT_HERMITE_FALLBACK | DFL_PHT_HERMITE_MEDIAL);
    cr_expect_float_eq(data[0], sqrt(0.3 * 0.3 + z * z) - 0.1, 1e-9);
    for (int b = 3; b < 8; b++)
        if (b != 4) cr_expect_eq(data[b], 0.0, "mask %d: mixed derivatives of the fallback", b);
    dfl_pht_source_free(src);
    dfl_shape_free(&s);
}
