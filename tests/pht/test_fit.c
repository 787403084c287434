/* Adaptive and uniform PHT fits (pht/fit.c): exactness for a linear SDF,
 * convergence and consistent level records on the circle, both split
 * rules and all estimators, bit-identical results at 1 and 2 threads,
 * uniform grids' counts, option checks. */
#include <criterion/criterion.h>
#include <math.h>
#include <omp.h>
#include <string.h>

#include "geom/bspline.h"
#include "geom/param_shape.h"
#include "geom/shape.h"
#include "pht/fit.h"
#include "pht/spline.h"

static dfl_shape circle(void)
{
    dfl_shape s;
    const double c[2] = {0.5, 0.5};
    cr_assert_eq(dfl_shape_circle(c, 0.3, &s, NULL), DFL_OK);
    return s;
}

static void fit(const dfl_shape *s, const dfl_pht_fit_opts *o, dfl_pht_fit *f)
{
    dfl_pht_source *src;
    dfl_err err;
    cr_assert_eq(dfl_pht_source_new(s, &src, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_pht_fit_run(src, o, f, &err), DFL_OK, "%s", err.msg);
    dfl_pht_source_free(src);
}

Test(pht_fit, a_linear_sdf_is_exact_on_one_cell)
{
    dfl_shape s;
    const double p[2] = {0.3, 0.4}, n[2] = {1, 2};
    cr_assert_eq(dfl_shape_plane(2, p, n, &s, NULL), DFL_OK);
    dfl_pht_fit_opts o;
    dfl_pht_fit_opts_default(2, &o);
    o.eps = 1e-13;
    dfl_pht_fit f;
    fit(&s, &o, &f);
    cr_assert_eq(f.nlevels, 1);
    cr_assert_eq(f.levels[0].cells, 1);
    cr_assert_eq(f.levels[0].dofs, 16);
    cr_assert(f.converged);
    cr_assert(f.levels[0].max_err < 1e-14, "%g", f.levels[0].max_err);
    dfl_pht_fit_free(&f);
    dfl_shape_free(&s);
}

Test(pht_fit, circle_converges_with_consistent_records)
{
    dfl_shape s = circle();
    for (int rule = 0; rule < DFL_PHT_SPLIT_COUNT; rule++)
        for (int est = 0; est < DFL_PHT_EST_COUNT; est++) {
            dfl_pht_fit_opts o;
            dfl_pht_fit_opts_default(2, &o);
            o.eps = 1e-4;
            o.max_level = rule == DFL_PHT_SPLIT_BINARY ? 40 : 20;
            o.split = (dfl_pht_split)rule;
            o.estimator = (dfl_pht_estimator)est;
            /* the gradient error at the circle's centre (a cone point) does
             * not shrink with the cell: that estimator stops at max_level */
            int grad = est == DFL_PHT_EST_GRADIENT;
            if (grad) o.max_level = rule == DFL_PHT_SPLIT_BINARY ? 20 : 10;
            dfl_pht_fit f;
            fit(&s, &o, &f);
            cr_assert_eq(f.converged, !grad, "%s/%s", dfl_pht_split_name(o.split),
                         dfl_pht_estimator_name(o.estimator));
            const dfl_pht_level *last = &f.levels[f.nlevels - 1];
            cr_assert(grad || last->max_err <= o.eps);
            cr_assert_eq(last->refined, 0);
            cr_assert_eq(last->cells, dfl_pht_spline_ncells(f.spline));
            cr_assert_eq(last->cells, dfl_tmesh_nleaves(f.mesh));
            cr_assert_eq(last->dofs, 4 * dfl_tmesh_nbase(f.mesh));
            cr_assert_eq(last->dofs, dfl_pht_spline_dofs(f.spline));
            size_t base = 0;
            for (int k = 0; k < f.nlevels; k++) {
                const dfl_pht_level *r = &f.levels[k];
                cr_assert_eq(r->level, k);
                cr_assert(r->base_vertices >= base);
                base += r->new_base;
                cr_assert_eq(r->base_vertices, base);
                if (k + 1 < f.nlevels) {
                    /* splitting n cells adds n (binary) or 3n (cross) leaves */
                    size_t add = rule == DFL_PHT_SPLIT_BINARY ? 1 : 3;
                    cr_assert_eq(f.levels[k + 1].cells, r->cells + add * r->refined);
                }
            }
            for (size_t i = 0; i < last->cells; i++) {
                int level;
                dfl_pht_spline_cell(f.spline, i, NULL, NULL, &level);
                cr_assert(f.cell_err[i] <= o.eps || level == o.max_level);
            }
            dfl_pht_fit_free(&f);
        }
    dfl_shape_free(&s);
}

Test(pht_fit, bit_identical_at_one_and_two_threads)
{
    dfl_shape s = circle();
    dfl_pht_fit_opts o;
    dfl_pht_fit_opts_default(2, &o);
    o.eps = 1e-5;
    o.max_level = 20;
    o.seed = 7;
    dfl_pht_fit f1, f2;
    omp_set_num_threads(1);
    fit(&s, &o, &f1);
    omp_set_num_threads(2);
    fit(&s, &o, &f2);
    cr_assert_eq(f1.nlevels, f2.nlevels);
    for (int k = 0; k < f1.nlevels; k++) {
        cr_assert_eq(f1.levels[k].cells, f2.levels[k].cells);
        cr_assert(memcmp(&f1.levels[k].max_err, &f2.levels[k].max_err, sizeof(double)) == 0);
        cr_assert(memcmp(&f1.levels[k].mean_err, &f2.levels[k].mean_err, sizeof(double)) == 0);
    }
    size_t n = dfl_pht_spline_ncells(f1.spline);
    cr_assert_eq(n, dfl_pht_spline_ncells(f2.spline));
    for (size_t i = 0; i < n; i++)
        cr_assert(memcmp(dfl_pht_spline_cell(f1.spline, i, NULL, NULL, NULL),
                         dfl_pht_spline_cell(f2.spline, i, NULL, NULL, NULL),
                         16 * sizeof(double)) == 0);
    /* another seed draws other points: the fit may differ, but stays valid */
    dfl_pht_fit f3;
    o.seed = 8;
    fit(&s, &o, &f3);
    cr_assert(f3.converged);
    dfl_pht_fit_free(&f1);
    dfl_pht_fit_free(&f2);
    dfl_pht_fit_free(&f3);
    dfl_shape_free(&s);
}

Test(pht_fit, uniform_grid_counts)
{
    dfl_shape s = circle();
    dfl_pht_source *src;
    cr_assert_eq(dfl_pht_source_new(&s, &src, NULL), DFL_OK);
    dfl_pht_fit_opts o;
    dfl_pht_fit_opts_default(2, &o);
    dfl_pht_fit f;
    cr_assert_eq(dfl_pht_fit_uniform(src, &o, 3, &f, NULL), DFL_OK);
    cr_assert_eq(f.nlevels, 1);
    cr_assert_eq(f.levels[0].level, 3);
    cr_assert_eq(f.levels[0].cells, 64);
    cr_assert_eq(f.levels[0].base_vertices, 81);
    cr_assert_eq(f.levels[0].dofs, 324);
    dfl_pht_fit_free(&f);
    dfl_pht_source_free(src);
    dfl_shape_free(&s);
    /* 3D: 2^3k cells, (2^k + 1)^3 base vertices, 8 data each */
    const double c[3] = {0.5, 0.5, 0.5};
    cr_assert_eq(dfl_shape_sphere(c, 0.3, &s, NULL), DFL_OK);
    cr_assert_eq(dfl_pht_source_new(&s, &src, NULL), DFL_OK);
    dfl_pht_fit_opts_default(3, &o);
    cr_assert_eq(dfl_pht_fit_uniform(src, &o, 2, &f, NULL), DFL_OK);
    cr_assert_eq(f.levels[0].cells, 64);
    cr_assert_eq(f.levels[0].base_vertices, 125);
    cr_assert_eq(f.levels[0].dofs, 1000);
    dfl_pht_fit_free(&f);
    dfl_pht_source_free(src);
    dfl_shape_free(&s);
}

Test(pht_fit, bad_options_name_the_option)
{
    dfl_pht_fit_opts o;
    dfl_err err;
    dfl_pht_fit_opts_default(2, &o);
    cr_assert_eq(dfl_pht_fit_opts_check(2, &o, &err), DFL_OK);
    o.eps = 0;
    cr_assert_eq(dfl_pht_fit_opts_check(2, &o, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "eps"), "%s", err.msg);
    dfl_pht_fit_opts_default(2, &o);
    o.max_level = 31;
    cr_assert_eq(dfl_pht_fit_opts_check(2, &o, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "max_level"), "%s", err.msg);
    o.split = DFL_PHT_SPLIT_BINARY; /* binary allows 30 * dim */
    cr_assert_eq(dfl_pht_fit_opts_check(2, &o, &err), DFL_OK);
    o.max_level = -1;
    cr_assert_eq(dfl_pht_fit_opts_check(2, &o, &err), DFL_E_INPUT);
    dfl_pht_fit_opts_default(2, &o);
    o.samples = 0;
    cr_assert_eq(dfl_pht_fit_opts_check(2, &o, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "samples"), "%s", err.msg);
    cr_assert_str_eq(dfl_pht_estimator_name(DFL_PHT_EST_GRADIENT), "gradient");
    dfl_pht_estimator e = DFL_PHT_EST_RANDOM;
    cr_assert_eq(dfl_pht_estimator_parse("grid", &e, &err), DFL_OK);
    cr_assert_eq(e, DFL_PHT_EST_GRID);
    cr_assert_eq(dfl_pht_estimator_parse("sobol", &e, &err), DFL_E_INPUT);
    cr_assert_eq(e, DFL_PHT_EST_GRID);
    cr_assert(strstr(err.msg, "'sobol'") && strstr(err.msg, "random|grid|gradient"), "%s",
              err.msg);
}

/* capped (fit.h): the leaf cells above eps at max_level; 0 iff converged. */
Test(pht_fit, capped_counts_the_cells_above_eps_at_max_level)
{
    dfl_shape s = circle();
    dfl_pht_fit_opts o;
    dfl_pht_fit_opts_default(2, &o);
    o.eps = 1e-5;
    o.max_level = 5;
    dfl_pht_fit f;
    fit(&s, &o, &f);
    cr_assert_eq(f.converged, 0);
    size_t above = 0;
    const size_t nl = dfl_tmesh_nleaves(f.mesh);
    const size_t *leaves = dfl_tmesh_leaves(f.mesh);
    for (size_t i = 0; i < nl; i++) {
        if (!(f.cell_err[i] > o.eps)) continue;
        dfl_tmesh_cell c;
        dfl_tmesh_cell_get(f.mesh, leaves[i], &c);
        cr_assert_eq(c.level, o.max_level, "a cell above eps below max_level");
        above++;
    }
    cr_assert_gt(above, 0);
    cr_assert_eq(f.capped, above);
    dfl_pht_fit_free(&f);
    o.eps = 1e-2;
    o.max_level = 10;
    fit(&s, &o, &f);
    cr_assert_eq(f.converged, 1);
    cr_assert_eq(f.capped, 0);
    dfl_pht_fit_free(&f);
    dfl_shape_free(&s);
}

/* mean_err (fit.h): the mean of |f - d| over all estimator points.  With
 * the grid estimator on a uniform fit the points are known: the centres of
 * the n x n subdivision of every cell (n = 2 for samples = 4). */
Test(pht_fit, mean_err_is_the_mean_over_the_estimator_points)
{
    dfl_shape s = circle();
    dfl_pht_source *src;
    cr_assert_eq(dfl_pht_source_new(&s, &src, NULL), DFL_OK);
    dfl_pht_fit_opts o;
    dfl_pht_fit_opts_default(2, &o);
    o.estimator = DFL_PHT_EST_GRID;
    o.samples = 4;
    dfl_pht_fit f;
    cr_assert_eq(dfl_pht_fit_uniform(src, &o, 3, &f, NULL), DFL_OK);
    const size_t nc = dfl_pht_spline_ncells(f.spline);
    cr_assert_eq(nc, 64);
    double sum = 0.0, mx = 0.0;
    for (size_t i = 0; i < nc; i++) {
        double lo[2], hi[2], x[8], v[4], d[4];
        dfl_pht_spline_cell(f.spline, i, lo, hi, NULL);
        for (int k = 0; k < 4; k++) {
            x[2 * k] = lo[0] + (hi[0] - lo[0]) * ((k % 2) + 0.5) / 2;
            x[2 * k + 1] = lo[1] + (hi[1] - lo[1]) * ((k / 2) + 0.5) / 2;
        }
        dfl_pht_eval(f.spline, 4, x, v, NULL, NULL);
        dfl_shape_eval(&s, 4, x, d, NULL);
        for (int k = 0; k < 4; k++) {
            sum += fabs(v[k] - d[k]);
            mx = fmax(mx, fabs(v[k] - d[k]));
        }
    }
    cr_assert_float_eq(f.levels[0].mean_err, sum / (4.0 * nc), 1e-12 * sum / nc + 1e-18);
    cr_assert_float_eq(f.levels[0].max_err, mx, 1e-12 * mx);
    dfl_pht_fit_free(&f);
    dfl_pht_source_free(src);
    dfl_shape_free(&s);
}

/* The gradient estimator (fit.h) takes max(|f - d|, |grad f - grad d|) at
 * the random estimator's points: on the same points (same seed and cells)
 * its error is >= the random estimator's, and strictly larger on a uniform
 * level-3 fit of the circle, whose gradient error next to the centre's kink
 * is O(1) while the value error is O(h). */
Test(pht_fit, gradient_estimator_adds_the_gradient_error)
{
    dfl_shape s = circle();
    dfl_pht_source *src;
    cr_assert_eq(dfl_pht_source_new(&s, &src, NULL), DFL_OK);
    dfl_pht_fit_opts o;
    dfl_pht_fit_opts_default(2, &o);
    dfl_pht_fit fr, fg;
    cr_assert_eq(dfl_pht_fit_uniform(src, &o, 3, &fr, NULL), DFL_OK);
    o.estimator = DFL_PHT_EST_GRADIENT;
    cr_assert_eq(dfl_pht_fit_uniform(src, &o, 3, &fg, NULL), DFL_OK);
    const size_t nc = dfl_pht_spline_ncells(fr.spline);
    for (size_t i = 0; i < nc; i++) cr_assert_geq(fg.cell_err[i], fr.cell_err[i], "cell %zu", i);
    cr_assert_gt(fg.levels[0].max_err, 2.0 * fr.levels[0].max_err, "gradient %g, value %g",
                 fg.levels[0].max_err, fr.levels[0].max_err);
    cr_assert_gt(fg.levels[0].max_err, 0.1);
    dfl_pht_fit_free(&fr);
    dfl_pht_fit_free(&fg);
    dfl_pht_source_free(src);
    dfl_shape_free(&s);
}

/* A library caller gets the signed-distance check (fit.h, hermite.h): an
 * open B-spline curve has jets and the kind of a closed one, so
 * dfl_pht_source_new takes it, but its distance is unsigned (no inside):
 * both fits refuse it with DFL_E_INPUT and a message saying why, and leave
 * *out zeroed. */
Test(pht_fit, an_open_curve_is_refused_with_a_message)
{
    const double cp[8] = {0.1, 0.1, 0.5, 0.9, 0.9, 0.1, 0.9, 0.5};
    dfl_bspline c;
    dfl_err err;
    cr_assert_eq(dfl_bspline_init(2, 4, 4, cp, NULL, 0, &c, &err), DFL_OK, "%s", err.msg);
    dfl_shape s;
    cr_assert_eq(dfl_shape_param_curve(&c, NULL, 0, &s, &err), DFL_OK, "%s", err.msg);
    dfl_pht_source *src;
    cr_assert_eq(dfl_pht_source_new(&s, &src, &err), DFL_OK, "%s", err.msg);
    dfl_pht_fit_opts o;
    dfl_pht_fit_opts_default(2, &o);
    dfl_pht_fit f;
    memset(&f, 0xff, sizeof f);
    cr_assert_eq(dfl_pht_fit_run(src, &o, &f, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "'bspline_curve'") && strstr(err.msg, "no inside") &&
                  strstr(err.msg, "unsigned"),
              "%s", err.msg);
    cr_expect_null(f.mesh);
    cr_expect_eq(f.nlevels, 0);
    err.msg[0] = 0;
    cr_assert_eq(dfl_pht_fit_uniform(src, &o, 2, &f, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "no inside"), "%s", err.msg);
    dfl_pht_source_free(src);
    dfl_shape_free(&s);
}

/* ---- a source whose estimator points are controlled ----
 * The plane d = x + y - 1 (exact for the cubic spline: every cell's error
 * is 0) whose batch evaluation without gradient (the estimator's exact
 * distances; Hermite data always ask for the gradient) returns d + bump at
 * the listed points, compared exactly.  With the grid estimator at one
 * sample the only estimator point of a cell is its centre, so a cell's
 * estimate is bump iff its centre is listed: the test decides which cells
 * the error rule splits, and the rest of the mesh is grading. */
typedef struct marked {
    dfl_shape plane;
    int n;
    double pts[8][2];
    double bump;
} marked;

static void marked_eval(const void *impl, size_t m, const double *pts, double *val, double *grad)
{
    const marked *M = impl;
    M->plane.ops->eval(M->plane.impl, m, pts, val, grad);
    if (grad) return;
    for (size_t i = 0; i < m; i++)
        for (int k = 0; k < M->n; k++)
            if (pts[2 * i] == M->pts[k][0] && pts[2 * i + 1] == M->pts[k][1]) val[i] += M->bump;
}

static dfl_status marked_jet(const void *impl, const double *x, const double *dir, int K,
                             dfl_jet *out, dfl_err *err)
{
    const marked *M = impl;
    return M->plane.ops->jet(M->plane.impl, x, dir, K, out, err);
}

static const dfl_shape_ops marked_ops = {"marked_plane", marked_eval, marked_jet, NULL, NULL};

static void marked_init(marked *M, int n, const double (*pts)[2], double bump, dfl_shape *s)
{
    const double p[2] = {0.5, 0.5}, nrm[2] = {1, 1};
    cr_assert_eq(dfl_shape_plane(2, p, nrm, &M->plane, NULL), DFL_OK);
    M->n = n;
    memcpy(M->pts, pts, (size_t)n * sizeof *pts);
    M->bump = bump;
    *s = (dfl_shape){.dim = 2, .ops = &marked_ops, .impl = M};
}

static void marked_fit(const double (*pts)[2], int n, double bump, int max_level, int grade,
                       dfl_pht_fit *f)
{
    static marked M;
    dfl_shape s;
    marked_init(&M, n, pts, bump, &s);
    dfl_pht_fit_opts o;
    dfl_pht_fit_opts_default(2, &o);
    o.estimator = DFL_PHT_EST_GRID;
    o.samples = 1;
    o.max_level = max_level;
    o.grade = grade;
    fit(&s, &o, f);
    dfl_shape_free(&M.plane);
}

static void expect_records(const dfl_pht_fit *f, int n, const size_t *cells,
                           const size_t *refined)
{
    cr_assert_eq(f->nlevels, n);
    for (int k = 0; k < n; k++) {
        cr_expect_eq(f->levels[k].cells, cells[k], "level %d: %zu cells, expected %zu", k,
                     f->levels[k].cells, cells[k]);
        cr_expect_eq(f->levels[k].refined, refined[k], "level %d: %zu refined, expected %zu", k,
                     f->levels[k].refined, refined[k]);
    }
}

/* Grading (fit.h): the owner of a hanging corner of a split cell is split
 * too iff it is >= 2 levels coarser.  The error rule splits the root
 * (centre (1/2, 1/2)), then A = [0, 1/2]^2 (centre (1/4, 1/4)), then its
 * child C = [1/4, 1/2]^2 (centre (3/8, 3/8)), all cross.  C (level 2) has
 * two hanging corners, (1/2, 1/4) on the edge of the level-1 leaf
 * E = [1/2, 1] x [0, 1/2] and (1/4, 1/2) on the level-1 leaf
 * N = [0, 1/2] x [1/2, 1]: one level coarser, so neither is split (one
 * level apart is what grading allows): records 1, 4, 7, 10 cells, one split
 * each.  Then also listing C's child F = [3/8, 1/2]^2 (centre (7/16,
 * 7/16), level 3): F's hanging corners (1/2, 3/8) and (3/8, 1/2) lie on E
 * and N, two levels coarser, so the level splits F, E and N (refined 3):
 * 10 + 3 * 3 = 19 cells, where the paper's rule alone (grade = 0) splits F
 * only: 13. */
Test(pht_fit, grading_splits_owners_two_levels_coarser_only)
{
    const double pts[4][2] = {{0.5, 0.5}, {0.25, 0.25}, {0.375, 0.375}, {0.4375, 0.4375}};
    dfl_pht_fit f;
    marked_fit(pts, 3, 1.0, 4, 1, &f);
    const size_t c3[4] = {1, 4, 7, 10}, r3[4] = {1, 1, 1, 0};
    expect_records(&f, 4, c3, r3);
    cr_expect(f.converged);
    dfl_pht_fit_free(&f);

    marked_fit(pts, 4, 1.0, 4, 1, &f);
    const size_t c4[5] = {1, 4, 7, 10, 19}, r4[5] = {1, 1, 1, 3, 0};
    expect_records(&f, 5, c4, r4);
    /* E and N were split into level-2 cells: the only level-1 leaf left is
     * [1/2, 1]^2 */
    for (size_t i = 0; i < dfl_pht_spline_ncells(f.spline); i++) {
        int level;
        double lo[2], hi[2];
        dfl_pht_spline_cell(f.spline, i, lo, hi, &level);
        if (level == 1) cr_expect(lo[0] == 0.5 && lo[1] == 0.5, "leaf at (%g, %g)", lo[0], lo[1]);
    }
    dfl_pht_fit_free(&f);

    marked_fit(pts, 4, 1.0, 4, 0, &f);
    const size_t c0[5] = {1, 4, 7, 10, 13}, r0[5] = {1, 1, 1, 1, 0};
    expect_records(&f, 5, c0, r0);
    dfl_pht_fit_free(&f);
}

/* A NaN exact distance at an estimator point (fit.c: "a NaN sticks")
 * makes its cell's estimate NaN, whatever the other points give, and the
 * level's max_err NaN whatever the other cells give: a NaN estimate is not
 * <= eps, so the cell is not converged (at max_level 0 it is capped).  The
 * one-cell mesh with the grid estimator at 4 samples has the points (1/4 or
 * 3/4, 1/4 or 3/4); the second, (3/4, 1/4), is NaN and the two after it
 * exact (error 0), so a maximum that a later finite point could replace
 * would end at 0.  Likewise the uniform level-1 fit at one sample (the 4
 * cell centres) with the NaN at the first leaf's centre. */
Test(pht_fit, a_nan_estimate_propagates_to_the_maximum)
{
    static marked M;
    const double pts[1][2] = {{0.75, 0.25}};
    dfl_shape s;
    marked_init(&M, 1, pts, NAN, &s);
    dfl_pht_fit_opts o;
    dfl_pht_fit_opts_default(2, &o);
    o.estimator = DFL_PHT_EST_GRID;
    o.samples = 4;
    o.max_level = 0;
    dfl_pht_fit f;
    fit(&s, &o, &f);
    cr_assert_eq(f.nlevels, 1);
    cr_expect(isnan(f.cell_err[0]), "cell error %g", f.cell_err[0]);
    cr_expect(isnan(f.levels[0].max_err), "max_err %g", f.levels[0].max_err);
    cr_expect_eq(f.converged, 0);
    cr_expect_eq(f.capped, 1);
    dfl_pht_fit_free(&f);
    dfl_shape_free(&M.plane);
    /* the same point finite but off by 1: the estimate is exactly 1 */
    marked_init(&M, 1, pts, 1.0, &s);
    fit(&s, &o, &f);
    cr_expect_eq(f.cell_err[0], 1.0);
    cr_expect_eq(f.levels[0].max_err, 1.0);
    dfl_pht_fit_free(&f);
    dfl_shape_free(&M.plane);
    /* over leaves: the NaN cell first, three exact cells after it */
    const double first[1][2] = {{0.25, 0.25}};
    marked_init(&M, 1, first, NAN, &s);
    o.samples = 1;
    dfl_pht_source *src;
    dfl_err err;
    cr_assert_eq(dfl_pht_source_new(&s, &src, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_pht_fit_uniform(src, &o, 1, &f, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(f.levels[0].cells, 4);
    double lo[2], hi[2];
    dfl_pht_spline_cell(f.spline, 0, lo, hi, NULL);
    cr_assert(lo[0] == 0 && lo[1] == 0, "the first leaf is not the low corner's");
    cr_expect(isnan(f.cell_err[0]) && f.cell_err[3] == 0.0);
    cr_expect(isnan(f.levels[0].max_err), "max_err %g", f.levels[0].max_err);
    cr_expect_eq(f.capped, 1);
    dfl_pht_fit_free(&f);
    dfl_pht_source_free(src);
    dfl_shape_free(&M.plane);
}

/* A circle whose batch evaluation without gradient (the estimator's exact
 * distances; Hermite data always ask for the gradient) counts its points. */
typedef struct counted {
    dfl_shape circle;
    size_t n;
} counted;

static void counted_eval(const void *impl, size_t m, const double *pts, double *val, double *grad)
{
    counted *C = (counted *)impl;
    C->circle.ops->eval(C->circle.impl, m, pts, val, grad);
    if (!grad) {
#pragma omp atomic
        C->n += m;
    }
}

static dfl_status counted_jet(const void *impl, const double *x, const double *dir, int K,
                              dfl_jet *out, dfl_err *err)
{
    const counted *C = impl;
    return C->circle.ops->jet(C->circle.impl, x, dir, K, out, err);
}

static const dfl_shape_ops counted_ops = {"counted_circle", counted_eval, counted_jet, NULL, NULL};

/* Exact distances are computed once per point a pass needs: on the uniform
 * n x n grid (one pass) every cell has 16 random points, its centre and 4
 * face centres, and each of the 2 n (n - 1) interior edges' centres is
 * shared by the two cells beside it, so n^2 21 - 2 n (n - 1) evaluations. */
Test(pht_fit, shared_face_centres_are_evaluated_once)
{
    counted C = {circle(), 0};
    dfl_shape s = {.dim = 2, .ops = &counted_ops, .impl = &C};
    dfl_pht_source *src;
    cr_assert_eq(dfl_pht_source_new(&s, &src, NULL), DFL_OK);
    dfl_pht_fit_opts o;
    dfl_pht_fit_opts_default(2, &o);
    dfl_pht_fit f;
    for (int L = 1; L <= 4; L++) {
        C.n = 0;
        cr_assert_eq(dfl_pht_fit_uniform(src, &o, L, &f, NULL), DFL_OK);
        const size_t n = (size_t)1 << L;
        cr_expect_eq(C.n, n * n * 21 - 2 * n * (n - 1), "level %d: %zu evaluations", L, C.n);
        dfl_pht_fit_free(&f);
    }
    dfl_pht_source_free(src);
    dfl_shape_free(&C.circle);
}

/* A cell re-estimated because its polynomial changed (a neighbour's
 * refinement turned a hanging corner into a base vertex) reuses the exact
 * values at its points: every cell ever created (the root and 4 children
 * per split, cross rule) evaluates its 16 points once, no more (peaks off:
 * no shared points).  The circle at eps 1e-5 re-estimates such cells. */
Test(pht_fit, re_estimated_cells_reuse_their_exact_values)
{
    counted C = {circle(), 0};
    dfl_shape s = {.dim = 2, .ops = &counted_ops, .impl = &C};
    dfl_pht_fit_opts o;
    dfl_pht_fit_opts_default(2, &o);
    o.eps = 1e-5;
    o.max_level = 12;
    o.peaks = 0;
    dfl_pht_fit f;
    fit(&s, &o, &f);
    size_t created = 1;
    for (int k = 0; k < f.nlevels; k++) created += 4 * f.levels[k].refined;
    cr_expect_eq(C.n, created * 16, "%zu evaluations for %zu cells", C.n, created);
    dfl_pht_fit_free(&f);
    dfl_shape_free(&C.circle);
}
