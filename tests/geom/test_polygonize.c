/* Certified polygonization: the bound must hold under dense sampling in
 * both directions (curve -> polyline and polyline -> curve), the bounds of
 * single pieces must dominate brute-force Hausdorff distances, and counts
 * must follow eps^(-1/2) (curves) and eps^(-1) (surfaces). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "geom/footpoint.h"
#include "core/fit.h"
#include "geom/polygonize.h"

static const double S_cp[] = {0.85, 0.85, 0.6, 1.0, 0.1, 0.95, 0.1, 0.6, 0.5,
                              0.5,  0.9,  0.4, 0.9, 0.05, 0.4, 0.0, 0.15, 0.15};
static const double W_cp[] = {0.05, 0.95, 0.2, 0.05, 0.35, 0.05, 0.5,
                              0.75, 0.65, 0.05, 0.8, 0.05, 0.95, 0.95};

/* brute-force distance from x to the polyline */
static double poly_dist(const dfl_polyline *p, const double *x)
{
    double best = INFINITY;
    for (size_t i = 0; i + 1 < p->n; i++) {
        const double *a = p->pts + i * (size_t)p->dim, *b = a + p->dim;
        /* cheap reject by bounding box */
        double lb = 0;
        for (int j = 0; j < p->dim; j++) {
            double lo = fmin(a[j], b[j]), hi = fmax(a[j], b[j]);
            double e = x[j] < lo ? lo - x[j] : (x[j] > hi ? x[j] - hi : 0);
            lb = fmax(lb, e);
        }
        if (lb >= best) continue;
        best = fmin(best, dfl_point_segment_dist(p->dim, x, a, b));
    }
    return best;
}

static void check_curve_bound(const dfl_bspline *c, double eps)
{
    dfl_polyline p;
    dfl_err err;
    cr_assert_eq(dfl_polygonize_curve(c, eps, 0, &p, &err), DFL_OK, "%s", err.msg);
    cr_assert(p.bound <= eps);
    /* curve -> polyline: 10^5 samples */
    double worst = 0;
    for (int k = 0; k <= 100000; k++) {
        double x[3];
        dfl_bspline_eval(c, c->t0 + (c->t1 - c->t0) * k / 100000.0, 0, x);
        worst = fmax(worst, poly_dist(&p, x));
    }
    cr_assert(worst <= p.bound * (1 + 1e-12), "sampled %g > bound %g", worst, p.bound);
    double meas;
    cr_assert_eq(dfl_polyline_deviation(c, &p, 16, &meas, &err), DFL_OK);
    cr_assert(meas <= p.bound * (1 + 1e-12) && meas >= worst * (1 - 1e-9),
              "measured %g, sampled %g, bound %g", meas, worst, p.bound);
    /* the bound is not vacuous: the real deviation is a sizeable part of it */
    cr_assert(meas > 0.3 * p.bound, "measured %g vs bound %g", meas, p.bound);
    /* polyline -> curve: points along every chord are within the bound of
     * the curve (footpoint solver, verified separately) */
    dfl_curve_locator *L;
    cr_assert_eq(dfl_curve_locator_new(c, NULL, &L, &err), DFL_OK);
    double worst2 = 0;
    for (size_t i = 0; i + 1 < p.n; i++)
        for (int k = 0; k <= 8; k++) {
            double x[3];
            for (int j = 0; j < c->dim; j++)
                x[j] = p.pts[i * (size_t)c->dim + (size_t)j] +
                       k / 8.0 * (p.pts[(i + 1) * (size_t)c->dim + (size_t)j] -
                                  p.pts[i * (size_t)c->dim + (size_t)j]);
            dfl_curve_foot f;
            dfl_curve_footpoint(L, x, &f, NULL);
            worst2 = fmax(worst2, f.dist);
            if (k == 0) cr_assert(f.dist < 1e-12, "vertex %zu off the curve by %g", i, f.dist);
        }
    cr_assert(worst2 <= p.bound * (1 + 1e-9), "chord->curve %g > bound %g", worst2, p.bound);
    /* parameters increase and span the domain */
    cr_assert_eq(p.t[0], c->t0);
    cr_assert_eq(p.t[p.n - 1], c->t1);
    for (size_t i = 0; i + 1 < p.n; i++) cr_assert(p.t[i] < p.t[i + 1]);
    dfl_curve_locator_free(L);
    dfl_polyline_free(&p);
}

Test(polygonize, curve_bound_holds_under_dense_sampling)
{
    dfl_bspline c;
    cr_assert_eq(dfl_bspline_init(2, 4, 9, S_cp, NULL, 0, &c, NULL), DFL_OK);
    check_curve_bound(&c, 1e-2);
    check_curve_bound(&c, 1e-3);
    check_curve_bound(&c, 1e-4);
    dfl_bspline_free(&c);
    cr_assert_eq(dfl_bspline_init(2, 4, 7, W_cp, NULL, 0, &c, NULL), DFL_OK);
    check_curve_bound(&c, 3e-3);
    dfl_bspline_free(&c);
    /* a space curve of order 5 with non-uniform knots */
    double cp[8 * 3];
    for (int i = 0; i < 8; i++) {
        cp[3 * i] = cos(i);
        cp[3 * i + 1] = sin(1.7 * i);
        cp[3 * i + 2] = 0.2 * i;
    }
    double kn5[13] = {0, 0, 0, 0, 0, 0.3, 0.4, 1.0, 2, 2, 2, 2, 2};
    cr_assert_eq(dfl_bspline_init(3, 5, 8, cp, kn5, 13, &c, NULL), DFL_OK);
    check_curve_bound(&c, 1e-3);
    dfl_bspline_free(&c);
}

Test(polygonize, closed_curve_polyline_closes)
{
    const double cp[] = {1, 0, 0.7, 0.7, 0, 1, -0.7, 0.7, -1, 0, -0.7, -0.7, 0, -1, 0.7, -0.7};
    dfl_bspline c;
    cr_assert_eq(dfl_bspline_init_periodic(2, 4, 8, cp, NULL, 0, &c, NULL), DFL_OK);
    check_curve_bound(&c, 1e-3);
    dfl_polyline p;
    cr_assert_eq(dfl_polygonize_curve(&c, 1e-3, 0, &p, NULL), DFL_OK);
    cr_assert_eq(p.pts[0], p.pts[2 * (p.n - 1)]);
    cr_assert_eq(p.pts[1], p.pts[2 * (p.n - 1) + 1]);
    dfl_polyline_free(&p);
    dfl_bspline_free(&c);
}

/* least-squares slope of log(count) against log(eps) */
Test(polygonize, segment_counts_grow_like_eps_to_minus_half)
{
    const double eps[] = {1e-2, 1e-3, 1e-4, 1e-5, 1e-6};
    const double *cps[2] = {S_cp, W_cp};
    const size_t ns[2] = {9, 7};
    for (int w = 0; w < 2; w++) {
        dfl_bspline c;
        cr_assert_eq(dfl_bspline_init(2, 4, ns[w], cps[w], NULL, 0, &c, NULL), DFL_OK);
        double cnt[5];
        for (int i = 0; i < 5; i++) {
            dfl_polyline p;
            cr_assert_eq(dfl_polygonize_curve(&c, eps[i], 0, &p, NULL), DFL_OK);
            cnt[i] = (double)(p.n - 1);
            if (i > 0) cr_assert(cnt[i] > cnt[i - 1]);
            dfl_polyline_free(&p);
        }
        double k = dfl_fit_loglog_slope(5, eps, cnt);
        cr_assert(k >= -0.6 && k <= -0.4, "curve %d: fitted exponent %g", w, k);
        dfl_bspline_free(&c);
    }
    /* a polyline (order 2) needs no subdivision at all: count is constant */
    dfl_bspline c;
    cr_assert_eq(dfl_bspline_init(2, 2, 9, S_cp, NULL, 0, &c, NULL), DFL_OK);
    dfl_polyline p;
    cr_assert_eq(dfl_polygonize_curve(&c, 1e-9, 0, &p, NULL), DFL_OK);
    cr_assert_eq(p.n, 9);
    cr_assert_eq(p.bound, 0.0);
    dfl_polyline_free(&p);
    dfl_bspline_free(&c);
}

/* brute-force two-sided Hausdorff distance between a Bezier piece and its chord */
static double hausdorff_piece(const double *bez, int np, int dim)
{
    const int N = 2000;
    static double cpts[2001 * 3], lpts[2001 * 3];
    const double *a = bez, *b = bez + (np - 1) * dim;
    for (int k = 0; k <= N; k++) {
        dfl_bezier_eval(bez, np, dim, (double)k / N, cpts + k * dim);
        for (int j = 0; j < dim; j++) lpts[k * dim + j] = a[j] + (b[j] - a[j]) * k / N;
    }
    double h = 0;
    for (int k = 0; k <= N; k++) {
        h = fmax(h, dfl_point_segment_dist(dim, cpts + k * dim, a, b));
        double m = INFINITY;
        for (int q = 0; q < N; q++)
            m = fmin(m, dfl_point_segment_dist(dim, lpts + k * dim, cpts + q * dim,
                                               cpts + (q + 1) * dim));
        h = fmax(h, m);
    }
    return h;
}

Test(polygonize, piece_bound_dominates_hausdorff)
{
    unsigned seed = 99;
    for (int q = 0; q < 40; q++) {
        int np = 2 + q % 5, dim = 2 + q % 2;
        double bez[8 * 3];
        for (int i = 0; i < np * dim; i++) bez[i] = dfl_rng_lcg(&seed);
        if (q % 3 == 0) /* nearly straight, sometimes folding back */
            for (int i = 1; i < np - 1; i++)
                for (int j = 0; j < dim; j++)
                    bez[i * dim + j] = bez[j] + (bez[(np - 1) * dim + j] - bez[j]) *
                                                    (1.4 * dfl_rng_lcg(&seed) - 0.2) +
                                       0.01 * dfl_rng_lcg(&seed);
        double b = dfl_bezier_chord_bound(bez, np, dim);
        double h = hausdorff_piece(bez, np, dim);
        cr_assert(h <= b * (1 + 1e-9) + 1e-12, "piece %d: Hausdorff %g > bound %g", q, h, b);
    }
    /* known values: a parabola arc of height 1 under control height 2 */
    double par[] = {0, 0, 1, 2, 2, 0};
    cr_assert_float_eq(dfl_bezier_chord_bound(par, 3, 2), 2.0, 1e-15);
    double back[] = {0, 0, -1, 0, 1, 0}; /* folds back by 1/3 */
    double b = dfl_bezier_chord_bound(back, 3, 2);
    cr_assert(b >= 1.0 / 3.0);
    cr_assert(fabs(hausdorff_piece(back, 3, 2) - 1.0 / 3.0) < 1e-6);
}

Test(polygonize, rejects_bad_eps)
{
    dfl_bspline c;
    cr_assert_eq(dfl_bspline_init(2, 4, 9, S_cp, NULL, 0, &c, NULL), DFL_OK);
    dfl_polyline p;
    dfl_err err;
    cr_assert_eq(dfl_polygonize_curve(&c, 0.0, 0, &p, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "eps"), "%s", err.msg);
    cr_assert_eq(dfl_polygonize_curve(&c, -1.0, 0, &p, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_polygonize_curve(&c, NAN, 0, &p, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_polygonize_curve(&c, 1e-9, 100, &p, &err), DFL_E_NUMERIC);
    dfl_bspline_free(&c);
}

/* ---- surfaces ---- */

static void make_surface(dfl_surface_set *set, int two)
{
    dfl_surface p[2];
    double cp[6 * 5 * 3];
    for (int j = 0; j < 5; j++)
        for (int i = 0; i < 6; i++) {
            double *P = cp + (i + 6 * j) * 3;
            P[0] = i / 5.0;
            P[1] = j / 4.0;
            P[2] = 0.3 * sin(2.0 * i) * cos(1.5 * j);
        }
    cr_assert_eq(dfl_surface_init(4, 3, 6, 5, cp, NULL, 0, NULL, 0, &p[0], NULL), DFL_OK);
    if (two) {
        double cb[16 * 3];
        for (int j = 0; j < 4; j++)
            for (int i = 0; i < 4; i++) {
                double *P = cb + (i + 4 * j) * 3;
                P[0] = 1.0 + i / 3.0;
                P[1] = j / 3.0;
                P[2] = 0.2 * i * j / 9.0 - 0.1 * i * i / 9.0;
            }
        cr_assert_eq(dfl_surface_init_bezier(4, 4, cb, &p[1], NULL), DFL_OK);
    }
    cr_assert_eq(dfl_surface_set_init(two ? 2 : 1, p, set, NULL), DFL_OK);
}

Test(polygonize, surface_bound_holds_both_ways)
{
    dfl_surface_set s;
    make_surface(&s, 1);
    dfl_trimesh m;
    dfl_err err;
    cr_assert_eq(dfl_polygonize_surface(&s, 2e-3, 0, &m, &err), DFL_OK, "%s", err.msg);
    cr_assert(m.bound <= 2e-3);
    cr_assert(m.ntris % 2 == 0);
    /* surface -> mesh: dense parameter samples against all triangles */
    unsigned seed = 4;
    double worst = 0;
    for (int q = 0; q < 3000; q++) {
        const dfl_surface *sp = &s.patch[q % 2];
        double u = sp->u0 + (sp->u1 - sp->u0) * dfl_rng_lcg(&seed);
        double v = sp->v0 + (sp->v1 - sp->v0) * dfl_rng_lcg(&seed), x[3];
        dfl_surface_eval(sp, u, v, 0, x);
        double best = INFINITY;
        for (size_t t = 0; t < m.ntris; t++)
            best = fmin(best, dfl_point_triangle_dist(x, m.verts + 3 * m.tris[3 * t],
                                                      m.verts + 3 * m.tris[3 * t + 1],
                                                      m.verts + 3 * m.tris[3 * t + 2]));
        worst = fmax(worst, best);
    }
    cr_assert(worst <= m.bound, "sampled %g > bound %g", worst, m.bound);
    double meas;
    cr_assert_eq(dfl_trimesh_deviation(&s, &m, 6, &meas, &err), DFL_OK);
    cr_assert(meas <= m.bound * (1 + 1e-12), "measured %g > bound %g", meas, m.bound);
    cr_assert(meas > 0.2 * m.bound, "measured %g vs bound %g", meas, m.bound);
    /* mesh -> surface: points on the triangles are within the bound */
    dfl_surface_locator *L;
    cr_assert_eq(dfl_surface_locator_new(&s, NULL, &L, &err), DFL_OK);
    double worst2 = 0;
    for (size_t t = 0; t < m.ntris; t += 7) {
        const double *A = m.verts + 3 * m.tris[3 * t], *B = m.verts + 3 * m.tris[3 * t + 1],
                     *C = m.verts + 3 * m.tris[3 * t + 2];
        for (int k = 0; k < 4; k++) {
            double a = dfl_rng_lcg(&seed), b = dfl_rng_lcg(&seed);
            if (a + b > 1) {
                a = 1 - a;
                b = 1 - b;
            }
            double x[3];
            for (int j = 0; j < 3; j++) x[j] = A[j] + a * (B[j] - A[j]) + b * (C[j] - A[j]);
            dfl_surface_foot f;
            dfl_surface_footpoint(L, x, &f, NULL);
            worst2 = fmax(worst2, f.dist);
        }
    }
    cr_assert(worst2 <= m.bound, "mesh->surface %g > bound %g", worst2, m.bound);
    dfl_surface_locator_free(L);
    dfl_trimesh_free(&m);
    dfl_surface_set_free(&s);
}

Test(polygonize, surface_bound_property_and_growth)
{
    unsigned seed = 8;
    for (int q = 0; q < 30; q++) {
        double bez[16 * 3];
        for (int i = 0; i < 48; i++) bez[i] = dfl_rng_lcg(&seed);
        double b = dfl_bezier_cell_bound(bez, 4, 4);
        /* brute force |S(u,v) - T(u,v)| over the two triangles */
        double worst = 0;
        for (int j = 0; j <= 60; j++)
            for (int i = 0; i <= 60; i++) {
                double u = i / 60.0, v = j / 60.0, S[3] = {0, 0, 0};
                for (int l = 0; l < 4; l++)
                    for (int k = 0; k < 4; k++) {
                        static const double C3[4] = {1, 3, 3, 1};
                        double w = C3[k] * pow(u, k) * pow(1 - u, 3 - k) * C3[l] * pow(v, l) *
                                   pow(1 - v, 3 - l);
                        for (int c = 0; c < 3; c++) S[c] += w * bez[(k + 4 * l) * 3 + c];
                    }
                const double *P00 = bez, *P10 = bez + 9, *P01 = bez + 36, *P11 = bez + 45;
                double T[3];
                for (int c = 0; c < 3; c++)
                    T[c] = u + v <= 1 ? P00[c] + u * (P10[c] - P00[c]) + v * (P01[c] - P00[c])
                                      : P11[c] + (1 - u) * (P01[c] - P11[c]) +
                                            (1 - v) * (P10[c] - P11[c]);
                worst = fmax(worst, sqrt((S[0] - T[0]) * (S[0] - T[0]) +
                                         (S[1] - T[1]) * (S[1] - T[1]) +
                                         (S[2] - T[2]) * (S[2] - T[2])));
            }
        cr_assert(worst <= b * (1 + 1e-12), "cell %d: %g > bound %g", q, worst, b);
    }
    dfl_surface_set s;
    make_surface(&s, 0);
    const double eps[] = {1e-2, 3e-3, 1e-3, 3e-4, 1e-4};
    double cnt[5];
    for (int i = 0; i < 5; i++) {
        dfl_trimesh m;
        cr_assert_eq(dfl_polygonize_surface(&s, eps[i], 0, &m, NULL), DFL_OK);
        cnt[i] = (double)m.ntris;
        dfl_trimesh_free(&m);
    }
    double k = dfl_fit_loglog_slope(5, eps, cnt);
    cr_assert(k >= -1.25 && k <= -0.75, "surface: fitted exponent %g", k);
    dfl_surface_set_free(&s);
}
