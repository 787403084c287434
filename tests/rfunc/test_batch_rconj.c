/* The R-conjunction kernel (rfunc/batch_rconj.c) against the field's
 * per-point path (the same field built with the fast path off).
 *
 * Tolerance: values 1e-12 relative; gradients 1e-12 times
 * s = sum_i |du/dh_i| |grad h_i|, the sum of absolute contributions to
 * grad u = sum_i (du/dh_i) grad h_i, where du/dh_i is the product of the
 * fold's partials (join.c's dfl_rfunc_rconj2), accumulated forward like
 * grad u: s_k = F_a s_(k-1) + F_b |grad h_k|.  On a part u = 0 and
 * grad u = 0 in both paths exactly. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/vec.h"
#include "rfunc/batch.h"
#include "rfunc/rfield.h"
#include "rfunc/segment.h"
#include "rfunc_util.h"

/* A wobbly spiral of n vertices in [0, 1]^2 (3D: rising in z). */
static void curve(int dim, size_t n, double *v)
{
    for (size_t i = 0; i < n; i++) {
        const double t = (double)i / (double)(n - 1);
        const double r = 0.1 + 0.35 * t + 0.02 * sin(40 * t);
        v[dim * i] = 0.5 + r * cos(5 * t);
        v[dim * i + 1] = 0.5 + r * sin(5 * t);
        if (dim == 3) v[dim * i + 2] = 0.3 * t + 0.05 * cos(17 * t);
    }
}

/* s of the header at x for the polyline v (n vertices). */
static double abs_sum(int dim, const double *v, size_t n, int closed, int p, dfl_rfunc_trim trim,
                      const double *x)
{
    const size_t ns = closed ? n : n - 1;
    double u = 0, s = 0;
    for (size_t k = 0; k < ns; k++) {
        dfl_rfunc_seg seg;
        double gh[3];
        cr_assert_eq(dfl_rfunc_seg_init(dim, v + dim * k, v + dim * ((k + 1) % n), trim, &seg,
                                        NULL),
                     DFL_OK);
        const double h = dfl_rfunc_seg_eval(&seg, x, gh), gn = tu_norm(dim, gh);
        if (k == 0) {
            u = h;
            s = gn;
            continue;
        }
        double Fa, Fb;
        u = dfl_rfunc_rconj2(u, h, p, &Fa, &Fb);
        s = fabs(Fa) * s + fabs(Fb) * gn;
    }
    return s;
}

/* Test points: random around the curve, on its segments, its vertices,
 * 1e-9 off its segments and beyond their end points, far (1e8) and at the
 * domain's edge (1e100).  Returns the count (<= cap). */
static size_t points(int dim, const double *v, size_t n, int closed, uint64_t seed, double *x,
                     size_t cap)
{
    size_t m = 0;
    uint64_t rng = seed;
#define PUT3(a, b, c)                   \
    do {                                \
        cr_assert(m < cap);             \
        x[dim * m] = (a);               \
        x[dim * m + 1] = (b);           \
        if (dim == 3) x[dim * m + 2] = (c); \
        m++;                            \
    } while (0)
    for (int i = 0; i < 211; i++)
        PUT3(tu_uniform(&rng, -0.3, 1.3), tu_uniform(&rng, -0.3, 1.3),
             tu_uniform(&rng, -0.3, 0.6));
    const size_t ns = closed ? n : n - 1;
    for (size_t k = 0; k < ns; k++) {
        const double *a = v + dim * k, *b = v + dim * ((k + 1) % n);
        double e[3] = {0, 0, 0}, q[3] = {0, 0, 0};
        for (int j = 0; j < dim; j++) e[j] = b[j] - a[j];
        const double d = tu_norm(dim, e);
        /* a unit vector across the segment */
        q[0] = e[1] / d;
        q[1] = -e[0] / d;
        PUT3(a[0], a[1], a[dim - 1]);
        PUT3(a[0] + 0.375 * e[0], a[1] + 0.375 * e[1], a[dim - 1] + 0.375 * e[dim - 1]);
        PUT3(a[0] + 0.5 * e[0] + 1e-9 * q[0], a[1] + 0.5 * e[1] + 1e-9 * q[1],
             a[dim - 1] + 0.5 * e[dim - 1]);
        PUT3(b[0] + 1e-9 * e[0] / d, b[1] + 1e-9 * e[1] / d, b[dim - 1] + 1e-9 * e[dim - 1] / d);
        PUT3(a[0] + 0.5 * e[0] + 0.3 * q[0], a[1] + 0.5 * e[1] + 0.3 * q[1],
             a[dim - 1] + 0.5 * e[dim - 1]);
    }
    for (int i = 0; i < 8; i++) {
        const double th = tu_uniform(&rng, 0, 6.283185307179586);
        PUT3(1e8 * cos(th), 1e8 * sin(th), 1e7);
    }
    PUT3(1e100, -3e99, 1e99);
    PUT3(-1e100, 1e100, -1e100);
#undef PUT3
    return m;
}

/* Builds the fast and the per-point field and compares them at the test
 * points (one call for all, then point by point: bitwise equal). */
static void compare(int dim, const double *v, size_t n, int closed, int p, dfl_rfunc_trim trim,
                      uint64_t seed)
{
    dfl_field fast, slow;
    dfl_err err;
    cr_assert_eq(dfl_rfield_polyline(dim, v, n, closed, DFL_RFUNC_RCONJ, p, trim, &fast, &err),
                 DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_rfield_polyline_opts(dim, v, n, closed, DFL_RFUNC_RCONJ, p, trim, false,
                                          &slow, &err),
                 DFL_OK, "%s", err.msg);
    cr_assert(dfl_rfield_is_fast(&fast), "dim %d p %d trim %d: not batched", dim, p, trim);
    cr_assert(!dfl_rfield_is_fast(&slow));
    enum { CAP = 800 };
    double *x = malloc(3 * CAP * sizeof *x), *uf = malloc(CAP * sizeof *uf);
    double *us = malloc(CAP * sizeof *us), *gf = malloc(3 * CAP * sizeof *gf);
    double *gs = malloc(3 * CAP * sizeof *gs);
    const size_t m = points(dim, v, n, closed, seed, x, CAP);
    fast.ops->eval(fast.ctx, m, x, uf, gf);
    slow.ops->eval(slow.ctx, m, x, us, gs);
    for (size_t i = 0; i < m; i++) {
        const double *xi = x + dim * i;
        if (us[i] == 0.0) {
            cr_assert(uf[i] == 0.0, "point %zu: %.17g vs 0", i, uf[i]);
            for (int j = 0; j < dim; j++) cr_assert(gf[dim * i + j] == 0.0);
            continue;
        }
        cr_assert(fabs(uf[i] - us[i]) <= 1e-12 * us[i],
                  "dim %d p %d trim %d closed %d point %zu (%g, %g): %.17g vs %.17g", dim, p,
                  trim, closed, i, xi[0], xi[1], uf[i], us[i]);
        const double s = abs_sum(dim, v, n, closed, p, trim, xi);
        for (int j = 0; j < dim; j++)
            cr_assert(fabs(gf[dim * i + j] - gs[dim * i + j]) <= 1e-12 * s,
                      "dim %d p %d trim %d point %zu grad %d: %.17g vs %.17g (s %g)", dim, p,
                      trim, i, j, gf[dim * i + j], gs[dim * i + j], s);
        /* chunking: the point alone gives the same bits, with or without
         * the gradient */
        double u1, g1[3], u0;
        fast.ops->eval(fast.ctx, 1, xi, &u1, g1);
        fast.ops->eval(fast.ctx, 1, xi, &u0, NULL);
        cr_assert(memcmp(&u1, &uf[i], sizeof u1) == 0 && memcmp(&u0, &uf[i], sizeof u0) == 0);
        cr_assert(memcmp(g1, gf + dim * i, (size_t)dim * sizeof *g1) == 0);
    }
    free(x);
    free(uf);
    free(us);
    free(gf);
    free(gs);
    dfl_field_destroy(&fast);
    dfl_field_destroy(&slow);
}

static const int ORDERS[] = {2, 3, 4, 5, 6, 7, 8, 9, 12, 23, 64};

Test(batch_rconj, agrees_2d)
{
    double v[2 * 14];
    curve(2, 14, v);
    for (size_t ip = 0; ip < sizeof ORDERS / sizeof *ORDERS; ip++)
        for (int closed = 0; closed < 2; closed++)
            for (int strip = 0; strip < 2; strip++)
                compare(2, v, 14, closed, ORDERS[ip],
                        strip ? DFL_RFUNC_TRIM_STRIP : DFL_RFUNC_TRIM_DISK, 17 + ip);
}

Test(batch_rconj, agrees_3d)
{
    double v[3 * 11];
    curve(3, 11, v);
    for (size_t ip = 0; ip < sizeof ORDERS / sizeof *ORDERS; ip++)
        for (int closed = 0; closed < 2; closed++)
            for (int strip = 0; strip < 2; strip++)
                compare(3, v, 11, closed, ORDERS[ip],
                        strip ? DFL_RFUNC_TRIM_STRIP : DFL_RFUNC_TRIM_DISK, 91 + ip);
}

/* Two segments where the fold's ratio r = lo/hi sweeps (0, 1]: tiny r
 * (r^p far below rounding: a ^ b = lo to the last bit in exact
 * arithmetic; x g(x) must not lose it), r = 1 on the bisector, and all of
 * the polynomial's range in between; any p.  One fold step, so the
 * tolerances are tight: the root to a few ulp. */
Test(batch_rconj, ratio_sweep)
{
    const double v[6] = {1, 0, 0, 0, 0, 1};
    for (int p = 2; p <= 20; p++) {
        dfl_field fast, slow;
        cr_assert_eq(dfl_rfield_polyline(2, v, 3, 0, DFL_RFUNC_RCONJ, p, DFL_RFUNC_TRIM_DISK,
                                         &fast, NULL),
                     DFL_OK);
        cr_assert_eq(dfl_rfield_polyline_opts(2, v, 3, 0, DFL_RFUNC_RCONJ, p,
                                              DFL_RFUNC_TRIM_DISK, false, &slow, NULL),
                     DFL_OK);
        cr_assert(dfl_rfield_is_fast(&fast));
        for (int i = 0; i <= 400; i++) {
            /* (0.5, y): h_1 = y, h_2 = 0.5 for y <= 0.5 */
            const double y = i < 200 ? 0.5 * pow(10.0, -12.0 * i / 200.0) : 0.5 * (i - 200) / 200.0;
            const double x[2] = {0.5, y > 0 ? y : 1e-30};
            double gf[2], gs[2];
            const double uf = dfl_field_eval1(&fast, x, gf), us = dfl_field_eval1(&slow, x, gs);
            /* one fold step: both paths within a few ulp of a ^ b (the
             * kernel's root, the polynomial for p >= 3, to ~1 ulp) */
            cr_assert(fabs(uf - us) <= 2e-15 * us, "p %d y %g: %.17g vs %.17g", p, x[1], uf, us);
            /* |grad h_i| = 1 here; join.c's partials 1 - w^(1-p) have
             * absolute accuracy ~p eps */
            cr_assert(fabs(gf[0] - gs[0]) <= 1e-13 && fabs(gf[1] - gs[1]) <= 1e-13,
                      "p %d y %g: (%.17g, %.17g) vs (%.17g, %.17g)", p, x[1], gf[0], gf[1], gs[0],
                      gs[1]);
        }
        dfl_field_destroy(&fast);
        dfl_field_destroy(&slow);
    }
}

/* Which fields the kernel takes: R-conjunction of segments with one eq. 4
 * trim (any arrangement, gaps included); not the smooth trims, mixed trims
 * or other part kinds. */
Test(batch_rconj, eligibility)
{
    double v[2 * 8];
    curve(2, 8, v);
    for (int variant = 0; variant < 5; variant++) {
        dfl_rfield *r;
        dfl_field f;
        cr_assert_eq(dfl_rfield_new(2, DFL_RFUNC_RCONJ, 3, &r, NULL), DFL_OK);
        for (size_t k = 0; k + 1 < 8; k++) {
            if (variant == 1 && k == 3) continue; /* a gap: still a set of segments */
            dfl_rfunc_trim t = DFL_RFUNC_TRIM_DISK;
            if (variant == 2) t = DFL_RFUNC_TRIM_DISK_SMOOTH;
            if (variant == 3 && k == 5) t = DFL_RFUNC_TRIM_STRIP;
            cr_assert_eq(dfl_rfield_add_segment(r, v + 2 * k, v + 2 * k + 2, t, NULL), DFL_OK);
        }
        if (variant == 4) cr_assert_eq(dfl_rfield_add_point(r, v, NULL), DFL_OK);
        cr_assert_eq(dfl_rfield_finish(&r, &f, NULL), DFL_OK);
        cr_assert_eq(dfl_rfield_is_fast(&f), variant <= 1, "variant %d", variant);
        if (variant == 1) {
            /* and it agrees at a point beside the gap */
            dfl_rfield *rs;
            dfl_field fs;
            cr_assert_eq(dfl_rfield_new(2, DFL_RFUNC_RCONJ, 3, &rs, NULL), DFL_OK);
            dfl_rfield_set_fast(rs, false);
            for (size_t k = 0; k + 1 < 8; k++)
                if (k != 3)
                    cr_assert_eq(dfl_rfield_add_segment(rs, v + 2 * k, v + 2 * k + 2,
                                                        DFL_RFUNC_TRIM_DISK, NULL),
                                 DFL_OK);
            cr_assert_eq(dfl_rfield_finish(&rs, &fs, NULL), DFL_OK);
            const double x[2] = {0.5 * (v[6] + v[8]), 0.5 * (v[7] + v[9])};
            const double a = dfl_field_eval1(&f, x, NULL), b = dfl_field_eval1(&fs, x, NULL);
            cr_assert(fabs(a - b) <= 1e-12 * b);
            dfl_field_destroy(&fs);
        }
        dfl_field_destroy(&f);
    }
}

/* Fallback: points on the parts (u = 0) fall back, points off them do
 * not, counted by the batch's diagnostic. */
Test(batch_rconj, fallback_count)
{
    double v[2 * 10], x[2 * 40];
    curve(2, 10, v);
    dfl_field slow;
    cr_assert_eq(dfl_rfield_polyline_opts(2, v, 10, 0, DFL_RFUNC_RCONJ, 2, DFL_RFUNC_TRIM_DISK,
                                          false, &slow, NULL),
                 DFL_OK);
    dfl_rfunc_part parts[9];
    for (int k = 0; k < 9; k++) {
        parts[k].kind = DFL_RFUNC_PART_SEGMENT;
        cr_assert_eq(dfl_rfunc_seg_init(2, v + 2 * k, v + 2 * k + 2, DFL_RFUNC_TRIM_DISK,
                                        &parts[k].u.seg, NULL),
                     DFL_OK);
    }
    const size_t vstart[10] = {0};
    const dfl_rfunc_batch_desc d = {2, DFL_RFUNC_RCONJ, 2, DFL_RFUNC_CORR_GUARDED, parts, 9,
                                    NULL, 0, vstart, &slow};
    dfl_rfunc_batch *b;
    cr_assert_eq(dfl_rfunc_batch_build(&d, &b, NULL), DFL_OK);
    cr_assert(b != NULL);
    uint64_t rng = 5;
    for (int i = 0; i < 40; i++) {
        x[2 * i] = tu_uniform(&rng, -0.3, 1.3);
        x[2 * i + 1] = tu_uniform(&rng, -0.3, 1.3);
    }
    cr_assert_eq(dfl_rfunc_batch_fallbacks(b, 40, x), 0);
    x[2] = v[4], x[3] = v[5];                   /* a vertex */
    x[20] = 0.5 * (v[8] + v[10]), x[21] = 0.5 * (v[9] + v[11]); /* on a segment (to rounding) */
    cr_assert_geq(dfl_rfunc_batch_fallbacks(b, 40, x), 1);
    double u[40];
    dfl_rfunc_batch_eval(b, 40, x, u, NULL);
    cr_assert(u[1] == 0.0);
    dfl_rfunc_batch_free(b);
    dfl_field_destroy(&slow);
}
