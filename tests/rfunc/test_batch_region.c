/* The convex-region kernel (rfunc/batch_region.c) against the per-point
 * path (the same field built with the fast path off): regions of 3, 4, 5,
 * 6, 9 and 12 edges (the kernel's fixed edge counts and its generic loop),
 * p = 1..9 and 12, at random points, inside regions (u = 0 without the
 * fallback), on edges and vertices, 1e-9 and 1e-160 off an edge, and at
 * huge coordinates.  Values to 1e-12 relative (0 exactly); gradients to
 * 1e-12 s, s = sum_k (u/h_k)^(p+1) |grad h_k| (see test_batch.c). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "core/rng.h"
#include "rfunc/batch.h"
#include "rfunc/region.h"
#include "rfunc/rfield.h"

enum { NR = 14, NPT = 120 };

/* Regions on a 4 x 4 grid of cells: regular polygons (of 3..12 edges) and
 * axis-aligned squares, which make exact edge points easy. */
static void regions(dfl_rfunc_region *r)
{
    static const size_t ne[NR] = {4, 3, 5, 6, 9, 12, 4, 3, 4, 5, 4, 6, 4, 4};
    for (int k = 0; k < NR; k++) {
        const double cx = (k % 4 + 0.5) / 4, cy = (k / 4 + 0.5) / 4, h = 0.09;
        double v[24];
        for (size_t j = 0; j < ne[k]; j++) {
            const double a = 2 * acos(-1.0) * (double)j / (double)ne[k] + 0.3 * k;
            v[2 * j] = cx + h * cos(a);
            v[2 * j + 1] = cy + h * sin(a);
        }
        if (ne[k] == 4 && k % 4 == 0) {
            const double q[8] = {cx - h, cy - h, cx + h, cy - h, cx + h, cy + h, cx - h, cy + h};
            memcpy(v, q, sizeof q);
        }
        cr_assert_eq(dfl_rfunc_region_init(v, ne[k], &r[k], NULL), DFL_OK);
    }
}

static void field(const dfl_rfunc_region *r, int p, bool fast, dfl_field *out)
{
    dfl_rfield *f;
    cr_assert_eq(dfl_rfield_new(2, DFL_RFUNC_REQUIV, p, &f, NULL), DFL_OK);
    dfl_rfield_set_fast(f, fast);
    for (int k = 0; k < NR; k++) cr_assert_eq(dfl_rfield_add_region(f, r[k].v, r[k].n, NULL), DFL_OK);
    cr_assert_eq(dfl_rfield_finish(&f, out, NULL), DFL_OK);
}

static void points(const dfl_rfunc_region *r, uint64_t *rng, double *x)
{
    for (int i = 0; i < NPT; i++) {
        double *xi = x + 2 * i;
        const dfl_rfunc_region *rk = &r[(size_t)dfl_rng_splitmix(rng, 0, NR)];
        const size_t e = (size_t)dfl_rng_splitmix(rng, 0, (double)rk->n);
        const double *a = rk->v + 2 * e, *b = rk->v + 2 * ((e + 1) % rk->n), *m = rk->m + 2 * e;
        const double t = dfl_rng_splitmix(rng, 0, 1);
        for (int j = 0; j < 2; j++) {
            const double on = a[j] + t * (b[j] - a[j]);
            switch (i % 8) {
            case 0: case 1: xi[j] = dfl_rng_splitmix(rng, -0.5, 1.5); break;
            case 2: xi[j] = on + 0.5 * t * m[j] * (i % 16 < 8 ? 1 : 0.01); break; /* inside */
            case 3: xi[j] = on - (i % 16 < 8 ? 1e-9 : 1e-160) * m[j]; break;       /* just off */
            case 4: xi[j] = i % 16 < 8 ? a[j] : on - 0.05 * m[j]; break;      /* vertex, near */
            case 5: xi[j] = (i % 24 < 8 ? 1e6 : i % 24 < 16 ? 1e50 : 1e100) *
                            dfl_rng_splitmix(rng, -1, 1); break;                   /* huge */
            default: xi[j] = on; break;                              /* on an edge (rounded) */
            }
        }
        if (i % 8 == 7 && rk == &r[0]) xi[1] = r[0].v[1]; /* exactly on the square's edge */
    }
}

static void compare(const dfl_rfunc_region *r, int p, const double *x)
{
    dfl_field ff, fs;
    field(r, p, true, &ff);
    field(r, p, false, &fs);
    cr_assert(dfl_rfield_is_fast(&ff) && !dfl_rfield_is_fast(&fs), "p %d", p);
    double ua[NPT], ub[NPT], ga[2 * NPT], gb[2 * NPT], u1[NPT], g1[2 * NPT];
    ff.ops->eval(ff.ctx, NPT, x, ua, ga);
    fs.ops->eval(fs.ctx, NPT, x, ub, gb);
    for (int i = 0; i < NPT; i++) u1[i] = dfl_field_eval1(&ff, x + 2 * i, g1 + 2 * i);
    cr_assert(memcmp(ua, u1, sizeof ua) == 0 && memcmp(ga, g1, sizeof ga) == 0, "p %d", p);
    int inside = 0;
    for (int i = 0; i < NPT; i++) {
        const double *xi = x + 2 * i;
        if (ub[i] == 0.0) {
            inside++;
            cr_assert(ua[i] == 0.0 && ga[2 * i] == gb[2 * i] && ga[2 * i + 1] == gb[2 * i + 1],
                      "p %d point %d", p, i);
            continue;
        }
        cr_assert(fabs(ua[i] - ub[i]) <= 1e-12 * ub[i], "p %d point %d (%g, %g): %.17g vs %.17g",
                  p, i, xi[0], xi[1], ua[i], ub[i]);
        double s = 0;
        for (int k = 0; k < NR; k++) {
            double g[2];
            const double h = dfl_rfunc_region_eval(&r[k], xi, g);
            s += pow(ub[i] / h, p + 1) * hypot(g[0], g[1]);
        }
        for (int j = 0; j < 2; j++)
            cr_assert(fabs(ga[2 * i + j] - gb[2 * i + j]) <= 1e-12 * s,
                      "p %d point %d grad %d: %.17g vs %.17g", p, i, j, ga[2 * i + j],
                      gb[2 * i + j]);
    }
    cr_assert(inside >= 8, "p %d: %d points inside", p, inside);
    dfl_field_destroy(&ff);
    dfl_field_destroy(&fs);
}

Test(batch_region, agrees_with_per_point_path)
{
    static const int ps[] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 12};
    dfl_rfunc_region r[NR];
    regions(r);
    uint64_t rng = 77;
    double x[2 * NPT];
    points(r, &rng, x);
    for (size_t i = 0; i < sizeof ps / sizeof ps[0]; i++) compare(r, ps[i], x);
    for (int k = 0; k < NR; k++) dfl_rfunc_region_free(&r[k]);
}

/* Points inside a region are the kernel's own (u = 0), not fallbacks;
 * points within 1e-160 of a region (h^2 underflows) are. */
Test(batch_region, inside_is_no_fallback)
{
    const double q0[8] = {0, 0, 1, 0, 1, 1, 0, 1}, q1[8] = {2, 0, 3, 0, 3, 1, 2, 1};
    dfl_rfunc_region r[2];
    cr_assert_eq(dfl_rfunc_region_init(q0, 4, &r[0], NULL), DFL_OK);
    cr_assert_eq(dfl_rfunc_region_init(q1, 4, &r[1], NULL), DFL_OK);
    dfl_rfunc_batch *b;
    cr_assert_eq(dfl_rfunc_batch_regions(r, 2, 2, &b, NULL), DFL_OK);
    const double in[2] = {0.5, 0.5}, edge[2] = {0.5, 0.0}, off[2] = {0.5, -1e-160},
                 out[2] = {1.5, 0.5};
    cr_expect_eq(dfl_rfunc_batch_fallbacks(b, 1, in), 0);
    cr_expect_eq(dfl_rfunc_batch_fallbacks(b, 1, edge), 0);
    cr_expect_eq(dfl_rfunc_batch_fallbacks(b, 1, off), 1);
    cr_expect_eq(dfl_rfunc_batch_fallbacks(b, 1, out), 0);
    double u, g[2];
    dfl_rfunc_batch_eval(b, 1, in, &u, g);
    cr_expect(u == 0.0 && g[0] == 0.0 && g[1] == 0.0);
    dfl_rfunc_batch_eval(b, 1, off, &u, g);
    cr_expect(u > 0.0 && fabs(u - 1e-160) <= 1e-12 * 1e-160, "%g", u);
    dfl_rfunc_batch_free(b);
    for (int k = 0; k < 2; k++) dfl_rfunc_region_free(&r[k]);
}
