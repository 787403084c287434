/* The triangle kernel (rfunc/batch_tri.c) against the per-point path (the
 * same field built with the fast path off), prism and conditional trims,
 * p = 1..9 and 12, at random points, near and on triangles (1e-9 and 1e-6
 * off, on a vertex, on a vertex line of the prism, on an edge's line),
 * and at huge coordinates.  Values to 1e-12 relative (0 and NaN exactly);
 * gradients to 1e-12 s, s = sum_k (u/h_k)^(p+1) |grad h_k| (the sum of
 * absolute contributions, which bounds the rounding; see test_batch.c). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "core/rng.h"
#include "rfunc/rfield.h"
#include "rfunc/tri3d.h"

enum { NT = 16, NPT = 120 };

/* A wavy strip of NT triangles over [0, 1] x [0, 0.5] in both orientations. */
static void mesh(dfl_rfunc_tri_opts o, dfl_rfunc_tri *t)
{
    for (int k = 0; k < NT; k++) {
        const double x0 = (k / 2 % 4) / 4.0, y0 = (k / 8) / 4.0, h = 0.25;
#define ZW(x, y) (0.2 * sin(3 * (x)) * cos(2 * (y)))
        const double A[3] = {x0, y0, ZW(x0, y0)}, B[3] = {x0 + h, y0, ZW(x0 + h, y0)},
                     C[3] = {x0, y0 + h, ZW(x0, y0 + h)},
                     D[3] = {x0 + h, y0 + h, ZW(x0 + h, y0 + h)};
#undef ZW
        dfl_status st = k % 2 ? dfl_rfunc_tri_init(B, D, C, &o, &t[k], NULL)
                              : dfl_rfunc_tri_init(A, C, B, &o, &t[k], NULL);
        cr_assert_eq(st, DFL_OK);
    }
}

static void field(const dfl_rfunc_tri *t, int p, bool fast, dfl_field *out)
{
    dfl_rfield *r;
    cr_assert_eq(dfl_rfield_new(3, DFL_RFUNC_REQUIV, p, &r, NULL), DFL_OK);
    dfl_rfield_set_fast(r, fast);
    for (int k = 0; k < NT; k++)
        cr_assert_eq(dfl_rfield_add_triangle(r, t[k].v[0], t[k].v[1], t[k].v[2], &t[k].o, NULL),
                     DFL_OK);
    cr_assert_eq(dfl_rfield_finish(&r, out, NULL), DFL_OK);
}

/* The test points: random, near and on triangles, special lines, huge. */
static void points(const dfl_rfunc_tri *t, uint64_t *rng, double *x)
{
    for (int i = 0; i < NPT; i++) {
        double *xi = x + 3 * i;
        const dfl_rfunc_tri *tk = &t[(size_t)dfl_rng_splitmix(rng, 0, NT)];
        double a = dfl_rng_splitmix(rng, 0, 1), b = dfl_rng_splitmix(rng, 0, 1);
        if (a + b > 1) a = 1 - a, b = 1 - b;
        const double off[] = {0.0, 1e-9, -1e-9, 1e-6, 0.3};
        for (int j = 0; j < 3; j++) {
            const double on = tk->v[0][j] + a * (tk->v[1][j] - tk->v[0][j]) +
                              b * (tk->v[2][j] - tk->v[0][j]);
            switch (i % 8) {
            case 0: case 1: case 2: xi[j] = dfl_rng_splitmix(rng, -0.5, 1.5); break;
            case 3: xi[j] = on + off[i / 8 % 5] * tk->n[j]; break;                /* near */
            case 4: xi[j] = tk->v[i / 8 % 3][j] + (i / 8 % 2 ? 0.0 : 0.4 * tk->n[j]);
                    break;                                         /* vertex, vertex line */
            case 5: xi[j] = tk->v[0][j] + (1 + a) * (tk->v[1][j] - tk->v[0][j]); break;
            case 6: xi[j] = on - (1e-9 + 1e-3 * a) * tk->m[0][j]; break;           /* past an edge */
            default: xi[j] = (i / 8 % 3 == 0 ? 1e6 : i / 8 % 3 == 1 ? 1e50 : 1e100) *
                             dfl_rng_splitmix(rng, -1, 1); break;                   /* huge */
            }
        }
    }
}

static void compare(const dfl_rfunc_tri *t, int p, const double *x)
{
    dfl_field ff, fs;
    field(t, p, true, &ff);
    field(t, p, false, &fs);
    cr_assert(dfl_rfield_is_fast(&ff) && !dfl_rfield_is_fast(&fs), "p %d", p);
    double ua[NPT], ub[NPT], ga[3 * NPT], gb[3 * NPT], u1[NPT], g1[3 * NPT];
    ff.ops->eval(ff.ctx, NPT, x, ua, ga);
    fs.ops->eval(fs.ctx, NPT, x, ub, gb);
    for (int i = 0; i < NPT; i++) u1[i] = dfl_field_eval1(&ff, x + 3 * i, g1 + 3 * i);
    /* a point's result does not depend on the points beside it */
    cr_assert(memcmp(ua, u1, sizeof ua) == 0 && memcmp(ga, g1, sizeof ga) == 0, "p %d", p);
    for (int i = 0; i < NPT; i++) {
        const double *xi = x + 3 * i;
        cr_assert_eq(isnan(ua[i]), isnan(ub[i]), "p %d point %d", p, i);
        if (ub[i] == 0.0 || isnan(ub[i])) {
            cr_assert(ua[i] == ub[i] || isnan(ub[i]), "p %d point %d", p, i);
            continue;
        }
        cr_assert(fabs(ua[i] - ub[i]) <= 1e-12 * ub[i], "p %d point %d (%g, %g, %g): %.17g vs %.17g",
                  p, i, xi[0], xi[1], xi[2], ua[i], ub[i]);
        double s = 0;
        for (int k = 0; k < NT; k++) {
            double g[3];
            const double h = dfl_rfunc_tri_eval(&t[k], xi, g);
            s += pow(ub[i] / h, p + 1) * sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
        }
        for (int j = 0; j < 3; j++)
            cr_assert(fabs(ga[3 * i + j] - gb[3 * i + j]) <= 1e-12 * s,
                      "p %d point %d (%g, %g, %g) grad %d: %.17g vs %.17g (s %g)", p, i, xi[0], xi[1], xi[2], j, ga[3 * i + j],
                      gb[3 * i + j], s);
    }
    dfl_field_destroy(&ff);
    dfl_field_destroy(&fs);
}

Test(batch_tri, agrees_with_per_point_path)
{
    static const int ps[] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 12};
    uint64_t rng = 2026;
    for (int trim = 0; trim < 2; trim++) {
        dfl_rfunc_tri_opts o = dfl_rfunc_tri_defaults();
        o.trim = (dfl_rfunc_tri_trim)trim;
        dfl_rfunc_tri t[NT];
        mesh(o, t);
        double x[3 * NPT];
        points(t, &rng, x);
        for (size_t i = 0; i < sizeof ps / sizeof ps[0]; i++) compare(t, ps[i], x);
    }
}

/* The kernel takes eq. 4 with one trim (prism, or conditional with k = 2
 * and one a) and leaves the rest to the per-point path. */
Test(batch_tri, eligibility)
{
    for (int c = 0; c < 5; c++) {
        dfl_rfunc_tri_opts o = dfl_rfunc_tri_defaults();
        dfl_rfunc_tri t[NT];
        o.trim = c == 0 ? DFL_RFUNC_TRI_PRISM : DFL_RFUNC_TRI_CONDITIONAL;
        if (c == 2) o.smooth = 1;
        if (c == 3) o.k = 4;
        mesh(o, t);
        if (c == 4) t[3].o.trim = DFL_RFUNC_TRI_PRISM; /* two trims */
        dfl_field f;
        field(t, 2, true, &f);
        /* two eq. 4 trims: the mixed kind sums one triangle group per trim */
        cr_expect_eq(dfl_rfield_is_fast(&f), c < 2 || c == 4, "case %d", c);
        dfl_field_destroy(&f);
    }
}
