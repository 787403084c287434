/* rfield's fast path (rfunc/batch.h as the eval of an eligible polyline
 * field) against its per-point accumulator (the same field built with the
 * fast path off), and which fields take it.
 *
 * Tolerance, as in test_batch.c: values 1e-12 relative; gradients 1e-12
 * times s = sum_i (u/h_i)^(p+1) |grad h_i| (the sum of absolute
 * contributions, which bounds the rounding of grad u = sum_i (u/h_i)^(p+1)
 * grad h_i where the contributions cancel), s from the library's segment
 * fields.  On the polyline u = 0 and grad u = 0 exactly in both paths. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "field/sample.h"
#include "rfunc/rfield.h"
#include "rfunc/segment.h"
#include "rfunc_util.h"

/* A wobbly spiral polyline of n vertices inside [0, 1]^2. */
static void spiral(size_t n, double *v)
{
    for (size_t i = 0; i < n; i++) {
        const double t = (double)i / (double)(n - 1);
        const double r = 0.1 + 0.35 * t + 0.02 * sin(40 * t);
        v[2 * i] = 0.5 + r * cos(9 * t);
        v[2 * i + 1] = 0.5 + r * sin(9 * t);
    }
}

/* Axis-parallel and diagonal segments with dyadic vertices, one at the
 * origin: points on them (dyadic parameters) are exact, and 1e-170 off
 * them is representable near the origin. */
static const double DYAD[10] = {0, 0, 1, 0, 1, 1, 0, 2, -1, 1};

/* s of the header for the polyline v (n vertices) at x, given u > 0. */
static double abs_sum(const double *v, size_t n, int closed, int p, double u, const double *x)
{
    const size_t ns = closed ? n : n - 1;
    double s = 0;
    for (size_t k = 0; k < ns; k++) {
        dfl_rfunc_seg seg;
        double gh[2];
        cr_assert_eq(dfl_rfunc_seg_init(2, v + 2 * k, v + 2 * ((k + 1) % n), DFL_RFUNC_TRIM_DISK,
                                        &seg, NULL),
                     DFL_OK);
        const double h = dfl_rfunc_seg_eval(&seg, x, gh);
        cr_assert(h > 0, "u = %g > 0 but h_%zu = 0", u, k);
        s += pow(u / h, p + 1) * hypot(gh[0], gh[1]);
    }
    return s;
}

/* Test points for the polyline v: random around it, on its segments
 * (dyadic parameters; exact for DYAD), its vertices, 1e-9 off its
 * segments, far away (1e8), and for DYAD 1e-170 off the segments and the
 * vertex at the origin.  Returns the count (<= cap). */
static size_t points(const double *v, size_t n, int closed, int dyad, uint64_t seed, double *x,
                     size_t cap)
{
    size_t m = 0;
#define PUT(a, b)              \
    do {                       \
        cr_assert(m < cap);    \
        x[2 * m] = (a);        \
        x[2 * m + 1] = (b);    \
        m++;                   \
    } while (0)
    uint64_t rng = seed;
    const double lo = dyad ? -1.5 : -0.3, hi = dyad ? 2.5 : 1.3;
    for (int i = 0; i < 301; i++) PUT(tu_uniform(&rng, lo, hi), tu_uniform(&rng, lo, hi));
    const size_t ns = closed ? n : n - 1;
    const double ts[4] = {0.25, 0.5, 0.75, 0.375};
    for (size_t k = 0; k < ns; k++) {
        const double *a = v + 2 * k, *b = v + 2 * ((k + 1) % n);
        const double dx = b[0] - a[0], dy = b[1] - a[1], d = hypot(dx, dy);
        PUT(a[0], a[1]);
        for (int j = 0; j < 4; j++) PUT(a[0] + ts[j] * dx, a[1] + ts[j] * dy);
        /* 1e-9 either side of the midpoint, and beyond the end point */
        PUT(a[0] + 0.5 * dx + 1e-9 * dy / d, a[1] + 0.5 * dy - 1e-9 * dx / d);
        PUT(a[0] + 0.5 * dx - 1e-9 * dy / d, a[1] + 0.5 * dy + 1e-9 * dx / d);
        PUT(b[0] + 1e-9 * dx / d, b[1] + 1e-9 * dy / d);
    }
    if (!closed) PUT(v[2 * n - 2], v[2 * n - 1]);
    for (int i = 0; i < 16; i++) {
        const double th = tu_uniform(&rng, 0, 2 * DFL_PI);
        PUT(1e8 * cos(th), 1e8 * sin(th));
    }
    PUT(1e8, 1e8);
    PUT(-1e8, 0.5);
    if (dyad) {
        const double e = 1e-170;
        PUT(0.5, e);
        PUT(0.5, -e);
        PUT(e, e);
        PUT(-e, -e);
        PUT(-e, 0);
        PUT(e, 0); /* on the first segment */
        PUT(0, -e);
        PUT(-e, 3 * e);
        PUT(1, e);
    }
#undef PUT
    return m;
}

static void compare(const double *v, size_t n, int closed, int p, int dyad, uint64_t seed)
{
    dfl_field fast, slow;
    dfl_err err;
    cr_assert_eq(dfl_rfield_polyline(2, v, n, closed, DFL_RFUNC_REQUIV, p, DFL_RFUNC_TRIM_DISK,
                                     &fast, &err),
                 DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_rfield_polyline_opts(2, v, n, closed, DFL_RFUNC_REQUIV, p,
                                          DFL_RFUNC_TRIM_DISK, false, &slow, &err),
                 DFL_OK, "%s", err.msg);
    /* otherwise the comparison below would compare the slow path with itself */
    cr_assert(dfl_rfield_is_fast(&fast), "p %d closed %d: fast path not taken", p, closed);
    cr_assert(!dfl_rfield_is_fast(&slow));
    enum { CAP = 1200 };
    double *x = malloc(2 * CAP * sizeof *x), *uf = malloc(CAP * sizeof *uf);
    double *us = malloc(CAP * sizeof *us), *uv = malloc(CAP * sizeof *uv);
    double *gf = malloc(2 * CAP * sizeof *gf), *gs = malloc(2 * CAP * sizeof *gs);
    const size_t m = points(v, n, closed, dyad, seed, x, CAP);
    /* one call for all m points (several of the sampler's chunks, not a
     * multiple of the vector block), as the sampler would make */
    fast.ops->eval(fast.ctx, m, x, uf, gf);
    slow.ops->eval(slow.ctx, m, x, us, gs);
    fast.ops->eval(fast.ctx, m, x, uv, NULL);
    size_t zeros = 0;
    for (size_t i = 0; i < m; i++) {
        const double *xi = x + 2 * i;
        cr_assert_eq(uv[i], uf[i], "value-only call differs at %zu", i);
        if (us[i] == 0.0) {
            zeros++;
            cr_assert(uf[i] == 0.0 && gf[2 * i] == 0.0 && gf[2 * i + 1] == 0.0 &&
                          gs[2 * i] == 0.0 && gs[2 * i + 1] == 0.0,
                      "p %d closed %d at (%.17g, %.17g): u %g (slow 0), grad %g %g", p, closed,
                      xi[0], xi[1], uf[i], gf[2 * i], gf[2 * i + 1]);
            continue;
        }
        cr_assert(fabs(uf[i] - us[i]) <= 1e-12 * us[i],
                  "p %d closed %d at (%.17g, %.17g): u %.17g vs %.17g", p, closed, xi[0], xi[1],
                  uf[i], us[i]);
        const double s = abs_sum(v, n, closed, p, us[i], xi);
        for (int j = 0; j < 2; j++)
            cr_assert(fabs(gf[2 * i + j] - gs[2 * i + j]) <= 1e-12 * s,
                      "p %d closed %d at (%.17g, %.17g): grad[%d] %.17g vs %.17g (s = %g)", p,
                      closed, xi[0], xi[1], j, gf[2 * i + j], gs[2 * i + j], s);
        /* one point at a time (dfl_field_eval1) is the same computation */
        double g1[2];
        const double u1 = dfl_field_eval1(&fast, xi, g1);
        cr_assert(u1 == uf[i] && g1[0] == gf[2 * i] && g1[1] == gf[2 * i + 1]);
    }
    /* the vertices at least are exactly on the polyline */
    cr_assert(zeros >= n, "p %d closed %d: %zu zeros", p, closed, zeros);
    free(x);
    free(uf);
    free(us);
    free(uv);
    free(gf);
    free(gs);
    dfl_field_destroy(&fast);
    dfl_field_destroy(&slow);
}

Test(rfield_fast, agrees_with_per_point_path)
{
    const int ps[] = {1, 2, 3, 7, 12, 13};
    double v[2 * 61];
    for (size_t i = 0; i < sizeof ps / sizeof *ps; i++) {
        for (int closed = 0; closed < 2; closed++) {
            const size_t n = closed ? 40 : 61;
            spiral(n, v);
            compare(v, n, closed, ps[i], 0, 7 + 13 * i + (uint64_t)closed);
            compare(DYAD, 5, closed, ps[i], 1, 101 + 13 * i + (uint64_t)closed);
        }
    }
}

Test(rfield_fast, sampler_uses_it)
{
    double v[2 * 30];
    spiral(30, v);
    dfl_field fast, slow;
    cr_assert_eq(dfl_rfield_polyline(2, v, 30, 1, DFL_RFUNC_REQUIV, 3, DFL_RFUNC_TRIM_DISK, &fast,
                                     NULL),
                 DFL_OK);
    cr_assert_eq(dfl_rfield_polyline_opts(2, v, 30, 1, DFL_RFUNC_REQUIV, 3, DFL_RFUNC_TRIM_DISK,
                                          false, &slow, NULL),
                 DFL_OK);
    dfl_grid g = {2, {53, 41, 1}, {-0.2, -0.1, 0}, {1.2, 1.1, 0}};
    const size_t m = dfl_grid_size(&g);
    double *uf = malloc(m * sizeof *uf), *gf = malloc(2 * m * sizeof *gf);
    double *us = malloc(m * sizeof *us), *gs = malloc(2 * m * sizeof *gs);
    dfl_err err;
    cr_assert_eq(dfl_field_sample(&fast, &g, 2, uf, gf, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_field_sample(&slow, &g, 2, us, gs, &err), DFL_OK, "%s", err.msg);
    for (size_t i = 0; i < m; i++) {
        double x[2];
        dfl_grid_node(&g, i, x);
        cr_assert(fabs(uf[i] - us[i]) <= 1e-12 * us[i], "node %zu: %.17g vs %.17g", i, uf[i],
                  us[i]);
        const double s = abs_sum(v, 30, 1, 3, us[i], x);
        cr_assert(fabs(gf[2 * i] - gs[2 * i]) <= 1e-12 * s &&
                  fabs(gf[2 * i + 1] - gs[2 * i + 1]) <= 1e-12 * s);
    }
    /* jets are the library's in both */
    const double x[2] = {0.31, 0.77}, dir[2] = {0.6, -0.8};
    dfl_jet jf, js;
    cr_assert_eq(dfl_field_jet(&fast, x, dir, 3, &jf, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_field_jet(&slow, x, dir, 3, &js, &err), DFL_OK, "%s", err.msg);
    for (int k = 0; k <= 3; k++) cr_assert_eq(dfl_jet_coeff(&jf, k), dfl_jet_coeff(&js, k));
    free(uf);
    free(gf);
    free(us);
    free(gs);
    dfl_field_destroy(&fast);
    dfl_field_destroy(&slow);
}

/* Only the batched cases take the fast path: R-equivalence of eq. 4
 * (disk or strip) segment chains, 2D or 3D, of two or more segments. */
Test(rfield_fast, eligibility)
{
    double v[2 * 12];
    spiral(12, v);
    const double v3[9] = {0, 0, 0, 1, 0, 0, 1, 1, 0};
    dfl_field f;
    struct {
        int dim;
        const double *v;
        size_t n;
        dfl_rfunc_join join;
        dfl_rfunc_trim trim;
        bool fast;
    } cases[] = {
        {2, v, 12, DFL_RFUNC_REQUIV, DFL_RFUNC_TRIM_DISK, true},
        {2, v, 12, DFL_RFUNC_RCONJ, DFL_RFUNC_TRIM_DISK, true},
        {2, v, 12, DFL_RFUNC_REQUIV_CORRECTED, DFL_RFUNC_TRIM_DISK, true},
        {2, v, 12, DFL_RFUNC_REQUIV, DFL_RFUNC_TRIM_STRIP, true},
        {2, v, 12, DFL_RFUNC_REQUIV, DFL_RFUNC_TRIM_DISK_SMOOTH, true},
        {3, v3, 3, DFL_RFUNC_REQUIV, DFL_RFUNC_TRIM_DISK, true},
        {3, v3, 3, DFL_RFUNC_REQUIV, DFL_RFUNC_TRIM_STRIP, true},
        {3, v3, 3, DFL_RFUNC_REQUIV, DFL_RFUNC_TRIM_STRIP_SMOOTH, true},
        {2, v, 3, DFL_RFUNC_REQUIV, DFL_RFUNC_TRIM_DISK, true},
        {2, v, 2, DFL_RFUNC_REQUIV, DFL_RFUNC_TRIM_DISK, false}, /* one segment: u = h exactly */
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        cr_assert_eq(dfl_rfield_polyline(cases[i].dim, cases[i].v, cases[i].n, 0, cases[i].join, 2,
                                         cases[i].trim, &f, NULL),
                     DFL_OK, "case %zu", i);
        cr_assert_eq(dfl_rfield_is_fast(&f), cases[i].fast, "case %zu", i);
        dfl_field_destroy(&f);
    }
    /* the builder: a chain of segments is a polyline; with a gap or an
     * extra point part the mixed kind takes it; the switch turned off, none */
    for (int variant = 0; variant < 4; variant++) {
        dfl_rfield *r;
        cr_assert_eq(dfl_rfield_new(2, DFL_RFUNC_REQUIV, 2, &r, NULL), DFL_OK);
        for (size_t k = 0; k + 1 < 12; k++) {
            if (variant == 1 && k == 5) continue; /* gap */
            cr_assert_eq(dfl_rfield_add_segment(r, v + 2 * k, v + 2 * k + 2, DFL_RFUNC_TRIM_DISK,
                                                NULL),
                         DFL_OK);
        }
        if (variant == 2) cr_assert_eq(dfl_rfield_add_point(r, v, NULL), DFL_OK);
        if (variant == 3) dfl_rfield_set_fast(r, false);
        cr_assert_eq(dfl_rfield_finish(&r, &f, NULL), DFL_OK);
        cr_assert_eq(dfl_rfield_is_fast(&f), variant != 3, "variant %d", variant);
        dfl_field_destroy(&f);
    }
    /* a field that is not an rfield */
    dfl_field other = {2, NULL, NULL};
    cr_assert(!dfl_rfield_is_fast(&other));
}
