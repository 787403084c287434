/* Tests for field/gridpeer: exactness where the decoded polynomial can be
 * exact (a plane for every kind; every tensor cubic for tricubic),
 * interpolation at the cell centres, a closed-form value at a kink, float16
 * rounding bounds, gradients against finite differences, the tricubic
 * spline against an independent B-spline sum and against SciPy, and bad
 * input. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <Imath/half.h>

#include "core/rng.h"
#include "field/gridpeer.h"
#include "util/e2e_util.h"
#include "util/per_isa.h"
#include "util/tmpdir.h"

static dfl_gridpeer_opts opts(dfl_gridpeer_kind k, dfl_gridpeer_storage s, int n)
{
    dfl_gridpeer_opts o = {k, s, n, {-1, -1, -1}, {1, 1, 1}, 1};
    return o;
}

static void centre(const dfl_gridpeer_opts *o, int i, int j, int k, double x[3])
{
    const int c[3] = {i, j, k};
    for (int a = 0; a < 3; a++) x[a] = o->lo[a] + (c[a] + 0.5) * (o->hi[a] - o->lo[a]) / o->n;
}

Test(gridpeer, every_kind_is_exact_for_a_plane)
{
    const double p[3] = {0.1, -0.2, 0.3}, nrm[3] = {1, 2, -2};
    dfl_shape s;
    cr_assert_eq(dfl_shape_plane(3, p, nrm, &s, NULL), DFL_OK);
    uint64_t seed = 7;
    for (int k = 0; k < DFL_GRIDPEER_KIND_COUNT; k++) {
        dfl_gridpeer_opts o = opts((dfl_gridpeer_kind)k, DFL_GRIDPEER_FLOAT64, 5);
        dfl_field f;
        dfl_err err;
        cr_assert_eq(dfl_gridpeer_new(&s, &o, &f, &err), DFL_OK, "%s", err.msg);
        for (int t = 0; t < 200; t++) {
            /* inside the box and beyond it (extrapolated / boundary cell) */
            double x[3], g[3], ge[3];
            for (int a = 0; a < 3; a++) x[a] = dfl_rng_splitmix(&seed, -1.3, 1.3);
            const double u = dfl_field_eval1(&f, x, g);
            const double d = dfl_shape_eval1(&s, x, ge);
            /* tricubic: coefficients exact to a few (4) ulps of the largest
             * |d| (<= 2.5 here), summed with the extrapolated end piece's
             * weights: 0.75 cells beyond the last centre (t = -1.25) the
             * weights of the stored coefficients (ghost rule included) are
             * 5.72, -10.09, 7.27, -1.90 per axis, |sum| <= 25, so <= 25^3
             * in 3D */
            const double tol =
                k == DFL_GRIDPEER_TRICUBIC ? 4 * 0x1p-52 * 2.5 * 25 * 25 * 25 : 1e-14;
            cr_assert(fabs(u - d) < tol, "%s: %g vs %g (%g)", dfl_gridpeer_kind_name(k), u, d,
                      u - d);
            /* tricubic: the derivative weights there sum to <= 30 in
             * absolute value, over h = 0.4 */
            const double tolg = k == DFL_GRIDPEER_TRICUBIC ? tol * 30 / 25 / 0.4 : 1e-13;
            for (int a = 0; a < 3; a++)
                cr_assert(fabs(g[a] - ge[a]) < tolg, "%s axis %d: %g", dfl_gridpeer_kind_name(k),
                          a, g[a] - ge[a]);
        }
        dfl_field_destroy(&f);
    }
    dfl_shape_free(&s);
}

Test(gridpeer, reproduces_the_samples_at_cell_centres)
{
    const double c[3] = {0.05, -0.1, 0.02}, ax[3] = {0.2, 0.1, 1};
    dfl_shape s;
    cr_assert_eq(dfl_shape_torus(c, ax, 0.6, 0.25, &s, NULL), DFL_OK);
    for (int k = 0; k < DFL_GRIDPEER_KIND_COUNT; k++) {
        dfl_gridpeer_opts o = opts((dfl_gridpeer_kind)k, DFL_GRIDPEER_FLOAT64, 6);
        dfl_field f;
        cr_assert_eq(dfl_gridpeer_new(&s, &o, &f, NULL), DFL_OK);
        /* tricubic: the sample is a sum of coefficients (prefiltered: a
         * solve per axis) with B-spline weights; rounding of order 64 ulps
         * of the largest |d| on the grid (|d| <= 1.5 in [-1, 1]^3 here) */
        const double tol = k == DFL_GRIDPEER_TRICUBIC ? 64 * 0x1p-52 * 1.5 : -1;
        for (int i = 0; i < 6; i++)
            for (int j = 0; j < 6; j++)
                for (int l = 0; l < 6; l++) {
                    double x[3], g[3], ge[3];
                    centre(&o, i, j, l, x);
                    const double u = dfl_field_eval1(&f, x, g), d = dfl_shape_eval1(&s, x, ge);
                    cr_assert(fabs(u - d) < (tol > 0 ? tol : 1e-15 * (1 + fabs(d))),
                              "%s: %g vs %g", dfl_gridpeer_kind_name(k), u, d);
                    if (k != DFL_GRIDPEER_TRILINEAR0 && k != DFL_GRIDPEER_TRICUBIC)
                        for (int a = 0; a < 3; a++) cr_assert(fabs(g[a] - ge[a]) < 1e-14);
                }
        dfl_field_destroy(&f);
    }
    dfl_shape_free(&s);
}

/* N even: the sphere's centre is the corner shared by 8 cell centres at
 * (+-h/2)^3, so trilinear decoding gives |c| - r = sqrt(3) h / 2 - r there
 * (the protocol's Linf at N = 16: 0.10825). */
Test(gridpeer, trilinear_value_at_the_sphere_centre)
{
    const double c[3] = {0, 0, 0};
    dfl_shape s;
    cr_assert_eq(dfl_shape_sphere(c, 0.5, &s, NULL), DFL_OK);
    dfl_gridpeer_opts o = opts(DFL_GRIDPEER_TRILINEAR0, DFL_GRIDPEER_FLOAT64, 16);
    dfl_field f;
    cr_assert_eq(dfl_gridpeer_new(&s, &o, &f, NULL), DFL_OK);
    const double h = 2.0 / 16, u = dfl_field_eval1(&f, c, NULL);
    cr_assert(fabs(u - (sqrt(3.0) * h / 2 - 0.5)) < 1e-15);
    dfl_field_destroy(&f);
    dfl_shape_free(&s);
}

/* float16 rounds each stored scalar to nearest: at a centre the value is
 * within half an ulp, 2^-11 relative (normal range). */
Test(gridpeer, float16_rounding_is_bounded)
{
    const double c[3] = {0.01, 0.02, -0.03};
    dfl_shape s;
    cr_assert_eq(dfl_shape_sphere(c, 0.5, &s, NULL), DFL_OK);
    dfl_gridpeer_opts o = opts(DFL_GRIDPEER_TAYLOR2, DFL_GRIDPEER_FLOAT16, 8);
    dfl_field f;
    cr_assert_eq(dfl_gridpeer_new(&s, &o, &f, NULL), DFL_OK);
    double worst = 0;
    for (int i = 0; i < 8; i++)
        for (int j = 0; j < 8; j++)
            for (int l = 0; l < 8; l++) {
                double x[3];
                centre(&o, i, j, l, x);
                const double u = dfl_field_eval1(&f, x, NULL), d = dfl_shape_eval1(&s, x, NULL);
                if (fabs(d) < 6.2e-5) continue;  /* subnormal halves: absolute bound */
                const double rel = fabs(u - d) / fabs(d);
                cr_assert(rel <= ldexp(1.0, -11) * (1 + 1e-6), "rel %g at d %g", rel, d);
                if (rel > worst) worst = rel;
            }
    cr_assert(worst > 0, "float16 must actually round");
    dfl_field_destroy(&f);
    dfl_shape_free(&s);
}

Test(gridpeer, gradients_match_finite_differences)
{
    const double c[3] = {0, 0, 0}, ax[3] = {0, 0, 1};
    dfl_shape s;
    cr_assert_eq(dfl_shape_torus(c, ax, 0.6, 0.25, &s, NULL), DFL_OK);
    uint64_t seed = 11;
    for (int k = 0; k < DFL_GRIDPEER_KIND_COUNT; k++) {
        dfl_gridpeer_opts o = opts((dfl_gridpeer_kind)k, DFL_GRIDPEER_FLOAT64, 8); /* 7 would put centres on the axis */
        dfl_field f;
        cr_assert_eq(dfl_gridpeer_new(&s, &o, &f, NULL), DFL_OK);
        for (int t = 0; t < 100; t++) {
            double x[3], g[3];
            for (int a = 0; a < 3; a++) x[a] = dfl_rng_splitmix(&seed, -0.95, 0.95);
            dfl_field_eval1(&f, x, g);
            for (int a = 0; a < 3; a++) {
                const double hs = 1e-6;
                double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]};
                xp[a] += hs, xm[a] -= hs;
                /* skip steps that cross a cell face (piecewise polynomials) */
                const double w = 2.0 / 8;
                if (floor((xp[a] + 1) / w) != floor((xm[a] + 1) / w) ||
                    floor((xp[a] + 1) / w - 0.5) != floor((xm[a] + 1) / w - 0.5))
                    continue;
                const double fd =
                    (dfl_field_eval1(&f, xp, NULL) - dfl_field_eval1(&f, xm, NULL)) / (2 * hs);
                cr_assert(fabs(fd - g[a]) < 1e-6, "%s axis %d: %g vs %g",
                          dfl_gridpeer_kind_name(k), a, fd, g[a]);
            }
        }
        dfl_field_destroy(&f);
    }
    dfl_shape_free(&s);
}

Test(gridpeer, scalars_and_names)
{
    cr_assert_eq(dfl_gridpeer_scalars(DFL_GRIDPEER_TRILINEAR0, 16), 4096);
    cr_assert_eq(dfl_gridpeer_scalars(DFL_GRIDPEER_TAYLOR1, 16), 16384);
    cr_assert_eq(dfl_gridpeer_scalars(DFL_GRIDPEER_TAYLOR2, 32), 327680);
    cr_assert_eq(dfl_gridpeer_scalars(DFL_GRIDPEER_TRICUBIC, 16), 4096);
    dfl_gridpeer_kind k;
    cr_assert_eq(dfl_gridpeer_kind_parse("taylor2", &k, NULL), DFL_OK);
    cr_assert_eq(k, DFL_GRIDPEER_TAYLOR2);
    cr_assert_eq(dfl_gridpeer_kind_parse("tricubic", &k, NULL), DFL_OK);
    cr_assert_eq(k, DFL_GRIDPEER_TRICUBIC);
    dfl_err err;
    cr_assert_eq(dfl_gridpeer_kind_parse("taylor3", &k, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "taylor3"));
}

Test(gridpeer, bad_input)
{
    const double c[3] = {0, 0, 0};
    dfl_shape s, s2;
    cr_assert_eq(dfl_shape_sphere(c, 0.5, &s, NULL), DFL_OK);
    cr_assert_eq(dfl_shape_circle(c, 0.5, &s2, NULL), DFL_OK);
    dfl_field f = {0};
    dfl_err err;
    dfl_gridpeer_opts o = opts(DFL_GRIDPEER_TAYLOR1, DFL_GRIDPEER_FLOAT64, 0);
    cr_assert_eq(dfl_gridpeer_new(&s, &o, &f, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "n"));
    o.n = 4;
    o.hi[1] = -1;
    cr_assert_eq(dfl_gridpeer_new(&s, &o, &f, &err), DFL_E_INPUT);
    o.hi[1] = 1;
    cr_assert_eq(dfl_gridpeer_new(&s2, &o, &f, &err), DFL_E_INPUT, "2D shape");
    cr_assert_null(f.ops, "out untouched on failure");
    /* a half overflows: distances near 3e5 */
    dfl_shape big;
    cr_assert_eq(dfl_shape_sphere(c, 1e-3, &big, NULL), DFL_OK);
    dfl_gridpeer_opts ob = {DFL_GRIDPEER_TRILINEAR0, DFL_GRIDPEER_FLOAT16, 2, {1e5, 1e5, 1e5},
                            {2e5, 2e5, 2e5}, 1};
    cr_assert_eq(dfl_gridpeer_new(&big, &ob, &f, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "half"));
    /* tricubic: its coefficients overflow (samples near 3e5 at n = 4) */
    ob.kind = DFL_GRIDPEER_TRICUBIC;
    ob.n = 4;
    cr_assert_eq(dfl_gridpeer_new(&big, &ob, &f, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "half"), "%s", err.msg);
    /* tricubic below its not-a-knot minimum */
    dfl_gridpeer_opts ot = opts(DFL_GRIDPEER_TRICUBIC, DFL_GRIDPEER_FLOAT64, 3);
    cr_assert_eq(dfl_gridpeer_new(&s, &ot, &f, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "n >= 4"), "%s", err.msg);
    cr_assert_null(f.ops, "out untouched on failure");
    dfl_shape_free(&s);
    dfl_shape_free(&s2);
    dfl_shape_free(&big);
}

/* Stored bytes: n^3 cells x the kind's scalars (1, 4, 10) x 8 (float64) or
 * 2 (float16) bytes: the scalars kept, not the doubles the decoder holds. */
Test(gridpeer, bytes_are_the_stored_scalars)
{
    const double p[3] = {0.1, -0.2, 0.3}, nrm[3] = {1, 2, -2};
    dfl_shape s;
    cr_assert_eq(dfl_shape_plane(3, p, nrm, &s, NULL), DFL_OK);
    static const int per_cell[DFL_GRIDPEER_KIND_COUNT] = {1, 4, 10, 1};
    for (int k = 0; k < DFL_GRIDPEER_KIND_COUNT; k++)
        for (int st = 0; st < DFL_GRIDPEER_STORAGE_COUNT; st++) {
            dfl_gridpeer_opts o = opts((dfl_gridpeer_kind)k, (dfl_gridpeer_storage)st, 6);
            dfl_field f;
            cr_assert_eq(dfl_gridpeer_new(&s, &o, &f, NULL), DFL_OK);
            size_t b = 0;
            cr_assert_eq(dfl_field_bytes(&f, &b), 1);
            const size_t each = st == DFL_GRIDPEER_FLOAT64 ? 8 : 2;
            cr_expect_eq(b, (size_t)6 * 6 * 6 * per_cell[k] * each, "kind %d storage %d", k, st);
            dfl_field_destroy(&f);
        }
    dfl_shape_free(&s);
}

/* ---- tricubic ---- */

/* A tensor polynomial of degree <= 3 in each variable (not a distance:
 * the grid samples whatever the shape's eval returns). */
static double tc_pow(double x, int e) { return e == 0 ? 1 : e == 1 ? x : e == 2 ? x * x : x * x * x; }
static const double tc_coef[] = {0.3, 1, -0.5, 0.25, 0.8, -0.7, 0.2, -0.4, 0.1, 0.3};
static const int tc_exp[][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 1, 0},
                                {0, 1, 2}, {3, 0, 0}, {0, 0, 3}, {3, 3, 3}, {2, 2, 1}};
static void tc_eval(const void *impl, size_t m, const double *pts, double *val, double *grad)
{
    (void)impl;
    for (size_t i = 0; i < m; i++) {
        const double *x = pts + 3 * i;
        double v = 0, g[3] = {0, 0, 0};
        for (size_t t = 0; t < sizeof tc_coef / sizeof tc_coef[0]; t++) {
            const int *e = tc_exp[t];
            v += tc_coef[t] * tc_pow(x[0], e[0]) * tc_pow(x[1], e[1]) * tc_pow(x[2], e[2]);
            for (int a = 0; a < 3; a++) {
                if (!e[a]) continue;
                double d = tc_coef[t] * e[a];
                for (int b = 0; b < 3; b++) d *= tc_pow(x[b], b == a ? e[b] - 1 : e[b]);
                g[a] += d;
            }
        }
        val[i] = v;
        if (grad) memcpy(grad + 3 * i, g, sizeof g);
    }
}
static void tc_free(void *impl) { (void)impl; }
static const dfl_shape_ops tc_ops = {"tensor_cubic", tc_eval, NULL, tc_free, NULL};

/* Not-a-knot keeps every cubic per axis: the B-spline coefficients of a
 * cubic are a cubic sequence (c = p - p''/6 at the centres), whose fourth
 * differences vanish, so the ghosts the rule extrapolates are the cubic's
 * own and the spline is the polynomial on every piece, the extended end
 * pieces included: value and gradient exact (to rounding) in the box and
 * beyond it, at the smallest n (4) and anisotropic cells. */
Test(gridpeer, tricubic_reproduces_tensor_cubics)
{
    dfl_shape s = {3, &tc_ops, NULL};
    static const int ns[] = {4, 5, 9};
    uint64_t seed = 3;
    for (size_t t = 0; t < 3; t++) {
        dfl_gridpeer_opts o = {DFL_GRIDPEER_TRICUBIC, DFL_GRIDPEER_FLOAT64, ns[t],
                               {-1, -0.5, -1.2}, {1.1, 0.5, 0.9}, 1};
        dfl_field f;
        dfl_err err;
        cr_assert_eq(dfl_gridpeer_new(&s, &o, &f, &err), DFL_OK, "%s", err.msg);
        double worst = 0;
        for (int q = 0; q < 300; q++) {
            double x[3], g[3], ge[3];
            for (int a = 0; a < 3; a++) {
                const double w = o.hi[a] - o.lo[a];
                x[a] = dfl_rng_splitmix(&seed, o.lo[a] - 0.1 * w, o.hi[a] + 0.1 * w);
            }
            const double u = dfl_field_eval1(&f, x, g), p = dfl_shape_eval1(&s, x, ge);
            cr_assert(fabs(u - p) < 1e-12, "n %d: %.17g vs %.17g", ns[t], u, p);
            for (int a = 0; a < 3; a++)
                cr_assert(fabs(g[a] - ge[a]) < 1e-11, "n %d axis %d: %.17g vs %.17g", ns[t], a,
                          g[a], ge[a]);
            worst = fmax(worst, fabs(u - p));
        }
        dfl_field_destroy(&f);
        (void)worst;
    }
    /* a mirror (or reflect) boundary would not: d/dx of x at the first
     * centre is 1, not the 0 a mirror forces */
}

/* The centred cubic B-spline and its derivative. */
static double beta3(double t)
{
    t = fabs(t);
    return t < 1 ? 2.0 / 3 - t * t + 0.5 * t * t * t : t < 2 ? (2 - t) * (2 - t) * (2 - t) / 6 : 0;
}
static double dbeta3(double t)
{
    const double a = fabs(t), s = t < 0 ? -1 : 1;
    return s * (a < 1 ? -2 * a + 1.5 * a * a : a < 2 ? -0.5 * (2 - a) * (2 - a) : 0);
}

/* Per axis, the weight of stored coefficient k (0 .. n - 1) at index
 * coordinate t in [0, n - 1]: the sum over the extended indices I = -1 ..
 * n of beta3(t - I) times row I of the not-a-knot extension (the identity
 * inside; (4, -6, 4, -1) from the nearest end for the ghosts). */
static void axis_weights(int n, double t, int deriv, double *w)
{
    static const double ghost[4] = {4, -6, 4, -1};
    for (int k = 0; k < n; k++) w[k] = deriv ? dbeta3(t - k) : beta3(t - k);
    const double bl = deriv ? dbeta3(t + 1) : beta3(t + 1), br = deriv ? dbeta3(t - n) : beta3(t - n);
    for (int k = 0; k < 4; k++) {
        w[k] += bl * ghost[k];
        w[n - 1 - k] += br * ghost[k];
    }
}

/* The spline sum_ijk c_ijk wx_i wy_j wz_k at x, and its gradient. */
static double spline_ref(const double *c, const dfl_gridpeer_opts *o, const double *x, double *g)
{
    const int n = o->n;
    double w[3][2][16];
    for (int a = 0; a < 3; a++) {
        const double h = (o->hi[a] - o->lo[a]) / n, t = (x[a] - o->lo[a]) / h - 0.5;
        axis_weights(n, t, 0, w[a][0]);
        axis_weights(n, t, 1, w[a][1]);
        for (int k = 0; k < n; k++) w[a][1][k] /= h;
    }
    double v = 0;
    g[0] = g[1] = g[2] = 0;
    for (int k = 0; k < n; k++)
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                const double cc = c[i + n * (j + n * k)];
                v += cc * w[0][0][i] * w[1][0][j] * w[2][0][k];
                g[0] += cc * w[0][1][i] * w[1][0][j] * w[2][0][k];
                g[1] += cc * w[0][0][i] * w[1][1][j] * w[2][0][k];
                g[2] += cc * w[0][0][i] * w[1][0][j] * w[2][1][k];
            }
    return v;
}

/* float16 rounds each coefficient (prefiltered in double) to the nearest
 * half, and both storages decode the spline of what they store: equal to
 * the B-spline sum of the stored coefficients (an independent formula:
 * the closed-form B-spline, the ghosts as an extension matrix) in value
 * and gradient, between the first and last centres of each axis. */
Test(gridpeer, tricubic_float16_and_the_bspline_sum)
{
    const double c[3] = {0.05, -0.1, 0.02}, ax[3] = {0.2, 0.1, 1};
    dfl_shape s;
    cr_assert_eq(dfl_shape_torus(c, ax, 0.6, 0.25, &s, NULL), DFL_OK);
    dfl_gridpeer_opts o64 = opts(DFL_GRIDPEER_TRICUBIC, DFL_GRIDPEER_FLOAT64, 7),
                      o16 = opts(DFL_GRIDPEER_TRICUBIC, DFL_GRIDPEER_FLOAT16, 7);
    dfl_field f64, f16;
    cr_assert_eq(dfl_gridpeer_new(&s, &o64, &f64, NULL), DFL_OK);
    cr_assert_eq(dfl_gridpeer_new(&s, &o16, &f16, NULL), DFL_OK);
    size_t n64 = 0, n16 = 0;
    const double *s64 = dfl_gridpeer_stored(&f64, &n64), *s16 = dfl_gridpeer_stored(&f16, &n16);
    cr_assert(s64 && s16);
    cr_assert_eq(n64, 343);
    cr_assert_eq(n16, 343);
    int rounded = 0;
    for (size_t i = 0; i < n64; i++) {
        const double h = imath_half_to_float(imath_float_to_half((float)s64[i]));
        cr_assert_eq(s16[i], h, "coefficient %zu: %.17g, the half of %.17g is %.17g", i, s16[i],
                     s64[i], h);
        if (fabs(s64[i]) >= 6.2e-5)
            cr_assert(fabs(s16[i] - s64[i]) <= ldexp(fabs(s64[i]), -11));
        rounded += s16[i] != s64[i];
    }
    cr_assert_gt(rounded, 0, "float16 must actually round");
    uint64_t seed = 5;
    const double h = 2.0 / 7;
    for (int q = 0; q < 100; q++) {
        double x[3], g[3], gr[3];
        for (int a = 0; a < 3; a++) x[a] = dfl_rng_splitmix(&seed, -1 + h / 2, 1 - h / 2);
        const dfl_field *fs[2] = {&f64, &f16};
        const double *cs[2] = {s64, s16};
        for (int k = 0; k < 2; k++) {
            const double u = dfl_field_eval1(fs[k], x, g), r = spline_ref(cs[k], &o64, x, gr);
            cr_assert(fabs(u - r) < 1e-13, "storage %d: %.17g vs %.17g", k, u, r);
            for (int a = 0; a < 3; a++)
                cr_assert(fabs(g[a] - gr[a]) < 1e-12, "storage %d axis %d: %.17g vs %.17g", k,
                          a, g[a], gr[a]);
        }
    }
    size_t cnt;
    cr_assert_null(dfl_gridpeer_stored(&(dfl_field){0}, &cnt));
    dfl_field_destroy(&f64);
    dfl_field_destroy(&f16);
    dfl_shape_free(&s);
}

/* Against SciPy (tests/field/gridpeer_scipy.py): the tensor of
 * make_interp_spline(k = 3) (not-a-knot, extrapolating its end pieces) on
 * the samples, value and gradient, in and beyond the box; and
 * ndimage.map_coordinates(order = 3, prefilter) on the samples padded with
 * K = 30 centres of our spline's extrapolation each side: its mirror ends
 * then sit 30 centres away, where their effect has decayed by
 * (2 - sqrt 3)^30 ~ 1e-17, so inside the box the two agree to rounding. */
Test(gridpeer, tricubic_matches_scipy, .timeout = 120)
{
    const double c[3] = {0.05, -0.1, 0.02}, ax[3] = {0.2, 0.1, 1};
    dfl_shape s;
    cr_assert_eq(dfl_shape_torus(c, ax, 0.6, 0.25, &s, NULL), DFL_OK);
    dfl_gridpeer_opts o = {DFL_GRIDPEER_TRICUBIC, DFL_GRIDPEER_FLOAT64, 9,
                           {-1, -0.9, -0.6}, {1, 1.1, 0.6}, 1};
    dfl_field f;
    cr_assert_eq(dfl_gridpeer_new(&s, &o, &f, NULL), DFL_OK);
    char dir[64], path[128];
    tmpdir_file(dir, sizeof dir, "grid.txt", path, sizeof path);
    FILE *fp = fopen(path, "w");
    cr_assert(fp);
    const int n = o.n, K = 30, M = n + 2 * K;
    fprintf(fp, "%d %d\n%.17g %.17g %.17g\n%.17g %.17g %.17g\n", n, K, o.lo[0], o.lo[1], o.lo[2],
            o.hi[0], o.hi[1], o.hi[2]);
    double h[3];
    for (int a = 0; a < 3; a++) h[a] = (o.hi[a] - o.lo[a]) / n;
    /* the samples (index i + n (j + n k)), then the padded grid (M^3, the
     * spline at the centres -K .. n - 1 + K) */
    for (int k = 0; k < n; k++)
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                double x[3];
                centre(&o, i, j, k, x);
                fprintf(fp, "%.17g\n", dfl_shape_eval1(&s, x, NULL));
            }
    for (int k = 0; k < M; k++)
        for (int j = 0; j < M; j++)
            for (int i = 0; i < M; i++) {
                const int id[3] = {i - K, j - K, k - K};
                double x[3];
                for (int a = 0; a < 3; a++) x[a] = o.lo[a] + (id[a] + 0.5) * h[a];
                fprintf(fp, "%.17g\n", dfl_field_eval1(&f, x, NULL));
            }
    uint64_t seed = 9;
    for (int q = 0; q < 200; q++) {
        double x[3], g[3];
        for (int a = 0; a < 3; a++)
            x[a] = dfl_rng_splitmix(&seed, o.lo[a] - 0.2 * h[a], o.hi[a] + 0.2 * h[a]);
        const double u = dfl_field_eval1(&f, x, g);
        fprintf(fp, "%.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", x[0], x[1], x[2], u, g[0],
                g[1], g[2]);
    }
    cr_assert_eq(fclose(fp), 0);
    char *out = NULL;
    const int rc = e2e_python_run(dir, &out, "tests/field/gridpeer_scipy.py '%s'", path);
    cr_expect_eq(rc, 0, "gridpeer_scipy.py: %s", out ? out : "");
    cr_log_info("gridpeer_scipy.py: %s", out ? out : "");
    free(out);
    tmpdir_remove(dir);
    dfl_field_destroy(&f);
    dfl_shape_free(&s);
}

/* The checks of nan_query_is_nan_and_stays_in_the_grid on one ISA: the
 * number of failures (printed to stderr). */
static int nan_queries(const void *ctx)
{
    (void)ctx;
    enum { M = 23 };
    const double c[3] = {0, 0, 0}, ax[3] = {0, 0, 1};
    dfl_shape s;
    if (dfl_shape_torus(c, ax, 0.6, 0.25, &s, NULL) != DFL_OK) return 1;
    double x[3 * M];
    uint64_t seed = 17;
    for (int i = 0; i < 3 * M; i++) x[i] = dfl_rng_splitmix(&seed, -1.3, 1.3);
    /* NaN on each axis (either sign), NaN with an infinity; infinities and
     * far points of either sign on each axis */
    x[3 * 2 + 0] = NAN;
    x[3 * 5 + 1] = NAN;
    x[3 * 9 + 2] = -NAN;
    x[3 * 13 + 0] = INFINITY, x[3 * 13 + 2] = NAN;
    x[3 * 3 + 0] = INFINITY, x[3 * 4 + 0] = 1e300;
    x[3 * 6 + 1] = -INFINITY, x[3 * 7 + 1] = -1e300;
    x[3 * 10 + 2] = INFINITY, x[3 * 11 + 2] = 1e300;
    x[3 * 15 + 0] = -INFINITY, x[3 * 16 + 0] = -1e300;
    int bad = 0;
    for (int k = 0; k < DFL_GRIDPEER_KIND_COUNT; k++)
        for (int st = 0; st < DFL_GRIDPEER_STORAGE_COUNT; st++)
            for (int n = 1; n <= 6; n++) {
                /* tricubic needs n >= 4; an odd n puts a centre on the torus'
                 * axis, where taylor2's jets fail */
                if ((k == DFL_GRIDPEER_TRICUBIC && n < 4) || (k == DFL_GRIDPEER_TAYLOR2 && n % 2))
                    continue;
                dfl_gridpeer_opts o = opts((dfl_gridpeer_kind)k, (dfl_gridpeer_storage)st, n);
                dfl_field f;
                if (dfl_gridpeer_new(&s, &o, &f, NULL) != DFL_OK) {
                    fprintf(stderr, "%s n %d: not built\n", dfl_gridpeer_kind_name(k), n);
                    bad++;
                    continue;
                }
                double v[M], g[3 * M];
                f.ops->eval(f.ctx, M, x, v, g);
                for (int i = 0; i < M; i++) {
                    const int nan = isnan(x[3 * i]) || isnan(x[3 * i + 1]) || isnan(x[3 * i + 2]);
                    const int inf = !nan && !(isfinite(x[3 * i]) && isfinite(x[3 * i + 1]) &&
                                              isfinite(x[3 * i + 2]));
                    if (nan && !isnan(v[i])) {
                        fprintf(stderr, "%s st %d n %d query %d: %g, not NaN\n",
                                dfl_gridpeer_kind_name(k), st, n, i, v[i]);
                        bad++;
                    }
                    if (!nan && !inf) { /* the value alone, byte for byte */
                        double g1[3];
                        const double v1 = dfl_field_eval1(&f, x + 3 * i, g1);
                        if (memcmp(&v1, v + i, sizeof v1) || memcmp(g1, g + 3 * i, sizeof g1)) {
                            fprintf(stderr, "%s st %d n %d query %d: %a vs %a alone\n",
                                    dfl_gridpeer_kind_name(k), st, n, i, v[i], v1);
                            bad++;
                        }
                    }
                    if ((nan || inf) && k == DFL_GRIDPEER_TAYLOR1) {
                        /* taylor1's gradient is its cell's stored gradient: the
                         * cell is cell 0 on a NaN axis (the far low side's), the
                         * boundary cell on an infinite one (a far point's) */
                        double y[3], g1[3];
                        for (int a = 0; a < 3; a++) {
                            const double xa = x[3 * i + a];
                            y[a] = isnan(xa) ? -1e300 : isinf(xa) ? copysign(1e300, xa) : xa;
                        }
                        (void)dfl_field_eval1(&f, y, g1);
                        if (memcmp(g1, g + 3 * i, sizeof g1)) {
                            fprintf(stderr, "taylor1 st %d n %d query %d: not cell 0 on a NaN "
                                    "axis or the far cell on an infinite one\n", st, n, i);
                            bad++;
                        }
                    }
                }
                dfl_field_destroy(&f);
            }
    dfl_shape_free(&s);
    return bad;
}

/* gridpeer.h: a query with a NaN coordinate gets a NaN value and reads no
 * cell outside the grid (cell 0 on that axis: seen in taylor1's gradient,
 * its cell's), an infinite coordinate is located like a far one, and the
 * other queries of the batch get what they get alone.  Every kind and
 * storage, n from 1 (one cell: trilinear0 decodes a constant) up, on every
 * ISA this CPU runs (a child per ISA: the ISA is chosen once per
 * process). */
Test(gridpeer, nan_query_is_nan_and_stays_in_the_grid)
{
    cr_assert(dfl_test_per_isa(nan_queries, NULL) >= 1);
}
