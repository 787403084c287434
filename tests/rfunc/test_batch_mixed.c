/* The mixed kind (rfunc/batch_mixed.c): R-equivalence of parts of several
 * kinds, and of one kind the built-in kernels refuse for its layout
 * (segments that are not a chain, triangles with different trims), against
 * the per-point path of the same field (dfl_rfield_set_fast(r, false)).
 *
 * Tolerance, as in test_batch.c: values 1e-12 relative; gradients 1e-12
 * times s = sum_i (u/h_i)^(p+1) |grad h_i|, the sum of absolute
 * contributions (from the library's part fields), which bounds the
 * rounding where they cancel.  The batch adds the parts group by group
 * (segments of one trim, points, regions, triangles of one trim), the
 * per-point path part by part: a different order of the same terms, which
 * these tolerances must absorb.  Points on a part (u = 0) and others the
 * kernels do not trust fall back to the per-point path: equal bitwise. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "field/sample.h"
#include "rfunc/batch.h"
#include "rfunc/part.h"
#include "rfunc/rfield.h"

enum { MAXP = 64, MAXX = 400 };

typedef struct scene {
    int dim;
    size_t n;
    dfl_rfunc_part parts[MAXP];
} scene;

static void add_seg(scene *s, const double *a, const double *b, dfl_rfunc_trim trim)
{
    cr_assert(s->n < MAXP);
    dfl_rfunc_part *pt = &s->parts[s->n++];
    memset(pt, 0, sizeof *pt);
    pt->kind = DFL_RFUNC_PART_SEGMENT;
    cr_assert_eq(dfl_rfunc_seg_init(s->dim, a, b, trim, &pt->u.seg, NULL), DFL_OK);
}

/* The open polyline v[0..nv-1] as separate segments. */
static void add_poly(scene *s, const double *v, size_t nv, dfl_rfunc_trim trim)
{
    for (size_t i = 0; i + 1 < nv; i++)
        add_seg(s, v + (size_t)s->dim * i, v + (size_t)s->dim * (i + 1), trim);
}

static void add_pt(scene *s, const double *c)
{
    dfl_rfunc_part *pt = &s->parts[s->n++];
    memset(pt, 0, sizeof *pt);
    pt->kind = DFL_RFUNC_PART_POINT;
    cr_assert_eq(dfl_rfunc_point_init(s->dim, c, &pt->u.pt, NULL), DFL_OK);
}

static void add_reg(scene *s, const double *v, size_t nv)
{
    dfl_rfunc_part *pt = &s->parts[s->n++];
    memset(pt, 0, sizeof *pt);
    pt->kind = DFL_RFUNC_PART_REGION;
    cr_assert_eq(dfl_rfunc_region_init(v, nv, &pt->u.reg, NULL), DFL_OK);
}

static void add_tri(scene *s, const double *A, const double *B, const double *C,
                    dfl_rfunc_tri_trim trim, double a, int smooth)
{
    dfl_rfunc_tri_opts o = dfl_rfunc_tri_defaults();
    o.trim = trim;
    o.a = a;
    o.smooth = smooth;
    dfl_rfunc_part *pt = &s->parts[s->n++];
    memset(pt, 0, sizeof *pt);
    pt->kind = DFL_RFUNC_PART_TRIANGLE;
    cr_assert_eq(dfl_rfunc_tri_init(A, B, C, &o, &pt->u.tri, NULL), DFL_OK);
}

static void scene_free(scene *s)
{
    for (size_t i = 0; i < s->n; i++)
        if (s->parts[i].kind == DFL_RFUNC_PART_REGION) dfl_rfunc_region_free(&s->parts[i].u.reg);
}

/* The scene's parts, in order, as an rfunc field. */
static void build(const scene *s, dfl_rfunc_join join, int p, bool fast, dfl_field *out)
{
    dfl_rfield *r;
    cr_assert_eq(dfl_rfield_new(s->dim, join, p, &r, NULL), DFL_OK);
    dfl_rfield_set_fast(r, fast);
    for (size_t i = 0; i < s->n; i++) {
        const dfl_rfunc_part *pt = &s->parts[i];
        dfl_err err;
        dfl_status st = DFL_OK;
        switch (pt->kind) {
        case DFL_RFUNC_PART_SEGMENT:
            st = dfl_rfield_add_segment(r, pt->u.seg.a, pt->u.seg.b, pt->u.seg.trim, &err);
            break;
        case DFL_RFUNC_PART_POINT: st = dfl_rfield_add_point(r, pt->u.pt.c, &err); break;
        case DFL_RFUNC_PART_REGION:
            st = dfl_rfield_add_region(r, pt->u.reg.v, pt->u.reg.n, &err);
            break;
        case DFL_RFUNC_PART_TRIANGLE:
            st = dfl_rfield_add_triangle(r, pt->u.tri.v[0], pt->u.tri.v[1], pt->u.tri.v[2],
                                         &pt->u.tri.o, &err);
            break;
        }
        cr_assert_eq(st, DFL_OK, "part %zu: %s", i, err.msg);
    }
    cr_assert_eq(dfl_rfield_finish(&r, out, NULL), DFL_OK);
}

static double part_h(const dfl_rfunc_part *pt, const double *x, double *g)
{
    switch (pt->kind) {
    case DFL_RFUNC_PART_SEGMENT: return dfl_rfunc_seg_eval(&pt->u.seg, x, g);
    case DFL_RFUNC_PART_POINT: return dfl_rfunc_point_eval(&pt->u.pt, x, g);
    case DFL_RFUNC_PART_REGION: return dfl_rfunc_region_eval(&pt->u.reg, x, g);
    case DFL_RFUNC_PART_TRIANGLE: return dfl_rfunc_tri_eval(&pt->u.tri, x, g);
    }
    return NAN;
}

/* s of the header at x for u > 0. */
static double abs_sum(const scene *s, int p, double u, const double *x)
{
    double sum = 0;
    for (size_t i = 0; i < s->n; i++) {
        double g[3] = {0, 0, 0};
        const double h = part_h(&s->parts[i], x, g);
        sum += pow(u / h, p + 1) * sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    }
    return sum;
}

/* Test points: random around [0, 1]^dim, then on every part (segment end
 * points and midpoints, point parts, region vertices and centres, triangle
 * corners), 1e-9 off segment midpoints, far away (1e8) and huge (1e50,
 * 9e99).  Returns the count. */
static size_t points(const scene *s, uint64_t seed, double *x)
{
    const size_t d = (size_t)s->dim;
    size_t m = 0;
    uint64_t rng = seed;
    for (; m < 150; m++)
        for (size_t j = 0; j < d; j++) x[d * m + j] = dfl_rng_splitmix(&rng, -0.3, 1.3);
    for (size_t i = 0; i < s->n && m + 4 <= MAXX - 4; i++) {
        const dfl_rfunc_part *pt = &s->parts[i];
        double *y = x + d * m;
        switch (pt->kind) {
        case DFL_RFUNC_PART_SEGMENT:
            for (size_t j = 0; j < d; j++) {
                y[j] = pt->u.seg.a[j];
                y[d + j] = 0.5 * (pt->u.seg.a[j] + pt->u.seg.b[j]);
                y[2 * d + j] = y[d + j] + 1e-9 * pt->u.seg.n1[j];
                y[3 * d + j] = pt->u.seg.b[j] + 1e-9 * pt->u.seg.e[j];
            }
            m += 4;
            break;
        case DFL_RFUNC_PART_POINT:
            for (size_t j = 0; j < d; j++) y[j] = pt->u.pt.c[j], y[d + j] = pt->u.pt.c[j] + 1e-9;
            m += 2;
            break;
        case DFL_RFUNC_PART_REGION:
            y[0] = pt->u.reg.v[0], y[1] = pt->u.reg.v[1];
            y[2] = (pt->u.reg.v[0] + pt->u.reg.v[2] + pt->u.reg.v[4]) / 3;
            y[3] = (pt->u.reg.v[1] + pt->u.reg.v[3] + pt->u.reg.v[5]) / 3;
            m += 2;
            break;
        case DFL_RFUNC_PART_TRIANGLE:
            for (size_t j = 0; j < d; j++)
                y[j] = pt->u.tri.v[1][j], y[d + j] = pt->u.tri.v[2][j] + 1e-9 * pt->u.tri.n[j];
            m += 2;
            break;
        }
    }
    const double far[3] = {1e8, 3e50, -9e99};
    for (int k = 0; k < 3; k++, m++)
        for (size_t j = 0; j < d; j++) x[d * m + j] = far[k] * (j == 1 ? -0.7 : 1.0);
    cr_assert(m <= MAXX);
    return m;
}

/* The fast field of s equals its per-point path at the test points, at
 * every order of the list, and is chunking-independent (all points at once
 * against one by one, bitwise). */
static void agree(const scene *s, uint64_t seed)
{
    static const int ps[] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 12};
    const size_t d = (size_t)s->dim;
    static double x[3 * MAXX], uf[MAXX], gf[3 * MAXX], us[MAXX], gs[3 * MAXX];
    const size_t m = points(s, seed, x);
    for (size_t ip = 0; ip < sizeof ps / sizeof *ps; ip++) {
        const int p = ps[ip];
        dfl_field ff, fs;
        build(s, DFL_RFUNC_REQUIV, p, true, &ff);
        build(s, DFL_RFUNC_REQUIV, p, false, &fs);
        cr_assert(dfl_rfield_is_fast(&ff), "p %d: not batched", p);
        cr_assert(!dfl_rfield_is_fast(&fs));
        ff.ops->eval(ff.ctx, m, x, uf, gf);
        fs.ops->eval(fs.ctx, m, x, us, gs);
        for (size_t i = 0; i < m; i++) {
            const double *xi = x + d * i;
            cr_assert_eq(isnan(uf[i]), isnan(us[i]), "p %d point %zu", p, i);
            if (!(us[i] > 0)) {
                cr_assert(uf[i] == us[i] || (isnan(uf[i]) && isnan(us[i])), "p %d point %zu", p,
                          i);
                for (size_t j = 0; j < d; j++) cr_assert_eq(gf[d * i + j], gs[d * i + j]);
                continue;
            }
            cr_assert(fabs(uf[i] - us[i]) <= 1e-12 * us[i],
                      "p %d point %zu (%.17g, %.17g): %.17g vs %.17g", p, i, xi[0], xi[1], uf[i],
                      us[i]);
            const double sa = abs_sum(s, p, us[i], xi);
            for (size_t j = 0; j < d; j++)
                cr_assert(fabs(gf[d * i + j] - gs[d * i + j]) <= 1e-12 * sa,
                          "p %d point %zu (%g %g) grad %zu: %.17g vs %.17g (s %g) u %.17g", p, i, xi[0], xi[1], j,
                          gf[d * i + j], gs[d * i + j], sa, uf[i]);
        }
        for (size_t i = 0; i < m; i++) {
            double u1, g1[3];
            ff.ops->eval(ff.ctx, 1, x + d * i, &u1, g1);
            cr_assert(memcmp(&u1, &uf[i], sizeof u1) == 0, "p %d point %zu: chunking", p, i);
            cr_assert(memcmp(g1, gf + d * i, d * sizeof *g1) == 0, "p %d point %zu", p, i);
        }
        dfl_field_destroy(&ff);
        dfl_field_destroy(&fs);
    }
}

/* A wobbly arc of nv vertices from angle t0 to t1 around (cx, cy). */
static void arc(double *v, size_t nv, double cx, double cy, double r, double t0, double t1)
{
    for (size_t i = 0; i < nv; i++) {
        const double t = t0 + (t1 - t0) * (double)i / (double)(nv - 1);
        v[2 * i] = cx + (r + 0.01 * sin(17 * t)) * cos(t);
        v[2 * i + 1] = cy + (r + 0.01 * sin(17 * t)) * sin(t);
    }
}

/* 2D: two disk polylines, strip segments, points and regions, interleaved
 * (the groups' order is not the parts' order). */
static void scene_mixed2(scene *s)
{
    memset(s, 0, sizeof *s);
    s->dim = 2;
    double v[2 * 12];
    const double sq[8] = {0.1, 0.1, 0.3, 0.1, 0.3, 0.3, 0.1, 0.3};
    double pent[10];
    for (int j = 0; j < 5; j++) {
        pent[2 * j] = 0.75 + 0.08 * cos(2 * acos(-1.0) * j / 5 + 0.3);
        pent[2 * j + 1] = 0.8 + 0.08 * sin(2 * acos(-1.0) * j / 5 + 0.3);
    }
    const double c1[2] = {0.5, 0.5}, c2[2] = {0.05, 0.9}, c3[2] = {0.95, 0.05};
    const double sa[2] = {0.6, 0.1}, sb[2] = {0.9, 0.3}, sc[2] = {0.2, 0.6}, sd[2] = {0.35, 0.95};
    arc(v, 12, 0.5, 0.5, 0.3, 0.0, 2.5);
    add_poly(s, v, 12, DFL_RFUNC_TRIM_DISK);
    add_pt(s, c1);
    add_seg(s, sa, sb, DFL_RFUNC_TRIM_STRIP);
    add_reg(s, sq, 4);
    arc(v, 8, 0.5, 0.5, 0.42, 3.0, 5.0);
    add_poly(s, v, 8, DFL_RFUNC_TRIM_DISK);
    add_pt(s, c2);
    add_reg(s, pent, 5);
    add_seg(s, sc, sd, DFL_RFUNC_TRIM_STRIP);
    add_seg(s, sb, sc, DFL_RFUNC_TRIM_STRIP); /* chained to the first strip segment */
    add_pt(s, c3);
}

Test(batch_mixed, mixed_2d_agrees_with_per_point)
{
    scene s;
    scene_mixed2(&s);
    agree(&s, 11);
    scene_free(&s);
}

/* One kind, not a chain: separate polylines (disk), a triangle's edges as
 * separate strip segments (bs04's triangle-edge sets), and bs04 Fig. 13a's
 * region, segment and point. */
Test(batch_mixed, one_kind_not_a_chain)
{
    scene s;
    double v[2 * 10];
    memset(&s, 0, sizeof s);
    s.dim = 2;
    arc(v, 10, 0.5, 0.5, 0.3, 0.0, 2.0);
    add_poly(&s, v, 10, DFL_RFUNC_TRIM_DISK);
    arc(v, 10, 0.5, 0.5, 0.3, 3.0, 5.5);
    add_poly(&s, v, 10, DFL_RFUNC_TRIM_DISK);
    agree(&s, 21);
    memset(&s, 0, sizeof s);
    s.dim = 2;
    const double T[3][2] = {{0.1, 0.2}, {0.9, 0.1}, {0.4, 0.85}};
    add_seg(&s, T[0], T[1], DFL_RFUNC_TRIM_STRIP);
    add_seg(&s, T[2], T[1], DFL_RFUNC_TRIM_STRIP); /* against the chain's direction */
    add_seg(&s, T[2], T[0], DFL_RFUNC_TRIM_STRIP);
    agree(&s, 22);
    memset(&s, 0, sizeof s);
    s.dim = 2;
    const double sq[8] = {0.1, 0.1, 0.4, 0.1, 0.4, 0.4, 0.1, 0.4};
    const double a[2] = {0.55, 0.2}, b[2] = {0.9, 0.75}, c[2] = {0.25, 0.75};
    add_reg(&s, sq, 4);
    add_seg(&s, a, b, DFL_RFUNC_TRIM_DISK);
    add_pt(&s, c);
    agree(&s, 23);
    scene_free(&s);
}

/* 3D: space-curve segments with both trims, triangles with the prism and
 * two conditional trims, points; and triangles alone with two trims. */
Test(batch_mixed, mixed_3d_agrees_with_per_point)
{
    scene s;
    memset(&s, 0, sizeof s);
    s.dim = 3;
    double v[3 * 9];
    for (int i = 0; i < 9; i++) {
        const double t = i / 8.0;
        v[3 * i] = 0.2 + 0.6 * t, v[3 * i + 1] = 0.5 + 0.3 * sin(5 * t), v[3 * i + 2] = 0.8 * t;
    }
    add_poly(&s, v, 5, DFL_RFUNC_TRIM_DISK);
    add_poly(&s, v + 12, 5, DFL_RFUNC_TRIM_STRIP);
    const double c[3] = {0.9, 0.1, 0.2};
    add_pt(&s, c);
    for (int k = 0; k < 6; k++) {
        const double x0 = (k % 3) / 3.0, y0 = (k / 3) / 2.0;
        const double A[3] = {x0, y0, 0.1 * sin(7 * x0)}, B[3] = {x0 + 1 / 3.0, y0, 0.05},
                     C[3] = {x0, y0 + 0.5, 0.1};
        add_tri(&s, A, B, C, k % 3 == 0 ? DFL_RFUNC_TRI_PRISM : DFL_RFUNC_TRI_CONDITIONAL,
                k % 3 == 2 ? 0.5 : 0.2, 0);
    }
    agree(&s, 31);
    scene t;
    memset(&t, 0, sizeof t);
    t.dim = 3;
    for (size_t i = 0; i < s.n; i++)
        if (s.parts[i].kind == DFL_RFUNC_PART_TRIANGLE) t.parts[t.n++] = s.parts[i];
    agree(&t, 32);
}

/* Sampling with threads gives the values of eval one point at a time. */
Test(batch_mixed, threads_and_chunks)
{
    scene s;
    scene_mixed2(&s);
    dfl_field f;
    build(&s, DFL_RFUNC_REQUIV, 3, true, &f);
    cr_assert(dfl_rfield_is_fast(&f));
    dfl_grid g = {2, {41, 37, 1}, {-0.2, -0.1, 0}, {1.2, 1.1, 0}};
    const size_t m = dfl_grid_size(&g);
    double *u = malloc(m * sizeof *u), *gu = malloc(2 * m * sizeof *gu);
    dfl_err err;
    cr_assert_eq(dfl_field_sample(&f, &g, 2, u, gu, &err), DFL_OK, "%s", err.msg);
    for (size_t i = 0; i < m; i++) {
        double x[2], g1[2];
        dfl_grid_node(&g, i, x);
        const double u1 = dfl_field_eval1(&f, x, g1);
        cr_assert(memcmp(&u1, &u[i], sizeof u1) == 0 && memcmp(g1, gu + 2 * i, sizeof g1) == 0,
                  "node %zu", i);
    }
    free(u);
    free(gu);
    dfl_field_destroy(&f);
    scene_free(&s);
}

/* Built from a description, the kind computes random points around the
 * parts with its kernels, not its fallback (points inside a region, where
 * u = 0 exactly, need none either). */
Test(batch_mixed, kernels_not_fallback)
{
    scene s;
    scene_mixed2(&s);
    dfl_field slow;
    build(&s, DFL_RFUNC_REQUIV, 2, false, &slow);
    size_t vstart[MAXP + 1] = {0};
    const dfl_rfunc_batch_desc d = {2,    DFL_RFUNC_REQUIV, 2, DFL_RFUNC_CORR_GUARDED,
                                    s.parts, s.n,           NULL, 0, vstart, &slow};
    dfl_rfunc_batch *b = NULL;
    dfl_err err;
    cr_assert_eq(dfl_rfunc_batch_build(&d, &b, &err), DFL_OK, "%s", err.msg);
    cr_assert_not_null(b);
    cr_assert_eq(dfl_rfunc_batch_segments(b), s.n);
    double x[2 * 150];
    uint64_t rng = 5;
    for (int i = 0; i < 2 * 150; i++) x[i] = dfl_rng_splitmix(&rng, -0.3, 1.3);
    /* some of them inside a region */
    size_t inside = 0;
    for (int i = 0; i < 150; i++)
        for (size_t k = 0; k < s.n; k++)
            inside += s.parts[k].kind == DFL_RFUNC_PART_REGION &&
                      dfl_rfunc_region_eval(&s.parts[k].u.reg, x + 2 * i, NULL) == 0.0;
    cr_assert(inside > 0);
    cr_assert_eq(dfl_rfunc_batch_fallbacks(b, 150, x), 0);
    /* on a point part and on a segment: those fall back */
    const double y[4] = {s.parts[11].u.pt.c[0], s.parts[11].u.pt.c[1], s.parts[0].u.seg.a[0],
                         s.parts[0].u.seg.a[1]};
    cr_assert_eq(s.parts[11].kind, DFL_RFUNC_PART_POINT);
    cr_assert_eq(dfl_rfunc_batch_fallbacks(b, 2, y), 2);
    dfl_rfunc_batch_free(b);
    dfl_field_destroy(&slow);
    scene_free(&s);
}

/* The kind takes R-equivalence of eq. 4 parts only: not eq. 5 trims, other
 * joins, or conditional triangles with k != 2. */
Test(batch_mixed, eligibility)
{
    scene s;
    scene_mixed2(&s);
    dfl_field f;
    build(&s, DFL_RFUNC_RCONJ, 2, true, &f);
    cr_expect(!dfl_rfield_is_fast(&f), "R-conjunction");
    dfl_field_destroy(&f);
    const double a[2] = {0.0, 1.2}, b[2] = {0.3, 1.25};
    add_seg(&s, a, b, DFL_RFUNC_TRIM_DISK_SMOOTH);
    build(&s, DFL_RFUNC_REQUIV, 2, true, &f);
    cr_expect(!dfl_rfield_is_fast(&f), "eq. 5 segment");
    dfl_field_destroy(&f);
    scene_free(&s);
    memset(&s, 0, sizeof s);
    s.dim = 3;
    const double A[3] = {0, 0, 0}, B[3] = {1, 0, 0}, C[3] = {0, 1, 0}, P[3] = {0.5, 0.5, 1};
    add_tri(&s, A, B, C, DFL_RFUNC_TRI_PRISM, 0.2, 0);
    add_pt(&s, P);
    build(&s, DFL_RFUNC_REQUIV, 2, true, &f);
    cr_expect(dfl_rfield_is_fast(&f), "triangle and point");
    dfl_field_destroy(&f);
    add_tri(&s, A, B, P, DFL_RFUNC_TRI_PRISM, 0.2, 1);
    build(&s, DFL_RFUNC_REQUIV, 2, true, &f);
    cr_expect(!dfl_rfield_is_fast(&f), "eq. 5 triangle");
    dfl_field_destroy(&f);
    s.n = 2;
    dfl_rfunc_tri_opts o = dfl_rfunc_tri_defaults();
    o.trim = DFL_RFUNC_TRI_CONDITIONAL;
    o.k = 4;
    dfl_rfunc_part *pt = &s.parts[s.n++];
    pt->kind = DFL_RFUNC_PART_TRIANGLE;
    cr_assert_eq(dfl_rfunc_tri_init(A, B, P, &o, &pt->u.tri, NULL), DFL_OK);
    build(&s, DFL_RFUNC_REQUIV, 2, true, &f);
    cr_expect(!dfl_rfield_is_fast(&f), "conditional k = 4");
    dfl_field_destroy(&f);
}
