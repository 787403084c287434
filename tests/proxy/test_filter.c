/* Decoding filters: the sphere constraint as documented, Hermite blending
 * reproduces value and gradient at cell centres, gradients are the
 * derivatives of the values, exact proxies blend to the exact field. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "core/vec.h"
#include "proxy/analytic_inputs.h"
#include "proxy/filter.h"
#include "util/per_isa.h"

static const ta_shape torus = {TA_TORUS, {0.05, -0.02, 0.03}, {0, 0.6, 0.8}, 0.6, 0.25};
static const ta_shape sphere = {TA_SPHERE, {0.02, -0.03, 0.01}, {0, 0, 1}, 0.5, 0};

static void build_at(const ta_shape *s, int order, int res, dfl_proxy_storage st,
                     dfl_proxy_position pos, dfl_proxy_grid *g)
{
    dfl_proxy_input in;
    ta_input(s, &in);
    dfl_proxy_build_opts o;
    dfl_proxy_build_opts_default(&o);
    o.order = order;
    o.res = res;
    o.storage = st;
    o.position = pos;
    cr_assert_eq(dfl_proxy_grid_build(&in, &o, g, NULL), DFL_OK);
}

/* The grid at the default footpoint position. */
static void build(const ta_shape *s, int order, int res, dfl_proxy_storage st, dfl_proxy_grid *g)
{
    dfl_proxy_build_opts o;
    dfl_proxy_build_opts_default(&o);
    build_at(s, order, res, st, o.position, g);
}

Test(proxy_filter, names_and_check)
{
    dfl_proxy_filter f;
    cr_expect_eq(dfl_proxy_filter_parse("hermite", &f, NULL), DFL_OK);
    cr_expect_eq(f, DFL_PROXY_HERMITE);
    dfl_err err;
    cr_expect_eq(dfl_proxy_filter_parse("cubic", &f, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "nearest|trilinear|hermite") != NULL, "%s", err.msg);
    dfl_proxy_grid g;
    build(&sphere, 1, 4, DFL_PROXY_DOUBLE, &g);
    dfl_proxy_filter_opts o;
    dfl_proxy_filter_opts_default(DFL_PROXY_NEAREST, &g, &o);
    cr_expect_float_eq(o.clip, 0.5, 1e-15);
    o.is_signed = 1;
    cr_expect_eq(dfl_proxy_filter_check(&g, &o, NULL), DFL_OK);
    g.has_inside = 0;
    cr_expect_eq(dfl_proxy_filter_check(&g, &o, &err), DFL_E_INPUT);
    o.is_signed = 0;
    o.clip = -1;
    cr_expect_eq(dfl_proxy_filter_check(&g, &o, &err), DFL_E_INPUT);
    dfl_proxy_filter_opts_default(DFL_PROXY_HERMITE, &g, &o);
    cr_expect_eq(o.clip, 0.0);
    dfl_proxy_grid_free(&g);
}

/* D = sgn(phi) max(|phi|, |x - p| - rho), by hand on a sphere grid. */
Test(proxy_filter, clip_definition)
{
    dfl_proxy_grid g;
    build(&sphere, 2, 8, DFL_PROXY_DOUBLE, &g);
    uint64_t seed = 1;
    for (int k = 0; k < 500; k++) {
        double x[3];
        for (int j = 0; j < 3; j++) x[j] = dfl_rng_splitmix(&seed, -1, 1);
        const size_t c = (size_t)(dfl_rng_splitmix(&seed, 0, 512));
        dfl_proxy_geom pg;
        dfl_proxy_cell_decode(&g, c, &pg);
        const double phi = dfl_proxy_geom_eval(&pg, 2, x, NULL);
        double v[3] = {x[0] - pg.p[0], x[1] - pg.p[1], x[2] - pg.p[2]};
        const double ball = dfl_vec3_norm(v) - 0.25;
        const double want = (phi < 0 ? -1 : 1) * fmax(fabs(phi), ball);
        cr_expect_eq(dfl_proxy_proxy_dist(&g, c, DFL_PROXY_CLIP_BOUND, 0.25, x, NULL), want);
        cr_expect_eq(dfl_proxy_proxy_dist(&g, c, DFL_PROXY_CLIP_BOUND, 0, x, NULL), phi);
    }
    dfl_proxy_grid_free(&g);
}

static double eval1(const dfl_proxy_grid *g, const dfl_proxy_filter_opts *o, const double x[3],
                    double *gr)
{
    double v;
    dfl_proxy_filter_eval(g, o, 1, x, &v, gr);
    return v;
}

/* At every cell centre the Hermite blend's value and gradient are the
 * centre proxy's, i.e. the torus's distance and its gradient (orders 1
 * and 2, signed and unsigned). */
Test(proxy_filter, hermite_reproduces_centres)
{
    for (int order = 1; order <= 2; order++) {
        dfl_proxy_grid g;
        build(&torus, order, 10, DFL_PROXY_DOUBLE, &g);
        for (int sg = 0; sg < 2; sg++) {
            dfl_proxy_filter_opts o;
            dfl_proxy_filter_opts_default(DFL_PROXY_HERMITE, &g, &o);
            o.is_signed = sg;
            for (size_t c = 0; c < g.ncells; c++) {
                double xc[3], gr[3];
                dfl_proxy_cell_centre(&g, c, xc);
                dfl_surfpoint sp;
                ta_answer(&torus, xc, &sp);
                const double v = eval1(&g, &o, xc, gr);
                const double s = sg || sp.d >= 0 ? 1 : -1;
                cr_expect_float_eq(v, s * sp.d, 1e-13, "order %d cell %zu", order, c);
                for (int j = 0; j < 3; j++)
                    cr_expect_float_eq(gr[j], s * sp.n[j], 1e-12, "order %d cell %zu", order, c);
            }
        }
        dfl_proxy_grid_free(&g);
    }
}

/* Filter f's gradients on g are the derivatives of its values: central
 * differences at 200 points uniform in [-half, half]^3 away from kinks (a
 * cell border or a clip switch between the two samples), drawn from *seed.
 * Bounded: a bug that rejects every point fails, it does not hang. */
static void expect_gradients_match_differences(const dfl_proxy_grid *g, dfl_proxy_filter f,
                                               uint64_t *seed, double half)
{
    dfl_proxy_filter_opts o;
    dfl_proxy_filter_opts_default(f, g, &o);
    o.is_signed = 1;
    int n = 0, tries = 0;
    while (n < 200 && tries++ < 200000) {
        double x[3], gr[3], fd[3];
        for (int j = 0; j < 3; j++) x[j] = dfl_rng_splitmix(seed, -half, half);
        const double v = eval1(g, &o, x, gr);
        int ok = 1;
        for (int j = 0; j < 3 && ok; j++) {
            double a[3] = {x[0], x[1], x[2]}, b[3] = {x[0], x[1], x[2]};
            a[j] += 1e-7;
            b[j] -= 1e-7;
            const double va = eval1(g, &o, a, NULL), vb = eval1(g, &o, b, NULL);
            fd[j] = (va - vb) / 2e-7;
            ok = fabs(va - 2 * v + vb) < 1e-11;
        }
        if (!ok) continue;
        n++;
        for (int j = 0; j < 3; j++)
            cr_expect_float_eq(gr[j], fd[j], 1e-6, "%s at %g %g %g", dfl_proxy_filter_name(f),
                               x[0], x[1], x[2]);
    }
    cr_expect_eq(n, 200, "%s: %d points away from kinks in %d tries", dfl_proxy_filter_name(f),
                 n, tries);
}

/* Gradients of every filter (order 2) are the derivatives of its values. */
Test(proxy_filter, gradients_match_differences)
{
    dfl_proxy_grid g;
    build(&torus, 2, 12, DFL_PROXY_FLOAT, &g);
    uint64_t seed = 9;
    for (int f = 0; f < DFL_PROXY_FILTER_COUNT; f++)
        expect_gradients_match_differences(&g, (dfl_proxy_filter)f, &seed, 1.1);
    dfl_proxy_grid_free(&g);
}

/* Order-2 sphere proxies are the sphere: all three filters give the exact
 * distance near the surface (nearest unclipped within the clip). */
Test(proxy_filter, exact_proxies_blend_exactly)
{
    dfl_proxy_grid g;
    build(&sphere, 2, 16, DFL_PROXY_DOUBLE, &g);
    uint64_t seed = 2;
    for (int f = 0; f < DFL_PROXY_FILTER_COUNT; f++) {
        dfl_proxy_filter_opts o;
        dfl_proxy_filter_opts_default((dfl_proxy_filter)f, &g, &o);
        for (int k = 0; k < 300; k++) {
            double x[3];
            do {
                for (int j = 0; j < 3; j++) x[j] = dfl_rng_splitmix(&seed, -0.8, 0.8);
            } while (fabs(ta_sdf(&sphere, x)) > 0.1);
            cr_expect_lt(fabs(eval1(&g, &o, x, NULL) - fabs(ta_sdf(&sphere, x))), 1e-10, "%s",
                         dfl_proxy_filter_name(f));
        }
    }
    dfl_proxy_grid_free(&g);
}

/* Batches give what single points give (no state across points). */
Test(proxy_filter, batch_equals_single)
{
    dfl_proxy_grid g;
    build(&torus, 2, 8, DFL_PROXY_HALF, &g);
    double x[3 * 64], v[64], gr[3 * 64];
    uint64_t seed = 4;
    for (int i = 0; i < 3 * 64; i++) x[i] = dfl_rng_splitmix(&seed, -1.2, 1.2);
    for (int f = 0; f < DFL_PROXY_FILTER_COUNT; f++) {
        dfl_proxy_filter_opts o;
        dfl_proxy_filter_opts_default((dfl_proxy_filter)f, &g, &o);
        dfl_proxy_filter_eval(&g, &o, 64, x, v, gr);
        for (int i = 0; i < 64; i++) {
            double g1[3];
            cr_expect_eq(eval1(&g, &o, x + 3 * i, g1), v[i]);
            cr_expect_eq(eval1(&g, &o, x + 3 * i, NULL), v[i]);
            for (int j = 0; j < 3; j++) cr_expect_eq(g1[j], gr[3 * i + j]);
        }
    }
    dfl_proxy_grid_free(&g);
}

/* h5 (order 2) also reproduces the Hessian at cell centres: differences of
 * the blend's gradient there equal those of the centre proxy's gradient
 * (up to the weights' h5'(t) = 30 t^2 terms, O(step): ~1e-6 here). */
Test(proxy_filter, hermite_order2_hessian_at_centres)
{
    dfl_proxy_grid g;
    build(&torus, 2, 10, DFL_PROXY_DOUBLE, &g);
    dfl_proxy_filter_opts o;
    dfl_proxy_filter_opts_default(DFL_PROXY_HERMITE, &g, &o);
    o.is_signed = 1;
    int checked = 0;
    for (size_t c = 0; c < g.ncells; c += 7) {
        double xc[3];
        dfl_proxy_cell_centre(&g, c, xc);
        if (fabs(ta_sdf(&torus, xc)) > 0.2) continue;
        for (int j = 0; j < 3; j++) {
            double a[3] = {xc[0], xc[1], xc[2]}, b[3] = {xc[0], xc[1], xc[2]};
            a[j] += 1e-7;
            b[j] -= 1e-7;
            double ga[3], gb[3], pa[3], pb[3];
            eval1(&g, &o, a, ga);
            eval1(&g, &o, b, gb);
            dfl_proxy_proxy_dist(&g, c, DFL_PROXY_CLIP_BOUND, 0, a, pa);
            dfl_proxy_proxy_dist(&g, c, DFL_PROXY_CLIP_BOUND, 0, b, pb);
            for (int k = 0; k < 3; k++)
                cr_expect_float_eq((ga[k] - gb[k]) / 2e-7, (pa[k] - pb[k]) / 2e-7, 1e-4,
                                   "cell %zu H[%d][%d] %g vs %g", c, k, j, (ga[k] - gb[k]) / 2e-7,
                                   (pa[k] - pb[k]) / 2e-7);
        }
        checked++;
    }
    cr_expect_gt(checked, 20);
    dfl_proxy_grid_free(&g);
}

/* The paper's reading of the clip, the proxy solid intersected with the
 * ball: D = max(phi, |x - p| - rho) exactly, gradient (x - p)/|x - p| where
 * the ball term is the larger, phi's gradient elsewhere; the off kind is
 * phi whatever rho; the kinds' names come from one list. */
Test(proxy_filter, paper_clip_is_solid_and_ball_and_off_is_none)
{
    dfl_proxy_grid g;
    build(&torus, 2, 8, DFL_PROXY_DOUBLE, &g);
    uint64_t seed = 5;
    int ball_won = 0, phi_won = 0;
    for (int k = 0; k < 2000; k++) {
        double x[3];
        for (int j = 0; j < 3; j++) x[j] = dfl_rng_splitmix(&seed, -1, 1);
        const size_t c = (size_t)(dfl_rng_splitmix(&seed, 0, 512));
        dfl_proxy_geom pg;
        dfl_proxy_cell_decode(&g, c, &pg);
        double gphi[3], gd[3];
        const double phi = dfl_proxy_geom_eval(&pg, 2, x, gphi);
        const double v[3] = {x[0] - pg.p[0], x[1] - pg.p[1], x[2] - pg.p[2]};
        const double r = dfl_vec3_norm(v), ball = r - 0.2;
        const double got = dfl_proxy_proxy_dist(&g, c, DFL_PROXY_CLIP_PAPER, 0.2, x, gd);
        cr_expect_eq(got, fmax(phi, ball), "x %g %g %g", x[0], x[1], x[2]);
        for (int j = 0; j < 3; j++)
            cr_expect_eq(gd[j], ball > phi ? v[j] / r : gphi[j], "component %d", j);
        ball_won += ball > phi;
        phi_won += ball < phi;
        cr_expect_eq(dfl_proxy_proxy_dist(&g, c, DFL_PROXY_CLIP_OFF, 0.2, x, NULL), phi);
    }
    cr_expect(ball_won > 100 && phi_won > 100, "both branches: %d %d", ball_won, phi_won);
    dfl_proxy_clip k;
    dfl_err err;
    dfl_proxy_filter_opts o;
    dfl_proxy_filter_opts_default(DFL_PROXY_NEAREST, &g, &o);
    cr_expect_eq(o.clip_kind, DFL_PROXY_CLIP_BOUND);
    cr_expect_eq(dfl_proxy_filter_check(&g, &o, &err), DFL_OK);
    o.clip_kind = (dfl_proxy_clip)DFL_PROXY_CLIP_COUNT;
    cr_expect_eq(dfl_proxy_filter_check(&g, &o, &err), DFL_E_INPUT);
    dfl_proxy_grid_free(&g);
    cr_expect_eq(dfl_proxy_clip_parse("paper", &k, &err), DFL_OK);
    cr_expect_eq(k, DFL_PROXY_CLIP_PAPER);
    cr_expect_eq(dfl_proxy_clip_parse("ball", &k, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "bound|paper|off") != NULL, "%s", err.msg);
}

/* The nearest filter is the clipped distance of the containing cell's
 * proxy (cell floor((x - lo) / h), clamped to the grid), folded to |D|
 * with its gradient negated for unsigned output: byte for byte (memcmp:
 * -0 and 0 differ), for every order, position, storage, clip on and off,
 * every clip kind (bound, paper, off), signed and unsigned, at 61 points
 * (blocks of the batched path and a short last one), some outside the box. */
Test(proxy_filter, nearest_is_the_cell_proxy_byte_for_byte)
{
    enum { M = 61 };
    double x[3 * M], v[M], gr[3 * M];
    uint64_t seed = 9;
    for (int i = 0; i < 3 * M; i++) x[i] = dfl_rng_splitmix(&seed, -1.3, 1.3);
    for (int order = 1; order <= 2; order++)
        for (int pos = 0; pos < 2; pos++)
            for (int st = 0; st < DFL_PROXY_STORAGE_COUNT; st += 2) {
                dfl_proxy_grid g;
                build_at(&torus, order, 8, (dfl_proxy_storage)st, (dfl_proxy_position)pos, &g);
                for (int variant = 0; variant < 4 * DFL_PROXY_CLIP_COUNT; variant++) {
                    dfl_proxy_filter_opts o;
                    dfl_proxy_filter_opts_default(DFL_PROXY_NEAREST, &g, &o);
                    if (variant & 1) o.clip = 0;
                    o.is_signed = (variant >> 1) & 1;
                    o.clip_kind = (dfl_proxy_clip)(variant >> 2);
                    dfl_proxy_filter_eval(&g, &o, M, x, v, gr);
                    double v2[M];
                    dfl_proxy_filter_eval(&g, &o, M, x, v2, NULL);
                    for (int i = 0; i < M; i++) {
                        size_t id[3];
                        for (int j = 0; j < 3; j++) {
                            const double s = floor((x[3 * i + j] - g.lo[j]) / g.h[j]);
                            id[j] = s < 0 ? 0 : s > g.res - 1 ? (size_t)g.res - 1 : (size_t)s;
                        }
                        const size_t n = (size_t)g.res, c = id[0] + n * (id[1] + n * id[2]);
                        double gw[3];
                        double w = dfl_proxy_proxy_dist(&g, c, o.clip_kind, o.clip, x + 3 * i, gw);
                        if (!o.is_signed && !(w >= 0)) {
                            w = -w;
                            for (int j = 0; j < 3; j++) gw[j] = -gw[j];
                        }
                        cr_expect(memcmp(&w, &v[i], sizeof w) == 0,
                                  "order %d pos %d storage %d variant %d point %d: %.17g vs %.17g",
                                  order, pos, st, variant, i, v[i], w);
                        cr_expect(memcmp(&w, &v2[i], sizeof w) == 0, "value without gradient");
                        cr_expect(memcmp(gw, gr + 3 * i, sizeof gw) == 0,
                                  "gradient: order %d pos %d storage %d variant %d point %d",
                                  order, pos, st, variant, i);
                    }
                }
                dfl_proxy_grid_free(&g);
            }
}

/* filter.h: the Hermite weight of an order-1 grid is h3(t) = 3t^2 - 2t^3,
 * and the gradient is the exact derivative of the value.  An order-1 grid
 * blends planes, so the value is smooth inside a cell of centres; central
 * differences there must equal the returned gradient (the order-2 test
 * above covers h5 only). */
Test(proxy_filter, order1_hermite_gradients_match_differences)
{
    dfl_proxy_grid g;
    build(&torus, 1, 12, DFL_PROXY_DOUBLE, &g);
    uint64_t seed = 17;
    expect_gradients_match_differences(&g, DFL_PROXY_HERMITE, &seed, 0.9);
    dfl_proxy_grid_free(&g);
}

/* filter.h: dfl_proxy_filter_check returns DFL_E_INPUT when the clip
 * radius is < 0 or not finite (an infinite ball is no constraint, and
 * NaN compares false everywhere in the clip). */
Test(proxy_filter, check_refuses_non_finite_clip)
{
    dfl_proxy_grid g;
    build(&sphere, 1, 4, DFL_PROXY_DOUBLE, &g);
    dfl_proxy_filter_opts o;
    dfl_proxy_filter_opts_default(DFL_PROXY_NEAREST, &g, &o);
    dfl_err err;
    o.clip = INFINITY;
    cr_expect_eq(dfl_proxy_filter_check(&g, &o, &err), DFL_E_INPUT);
    o.clip = NAN;
    cr_expect_eq(dfl_proxy_filter_check(&g, &o, &err), DFL_E_INPUT);
    o.clip = 0.0; /* 0: no clip, valid */
    cr_expect_eq(dfl_proxy_filter_check(&g, &o, &err), DFL_OK);
    dfl_proxy_grid_free(&g);
}

/* The blends as filter.h states them, one query at a time from
 * dfl_proxy_proxy_dist: per axis s = (x - lo) / h - 1/2 clamped to the
 * centres' hull (lower corner floor(s), at most res - 2; t = s - floor(s),
 * 0 below and 1 above the hull, dt = 1/h inside, 0 outside), weights
 * (1 - w(t), w(t)) with w = t (trilinear), h3 or h5 (Hermite); corners in
 * the order x fastest, each folded before the sum (d < 0 negated, with its
 * gradient), a zero weight skipped when no gradient is asked for. */
static double blend_ref(const dfl_proxy_grid *g, const dfl_proxy_filter_opts *o,
                        const double x[3], double *grad)
{
    size_t i0[3], i1[3];
    double w[3][2], dw[3][2];
    for (int j = 0; j < 3; j++) {
        const double s = (x[j] - g->lo[j]) / g->h[j] - 0.5;
        double t, dt = 1.0 / g->h[j];
        if (g->res == 1 || s <= 0) {
            i0[j] = 0, t = 0, dt = 0;
        } else if (s >= g->res - 1) {
            i0[j] = (size_t)g->res - 2, t = 1, dt = 0;
        } else {
            double f = floor(s);
            if (f > g->res - 2) f = g->res - 2;
            i0[j] = (size_t)f;
            t = s - f;
        }
        i1[j] = g->res == 1 ? 0 : i0[j] + 1;
        double wt, dwt;
        if (o->filter == DFL_PROXY_TRILINEAR) {
            wt = t, dwt = 1.0;
        } else if (g->order == 1) {
            wt = t * t * (3.0 - 2.0 * t), dwt = 6.0 * t * (1.0 - t);
        } else {
            wt = t * t * t * (10.0 + t * (-15.0 + 6.0 * t));
            const double u = t * (1.0 - t);
            dwt = 30.0 * u * u;
        }
        w[j][0] = 1.0 - wt, w[j][1] = wt;
        dw[j][0] = -dwt * dt, dw[j][1] = dwt * dt;
    }
    const size_t n = (size_t)g->res;
    double val = 0, gr[3] = {0, 0, 0};
    for (int q = 0; q < 8; q++) {
        const int a = q & 1, b = (q >> 1) & 1, c = (q >> 2) & 1;
        const double W = w[0][a] * w[1][b] * w[2][c];
        if (W == 0 && !grad) continue;
        const size_t cell = (a ? i1[0] : i0[0]) + n * ((b ? i1[1] : i0[1]) + n * (c ? i1[2] : i0[2]));
        double gd[3];
        double d = dfl_proxy_proxy_dist(g, cell, o->clip_kind, o->clip, x, grad ? gd : NULL);
        if (!o->is_signed && d < 0) {
            d = -d;
            if (grad)
                for (int j = 0; j < 3; j++) gd[j] = -gd[j];
        }
        val += W * d;
        if (grad) {
            const double gw[3] = {dw[0][a] * w[1][b] * w[2][c], w[0][a] * dw[1][b] * w[2][c],
                                  w[0][a] * w[1][b] * dw[2][c]};
            for (int j = 0; j < 3; j++) gr[j] += W * gd[j] + d * gw[j];
        }
    }
    if (grad)
        for (int j = 0; j < 3; j++) grad[j] = gr[j];
    return val;
}

/* Trilinear and Hermite (batched across queries) are blend_ref byte for
 * byte (memcmp): every order, position, storage, clip kind with the clip on
 * and off, signed and unsigned, at 61 points (blocks and a short last
 * one; some outside the box, some on centre planes where weights vanish),
 * with one failed (NaN) cell in the grid, so that NaN corners meet both
 * zero weights (skipped without gradient, NaN with it) and non-zero ones. */
Test(proxy_filter, blends_are_the_corner_proxies_byte_for_byte)
{
    enum { M = 61 };
    double x[3 * M], v[M], v2[M], gr[3 * M];
    uint64_t seed = 21;
    for (int i = 0; i < 3 * M; i++) x[i] = dfl_rng_splitmix(&seed, -1.3, 1.3);
    /* res 8 on [-1, 1]^3: centre j at -1 + (j + 1/2) / 4 */
    for (int i = 0; i < M; i += 3) x[3 * i + 1] = -1 + 2.5 * 0.25; /* centre plane j = 2 */
    for (int i = 1; i < M; i += 5) x[3 * i] = -1 + 3.5 * 0.25;     /* centre plane i = 3 */
    for (int i = 0; i < M; i += 3) {
        /* every other one of these next to the failed cell (3, 3, 4): on
         * the plane j = 2 (weight 0 for j = 3) or off it (weight > 0) */
        if (i % 2) continue;
        x[3 * i] = -1 + (3.5 + dfl_rng_splitmix(&seed, 0, 1)) * 0.25;
        x[3 * i + 2] = -1 + (4.5 + dfl_rng_splitmix(&seed, 0, 1)) * 0.25;
        if (i % 4 == 0) x[3 * i + 1] = -1 + (2.5 + dfl_rng_splitmix(&seed, 0, 1)) * 0.25;
    }
    for (int order = 1; order <= 2; order++)
        for (int pos = 0; pos < 2; pos++)
            for (int st = 0; st < DFL_PROXY_STORAGE_COUNT; st++) {
                dfl_proxy_grid g;
                build_at(&torus, order, 8, (dfl_proxy_storage)st, (dfl_proxy_position)pos, &g);
                /* cell (3, 3, 4) failed: its scalars NaN */
                const size_t bad = 3 + 8 * (3 + 8 * 4);
                for (int k = 0; k < g.nscalar; k++) {
                    const size_t at = bad * (size_t)g.nscalar + (size_t)k;
                    if (st == DFL_PROXY_DOUBLE) ((double *)g.data)[at] = NAN;
                    else if (st == DFL_PROXY_FLOAT) ((float *)g.data)[at] = NAN;
                    else ((uint16_t *)g.data)[at] = 0x7e00;
                }
                for (int f = DFL_PROXY_TRILINEAR; f <= DFL_PROXY_HERMITE; f++)
                    for (int variant = 0; variant < 4 * DFL_PROXY_CLIP_COUNT; variant++) {
                        dfl_proxy_filter_opts o;
                        dfl_proxy_filter_opts_default((dfl_proxy_filter)f, &g, &o);
                        o.clip = variant & 1 ? 0 : dfl_proxy_cell_size(&g);
                        o.is_signed = (variant >> 1) & 1;
                        o.clip_kind = (dfl_proxy_clip)(variant >> 2);
                        dfl_proxy_filter_eval(&g, &o, M, x, v, gr);
                        dfl_proxy_filter_eval(&g, &o, M, x, v2, NULL);
                        for (int i = 0; i < M; i++) {
                            double gw[3];
                            const double w = blend_ref(&g, &o, x + 3 * i, gw);
                            const double w2 = blend_ref(&g, &o, x + 3 * i, NULL);
                            cr_expect(memcmp(&w, &v[i], sizeof w) == 0,
                                      "filter %d order %d pos %d storage %d variant %d point %d: "
                                      "%.17g vs %.17g", f, order, pos, st, variant, i, v[i], w);
                            cr_expect(memcmp(&w2, &v2[i], sizeof w2) == 0,
                                      "value without gradient: filter %d variant %d point %d: "
                                      "%.17g vs %.17g", f, variant, i, v2[i], w2);
                            cr_expect(memcmp(gw, gr + 3 * i, sizeof gw) == 0,
                                      "gradient: filter %d order %d pos %d storage %d variant %d "
                                      "point %d", f, order, pos, st, variant, i);
                        }
                    }
                dfl_proxy_grid_free(&g);
            }
}

/* The checks of nan_query_is_nan_and_stays_in_the_grid on one grid;
 * returns the number of failures (printed to stderr). */
static int nan_queries_on(const dfl_proxy_grid *g, int order, int si)
{
    enum { M = 19 };
    double x[3 * M];
    uint64_t seed = 5;
    for (int i = 0; i < 3 * M; i++) x[i] = dfl_rng_splitmix(&seed, -1.2, 1.2);
    x[3 * 2 + 0] = NAN;
    x[3 * 7 + 1] = NAN;
    x[3 * 9 + 2] = -NAN;
    x[3 * 16 + 0] = NAN, x[3 * 16 + 1] = INFINITY;
    x[3 * 11 + 1] = INFINITY; /* clamped: a value, NaN or not */
    x[3 * 12 + 2] = -INFINITY;
    int bad = 0;
    for (int f = 0; f < DFL_PROXY_FILTER_COUNT; f++)
        for (int ck = 0; ck < DFL_PROXY_CLIP_COUNT; ck++)
            for (int sg = 0; sg < 2; sg++)
                for (int wg = 0; wg < 2; wg++) {
                    dfl_proxy_filter_opts o;
                    dfl_proxy_filter_opts_default((dfl_proxy_filter)f, g, &o);
                    o.clip_kind = (dfl_proxy_clip)ck;
                    o.clip = dfl_proxy_cell_size(g);
                    o.is_signed = sg;
                    double v[M], gr[3 * M];
                    dfl_proxy_filter_eval(g, &o, M, x, v, wg ? gr : NULL);
                    for (int i = 0; i < M; i++) {
                        const int nan = i == 2 || i == 7 || i == 9 || i == 16;
                        if (nan && !isnan(v[i])) {
                            fprintf(stderr, "order %d st %d filter %d clip %d signed %d grad %d "
                                    "query %d: %g, not NaN\n", order, si, f, ck, sg, wg, i, v[i]);
                            bad++;
                        }
                        if (nan && order == 1 && f == DFL_PROXY_NEAREST &&
                            ck == DFL_PROXY_CLIP_OFF && sg && wg) {
                            /* an order-1 proxy's gradient is its normal wherever x is
                             * (no clip, signed: no fold): the cell the query was
                             * located in */
                            double y[3], g1[3];
                            size_t id[3];
                            for (int j = 0; j < 3; j++) {
                                y[j] = isnan(x[3 * i + j]) ? g->lo[j] : x[3 * i + j];
                                const double t = floor((y[j] - g->lo[j]) / g->h[j]);
                                id[j] = t < 0 ? 0 : t > g->res - 1 ? (size_t)g->res - 1 : (size_t)t;
                            }
                            const size_t n = (size_t)g->res, c = id[0] + n * (id[1] + n * id[2]);
                            (void)dfl_proxy_proxy_dist(g, c, DFL_PROXY_CLIP_OFF, 0.0, y, g1);
                            if (memcmp(g1, gr + 3 * i, sizeof g1) != 0) {
                                fprintf(stderr, "order 1 st %d query %d: not cell 0 on the NaN "
                                        "axis\n", si, i);
                                bad++;
                            }
                        }
                        if (nan) continue;
                        double g1[3];
                        const double v1 = eval1(g, &o, x + 3 * i, wg ? g1 : NULL);
                        if (memcmp(&v1, &v[i], sizeof v1) != 0) {
                            fprintf(stderr, "order %d st %d filter %d clip %d query %d: %a vs "
                                    "%a\n", order, si, f, ck, i, v[i], v1);
                            bad++;
                        }
                    }
                }
    return bad;
}

/* filter.h: a query with a NaN coordinate gets a NaN value and reads no
 * cell outside the grid (it is located in cell 0 on that axis: seen in an
 * order-1 nearest gradient, the cell's normal), while the other queries of
 * its batch get what they get alone; an infinite coordinate is clamped to
 * the grid.  Every filter, clip kind, order, storage and sign, with the
 * NaN on each axis at a different place in a batch longer than one block
 * of lanes; and on every ISA this CPU runs, each in a child process with
 * DFL_ISA set (the ISA is chosen once per process), because a NaN cast to
 * an index differs between them: a read out of the grid crashes on one
 * and reads a neighbour's cell on another. */
/* The checks above on every order and storage (one child per ISA). */
static int nan_queries_all(const void *ctx)
{
    (void)ctx;
    static const dfl_proxy_storage sts[3] = {DFL_PROXY_DOUBLE, DFL_PROXY_FLOAT, DFL_PROXY_HALF};
    int bad = 0;
    for (int order = 1; order <= 2; order++)
        for (int si = 0; si < 3; si++) {
            dfl_proxy_grid g;
            build(&torus, order, 6, sts[si], &g);
            bad += nan_queries_on(&g, order, si);
            dfl_proxy_grid_free(&g);
        }
    return bad;
}

Test(proxy_filter, nan_query_is_nan_and_stays_in_the_grid)
{
    cr_assert(dfl_test_per_isa(nan_queries_all, NULL) >= 1);
}
