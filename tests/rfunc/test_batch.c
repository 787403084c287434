/* The fast (vectorized) evaluator of rfunc/batch.h and the benchmark's
 * naive one (tests/bench/rfunc_naive.h) against each other and against a brute-force sum over the library's
 * per-segment fields (rfunc/segment.h), which is how eq. 6 is defined.
 *
 * Tolerance.  Values: 1e-12 relative.  Gradients: the sum
 * grad u = sum_i (u/h_i)^(p+1) grad h_i cancels where the contributions
 * point in different directions (at the centre of a closed polyline it is
 * 0 by symmetry), so its rounding error scales with the sum of absolute
 * contributions  s = sum_i (u/h_i)^(p+1) |grad h_i|  (>= |grad u|), not
 * with |grad u|: the gradient agrees to 1e-12 s.  That is the
 * "1e-12 relative" of the brief, measured against the quantity that
 * bounds the rounding. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "bench/rfunc_naive.h"
#include "core/rng.h"
#include "field/sample.h"
#include "rfunc/join.h"
#include "rfunc/segment.h"
#include "rfunc/batch.h"
#include "rfunc/tri3d.h"
#include "rfunc/rfield.h"

/* A wobbly spiral polyline of n vertices inside [0, 1]^2. */
static double *spiral(size_t n)
{
    double *v = malloc(2 * n * sizeof *v);
    for (size_t i = 0; i < n; i++) {
        const double t = (double)i / (double)(n - 1);
        const double r = 0.1 + 0.35 * t + 0.02 * sin(40 * t);
        v[2 * i] = 0.5 + r * cos(9 * t);
        v[2 * i + 1] = 0.5 + r * sin(9 * t);
    }
    return v;
}

/* Brute force from the library's segment fields: u, grad u and s (above). */
static double brute(const double *v, size_t n, int closed, int p, const double *x, double *g,
                    double *s)
{
    const size_t ns = closed ? n : n - 1;
    double *h = malloc(ns * sizeof *h), *gh = malloc(2 * ns * sizeof *gh);
    double S = 0;
    for (size_t k = 0; k < ns; k++) {
        dfl_rfunc_seg seg;
        cr_assert_eq(dfl_rfunc_seg_init(2, v + 2 * k, v + 2 * ((k + 1) % n), DFL_RFUNC_TRIM_DISK,
                                        &seg, NULL),
                     DFL_OK);
        h[k] = dfl_rfunc_seg_eval(&seg, x, gh + 2 * k);
        cr_assert(h[k] > 0);
        S += pow(h[k], -p);
    }
    const double u = pow(S, -1.0 / p);
    g[0] = g[1] = *s = 0;
    for (size_t k = 0; k < ns; k++) {
        const double c = pow(u / h[k], p + 1);
        g[0] += c * gh[2 * k];
        g[1] += c * gh[2 * k + 1];
        *s += c * hypot(gh[2 * k], gh[2 * k + 1]);
    }
    free(h);
    free(gh);
    return u;
}

static void agree(double u, const double *g, double ur, const double *gr, double s,
                  const char *what, const double *x)
{
    cr_assert(fabs(u - ur) <= 1e-12 * ur, "%s at (%.17g, %.17g): u %.17g vs %.17g", what, x[0],
              x[1], u, ur);
    for (int j = 0; j < 2; j++)
        cr_assert(fabs(g[j] - gr[j]) <= 1e-12 * s,
                  "%s at (%.17g, %.17g): grad[%d] %.17g vs %.17g (s = %g)", what, x[0], x[1], j,
                  g[j], gr[j], s);
}

static void compare_random(size_t nv, int closed, int p, uint64_t seed)
{
    double *v = spiral(nv);
    dfl_rfunc_batch *b;
    dfl_err err;
    cr_assert_eq(dfl_rfunc_batch_new(v, nv, closed, p, &b, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_rfunc_batch_segments(b), closed ? nv : nv - 1);
    enum { M = 157 }; /* not a multiple of the block sizes */
    double pts[2 * M], uf[M], gf[2 * M], un[M], gn[2 * M], ul[M], gl[2 * M];
    uint64_t rng = seed;
    for (int i = 0; i < M; i++) {
        pts[2 * i] = dfl_rng_splitmix(&rng, -0.3, 1.3);
        pts[2 * i + 1] = dfl_rng_splitmix(&rng, -0.3, 1.3);
    }
    /* the fast path itself must be what is compared, not its fallback */
    cr_assert_eq(dfl_rfunc_batch_fallbacks(b, M, pts), 0);
    dfl_rfunc_batch_eval(b, M, pts, uf, gf);
    rfunc_naive naive;
    cr_assert_eq(rfunc_naive_init(&naive, v, nv, closed, p), 0);
    rfunc_naive_eval(&naive, M, pts, un, gn);
    rfunc_naive_free(&naive);
    const dfl_field *ref = dfl_rfunc_batch_reference(b);
    ref->ops->eval(ref->ctx, M, pts, ul, gl);
    for (int i = 0; i < M; i++) {
        double gb[2], s;
        const double ub = brute(v, nv, closed, p, pts + 2 * i, gb, &s);
        agree(uf[i], gf + 2 * i, ub, gb, s, "fast vs brute force", pts + 2 * i);
        agree(un[i], gn + 2 * i, ub, gb, s, "naive vs brute force", pts + 2 * i);
        agree(uf[i], gf + 2 * i, un[i], gn + 2 * i, s, "fast vs naive", pts + 2 * i);
        agree(uf[i], gf + 2 * i, ul[i], gl + 2 * i, s, "fast vs library rfield", pts + 2 * i);
    }
    /* value-only calls give the same values */
    double uv[M];
    dfl_rfunc_batch_eval(b, M, pts, uv, NULL);
    for (int i = 0; i < M; i++) cr_assert_eq(uv[i], uf[i]);
    dfl_rfunc_batch_free(b);
    free(v);
}

Test(rfunc_batch, fast_naive_and_brute_force_agree)
{
    /* specialized orders, the generic order 13, open and closed, a segment
     * count that is not a multiple of the vector block */
    const int ps[] = {1, 2, 3, 7, 12, 13};
    for (size_t i = 0; i < sizeof ps / sizeof *ps; i++) {
        compare_random(61, 0, ps[i], 17 + i);
        compare_random(40, 1, ps[i], 91 + i);
    }
}

Test(rfunc_batch, on_and_near_the_polyline)
{
    const size_t nv = 25;
    double *v = spiral(nv);
    const int ps[] = {2, 7};
    for (int ip = 0; ip < 2; ip++) {
        dfl_rfunc_batch *b;
        cr_assert_eq(dfl_rfunc_batch_new(v, nv, 0, ps[ip], &b, NULL), DFL_OK);
        const dfl_field *ref = dfl_rfunc_batch_reference(b);
        rfunc_naive naive;
        cr_assert_eq(rfunc_naive_init(&naive, v, nv, 0, ps[ip]), 0);
        for (size_t k = 0; k + 1 < nv; k++) {
            /* vertex and midpoint: u = 0, gradient 0 (the library's convention) */
            double x[2][2] = {{v[2 * k], v[2 * k + 1]},
                              {0.5 * (v[2 * k] + v[2 * k + 2]), 0.5 * (v[2 * k + 1] + v[2 * k + 3])}};
            for (int w = 0; w < 2; w++) {
                double u, g[2], un, gn[2];
                dfl_rfunc_batch_eval(b, 1, x[w], &u, g);
                rfunc_naive_eval(&naive, 1, x[w], &un, gn);
                double ul = dfl_field_eval1(ref, x[w], NULL);
                /* the naive trim (d/2)^2 - |x - c|^2 is 0 only to rounding at
                 * the end points (the library's (x - a).(x - b) is exactly
                 * 0): its u is 0 to the rounding of the coordinates */
                cr_assert(un <= 4e-16, "k %zu: naive u %g", k, un);
                if (w == 0) {
                    /* a vertex is the exact start of segment k: h = 0 */
                    cr_assert(ul == 0.0, "k %zu: library u %g", k, ul);
                    cr_assert(u == 0.0 && g[0] == 0.0 && g[1] == 0.0, "k %zu: u %g", k, u);
                } else {
                    /* a rounded midpoint is on the segment only to rounding
                     * (~eps |x|, |x| <= 1), computed differently by each */
                    cr_assert(u <= 4e-16 && ul <= 4e-16, "k %zu: %g vs %g", k, u, ul);
                }
            }
        }
        /* far away (h^-12 underflows for p = 12, not for 2 and 7: compare) */
        double far[2] = {3e30, -1e30}, u, g[2], gl[2];
        dfl_rfunc_batch_eval(b, 1, far, &u, g);
        const double ul = dfl_field_eval1(ref, far, gl);
        /* seen from far away all segments pull the same way: no
         * cancellation, the gradient (~2|x - c|/d, huge for the disk trim's
         * h ~ |x - c|^2/d) agrees relatively */
        const double gn = hypot(gl[0], gl[1]);
        cr_assert(fabs(u - ul) <= 1e-12 * ul && fabs(g[0] - gl[0]) <= 1e-12 * gn &&
                      fabs(g[1] - gl[1]) <= 1e-12 * gn,
                  "p %d: u %.17g vs %.17g, grad %.17g %.17g vs %.17g %.17g", ps[ip], u, ul, g[0],
                  g[1], gl[0], gl[1]);
        rfunc_naive_free(&naive);
        dfl_rfunc_batch_free(b);
    }
    /* 1e-170 off a segment (representable only near the origin): h^2 ~
     * 1e-340 is subnormal, the sums overflow, and the fallback must give
     * the library's value, which is the distance itself */
    const double L[6] = {0, 0, 1, 0, 1, 1};
    for (int ip = 0; ip < 2; ip++) {
        dfl_rfunc_batch *bl;
        cr_assert_eq(dfl_rfunc_batch_new(L, 3, 0, ps[ip], &bl, NULL), DFL_OK);
        const double y[3][2] = {{0.5, 1e-170}, {0.5, -1e-170}, {-1e-170, 0}};
        for (int w = 0; w < 3; w++) {
            cr_assert_eq(dfl_rfunc_batch_fallbacks(bl, 1, y[w]), 1);
            double u, g[2], gl[2];
            dfl_rfunc_batch_eval(bl, 1, y[w], &u, g);
            const double ul = dfl_field_eval1(dfl_rfunc_batch_reference(bl), y[w], gl);
            cr_assert(u == ul && g[0] == gl[0] && g[1] == gl[1], "%d: %g vs %g", w, u, ul);
            cr_assert(fabs(u - 1e-170) <= 1e-185, "%d: u = %g", w, u);
        }
        dfl_rfunc_batch_free(bl);
    }
    dfl_rfunc_batch *b;
    cr_assert_eq(dfl_rfunc_batch_new(v, nv, 0, 12, &b, NULL), DFL_OK);
    double far[2] = {3e30, -1e30}, u, g[2], gl[2];
    cr_assert_eq(dfl_rfunc_batch_fallbacks(b, 1, far), 1);
    dfl_rfunc_batch_eval(b, 1, far, &u, g);
    const double ul = dfl_field_eval1(dfl_rfunc_batch_reference(b), far, gl);
    cr_assert(fabs(u - ul) <= 1e-12 * ul);
    /* eq. 6 bounds: n^(-1/p) min h_i <= u <= min h_i (n = 24 segments) */
    double hmin = INFINITY;
    for (size_t k = 0; k + 1 < nv; k++) {
        dfl_rfunc_seg seg;
        cr_assert_eq(dfl_rfunc_seg_init(2, v + 2 * k, v + 2 * k + 2, DFL_RFUNC_TRIM_DISK, &seg,
                                        NULL),
                     DFL_OK);
        hmin = fmin(hmin, dfl_rfunc_seg_eval(&seg, far, NULL));
    }
    cr_assert(u <= hmin * (1 + 1e-12) && u >= pow(24.0, -1.0 / 12) * hmin * (1 - 1e-12),
              "u %g, min h %g", u, hmin);
    dfl_rfunc_batch_free(b);
    free(v);
}

Test(rfunc_batch, field_wrapper_and_sampler)
{
    const size_t nv = 30;
    double *v = spiral(nv);
    dfl_field f;
    dfl_err err;
    cr_assert_eq(dfl_rfunc_batch_field(v, nv, 1, 7, &f, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(f.dim, 2);
    dfl_grid g = {2, {37, 29, 1}, {-0.2, -0.1, 0}, {1.2, 1.1, 0}};
    const size_t m = dfl_grid_size(&g);
    double *u = malloc(m * sizeof *u), *gu = malloc(2 * m * sizeof *gu);
    cr_assert_eq(dfl_field_sample(&f, &g, 2, u, gu, &err), DFL_OK, "%s", err.msg);
    for (size_t i = 0; i < m; i++) {
        double x[2], g1[2];
        dfl_grid_node(&g, i, x);
        const double u1 = dfl_field_eval1(&f, x, g1);
        cr_assert(u1 == u[i] && g1[0] == gu[2 * i] && g1[1] == gu[2 * i + 1]);
    }
    /* jets come from the library: first derivative = grad . dir */
    double x[2] = {0.31, 0.77}, dir[2] = {0.6, -0.8}, g1[2];
    const double u1 = dfl_field_eval1(&f, x, g1);
    dfl_jet jt;
    cr_assert_eq(dfl_field_jet(&f, x, dir, 2, &jt, &err), DFL_OK, "%s", err.msg);
    cr_assert(fabs(dfl_jet_coeff(&jt, 0) - u1) <= 1e-12 * u1);
    cr_assert(fabs(dfl_jet_deriv(&jt, 1) - (g1[0] * dir[0] + g1[1] * dir[1])) <= 1e-10);
    free(u);
    free(gu);
    dfl_field_destroy(&f);
    free(v);
}

Test(rfunc_batch, bad_input)
{
    const double one[2] = {0, 0};
    const double rep[6] = {0, 0, 1, 1, 1, 1};
    const double ok[4] = {0, 0, 1, 1};
    dfl_rfunc_batch *b = NULL;
    dfl_err err;
    cr_expect_eq(dfl_rfunc_batch_new(one, 1, 0, 2, &b, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_rfunc_batch_new(ok, 2, 1, 2, &b, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_rfunc_batch_new(rep, 3, 0, 2, &b, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_rfunc_batch_new(ok, 2, 0, 0, &b, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_rfunc_batch_new(ok, 2, 0, DFL_RFUNC_P_MAX + 1, &b, &err), DFL_E_INPUT);
    cr_expect_null(b);
    const int w = dfl_rfunc_batch_simd_width();
    cr_expect(w == 2 || w == 4 || w == 8, "width %d", w);
}

/* The strip-trim and 3D kernels against a brute-force sum over the
 * library's segment fields (same tolerance as above), open and closed, at
 * random points and at points near the polyline (1e-6 off a vertex and off
 * a segment's interior), with the fast path actually taken (no fallback). */
static void compare_kind(int dim, dfl_rfunc_trim trim, size_t nv, int closed, int p,
                         uint64_t seed)
{
    double *v2 = spiral(nv), *v = malloc(3 * nv * sizeof *v);
    const size_t d = (size_t)dim;
    for (size_t i = 0; i < nv; i++) {
        v[d * i] = v2[2 * i];
        v[d * i + 1] = v2[2 * i + 1];
        if (dim == 3) v[3 * i + 2] = 0.3 * sin(7.0 * (double)i / (double)nv);
    }
    free(v2);
    dfl_rfunc_batch *b;
    dfl_err err;
    cr_assert_eq(dfl_rfunc_batch_new_opts(dim, v, nv, closed, p, trim, &b, &err), DFL_OK, "%s",
                 err.msg);
    enum { M = 101 };
    double pts[3 * M], uf[M], gf[3 * M];
    uint64_t rng = seed;
    for (int i = 0; i < M; i++)
        for (size_t j = 0; j < d; j++) pts[d * i + j] = dfl_rng_splitmix(&rng, -0.3, 1.3);
    /* two points near the polyline */
    for (size_t j = 0; j < d; j++) {
        pts[j] = v[d * 3 + j] + 1e-6;
        pts[d + j] = 0.5 * (v[d * 5 + j] + v[d * 6 + j]) + (j == 0 ? 1e-6 : 0.0);
    }
    cr_assert_eq(dfl_rfunc_batch_fallbacks(b, M, pts), 0);
    dfl_rfunc_batch_eval(b, M, pts, uf, gf);
    const size_t ns = closed ? nv : nv - 1;
    for (int i = 0; i < M; i++) {
        const double *x = pts + d * i;
        double S = 0, h[128], gh[3 * 128];
        cr_assert(ns <= 128);
        for (size_t k = 0; k < ns; k++) {
            dfl_rfunc_seg seg;
            cr_assert_eq(dfl_rfunc_seg_init(dim, v + d * k, v + d * ((k + 1) % nv), trim, &seg,
                                            NULL),
                         DFL_OK);
            h[k] = dfl_rfunc_seg_eval(&seg, x, gh + 3 * k);
            S += pow(h[k], -p);
        }
        const double u = pow(S, -1.0 / p);
        double g[3] = {0, 0, 0}, s = 0;
        for (size_t k = 0; k < ns; k++) {
            const double c = pow(u / h[k], p + 1);
            double n2 = 0;
            for (size_t j = 0; j < d; j++) g[j] += c * gh[3 * k + j], n2 += gh[3 * k + j] * gh[3 * k + j];
            s += c * sqrt(n2);
        }
        cr_assert(fabs(uf[i] - u) <= 1e-12 * u, "dim %d trim %d p %d point %d: %.17g vs %.17g",
                  dim, (int)trim, p, i, uf[i], u);
        for (size_t j = 0; j < d; j++)
            cr_assert(fabs(gf[d * i + j] - g[j]) <= 1e-12 * s,
                      "dim %d trim %d p %d point %d grad %zu: %.17g vs %.17g", dim, (int)trim, p,
                      i, j, gf[d * i + j], g[j]);
    }
    dfl_rfunc_batch_free(b);
    free(v);
}

Test(rfunc_batch, strip_and_3d_kernels_agree)
{
    const int ps[] = {1, 2, 3, 7, 12, 13};
    for (size_t i = 0; i < sizeof ps / sizeof *ps; i++) {
        compare_kind(2, DFL_RFUNC_TRIM_STRIP, 41, 0, ps[i], 5 + i);
        compare_kind(2, DFL_RFUNC_TRIM_STRIP, 30, 1, ps[i], 55 + i);
        compare_kind(3, DFL_RFUNC_TRIM_DISK, 41, 0, ps[i], 7 + i);
        compare_kind(3, DFL_RFUNC_TRIM_STRIP, 30, 1, ps[i], 77 + i);
    }
}

/* rfield takes the kernels for exactly these fields, and equals its own
 * per-point path to 1e-12 there. */
Test(rfunc_batch, rfield_uses_every_eq4_kernel)
{
    double *v2 = spiral(20), v3[60];
    for (int i = 0; i < 20; i++) {
        v3[3 * i] = v2[2 * i];
        v3[3 * i + 1] = v2[2 * i + 1];
        v3[3 * i + 2] = 0.1 * i;
    }
    for (int dim = 2; dim <= 3; dim++)
        for (int t = 0; t < DFL_RFUNC_TRIM_COUNT; t++) {
            dfl_field ff, fs;
            const double *v = dim == 2 ? v2 : v3;
            cr_assert_eq(dfl_rfield_polyline_opts(dim, v, 20, false, DFL_RFUNC_REQUIV, 2,
                                                  (dfl_rfunc_trim)t, true, &ff, NULL),
                         DFL_OK);
            cr_assert_eq(dfl_rfield_polyline_opts(dim, v, 20, false, DFL_RFUNC_REQUIV, 2,
                                                  (dfl_rfunc_trim)t, false, &fs, NULL),
                         DFL_OK);
            /* eq. 4: the built-in kernels; eq. 5: batch_smooth.c */
            cr_expect(dfl_rfield_is_fast(&ff), "dim %d trim %d", dim, t);
            cr_expect(!dfl_rfield_is_fast(&fs));
            const double x[3] = {0.61, 0.37, 0.2};
            double ga[3], gb[3];
            const double ua = dfl_field_eval1(&ff, x, ga), ub = dfl_field_eval1(&fs, x, gb);
            cr_expect(fabs(ua - ub) <= 1e-12 * ub, "dim %d trim %d", dim, t);
            dfl_field_destroy(&ff);
            dfl_field_destroy(&fs);
        }
    free(v2);
}

/* The point kernel: rfield's batched points field against its per-point
 * path (1e-12; gradients against the sum of absolute contributions, which
 * here is bounded by |grad u| + the cancelling parts: use 1e-12 (1 + s)
 * with s = sum (u/h_i)^(p+1)), 2D and 3D, at random points and on a part. */
Test(rfunc_batch, points_kernel_agrees)
{
    uint64_t rng = 4242;
    for (int dim = 2; dim <= 3; dim++)
        for (int p = 1; p <= 13; p += 3) {
            double c[3 * 37];
            for (int i = 0; i < 3 * 37; i++) c[i] = dfl_rng_splitmix(&rng, 0, 1);
            dfl_field ff, fs;
            dfl_rfield *r;
            for (int fast = 0; fast < 2; fast++) {
                cr_assert_eq(dfl_rfield_new(dim, DFL_RFUNC_REQUIV, p, &r, NULL), DFL_OK);
                dfl_rfield_set_fast(r, fast);
                for (int i = 0; i < 37; i++)
                    cr_assert_eq(dfl_rfield_add_point(r, c + dim * i, NULL), DFL_OK);
                cr_assert_eq(dfl_rfield_finish(&r, fast ? &ff : &fs, NULL), DFL_OK);
            }
            cr_assert(dfl_rfield_is_fast(&ff) && !dfl_rfield_is_fast(&fs));
            for (int i = 0; i < 60; i++) {
                double x[3];
                for (int j = 0; j < dim; j++) x[j] = dfl_rng_splitmix(&rng, -0.5, 1.5);
                if (i == 0)
                    for (int j = 0; j < dim; j++) x[j] = c[j]; /* on a part: u = 0 */
                double ga[3], gb[3];
                const double ua = dfl_field_eval1(&ff, x, ga), ub = dfl_field_eval1(&fs, x, gb);
                cr_assert(fabs(ua - ub) <= 1e-12 * ub, "dim %d p %d: %.17g vs %.17g", dim, p, ua,
                          ub);
                double s = 0;
                for (int k = 0; k < 37 && ub > 0; k++) {
                    double w2 = 0;
                    for (int j = 0; j < dim; j++) w2 += (x[j] - c[dim * k + j]) * (x[j] - c[dim * k + j]);
                    s += pow(ub / sqrt(w2), p + 1);
                }
                for (int j = 0; j < dim; j++)
                    cr_assert(fabs(ga[j] - gb[j]) <= 1e-12 * (1 + s), "dim %d p %d grad %d", dim, p,
                              j);
            }
            dfl_field_destroy(&ff);
            dfl_field_destroy(&fs);
        }
}

/* The triangle kernel against the per-point path (1e-12; gradients
 * against s = sum (u/h_i)^(p+1) |grad h_i|, evaluated from the library's
 * triangle fields), prism and conditional, with points near the mesh and
 * on its vertex lines (those fall back). */
Test(rfunc_batch, triangles_kernel_agrees)
{
    uint64_t rng = 99;
    for (int trim = 0; trim < 2; trim++)
        for (int p = 1; p <= 12; p += 11) {
            dfl_rfunc_tri_opts o = dfl_rfunc_tri_defaults();
            o.trim = (dfl_rfunc_tri_trim)trim;
            enum { NT = 18 };
            dfl_rfunc_tri t[NT];
            dfl_field ff, fs;
            for (int fast = 0; fast < 2; fast++) {
                dfl_rfield *r;
                cr_assert_eq(dfl_rfield_new(3, DFL_RFUNC_REQUIV, p, &r, NULL), DFL_OK);
                dfl_rfield_set_fast(r, fast);
                for (int k = 0; k < NT; k++) {
                    const double x0 = (k % 6) / 6.0, y0 = (k / 6) / 3.0;
                    const double A[3] = {x0, y0, 0.1 * sin(7 * x0)},
                                 B[3] = {x0 + 1 / 6.0, y0, 0.1 * sin(7 * x0 + 1)},
                                 C[3] = {x0, y0 + 1 / 3.0, 0.05};
                    cr_assert_eq(dfl_rfield_add_triangle(r, A, B, C, &o, NULL), DFL_OK);
                    cr_assert_eq(dfl_rfunc_tri_init(A, B, C, &o, &t[k], NULL), DFL_OK);
                }
                cr_assert_eq(dfl_rfield_finish(&r, fast ? &ff : &fs, NULL), DFL_OK);
            }
            cr_assert(dfl_rfield_is_fast(&ff) && !dfl_rfield_is_fast(&fs));
            for (int i = 0; i < 80; i++) {
                double x[3];
                for (int j = 0; j < 3; j++) x[j] = dfl_rng_splitmix(&rng, -0.3, 1.3);
                if (i == 0) x[0] = t[3].v[1][0], x[1] = t[3].v[1][1], x[2] = 0.7; /* vertex line */
                if (i == 1) x[0] = 0.3, x[1] = 0.2, x[2] = t[0].v[0][2] + 1e-7;
                double ga[3], gb[3], s = 0;
                const double ua = dfl_field_eval1(&ff, x, ga), ub = dfl_field_eval1(&fs, x, gb);
                cr_assert(fabs(ua - ub) <= 1e-12 * ub, "trim %d p %d point %d: %.17g vs %.17g",
                          trim, p, i, ua, ub);
                for (int k = 0; k < NT; k++) {
                    double g[3];
                    const double h = dfl_rfunc_tri_eval(&t[k], x, g);
                    s += pow(ub / h, p + 1) * sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
                }
                for (int j = 0; j < 3; j++)
                    cr_assert(fabs(ga[j] - gb[j]) <= 1e-12 * s, "trim %d p %d point %d grad %d: "
                              "%.17g vs %.17g", trim, p, i, j, ga[j], gb[j]);
            }
            dfl_field_destroy(&ff);
            dfl_field_destroy(&fs);
        }
}

/* The region kernel against the per-point path (values 1e-12, gradients
 * 1e-12 (1 + |grad u|): the regions are apart, so few contributions
 * cancel), with points inside a region (u = 0). */
Test(rfunc_batch, regions_kernel_agrees)
{
    uint64_t rng = 7;
    for (int p = 1; p <= 12; p += 11) {
        dfl_field ff, fs;
        for (int fast = 0; fast < 2; fast++) {
            dfl_rfield *r;
            cr_assert_eq(dfl_rfield_new(2, DFL_RFUNC_REQUIV, p, &r, NULL), DFL_OK);
            dfl_rfield_set_fast(r, fast);
            for (int i = 0; i < 12; i++) {
                const double cx = (i % 4 + 0.5) / 4, cy = (i / 4 + 0.5) / 3, h = 0.08;
                /* a pentagon */
                double q[10];
                for (int j = 0; j < 5; j++) {
                    q[2 * j] = cx + h * cos(2 * acos(-1.0) * j / 5 + i);
                    q[2 * j + 1] = cy + h * sin(2 * acos(-1.0) * j / 5 + i);
                }
                cr_assert_eq(dfl_rfield_add_region(r, q, 5, NULL), DFL_OK);
            }
            cr_assert_eq(dfl_rfield_finish(&r, fast ? &ff : &fs, NULL), DFL_OK);
        }
        cr_assert(dfl_rfield_is_fast(&ff) && !dfl_rfield_is_fast(&fs));
        for (int i = 0; i < 100; i++) {
            double x[2] = {dfl_rng_splitmix(&rng, -0.3, 1.3), dfl_rng_splitmix(&rng, -0.3, 1.3)};
            if (i == 0) x[0] = 0.125, x[1] = 1.0 / 6; /* inside the first region */
            double ga[2], gb[2];
            const double ua = dfl_field_eval1(&ff, x, ga), ub = dfl_field_eval1(&fs, x, gb);
            if (i == 0) cr_expect_eq(ua, 0.0);
            cr_assert(fabs(ua - ub) <= 1e-12 * ub, "p %d point %d: %.17g vs %.17g", p, i, ua, ub);
            for (int j = 0; j < 2; j++)
                cr_assert(fabs(ga[j] - gb[j]) <= 1e-12 * (1 + fabs(gb[j])), "p %d point %d", p, i);
        }
        dfl_field_destroy(&ff);
        dfl_field_destroy(&fs);
    }
}

/* dfl_rfunc_batch_points needs n >= 2 point parts (batch.h: DFL_E_INPUT for
 * n < 2), so one point is refused and two are accepted. */
Test(rfunc_batch, points_kernel_needs_two_points)
{
    const double c[6] = {0.1, 0.2, 0.3, 0.9, -0.4, 0.5};
    for (int dim = 2; dim <= 3; dim++) {
        dfl_rfunc_batch *b = NULL;
        dfl_err err;
        cr_expect_eq(dfl_rfunc_batch_points(dim, c, 0, 2, &b, &err), DFL_E_INPUT, "dim %d", dim);
        cr_expect_eq(dfl_rfunc_batch_points(dim, c, 1, 2, &b, &err), DFL_E_INPUT, "dim %d", dim);
        cr_expect_null(b);
        cr_assert_eq(dfl_rfunc_batch_points(dim, c, 2, 2, &b, &err), DFL_OK, "%s", err.msg);
        dfl_rfunc_batch_free(b);
    }
}
