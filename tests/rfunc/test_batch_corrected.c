/* The corrected join's batched kernel (rfunc/batch_corrected.c) against
 * the per-point path (the same field built with the fast path off), both
 * forms (guarded, eq20), disk and strip trims, 2D and 3D, open and closed
 * polylines.
 *
 * Tolerance: values 1e-12 relative; gradients 1e-12 times s = sum_i
 * (u/h_i)^(p+1) |grad h_i| + sum_v (u/qt_v)^(p+1) |grad qt_v| (the sum of
 * absolute contributions, which bounds the rounding of grad u where they
 * cancel; |grad qt| = 1 for q, and the parts' gradients are those of the
 * library's segment fields).  NaN (eq20 undefined) exactly where the
 * per-point path gives NaN; chunking independence bitwise. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "rfunc/batch.h"
#include "rfunc/rfield.h"
#include "rfunc/segment.h"
#include "rfunc_util.h"

/* m points at once through the field's batched eval */
#define FEVAL(f, m, x, u, g) (f)->ops->eval((f)->ctx, (m), (x), (u), (g))

typedef struct shape {
    int dim;
    const double *v;
    size_t n;
    bool closed;
} shape;

/* fast (or per-point) field of the polyline with the corrected join. */
static void build(const shape *s, int p, dfl_rfunc_trim trim, dfl_rfunc_correction corr,
                  bool fast, dfl_field *out)
{
    dfl_rfield *r;
    dfl_err err;
    cr_assert_eq(dfl_rfield_new(s->dim, DFL_RFUNC_REQUIV_CORRECTED, p, &r, &err), DFL_OK, "%s",
                 err.msg);
    dfl_rfield_set_fast(r, fast);
    dfl_rfield_set_correction(r, corr);
    cr_assert_eq(dfl_rfield_add_polyline(r, s->v, s->n, s->closed, trim, &err), DFL_OK, "%s",
                 err.msg);
    cr_assert_eq(dfl_rfield_finish(&r, out, &err), DFL_OK, "%s", err.msg);
}

/* s of the header at x for u > 0. */
static double abs_sum(const shape *s, int p, dfl_rfunc_trim trim, int eq20, double u,
                      const double *x)
{
    const int dim = s->dim;
    const size_t ns = s->closed ? s->n : s->n - 1;
    double h[64], acc = 0;
    cr_assert(ns <= 64);
    for (size_t k = 0; k < ns; k++) {
        dfl_rfunc_seg seg;
        double gh[3];
        cr_assert_eq(dfl_rfunc_seg_init(dim, s->v + dim * k, s->v + dim * ((k + 1) % s->n), trim,
                                        &seg, NULL),
                     DFL_OK);
        h[k] = dfl_rfunc_seg_eval(&seg, x, gh);
        acc += pow(u / h[k], p + 1) * tu_norm(dim, gh);
    }
    for (size_t i = s->closed ? 0 : 1; i < (s->closed ? s->n : s->n - 1); i++) {
        double w[3] = {0, 0, 0};
        for (int j = 0; j < dim; j++) w[j] = x[j] - s->v[dim * i + j];
        double qt = tu_norm(dim, w);
        if (!eq20) qt = fmax(qt, fmax(h[i == 0 ? ns - 1 : i - 1], h[i]));
        acc += pow(u / qt, p + 1);
    }
    return acc;
}

/* Test points for s: random around it, on its segments, its vertices,
 * 1e-9 off, far (1e8) and huge (1e100) coordinates.  Returns the count. */
static size_t points(const shape *s, uint64_t seed, double *x, size_t cap)
{
    const int dim = s->dim;
    size_t m = 0;
#define PUT3(a, b, c)                          \
    do {                                       \
        cr_assert(m < cap);                    \
        x[dim * m] = (a);                      \
        x[dim * m + 1] = (b);                  \
        if (dim == 3) x[dim * m + 2] = (c);    \
        m++;                                   \
    } while (0)
    uint64_t rng = seed;
    for (int i = 0; i < 400; i++)
        PUT3(tu_uniform(&rng, -1.5, 1.5), tu_uniform(&rng, -1.5, 1.5),
             tu_uniform(&rng, -1.5, 1.5));
    const size_t ns = s->closed ? s->n : s->n - 1;
    for (size_t k = 0; k < ns; k++) {
        const double *a = s->v + dim * k, *b = s->v + dim * ((k + 1) % s->n);
        double e[3] = {0, 0, 0}, nn[3] = {0, 0, 0};
        for (int j = 0; j < dim; j++) e[j] = b[j] - a[j];
        const double d = tu_norm(dim, e);
        nn[0] = e[1] / d, nn[1] = -e[0] / d;
        PUT3(a[0], a[1], dim == 3 ? a[2] : 0);
        PUT3(a[0] + 0.375 * e[0], a[1] + 0.375 * e[1], dim == 3 ? a[2] + 0.375 * e[2] : 0);
        for (int sg = -1; sg <= 1; sg += 2) {
            PUT3(a[0] + 0.5 * e[0] + sg * 1e-9 * nn[0], a[1] + 0.5 * e[1] + sg * 1e-9 * nn[1],
                 dim == 3 ? a[2] + 0.5 * e[2] : 0);
            PUT3(b[0] + sg * 1e-9 * e[0] / d, b[1] + sg * 1e-9 * e[1] / d,
                 dim == 3 ? b[2] + sg * 1e-9 * e[2] / d : 0);
            /* beyond the end, in the hatched sector's direction */
            PUT3(b[0] + sg * 0.3 * nn[0] + 0.2 * e[0] / d, b[1] + sg * 0.3 * nn[1] + 0.2 * e[1] / d,
                 dim == 3 ? b[2] + 0.2 * e[2] / d : 0);
        }
    }
    for (int i = 0; i < 12; i++) {
        const double th = tu_uniform(&rng, 0, 2 * DFL_PI);
        PUT3(1e8 * cos(th), 1e8 * sin(th), 3e7);
        PUT3(1e100 * cos(th), 1e100 * sin(th), 0.5e100);
        PUT3(3 * cos(th), 3 * sin(th), 1);
    }
#undef PUT3
    return m;
}

/* Fast against per-point at the points of s; returns the NaN count. */
static size_t compare(const shape *s, int p, dfl_rfunc_trim trim, dfl_rfunc_correction corr,
                      uint64_t seed)
{
    dfl_field fast, slow;
    build(s, p, trim, corr, true, &fast);
    build(s, p, trim, corr, false, &slow);
    cr_assert(dfl_rfield_is_fast(&fast), "p %d trim %d corr %d: fast path not taken", p, trim,
              corr);
    cr_assert(!dfl_rfield_is_fast(&slow));
    enum { CAP = 1200 };
    const int dim = s->dim;
    double *x = malloc(3 * CAP * sizeof *x), *uf = malloc(CAP * sizeof *uf),
           *us = malloc(CAP * sizeof *us), *gf = malloc(3 * CAP * sizeof *gf),
           *gs = malloc(3 * CAP * sizeof *gs);
    const size_t m = points(s, seed, x, CAP);
    FEVAL(&fast, m, x, uf, gf);
    FEVAL(&slow, m, x, us, gs);
    size_t nan = 0;
    for (size_t i = 0; i < m; i++) {
        const double *xi = x + dim * i;
        cr_assert_eq(isnan(uf[i]), isnan(us[i]), "NaN-ness at (%.17g, %.17g): %g vs %g", xi[0],
                     xi[1], uf[i], us[i]);
        if (isnan(us[i])) {
            nan++;
            for (int j = 0; j < dim; j++) cr_assert(isnan(gf[dim * i + j]));
            continue;
        }
        cr_assert(fabs(uf[i] - us[i]) <= 1e-12 * us[i],
                  "p %d trim %d corr %d at (%.17g, %.17g): u %.17g vs %.17g", p, trim, corr,
                  xi[0], xi[1], uf[i], us[i]);
        if (us[i] == 0.0) {
            for (int j = 0; j < dim; j++) cr_assert_eq(gf[dim * i + j], gs[dim * i + j]);
            continue;
        }
        const double sabs = abs_sum(s, p, trim, corr == DFL_RFUNC_CORR_EQ20, us[i], xi);
        for (int j = 0; j < dim; j++)
            cr_assert(fabs(gf[dim * i + j] - gs[dim * i + j]) <= 1e-12 * sabs,
                      "p %d trim %d corr %d at (%.17g, %.17g): grad %d %.17g vs %.17g (s %g)", p,
                      trim, corr, xi[0], xi[1], j, gf[dim * i + j], gs[dim * i + j], sabs);
    }
    /* chunking: one by one equals all at once, bitwise */
    for (size_t i = 0; i < m; i += 7) {
        double u1, g1[3];
        FEVAL(&fast, 1, x + dim * i, &u1, g1);
        cr_assert(memcmp(&u1, uf + i, sizeof u1) == 0, "chunking at %zu", i);
        cr_assert(memcmp(g1, gf + dim * i, dim * sizeof *g1) == 0, "chunking grad at %zu", i);
    }
    free(x), free(uf), free(us), free(gf), free(gs);
    dfl_field_destroy(&fast);
    dfl_field_destroy(&slow);
    return nan;
}

/* A wobbly spiral of n vertices in [0, 1]^2 (3D: rising). */
static void spiral(int dim, size_t n, double *v)
{
    for (size_t i = 0; i < n; i++) {
        const double t = (double)i / (double)(n - 1);
        const double r = 0.1 + 0.35 * t + 0.02 * sin(40 * t);
        v[dim * i] = 0.5 + r * cos(9 * t);
        v[dim * i + 1] = 0.5 + r * sin(9 * t);
        if (dim == 3) v[dim * i + 2] = 0.3 * t;
    }
}

/* bs04_corrected's pair (experiments/bs04/vjoin.c): (L, 0), O, L (cos a, sin a). */
static void vjoin(double alpha_deg, double *v)
{
    double c = cos(alpha_deg * DFL_PI / 180), s = sin(alpha_deg * DFL_PI / 180);
    if (alpha_deg == 90.0) c = 0.0, s = 1.0;
    if (alpha_deg == 180.0) c = -1.0, s = 0.0;
    if (alpha_deg == 270.0) c = 0.0, s = -1.0;
    const double w[6] = {1, 0, 0, 0, c, s};
    memcpy(v, w, sizeof w);
}

static const int PS[] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 12};

Test(batch_corrected, agrees_2d)
{
    double sp[2 * 12], sq[2 * 5] = {0, 0, 1, 0, 1, 1, 0.5, 1.4, 0, 1}, vj[6];
    spiral(2, 12, sp);
    vjoin(90, vj);
    const shape shapes[] = {{2, sp, 12, false}, {2, sp, 12, true}, {2, sq, 5, true},
                            {2, vj, 3, false}};
    for (size_t si = 0; si < sizeof shapes / sizeof *shapes; si++)
        for (size_t pi = 0; pi < sizeof PS / sizeof *PS; pi++)
            for (int c = 0; c < DFL_RFUNC_CORRECTION_COUNT; c++) {
                compare(&shapes[si], PS[pi], DFL_RFUNC_TRIM_DISK, (dfl_rfunc_correction)c,
                        100 + si);
                compare(&shapes[si], PS[pi], DFL_RFUNC_TRIM_STRIP, (dfl_rfunc_correction)c,
                        200 + si);
            }
}

Test(batch_corrected, agrees_3d)
{
    double sp[3 * 8];
    spiral(3, 8, sp);
    const shape shapes[] = {{3, sp, 8, false}, {3, sp, 8, true}};
    const int ps[] = {1, 2, 7, 9};
    for (size_t si = 0; si < 2; si++)
        for (size_t pi = 0; pi < 4; pi++)
            for (int c = 0; c < DFL_RFUNC_CORRECTION_COUNT; c++)
                for (int t = 0; t < 2; t++)
                    compare(&shapes[si], ps[pi], t ? DFL_RFUNC_TRIM_STRIP : DFL_RFUNC_TRIM_DISK,
                            (dfl_rfunc_correction)c, 300 + si);
}

/* Which fields the kernel takes: segments with one eq. 4 trim; the guard's
 * lo the previous part or one of 4 kept parts (eq20 reads no lo). */
Test(batch_corrected, eligibility)
{
    double sp[2 * 12];
    spiral(2, 12, sp);
    const shape s = {2, sp, 12, true};
    dfl_field f;
    for (int c = 0; c < DFL_RFUNC_CORRECTION_COUNT; c++) {
        build(&s, 2, DFL_RFUNC_TRIM_DISK_SMOOTH, (dfl_rfunc_correction)c, true, &f);
        cr_expect(!dfl_rfield_is_fast(&f), "smooth trim corr %d", c);
        dfl_field_destroy(&f);
        /* k closed triangles in one field: k closing vertices with lo = the
         * triangle's first segment */
        for (int k = 4; k <= 5; k++) {
            dfl_rfield *r;
            cr_assert_eq(dfl_rfield_new(2, DFL_RFUNC_REQUIV_CORRECTED, 2, &r, NULL), DFL_OK);
            dfl_rfield_set_correction(r, (dfl_rfunc_correction)c);
            for (int i = 0; i < k; i++) {
                const double t[6] = {3.0 * i, 0, 3.0 * i + 1, 0, 3.0 * i, 1};
                cr_assert_eq(dfl_rfield_add_polyline(r, t, 3, true, DFL_RFUNC_TRIM_DISK, NULL),
                             DFL_OK);
            }
            cr_assert_eq(dfl_rfield_finish(&r, &f, NULL), DFL_OK);
            const bool want = c == DFL_RFUNC_CORR_EQ20 || k <= 4;
            cr_expect_eq(dfl_rfield_is_fast(&f), want, "corr %d, %d triangles", c, k);
            /* and it agrees with the per-point path where it is taken */
            const double x[2] = {7.2, 0.4};
            double g[2];
            const double u = dfl_field_eval1(&f, x, g);
            dfl_field_destroy(&f);
            cr_assert_eq(dfl_rfield_new(2, DFL_RFUNC_REQUIV_CORRECTED, 2, &r, NULL), DFL_OK);
            dfl_rfield_set_correction(r, (dfl_rfunc_correction)c);
            dfl_rfield_set_fast(r, false);
            for (int i = 0; i < k; i++) {
                const double t[6] = {3.0 * i, 0, 3.0 * i + 1, 0, 3.0 * i, 1};
                cr_assert_eq(dfl_rfield_add_polyline(r, t, 3, true, DFL_RFUNC_TRIM_DISK, NULL),
                             DFL_OK);
            }
            cr_assert_eq(dfl_rfield_finish(&r, &f, NULL), DFL_OK);
            double g2[2];
            const double u2 = dfl_field_eval1(&f, x, g2);
            cr_expect(fabs(u - u2) <= 1e-12 * u2, "corr %d, %d triangles: %.17g vs %.17g", c, k,
                      u, u2);
            dfl_field_destroy(&f);
        }
    }
}

/* bs04_corrected's shapes on its 99 x 99 grid over [-1.5, 1.5]^2: eq20's
 * NaN set is the per-point path's exactly (and the values agree), for
 * disk and strip trims at p = 2 and 7 and every alpha of the config.  With
 * disk trims at alpha = 90 eq. 20 is undefined on a large share of the
 * grid (issue 10: 30-50 %); with strip trims at p = 2 nowhere. */
Test(batch_corrected, eq20_nan_set_bs04_grid)
{
    enum { N = 99 };
    double *x = malloc(2 * N * N * sizeof *x), *uf = malloc(N * N * sizeof *uf),
           *us = malloc(N * N * sizeof *us), *gf = malloc(2 * N * N * sizeof *gf),
           *gs = malloc(2 * N * N * sizeof *gs);
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++) {
            x[2 * (i * N + j)] = -1.5 + 3.0 * j / (N - 1);
            x[2 * (i * N + j) + 1] = -1.5 + 3.0 * i / (N - 1);
        }
    const double alphas[] = {60, 90, 135, 180, 270};
    const int ps[] = {2, 7};
    for (size_t ai = 0; ai < 5; ai++)
        for (int pi = 0; pi < 2; pi++)
            for (int t = 0; t < 2; t++) {
                double v[6];
                vjoin(alphas[ai], v);
                const shape s = {2, v, 3, false};
                const dfl_rfunc_trim trim = t ? DFL_RFUNC_TRIM_STRIP : DFL_RFUNC_TRIM_DISK;
                dfl_field fast, slow;
                build(&s, ps[pi], trim, DFL_RFUNC_CORR_EQ20, true, &fast);
                build(&s, ps[pi], trim, DFL_RFUNC_CORR_EQ20, false, &slow);
                cr_assert(dfl_rfield_is_fast(&fast));
                FEVAL(&fast, N * N, x, uf, gf);
                FEVAL(&slow, N * N, x, us, gs);
                size_t nan = 0;
                for (size_t i = 0; i < N * N; i++) {
                    cr_assert_eq(isnan(uf[i]), isnan(us[i]),
                                 "alpha %g p %d trim %d at (%.17g, %.17g): %g vs %g",
                                 alphas[ai], ps[pi], t, x[2 * i], x[2 * i + 1], uf[i], us[i]);
                    nan += isnan(us[i]) != 0;
                    if (!isnan(us[i]))
                        cr_assert(fabs(uf[i] - us[i]) <= 1e-12 * us[i]);
                }
                if (t == 0 && alphas[ai] == 90.0)
                    cr_expect(nan > N * N / 4 && nan < N * N / 2, "alpha 90 disk p %d: %zu NaN",
                              ps[pi], nan);
                if (t == 1 && ps[pi] == 2 && alphas[ai] >= 90.0)
                    cr_expect_eq(nan, 0, "alpha %g strip p 2: %zu NaN", alphas[ai], nan);
                dfl_field_destroy(&fast);
                dfl_field_destroy(&slow);
            }
    free(x), free(uf), free(us), free(gf), free(gs);
}

/* A fine closed curve (the bench's: 1500 segments): the guarded sum
 * cancels to 1/64..1/512 of its absolute terms on most nodes, the
 * hardest case for the agreement; eq. 20 with disk trims is undefined
 * almost everywhere on it. */
Test(batch_corrected, fine_closed_curve)
{
    enum { NS = 1500, G = 24 };
    static double v[2 * NS];
    for (int i = 0; i < NS; i++) {
        const double th = 2.0 * DFL_PI * i / NS, r = 0.3 + 0.05 * sin(5.0 * th);
        v[2 * i] = 0.5 + r * cos(th);
        v[2 * i + 1] = 0.5 + r * sin(th);
    }
    const shape s = {2, v, NS, true};
    double x[2 * G * G], uf[G * G], us[G * G], gf[2 * G * G], gs[2 * G * G];
    for (int j = 0; j < G; j++)
        for (int i = 0; i < G; i++) {
            x[2 * (j * G + i)] = (i + 0.5) / G;
            x[2 * (j * G + i) + 1] = (j + 0.5) / G;
        }
    const int ps[] = {1, 2, 7};
    for (int pi = 0; pi < 3; pi++)
        for (int c = 0; c < DFL_RFUNC_CORRECTION_COUNT; c++) {
            dfl_field fast, slow;
            build(&s, ps[pi], DFL_RFUNC_TRIM_DISK, (dfl_rfunc_correction)c, true, &fast);
            build(&s, ps[pi], DFL_RFUNC_TRIM_DISK, (dfl_rfunc_correction)c, false, &slow);
            cr_assert(dfl_rfield_is_fast(&fast));
            FEVAL(&fast, G * G, x, uf, gf);
            FEVAL(&slow, G * G, x, us, gs);
            for (size_t i = 0; i < G * G; i++) {
                cr_assert_eq(isnan(uf[i]), isnan(us[i]));
                if (isnan(us[i])) continue;
                cr_assert(fabs(uf[i] - us[i]) <= 1e-12 * us[i], "p %d corr %d: %.17g vs %.17g",
                          ps[pi], c, uf[i], us[i]);
                const double gn = hypot(gs[2 * i], gs[2 * i + 1]);
                /* |grad u| <= s: a stricter bound than the header's */
                cr_assert(hypot(gf[2 * i] - gs[2 * i], gf[2 * i + 1] - gs[2 * i + 1]) <= 1e-12 * gn,
                          "p %d corr %d grad", ps[pi], c);
            }
            dfl_field_destroy(&fast);
            dfl_field_destroy(&slow);
        }
}
