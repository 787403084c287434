/* PHT splines (pht/spline.c): exact reproduction of bicubic / tricubic
 * polynomials on refined T-meshes for both rules (values, gradients,
 * Hessians, jets, resolved hanging data); C1 continuity across every
 * interior edge / face of refined meshes with random data; cell
 * polynomials against their corner data. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "pht/hermite.h"
#include "pht/pht_fixtures.h"
#include "pht/spline.h"
#include "util/per_isa.h"

static dfl_tmesh *refined(int dim, int rule, uint64_t seed, const double *lo, const double *hi)
{
    dfl_tmesh *m;
    cr_assert_eq(dfl_tmesh_new(dim, lo, hi, &m, NULL), DFL_OK);
    size_t root = 0;
    cr_assert_eq(dfl_tmesh_refine(m, 1, &root, (dfl_pht_split)rule, NULL), DFL_OK);
    int rounds = dim == 2 ? (rule ? 9 : 4) : (rule ? 7 : 2);
    pf_random_refine(m, (dfl_pht_split)rule, rounds, 0.35, seed);
    return m;
}

static const double LO[3] = {-0.3, 0.2, -1.0}, HI[3] = {1.7, 0.9, 0.5};

Test(pht_spline, reproduces_cubic_polynomials_on_any_refined_mesh)
{
    for (int dim = 2; dim <= 3; dim++)
        for (int rule = 0; rule < DFL_PHT_SPLIT_COUNT; rule++)
            for (uint64_t seed = 11; seed <= 12; seed++) {
                dfl_tmesh *m = refined(dim, rule, seed, LO, HI);
                pf_poly P;
                pf_poly_random(dim, seed, &P);
                int nd = DFL_PHT_NDATA(dim);
                size_t nv = dfl_tmesh_nverts(m);
                double *data = calloc(nv * (size_t)nd, sizeof *data);
                for (size_t v = 0; v < nv; v++) {
                    dfl_tmesh_vertex t;
                    dfl_tmesh_vertex_get(m, v, &t);
                    if (t.kind == DFL_TMESH_BASE) pf_poly_hermite(&P, t.x, data + v * nd);
                }
                dfl_pht_resolve(m, data);
                /* hanging data are the polynomial's */
                for (size_t v = 0; v < nv; v++) {
                    dfl_tmesh_vertex t;
                    double ref[8];
                    dfl_tmesh_vertex_get(m, v, &t);
                    pf_poly_hermite(&P, t.x, ref);
                    for (int b = 0; b < nd; b++)
                        cr_assert(fabs(data[v * nd + b] - ref[b]) <= 1e-11 * (1 + fabs(ref[b])),
                                  "dim %d rule %d vertex %zu datum %d: %.17g vs %.17g", dim,
                                  rule, v, b, data[v * nd + b], ref[b]);
                }
                dfl_pht_spline *s;
                cr_assert_eq(dfl_pht_spline_new(m, data, &s, NULL), DFL_OK);
                cr_assert_eq(dfl_pht_spline_ncells(s), dfl_tmesh_nleaves(m));
                cr_assert_eq(dfl_pht_spline_dofs(s), dfl_tmesh_nbase(m) * (size_t)nd);
                uint64_t rs = seed;
                enum { NP = 300 };
                double pts[NP * 3], val[NP], g[NP * 3], H[NP * 9];
                for (int i = 0; i < NP; i++)
                    for (int j = 0; j < dim; j++)
                        pts[i * dim + j] = dfl_rng_splitmix(&rs, LO[j], HI[j]);
                dfl_pht_eval(s, NP, pts, val, g, H);
                for (int i = 0; i < NP; i++) {
                    const double *x = pts + i * dim;
                    int b0[3] = {0, 0, 0};
                    double ref = pf_poly_deriv(&P, x, b0);
                    cr_assert(fabs(val[i] - ref) <= 1e-11 * (1 + fabs(ref)), "value");
                    for (int j = 0; j < dim; j++) {
                        int b[3] = {0, 0, 0};
                        b[j] = 1;
                        ref = pf_poly_deriv(&P, x, b);
                        cr_assert(fabs(g[i * dim + j] - ref) <= 1e-10 * (1 + fabs(ref)), "grad");
                        for (int k = 0; k < dim; k++) {
                            int bb[3] = {0, 0, 0};
                            bb[j]++;
                            bb[k]++;
                            ref = pf_poly_deriv(&P, x, bb);
                            cr_assert(fabs(H[i * dim * dim + j * dim + k] - ref) <=
                                          1e-9 * (1 + fabs(ref)),
                                      "hess %d %d: %g vs %g", j, k, H[i * dim * dim + j * dim + k],
                                      ref);
                        }
                    }
                    /* jet along a random direction: D1 = grad . dir, D2 = dir^T H dir */
                    double dir[3];
                    for (int j = 0; j < dim; j++) dir[j] = dfl_rng_splitmix(&rs, -1, 1);
                    dfl_jet J;
                    cr_assert_eq(dfl_pht_jet(s, x, dir, 4, &J, NULL), DFL_OK);
                    double d1 = 0, d2 = 0;
                    for (int j = 0; j < dim; j++) {
                        d1 += g[i * dim + j] * dir[j];
                        for (int k = 0; k < dim; k++) d2 += dir[j] * H[i * dim * dim + j * dim + k] * dir[k];
                    }
                    cr_assert(fabs(dfl_jet_deriv(&J, 0) - val[i]) <= 1e-12 * (1 + fabs(val[i])));
                    cr_assert(fabs(dfl_jet_deriv(&J, 1) - d1) <= 1e-10 * (1 + fabs(d1)));
                    cr_assert(fabs(dfl_jet_deriv(&J, 2) - d2) <= 1e-9 * (1 + fabs(d2)));
                }
                dfl_pht_spline_free(s);
                free(data);
                dfl_tmesh_free(m);
            }
}

/* Largest relative jump of value and gradient across the cell faces: for
 * every leaf and each of its 2 dim faces, random points on the face are
 * evaluated with the leaf's polynomial and with the neighbour's (located
 * with the outward normal as direction). */
static double max_jump(const dfl_pht_spline *s, uint64_t seed)
{
    int dim = dfl_pht_spline_dim(s);
    double worst = 0.0, lo[3], hi[3], blo[3], bhi[3];
    dfl_pht_spline_box(s, blo, bhi);
    for (size_t c = 0; c < dfl_pht_spline_ncells(s); c++) {
        dfl_pht_spline_cell(s, c, lo, hi, NULL);
        for (int f = 0; f < 2 * dim; f++) {
            int ax = f / 2, side = f % 2;
            double pos = side ? hi[ax] : lo[ax];
            if (pos == blo[ax] || pos == bhi[ax]) continue;
            for (int k = 0; k < 4; k++) {
                double x[3], dir[3] = {0, 0, 0};
                for (int j = 0; j < dim; j++) x[j] = dfl_rng_splitmix(&seed, lo[j], hi[j]);
                x[ax] = pos;
                dir[ax] = side ? 1 : -1;
                size_t nb = dfl_pht_spline_locate(s, x, dir);
                cr_assert_neq(nb, c);
                double v0, v1, g0[3], g1[3];
                dfl_pht_eval_cell(s, c, 1, x, &v0, g0, NULL);
                dfl_pht_eval_cell(s, nb, 1, x, &v1, g1, NULL);
                double scale = 1.0 + fabs(v0), gs = 1e-300;
                for (int j = 0; j < dim; j++) gs = fmax(gs, fabs(g0[j]));
                double jv = fabs(v0 - v1) / scale;
                if (jv > worst) worst = jv;
                for (int j = 0; j < dim; j++) {
                    double jg = fabs(g0[j] - g1[j]) / (1.0 + gs);
                    if (jg > worst) worst = jg;
                }
            }
        }
    }
    return worst;
}

Test(pht_spline, value_and_gradient_are_continuous_across_every_face)
{
    for (int dim = 2; dim <= 3; dim++)
        for (int rule = 0; rule < DFL_PHT_SPLIT_COUNT; rule++)
            for (uint64_t seed = 21; seed <= 23; seed++) {
                dfl_tmesh *m = refined(dim, rule, seed, LO, HI);
                int nd = DFL_PHT_NDATA(dim);
                size_t nv = dfl_tmesh_nverts(m);
                double *data = calloc(nv * (size_t)nd, sizeof *data);
                uint64_t rs = seed * 3;
                for (size_t v = 0; v < nv; v++)
                    for (int b = 0; b < nd; b++) data[v * nd + b] = dfl_rng_splitmix(&rs, -1, 1);
                dfl_pht_resolve(m, data);
                dfl_pht_spline *s;
                cr_assert_eq(dfl_pht_spline_new(m, data, &s, NULL), DFL_OK);
                double j = max_jump(s, seed);
                cr_assert(j < 1e-12, "dim %d rule %s seed %d: jump %.3g", dim,
                          dfl_pht_split_name((dfl_pht_split)rule), (int)seed, j);
                dfl_pht_spline_free(s);
                free(data);
                dfl_tmesh_free(m);
            }
}

Test(pht_spline, cell_polynomial_interpolates_its_corner_data)
{
    for (int dim = 2; dim <= 3; dim++) {
        int nd = DFL_PHT_NDATA(dim), nc = DFL_PHT_NCOEF(dim);
        double lo[3] = {0.25, -1, 2}, hi[3] = {0.75, 0.5, 2.125}, corner[64], coef[64];
        uint64_t rs = 5;
        for (int i = 0; i < (nd << dim); i++) corner[i] = dfl_rng_splitmix(&rs, -1, 1);
        dfl_pht_cell_poly(dim, lo, hi, corner, coef);
        /* derivative of the local polynomial at corner c, mask b, in world units */
        for (int c = 0; c < (1 << dim); c++)
            for (int b = 0; b < nd; b++) {
                double acc = 0;
                for (int k = 0; k < nc; k++) {
                    double t = coef[k];
                    for (int j = 0; j < dim; j++) {
                        int e = (k >> (2 * j)) & 3, u = (c >> j) & 1, r = (b >> j) & 1;
                        double f = r ? e * (e ? pow(u, e - 1) : 0) : pow(u, e);
                        t *= f / (r ? hi[j] - lo[j] : 1.0);
                    }
                    acc += t;
                }
                /* rounding of the local polynomial, scaled by 1/h per derivative */
                double tol = 1e-12;
                for (int j = 0; j < dim; j++)
                    if (b >> j & 1) tol /= hi[j] - lo[j];
                cr_assert(fabs(acc - corner[c * nd + b]) < tol, "dim %d corner %d mask %d: %.3g",
                          dim, c, b, acc - corner[c * nd + b]);
            }
    }
}

/* dfl_pht_eval locates through its grid index; it must pick the cell that
 * dfl_pht_spline_locate picks (ties to the high side), also for points on
 * cell faces and outside the box. */
Test(pht_spline, eval_locates_like_the_tree)
{
    for (int dim = 2; dim <= 3; dim++)
        for (int rule = 0; rule < DFL_PHT_SPLIT_COUNT; rule++) {
            dfl_tmesh *m = refined(dim, rule, 31, LO, HI);
            int nd = DFL_PHT_NDATA(dim);
            size_t nv = dfl_tmesh_nverts(m);
            double *data = calloc(nv * (size_t)nd, sizeof *data);
            uint64_t rs = 77;
            for (size_t v = 0; v < nv * (size_t)nd; v++) data[v] = dfl_rng_splitmix(&rs, -1, 1);
            dfl_pht_resolve(m, data);
            dfl_pht_spline *s;
            cr_assert_eq(dfl_pht_spline_new(m, data, &s, NULL), DFL_OK);
            for (int k = 0; k < 2000; k++) {
                double x[3], lo[3], hi[3];
                size_t c = (size_t)dfl_rng_splitmix(&rs, 0, (double)dfl_pht_spline_ncells(s));
                dfl_pht_spline_cell(s, c, lo, hi, NULL);
                for (int j = 0; j < dim; j++) {
                    double u = dfl_rng_splitmix(&rs, 0, 1);
                    /* a third of the coordinates exactly on a face, some outside */
                    x[j] = u < 0.2 ? lo[j] : u < 0.33 ? hi[j] : lo[j] + (hi[j] - lo[j]) * u;
                    if (k % 50 == 0) x[j] = LO[j] - 0.1 + (HI[j] - LO[j] + 0.2) * u;
                }
                double v0, v1, g0[3], g1[3];
                dfl_pht_eval(s, 1, x, &v0, g0, NULL);
                dfl_pht_eval_cell(s, dfl_pht_spline_locate(s, x, NULL), 1, x, &v1, g1, NULL);
                cr_assert(v0 == v1 && g0[0] == g1[0] && g0[1] == g1[1] &&
                              (dim < 3 || g0[2] == g1[2]),
                          "dim %d rule %d", dim, rule);
            }
            dfl_pht_spline_free(s);
            free(data);
            dfl_tmesh_free(m);
        }
}

/* A spline of random resolved data on refined(dim, rule, nref) over
 * LO..HI (rs seeds the data and goes on to the caller's points); the caller
 * frees the spline, *m and *data. */
static dfl_pht_spline *random_spline(int dim, int rule, int nref, uint64_t *rs, dfl_tmesh **m,
                                     double **data)
{
    *m = refined(dim, rule, nref, LO, HI);
    const size_t n = dfl_tmesh_nverts(*m) * (size_t)DFL_PHT_NDATA(dim);
    *data = calloc(n, sizeof **data);
    cr_assert_not_null(*data);
    for (size_t v = 0; v < n; v++) (*data)[v] = dfl_rng_splitmix(rs, -1, 1);
    dfl_pht_resolve(*m, *data);
    dfl_pht_spline *s;
    cr_assert_eq(dfl_pht_spline_new(*m, *data, &s, NULL), DFL_OK);
    return s;
}

/* dfl_pht_eval starts each point at a node of a uniform location grid of
 * gn^dim cells (gn a power of two, at most 2^7 in 2D, 2^5 in 3D) whose
 * lines lo + (hi - lo) k / gn are rounded: a point on a line, or one ulp
 * either side of it, must still get the tree's cell (ties to the high
 * side), so batches of such points must give the bytes of the cell that
 * dfl_pht_spline_locate picks.  The lines of every gn up to the maximum are
 * among k / 128 (k / 32), and the box's spans are not dyadic. */
Test(pht_spline, eval_locates_points_on_the_location_grid_lines_like_the_tree)
{
    enum { N = 3000 };
    for (int dim = 2; dim <= 3; dim++)
        for (int rule = 0; rule < DFL_PHT_SPLIT_COUNT; rule++) {
            dfl_tmesh *m;
            double *data;
            uint64_t rs = 123;
            dfl_pht_spline *s = random_spline(dim, rule, 57, &rs, &m, &data);
            const int G = dim == 2 ? 128 : 32;
            static double x[N * 3], v[N], g[N * 3];
            for (int i = 0; i < N * dim; i++) {
                const int j = i % dim, k = (int)dfl_rng_splitmix(&rs, 0, G + 1 - 1e-9);
                const double line = LO[j] + (HI[j] - LO[j]) * ((double)k / G),
                             u = dfl_rng_splitmix(&rs, 0, 3);
                x[i] = u < 1   ? line
                       : u < 2 ? nextafter(line, -INFINITY)
                               : nextafter(line, INFINITY);
            }
            dfl_pht_eval(s, N, x, v, g, NULL);
            for (int i = 0; i < N; i++) {
                double v1, g1[3];
                dfl_pht_eval_cell(s, dfl_pht_spline_locate(s, x + i * dim, NULL), 1, x + i * dim,
                                  &v1, g1, NULL);
                cr_assert(memcmp(&v[i], &v1, sizeof v1) == 0 &&
                              memcmp(g + i * dim, g1, (size_t)dim * sizeof *g1) == 0,
                          "dim %d rule %d point %d", dim, rule, i);
            }
            dfl_pht_spline_free(s);
            free(data);
            dfl_tmesh_free(m);
        }
}

/* A batch goes through blocks of located points (software-pipelined) and,
 * for value + gradient, a kernel without the Hessian's terms: every output
 * combination of a batch that spans several blocks and ends mid-block must
 * give the bytes of dfl_pht_eval_cell on the tree's cell, point by point. */
Test(pht_spline, batches_give_the_bytes_of_single_cell_evaluation)
{
    enum { N = 1000 };
    for (int dim = 2; dim <= 3; dim++)
        for (int rule = 0; rule < DFL_PHT_SPLIT_COUNT; rule++) {
            dfl_tmesh *m;
            double *data;
            uint64_t rs = 91;
            dfl_pht_spline *s = random_spline(dim, rule, 43, &rs, &m, &data);
            static double x[N * 3], v[N], g[N * 3], H[N * 9], v1[N], g1[N * 3], H1[N * 9];
            for (int i = 0; i < N * dim; i++) {
                int j = i % dim;
                x[i] = LO[j] - 0.1 + (HI[j] - LO[j] + 0.2) * dfl_rng_splitmix(&rs, 0, 1);
            }
            for (int i = 0; i < N; i++)
                dfl_pht_eval_cell(s, dfl_pht_spline_locate(s, x + i * dim, NULL), 1, x + i * dim,
                                  v1 + i, g1 + i * dim, H1 + i * dim * dim);
            const size_t vb = N * sizeof(double), gb = vb * (size_t)dim, hb = gb * (size_t)dim;
            for (int mask = 1; mask < 8; mask++) {
                memset(v, 0xff, sizeof v), memset(g, 0xff, sizeof g), memset(H, 0xff, sizeof H);
                dfl_pht_eval(s, N, x, mask & 1 ? v : NULL, mask & 2 ? g : NULL,
                             mask & 4 ? H : NULL);
                cr_assert(!(mask & 1) || memcmp(v, v1, vb) == 0, "dim %d rule %d mask %d", dim,
                          rule, mask);
                cr_assert(!(mask & 2) || memcmp(g, g1, gb) == 0, "dim %d rule %d mask %d", dim,
                          rule, mask);
                cr_assert(!(mask & 4) || memcmp(H, H1, hb) == 0, "dim %d rule %d mask %d", dim,
                          rule, mask);
            }
            dfl_pht_spline_free(s);
            free(data);
            dfl_tmesh_free(m);
        }
}

/* Equal bytes, or both NaN (an infinite coordinate's polynomial may give
 * inf - inf). */
static int same(double a, double b) { return memcmp(&a, &b, sizeof a) == 0 || (isnan(a) && isnan(b)); }

/* The checks of nan_query_is_nan_and_stays_in_the_tree on one ISA: the
 * number of failures (printed to stderr). */
static int nan_queries(const void *ctx)
{
    (void)ctx;
    enum { M = 75 }; /* three blocks of located points, the last one short */
    int bad = 0;
    for (int dim = 2; dim <= 3; dim++)
        for (int rule = 0; rule < DFL_PHT_SPLIT_COUNT; rule++) {
            dfl_tmesh *m;
            double *data;
            uint64_t rs = 29;
            dfl_pht_spline *s = random_spline(dim, rule, 31, &rs, &m, &data);
            double x[3 * M], v[M], g[3 * M], H[9 * M];
            for (int i = 0; i < M * dim; i++) {
                const int j = i % dim;
                x[i] = LO[j] - 0.1 + (HI[j] - LO[j] + 0.2) * dfl_rng_splitmix(&rs, 0, 1);
            }
            /* NaN, +inf, -inf, +-1e300 on every axis, spread over the blocks;
             * a NaN with an infinity */
            static const double odd[5] = {NAN, INFINITY, -INFINITY, 1e300, -1e300};
            for (int j = 0, i = 1; j < dim; j++)
                for (int q = 0; q < 5; q++, i += 4) x[i * dim + j] = odd[q];
            x[70 * dim] = -NAN, x[70 * dim + 1] = INFINITY;
            x[73 * dim + dim - 1] = NAN;
            for (int mask = 1; mask < 8; mask++) {
                memset(v, 0, sizeof v), memset(g, 0, sizeof g), memset(H, 0, sizeof H);
                dfl_pht_eval(s, M, x, mask & 1 ? v : NULL, mask & 2 ? g : NULL,
                             mask & 4 ? H : NULL);
                for (int i = 0; i < M; i++) {
                    const double *xi = x + i * dim;
                    int nan = 0;
                    for (int j = 0; j < dim; j++) nan |= isnan(xi[j]);
                    double v1, g1[3], H1[9];
                    dfl_pht_eval_cell(s, dfl_pht_spline_locate(s, xi, NULL), 1, xi, &v1, g1, H1);
                    int ok = !(mask & 1) || (nan ? isnan(v[i]) : same(v[i], v1));
                    for (int j = 0; j < dim && mask & 2; j++)
                        ok &= nan ? isnan(g[i * dim + j]) : same(g[i * dim + j], g1[j]);
                    for (int j = 0; j < dim * dim && mask & 4; j++)
                        ok &= nan ? isnan(H[i * dim * dim + j]) : same(H[i * dim * dim + j], H1[j]);
                    if (!ok) {
                        fprintf(stderr, "dim %d rule %d mask %d point %d (%g %g): %g vs %g\n", dim,
                                rule, mask, i, xi[0], xi[1], v[i], v1);
                        bad++;
                    }
                }
            }
            /* dfl_pht_spline_locate: NaN below every split on its axis, i.e.
             * where the box's low face is; an infinity where a far point is */
            for (int i = 0; i < M; i++) {
                const double *xi = x + i * dim;
                double y[3];
                for (int j = 0; j < dim; j++)
                    y[j] = isnan(xi[j]) ? LO[j] : isinf(xi[j]) ? copysign(1e300, xi[j]) : xi[j];
                if (dfl_pht_spline_locate(s, xi, NULL) != dfl_pht_spline_locate(s, y, NULL)) {
                    fprintf(stderr, "dim %d rule %d point %d: located elsewhere\n", dim, rule, i);
                    bad++;
                }
            }
            dfl_pht_spline_free(s);
            free(data);
            dfl_tmesh_free(m);
        }
    return bad;
}

/* spline.h: a point with a NaN coordinate gets NaN value, gradient and
 * Hessian and reads nothing outside the tree and its cells (it is located
 * below every split on that axis); an infinite coordinate is located like
 * a far point (the boundary cell's polynomial); the other points of the
 * batch get the bytes of their cell alone.  2D and 3D, both split rules,
 * every output combination, the odd coordinates spread over three blocks
 * of located points, on every ISA this CPU runs (a child per ISA: the
 * location grid's index is vectorized differently per ISA). */
Test(pht_spline, nan_query_is_nan_and_stays_in_the_tree)
{
    cr_assert(dfl_test_per_isa(nan_queries, NULL) >= 1);
}
