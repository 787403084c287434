/* The batched kernel of the eq. 5 trims (rfunc/batch_smooth.c) against the
 * per-point path of the same field (built with dfl_rfield_set_fast off).
 *
 * Tolerance, as in test_batch.c: values 1e-12 relative; gradients 1e-12
 * times s = sum_i (u/h_i)^(p+1) |grad h_i| (the sum of absolute
 * contributions, which bounds the rounding of grad u where they cancel),
 * s from the library's segment fields.  Where the per-point path gives
 * u = 0 (on a segment), the batch must give exactly 0 with a zero
 * gradient; NaN-ness must agree. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "rfunc/batch_impl.h"
#include "rfunc/rfield.h"
#include "rfunc/segment.h"
#include "rfunc_util.h"

#define MAXSEG 40
#define CAP 1400

typedef struct segset {
    int dim;
    size_t n;
    double a[MAXSEG][3], b[MAXSEG][3];
} segset;

/* A wobbly spiral of nv vertices (a polyline: open, or closed) as segments. */
static void spiral(int dim, size_t nv, int closed, segset *s)
{
    double v[MAXSEG + 1][3];
    for (size_t i = 0; i < nv; i++) {
        const double t = (double)i / (double)(nv - 1);
        const double r = 0.1 + 0.35 * t + 0.02 * sin(40 * t);
        v[i][0] = 0.5 + r * cos(9 * t);
        v[i][1] = 0.5 + r * sin(9 * t);
        v[i][2] = 0.3 * sin(7.0 * t);
    }
    s->dim = dim;
    s->n = closed ? nv : nv - 1;
    cr_assert(s->n <= MAXSEG);
    for (size_t k = 0; k < s->n; k++)
        for (int j = 0; j < 3; j++) {
            s->a[k][j] = v[k][j];
            s->b[k][j] = v[(k + 1) % nv][j];
        }
}

/* Dyadic segments through the origin, not a chain (the second does not
 * start where the first ends): points on them at dyadic parameters are
 * exact, and 1e-170 off them is representable near the origin. */
static void dyadic(int dim, segset *s)
{
    static const double A[4][3] = {{0, 0, 0}, {0, 0, 0}, {1, 1, 0}, {-1, 1, 0.5}};
    static const double B[4][3] = {{1, 0, 0}, {0, 2, 0}, {2, 1, 1}, {-1, 3, 0.5}};
    s->dim = dim;
    s->n = 4;
    for (size_t k = 0; k < 4; k++)
        for (int j = 0; j < 3; j++) {
            s->a[k][j] = j < dim ? A[k][j] : 0.0;
            s->b[k][j] = j < dim ? B[k][j] : 0.0;
        }
}

static dfl_status build(const segset *s, dfl_rfunc_join join, int p, dfl_rfunc_trim trim,
                        bool fast, dfl_field *out)
{
    dfl_rfield *r;
    dfl_status st = dfl_rfield_new(s->dim, join, p, &r, NULL);
    cr_assert_eq(st, DFL_OK);
    dfl_rfield_set_fast(r, fast);
    for (size_t k = 0; k < s->n; k++)
        cr_assert_eq(dfl_rfield_add_segment(r, s->a[k], s->b[k], trim, NULL), DFL_OK);
    return dfl_rfield_finish(&r, out, NULL);
}

/* Test points: random around the segments, on them, their end points, 1e-9
 * off them, far away (1e8), huge (1e50, 1e100), and 1e-170 off the dyadic
 * segments near the origin. */
static size_t points(const segset *s, int dyad, uint64_t seed, double *x)
{
    const size_t d = (size_t)s->dim;
    size_t m = 0;
#define PUT3(a, b, c)                                                  \
    do {                                                               \
        cr_assert(m < CAP);                                            \
        const double q_[3] = {(a), (b), (c)};                          \
        for (size_t j_ = 0; j_ < d; j_++) x[d * m + j_] = q_[j_];      \
        m++;                                                           \
    } while (0)
    uint64_t rng = seed;
    const double lo = dyad ? -1.5 : -0.3, hi = dyad ? 2.5 : 1.3;
    for (int i = 0; i < 301; i++)
        PUT3(tu_uniform(&rng, lo, hi), tu_uniform(&rng, lo, hi), tu_uniform(&rng, lo, hi));
    const double ts[5] = {0, 0.25, 0.5, 0.75, 0.375};
    for (size_t k = 0; k < s->n; k++) {
        const double *a = s->a[k], *b = s->b[k];
        double e[3], nn[3] = {0, 0, 0}, len = 0;
        for (int j = 0; j < 3; j++) e[j] = b[j] - a[j], len += e[j] * e[j];
        len = sqrt(len);
        for (int j = 0; j < 3; j++) e[j] /= len;
        nn[0] = -e[1], nn[1] = e[0]; /* perpendicular to e in 2D and 3D */
        const double nl = hypot(nn[0], nn[1]) > 0 ? hypot(nn[0], nn[1]) : 1;
        if (!(hypot(nn[0], nn[1]) > 0)) nn[0] = 1;
        for (int j = 0; j < 2; j++) nn[j] /= nl;
        for (int i = 0; i < 5; i++)
            PUT3(a[0] + ts[i] * (b[0] - a[0]), a[1] + ts[i] * (b[1] - a[1]),
                 a[2] + ts[i] * (b[2] - a[2]));
        PUT3(b[0], b[1], b[2]);
        for (int sg = -1; sg <= 1; sg += 2) {
            const double o = sg * 1e-9;
            PUT3(0.5 * (a[0] + b[0]) + o * nn[0], 0.5 * (a[1] + b[1]) + o * nn[1],
                 0.5 * (a[2] + b[2]) + o * nn[2]);
            /* 1e-9 beyond either end point, and beside it */
            PUT3(b[0] + 1e-9 * e[0], b[1] + 1e-9 * e[1], b[2] + 1e-9 * e[2]);
            PUT3(a[0] - 1e-9 * e[0] + o * nn[0], a[1] - 1e-9 * e[1] + o * nn[1],
                 a[2] - 1e-9 * e[2] + o * nn[2]);
        }
    }
    for (int i = 0; i < 16; i++) {
        const double th = tu_uniform(&rng, 0, 2 * DFL_PI);
        PUT3(1e8 * cos(th), 1e8 * sin(th), 1e7 * cos(3 * th));
    }
    PUT3(1e8, 1e8, 1e8);
    PUT3(-1e8, 0.5, 0.25);
    PUT3(1e50, -3e49, 1e50);
    PUT3(1e72, 1e72, -1e72);
    PUT3(-1e100, 1e100, 1e100);
    PUT3(1e100, 0.5, 0.5);
    if (dyad) {
        const double e = 1e-170;
        PUT3(0.5, e, 0);
        PUT3(0.5, -e, e);
        PUT3(e, e, 0);
        PUT3(-e, -e, e);
        PUT3(-e, 0, 0);
        PUT3(e, 0, 0); /* on the first segment */
        PUT3(0, -e, 0);
        PUT3(-e, 3 * e, -e);
        PUT3(1, e, 0);
        PUT3(1e-150, 1e-150, 0);
        PUT3(-1e-140, 1e-140, 0);
        PUT3(0.5, 1e-80, 0);
    }
#undef PUT3
    return m;
}

/* s of the header at x, given u > 0. */
static double abs_sum(const segset *s, dfl_rfunc_trim trim, int p, double u, const double *x)
{
    double sum = 0;
    for (size_t k = 0; k < s->n; k++) {
        dfl_rfunc_seg seg;
        double gh[3];
        cr_assert_eq(dfl_rfunc_seg_init(s->dim, s->a[k], s->b[k], trim, &seg, NULL), DFL_OK);
        const double h = dfl_rfunc_seg_eval(&seg, x, gh);
        cr_assert(h > 0, "u = %g > 0 but h_%zu = 0", u, k);
        sum += pow(u / h, p + 1) * tu_norm(s->dim, gh);
    }
    return sum;
}

static void compare(const segset *s, dfl_rfunc_trim trim, int p, int dyad, uint64_t seed)
{
    dfl_field fast, slow;
    const size_t d = (size_t)s->dim;
    cr_assert_eq(build(s, DFL_RFUNC_REQUIV, p, trim, true, &fast), DFL_OK);
    cr_assert_eq(build(s, DFL_RFUNC_REQUIV, p, trim, false, &slow), DFL_OK);
    cr_assert(dfl_rfield_is_fast(&fast), "dim %zu trim %d p %d: not batched", d, (int)trim, p);
    cr_assert(!dfl_rfield_is_fast(&slow));
    double *x = malloc(3 * CAP * sizeof *x), *uf = malloc(CAP * sizeof *uf);
    double *us = malloc(CAP * sizeof *us), *uv = malloc(CAP * sizeof *uv);
    double *gf = malloc(3 * CAP * sizeof *gf), *gs = malloc(3 * CAP * sizeof *gs);
    const size_t m = points(s, dyad, seed, x);
    fast.ops->eval(fast.ctx, m, x, uf, gf);
    slow.ops->eval(slow.ctx, m, x, us, gs);
    fast.ops->eval(fast.ctx, m, x, uv, NULL);
    size_t zeros = 0;
    for (size_t i = 0; i < m; i++) {
        const double *xi = x + d * i;
        cr_assert(uv[i] == uf[i] || (isnan(uv[i]) && isnan(uf[i])),
                  "value-only call differs at %zu", i);
        /* one point at a time (dfl_field_eval1) is the same computation */
        double g1[3];
        const double u1 = dfl_field_eval1(&fast, xi, g1);
        cr_assert(memcmp(&u1, &uf[i], sizeof u1) == 0 &&
                      memcmp(g1, gf + d * i, d * sizeof *g1) == 0,
                  "chunking changes point %zu", i);
        cr_assert_eq(isnan(uf[i]), isnan(us[i]), "NaN-ness at %zu", i);
        if (us[i] == 0.0) {
            zeros++;
            cr_assert(uf[i] == 0.0, "dim %zu trim %d p %d point %zu: u %g (slow 0)", d,
                      (int)trim, p, i, uf[i]);
            for (size_t j = 0; j < d; j++)
                cr_assert(gf[d * i + j] == 0.0 && gs[d * i + j] == 0.0);
            continue;
        }
        cr_assert(fabs(uf[i] - us[i]) <= 1e-12 * us[i],
                  "dim %zu trim %d p %d at (%.17g, %.17g, %.17g): u %.17g vs %.17g", d,
                  (int)trim, p, xi[0], xi[1], d == 3 ? xi[2] : 0.0, uf[i], us[i]);
        const double sa = abs_sum(s, trim, p, us[i], xi);
        for (size_t j = 0; j < d; j++)
            cr_assert(fabs(gf[d * i + j] - gs[d * i + j]) <= 1e-12 * sa,
                      "dim %zu trim %d p %d at (%.17g, %.17g, %.17g): grad[%zu] %.17g vs %.17g"
                      " (s = %g)",
                      d, (int)trim, p, xi[0], xi[1], d == 3 ? xi[2] : 0.0, j, gf[d * i + j],
                      gs[d * i + j], sa);
    }
    /* the end points at least are exactly on the segments */
    cr_assert(zeros >= s->n, "%zu zeros", zeros);
    free(x);
    free(uf);
    free(us);
    free(uv);
    free(gf);
    free(gs);
    dfl_field_destroy(&fast);
    dfl_field_destroy(&slow);
}

static const int PS[] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 12};
#define NPS (sizeof PS / sizeof PS[0])

static void compare_all(dfl_rfunc_trim trim, int dim)
{
    segset s;
    for (size_t i = 0; i < NPS; i++) {
        for (int closed = 0; closed < 2; closed++) {
            spiral(dim, closed ? 25 : 31, closed, &s);
            compare(&s, trim, PS[i], 0, 7 + 13 * i + (uint64_t)closed);
        }
        dyadic(dim, &s);
        compare(&s, trim, PS[i], 1, 101 + 13 * i);
    }
}

Test(batch_smooth, disk_smooth_2d) { compare_all(DFL_RFUNC_TRIM_DISK_SMOOTH, 2); }
Test(batch_smooth, strip_smooth_2d) { compare_all(DFL_RFUNC_TRIM_STRIP_SMOOTH, 2); }
Test(batch_smooth, disk_smooth_3d) { compare_all(DFL_RFUNC_TRIM_DISK_SMOOTH, 3); }
Test(batch_smooth, strip_smooth_3d) { compare_all(DFL_RFUNC_TRIM_STRIP_SMOOTH, 3); }

/* dfl_rfunc_batch_try_smooth takes R-equivalence of segments that all
 * share one eq. 5 trim, and nothing else (other kinds may take the rest). */
static int takes(dfl_rfunc_join join, const dfl_rfunc_part *parts, size_t n)
{
    const dfl_rfunc_batch_desc d = {2, join, 2, DFL_RFUNC_CORR_GUARDED, parts, n, NULL, 0, NULL,
                                    NULL};
    dfl_rfunc_batch *b = NULL;
    cr_assert_eq(dfl_rfunc_batch_try_smooth(&d, &b, NULL), DFL_OK);
    const int took = b != NULL;
    dfl_rfunc_batch_free(b);
    return took;
}

Test(batch_smooth, eligibility)
{
    segset s;
    spiral(2, 6, 0, &s);
    dfl_rfunc_part parts[6];
    const dfl_rfunc_trim sm[2] = {DFL_RFUNC_TRIM_DISK_SMOOTH, DFL_RFUNC_TRIM_STRIP_SMOOTH};
    for (int variant = 0; variant < 8; variant++) {
        memset(parts, 0, sizeof parts);
        for (size_t k = 0; k < s.n; k++) {
            dfl_rfunc_trim t = sm[variant & 1];
            if (k == 3 && variant >= 2 && variant < 4) t = sm[1 - (variant & 1)];
            if (k == 3 && variant >= 4 && variant < 6) t = DFL_RFUNC_TRIM_DISK;
            parts[k].kind = DFL_RFUNC_PART_SEGMENT;
            cr_assert_eq(dfl_rfunc_seg_init(2, s.a[k], s.b[k], t, &parts[k].u.seg, NULL), DFL_OK);
        }
        if (variant >= 6) {
            parts[2].kind = DFL_RFUNC_PART_POINT;
            cr_assert_eq(dfl_rfunc_point_init(2, s.a[0], &parts[2].u.pt, NULL), DFL_OK);
        }
        cr_assert_eq(takes(DFL_RFUNC_REQUIV, parts, s.n), variant < 2, "variant %d", variant);
        if (variant < 2) {
            cr_assert(!takes(DFL_RFUNC_RCONJ, parts, s.n));
            cr_assert(!takes(DFL_RFUNC_REQUIV_CORRECTED, parts, s.n));
            cr_assert(!takes(DFL_RFUNC_REQUIV, parts, 1));
        }
    }
    /* eq. 4 trims are the built-in kernels' */
    for (size_t k = 0; k < s.n; k++)
        cr_assert_eq(dfl_rfunc_seg_init(2, s.a[k], s.b[k], DFL_RFUNC_TRIM_STRIP, &parts[k].u.seg,
                                        NULL),
                     DFL_OK);
    cr_assert(!takes(DFL_RFUNC_REQUIV, parts, s.n));
    /* and the fields: smooth polylines and scattered smooth segments are fast */
    dfl_field f;
    for (int i = 0; i < 2; i++) {
        cr_assert_eq(build(&s, DFL_RFUNC_REQUIV, 2, sm[i], true, &f), DFL_OK);
        cr_assert(dfl_rfield_is_fast(&f));
        dfl_field_destroy(&f);
        cr_assert_eq(build(&s, DFL_RFUNC_REQUIV, 2, sm[i], false, &f), DFL_OK);
        cr_assert(!dfl_rfield_is_fast(&f));
        dfl_field_destroy(&f);
    }
}
