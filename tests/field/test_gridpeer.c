/* Tests for field/gridpeer: exactness where the decoded polynomial can be
 * exact (a plane for every kind), interpolation at the cell centres, a
 * closed-form value at a kink, float16 rounding bounds, gradients against
 * finite differences, and bad input. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "field/gridpeer.h"

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
            cr_assert(fabs(u - d) < 1e-14, "%s: %g vs %g", dfl_gridpeer_kind_name(k), u, d);
            for (int a = 0; a < 3; a++) cr_assert(fabs(g[a] - ge[a]) < 1e-13);
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
        for (int i = 0; i < 6; i++)
            for (int j = 0; j < 6; j++)
                for (int l = 0; l < 6; l++) {
                    double x[3], g[3], ge[3];
                    centre(&o, i, j, l, x);
                    const double u = dfl_field_eval1(&f, x, g), d = dfl_shape_eval1(&s, x, ge);
                    cr_assert(fabs(u - d) < 1e-15 * (1 + fabs(d)));
                    if (k != DFL_GRIDPEER_TRILINEAR0)
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
    dfl_gridpeer_kind k;
    cr_assert_eq(dfl_gridpeer_kind_parse("taylor2", &k, NULL), DFL_OK);
    cr_assert_eq(k, DFL_GRIDPEER_TAYLOR2);
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
    static const int per_cell[DFL_GRIDPEER_KIND_COUNT] = {1, 4, 10};
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
