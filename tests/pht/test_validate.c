/* Validation (pht/validate.c): the medial band of a circle is the disc of
 * radius w around its centre (its medial axis is the centre, and there the
 * normal-line distance is the Euclidean one); the exact field validates to
 * zero; fitted circle and sphere meet eps at 10^4 random points off the
 * medial axis; the field adapter and its jets.  The per-cell protocol: its
 * maximum is within 10 % of an independent dense probe of the same fit
 * (circles whose centre is off the cell lattice), it partitions its
 * points into band and off-band, finds near-medial points only where there
 * is a medial axis, and does not depend on the thread count. */
#include <criterion/criterion.h>
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "field/exact.h"
#include "geom/shape.h"
#include "pht/fit.h"
#include "pht/pht_field.h"
#include "pht/validate.h"

Test(pht_validate, circle_band_is_the_disc_around_the_centre)
{
    dfl_shape s;
    const double c[2] = {0.5, 0.5};
    cr_assert_eq(dfl_shape_circle(c, 0.3, &s, NULL), DFL_OK);
    enum { N = 4000 };
    double *pts = malloc(2 * N * sizeof *pts);
    unsigned char near[N];
    uint64_t seed = 4;
    for (int i = 0; i < 2 * N; i++) pts[i] = dfl_rng_splitmix(&seed, 0, 1);
    const double w = 0.1;
    cr_assert_eq(dfl_pht_medial_band(&s, N, pts, w, near, NULL), DFL_OK);
    int inside = 0;
    for (int i = 0; i < N; i++) {
        double r = hypot(pts[2 * i] - c[0], pts[2 * i + 1] - c[1]);
        if (fabs(r - w) < 1e-6) continue;
        cr_assert_eq(near[i], r < w, "r = %g", r);
        inside += near[i];
    }
    cr_assert(inside > 50);
    free(pts);
    dfl_shape_free(&s);
}

Test(pht_validate, exact_field_has_zero_error)
{
    dfl_shape s, s2;
    const double c[2] = {0.5, 0.5};
    cr_assert_eq(dfl_shape_circle(c, 0.3, &s, NULL), DFL_OK);
    cr_assert_eq(dfl_shape_circle(c, 0.3, &s2, NULL), DFL_OK);
    dfl_field f;
    cr_assert_eq(dfl_field_exact_new(&s2, &f, NULL), DFL_OK);
    dfl_pht_val_opts o = {{0, 0, 0}, {1, 1, 0}, 33, 0.05};
    dfl_pht_val v;
    cr_assert_eq(dfl_pht_validate_grid(&f, &s, &o, &v, NULL), DFL_OK);
    cr_assert_eq(v.all.n, 33 * 33 + 32 * 32);
    cr_assert_eq(v.all.max, 0.0);
    cr_assert_eq(v.off.n + v.band, v.all.n);
    cr_assert(v.band > 0);
    o.n = 1;
    cr_assert_eq(dfl_pht_validate_grid(&f, &s, &o, &v, NULL), DFL_E_INPUT);
    dfl_field_destroy(&f);
    dfl_shape_free(&s);
}

/* Fits s at eps and checks eps at 10^4 random points of the box off the
 * medial band of width w; returns the field (caller destroys). */
static void fit_meets_eps(const dfl_shape *s, double eps, int max_level, double w)
{
    int dim = s->dim;
    dfl_pht_source *src;
    cr_assert_eq(dfl_pht_source_new(s, &src, NULL), DFL_OK);
    dfl_pht_fit_opts o;
    dfl_pht_fit_opts_default(dim, &o);
    o.eps = eps;
    o.max_level = max_level;
    dfl_pht_fit fit;
    dfl_err err;
    cr_assert_eq(dfl_pht_fit_run(src, &o, &fit, &err), DFL_OK, "%s", err.msg);
    dfl_field f;
    cr_assert_eq(dfl_pht_field_new(&fit.spline, &f, NULL), DFL_OK);
    cr_assert_null(fit.spline);
    cr_assert_not_null(dfl_pht_field_spline(&f));
    enum { N = 10000 };
    double *pts = malloc(3 * N * sizeof *pts);
    uint64_t seed = 12345;
    for (int i = 0; i < dim * N; i++) pts[i] = dfl_rng_splitmix(&seed, 0, 1);
    dfl_pht_val v;
    cr_assert_eq(dfl_pht_validate_points(&f, s, N, pts, w, &v, NULL), DFL_OK);
    cr_assert_eq(v.all.n, N);
    cr_assert(v.off.n > N / 2);
    cr_log_info("%s: off-band max %.3g (all %.3g, band %zu)", s->ops->kind, v.off.max, v.all.max, v.band);
    cr_assert(v.off.max <= eps, "%s: off-band max %.3g > eps %.3g (all: %.3g)", s->ops->kind,
              v.off.max, eps, v.all.max);
    free(pts);
    dfl_field_destroy(&f);
    dfl_pht_fit_free(&fit);
    dfl_pht_source_free(src);
}

Test(pht_validate, fitted_circle_meets_eps_off_the_medial_axis)
{
    dfl_shape s;
    const double c[2] = {0.5, 0.5};
    cr_assert_eq(dfl_shape_circle(c, 0.3, &s, NULL), DFL_OK);
    fit_meets_eps(&s, 1e-5, 20, 0.05);
    dfl_shape_free(&s);
}

Test(pht_validate, fitted_sphere_meets_eps_off_the_medial_axis)
{
    dfl_shape s;
    const double c[3] = {0.5, 0.5, 0.5};
    cr_assert_eq(dfl_shape_sphere(c, 0.3, &s, NULL), DFL_OK);
    fit_meets_eps(&s, 1e-3, 12, 0.1);
    dfl_shape_free(&s);
}

/* Fit of s at eps (max_level ml); the caller frees fit and src. */
static void small_fit(const dfl_shape *s, double eps, int ml, dfl_pht_source **src,
                      dfl_pht_fit *fit)
{
    cr_assert_eq(dfl_pht_source_new(s, src, NULL), DFL_OK);
    dfl_pht_fit_opts o;
    dfl_pht_fit_opts_default(s->dim, &o);
    o.eps = eps;
    o.max_level = ml;
    dfl_err err;
    cr_assert_eq(dfl_pht_fit_run(*src, &o, fit, &err), DFL_OK, "%s", err.msg);
}

/* Brute force: max |f - d| over the q^2 nodes of every leaf cell of a 2D
 * spline (cell edges included), each cell's own polynomial. */
static double dense_probe(const dfl_pht_spline *sp, const dfl_shape *s, int q)
{
    const size_t nc = dfl_pht_spline_ncells(sp);
    double *pts = malloc(2 * (size_t)q * q * sizeof *pts), *f = malloc((size_t)q * q * sizeof *f);
    double *d = malloc((size_t)q * q * sizeof *d), best = 0.0;
    for (size_t i = 0; i < nc; i++) {
        double lo[2], hi[2];
        dfl_pht_spline_cell(sp, i, lo, hi, NULL);
        for (int a = 0; a < q; a++)
            for (int b = 0; b < q; b++) {
                pts[2 * (a * q + b)] = lo[0] + (hi[0] - lo[0]) * b / (q - 1);
                pts[2 * (a * q + b) + 1] = lo[1] + (hi[1] - lo[1]) * a / (q - 1);
            }
        dfl_pht_eval_cell(sp, i, (size_t)q * q, pts, f, NULL, NULL);
        dfl_shape_eval(s, (size_t)q * q, pts, d, NULL);
        for (int k = 0; k < q * q; k++) best = fmax(best, fabs(f[k] - d[k]));
    }
    free(pts), free(f), free(d);
    return best;
}

static void cells_match_probe(const dfl_shape *s, double eps, int ml)
{
    dfl_pht_source *src;
    dfl_pht_fit fit;
    small_fit(s, eps, ml, &src, &fit);
    dfl_pht_cellval_opts o;
    dfl_pht_cellval_opts_default(2, &o);
    o.band = 0.02;
    o.eps = eps;
    dfl_pht_cellval v;
    cr_assert_eq(dfl_pht_validate_cells(fit.spline, s, &o, &v, NULL), DFL_OK);
    const double probe = dense_probe(fit.spline, s, 129);
    cr_log_info("%s: cells %zu, cell protocol max %.4g (medial %.4g, %zu points), probe %.4g",
                s->ops->kind, dfl_pht_spline_ncells(fit.spline), v.max, v.medial_max, v.medial,
                probe);
    cr_assert(probe > eps, "the case must have an error above eps (probe %g)", probe);
    cr_assert(v.max >= 0.9 * probe && v.max <= 1.1 * probe, "%s: max %.4g vs dense probe %.4g",
              s->ops->kind, v.max, probe);
    cr_assert_eq(v.band + v.off, v.n);
    cr_assert(v.medial > 0 && v.medial_cells > 0);
    cr_assert(v.above > 0 && v.above < v.n);
    cr_assert(v.medial_max <= v.max && v.band_max <= v.max && v.off_max <= v.max);
    cr_assert(v.max == fmax(v.band_max, v.off_max));
    dfl_pht_fit_free(&fit);
    dfl_pht_source_free(src);
}

Test(pht_validate, cell_protocol_max_is_within_10_percent_of_a_dense_probe_circle)
{
    dfl_shape s;
    const double c[2] = {0.43, 0.521};
    cr_assert_eq(dfl_shape_circle(c, 0.3, &s, NULL), DFL_OK);
    cells_match_probe(&s, 1e-4, 6);
    dfl_shape_free(&s);
}

/* validate.h: a maximum over an empty set is NaN, not 0.  Band width 0
 * puts every point off the band: band 0, band_max NaN, off_max = max.  A
 * circle of radius 0.3 centred in the box has its medial point (the centre)
 * inside, so the medial set is not empty and its max is a number. */
Test(pht_validate, the_max_over_an_empty_set_is_nan)
{
    dfl_shape s;
    const double c[2] = {0.43, 0.521};
    cr_assert_eq(dfl_shape_circle(c, 0.3, &s, NULL), DFL_OK);
    dfl_pht_source *src;
    dfl_pht_fit fit;
    small_fit(&s, 1e-3, 4, &src, &fit);
    dfl_pht_cellval_opts o;
    dfl_pht_cellval_opts_default(2, &o);
    o.band = 0.0;
    dfl_pht_cellval v;
    cr_assert_eq(dfl_pht_validate_cells(fit.spline, &s, &o, &v, NULL), DFL_OK);
    cr_assert_eq(v.band, 0);
    cr_assert(isnan(v.band_max), "band_max %g over no point", v.band_max);
    cr_assert_eq(v.off, v.n);
    cr_assert(v.n > 0 && v.off_max == v.max && isfinite(v.max));
    cr_assert(v.medial > 0 && isfinite(v.medial_max));
    dfl_pht_fit_free(&fit);
    dfl_pht_source_free(src);
    dfl_shape_free(&s);
}

Test(pht_validate, cell_protocol_max_is_within_10_percent_of_a_dense_probe_deeper)
{
    dfl_shape s;
    const double c[2] = {0.6123, 0.377};
    cr_assert_eq(dfl_shape_circle(c, 0.27, &s, NULL), DFL_OK);
    cells_match_probe(&s, 1e-5, 8);
    dfl_shape_free(&s);
}

Test(pht_validate, cell_protocol_no_medial_points_without_a_medial_axis)
{
    dfl_shape s;
    const double c[2] = {-0.4, 0.5};
    cr_assert_eq(dfl_shape_circle(c, 0.1, &s, NULL), DFL_OK);
    dfl_pht_source *src;
    dfl_pht_fit fit;
    small_fit(&s, 1e-5, 8, &src, &fit);
    dfl_pht_cellval_opts o;
    dfl_pht_cellval_opts_default(2, &o);
    o.eps = 1e-5;
    dfl_pht_cellval v;
    cr_assert_eq(dfl_pht_validate_cells(fit.spline, &s, &o, &v, NULL), DFL_OK);
    cr_assert_eq(v.medial, 0);
    cr_assert_eq(v.medial_cells, 0);
    cr_assert_eq(v.band, 0); /* band 0: every point is off the band */
    cr_assert_eq(v.off, v.n);
    const size_t nc = dfl_pht_spline_ncells(fit.spline);
    cr_assert_eq(v.n, nc * (9 + (size_t)o.random));
    o.dense = 1;
    cr_assert_eq(dfl_pht_validate_cells(fit.spline, &s, &o, &v, NULL), DFL_E_INPUT);
    dfl_pht_fit_free(&fit);
    dfl_pht_source_free(src);
    dfl_shape_free(&s);
}

Test(pht_validate, cell_protocol_is_thread_count_independent)
{
    dfl_shape s;
    const double c[2] = {0.43, 0.521};
    cr_assert_eq(dfl_shape_circle(c, 0.3, &s, NULL), DFL_OK);
    dfl_pht_source *src;
    dfl_pht_fit fit;
    small_fit(&s, 1e-3, 6, &src, &fit);
    dfl_pht_cellval_opts o;
    dfl_pht_cellval_opts_default(2, &o);
    o.band = 0.05;
    o.eps = 1e-3;
    dfl_pht_cellval v1, v2;
    omp_set_num_threads(1);
    cr_assert_eq(dfl_pht_validate_cells(fit.spline, &s, &o, &v1, NULL), DFL_OK);
    omp_set_num_threads(2);
    cr_assert_eq(dfl_pht_validate_cells(fit.spline, &s, &o, &v2, NULL), DFL_OK);
    cr_assert(memcmp(&v1, &v2, sizeof v1) == 0);
    dfl_pht_fit_free(&fit);
    dfl_pht_source_free(src);
    dfl_shape_free(&s);
}

/* A NaN is an error of +inf, counted, never dropped: one cell's polynomial
 * poisoned with a NaN makes exactly its own protocol points non-finite in
 * the per-cell protocol (9 + random points of a non-medial cell), and in the
 * grid protocol as many points as a brute-force count of non-finite field
 * values finds; every maximum they enter is +inf, gradients included. */
Test(pht_validate, nonfinite_values_are_counted_and_infinite)
{
    dfl_shape s;
    const double c[2] = {-0.4, 0.5};
    cr_assert_eq(dfl_shape_circle(c, 0.1, &s, NULL), DFL_OK);
    dfl_pht_source *src;
    dfl_pht_fit fit;
    small_fit(&s, 1e-3, 5, &src, &fit);
    const size_t nc = dfl_pht_spline_ncells(fit.spline);
    dfl_pht_cellval_opts o;
    dfl_pht_cellval_opts_default(2, &o);
    dfl_pht_cellval v;
    cr_assert_eq(dfl_pht_validate_cells(fit.spline, &s, &o, &v, NULL), DFL_OK);
    cr_assert_eq(v.nonfinite, 0);
    cr_assert(isfinite(v.max) && isfinite(v.gmax));
    /* poison the last cell (the test reaches into the borrowed storage) */
    double *coef = (double *)dfl_pht_spline_cell(fit.spline, nc - 1, NULL, NULL, NULL);
    for (int k = 0; k < DFL_PHT_NCOEF(2); k++) coef[k] = NAN; /* value and gradient */
    cr_assert_eq(dfl_pht_validate_cells(fit.spline, &s, &o, &v, NULL), DFL_OK);
    cr_expect_eq(v.nonfinite, 9 + (size_t)o.random, "the poisoned cell's own points");
    cr_expect(isinf(v.max) && v.max > 0 && isinf(v.off_max) && isinf(v.gmax));
    /* grid protocol through the field adapter */
    dfl_field f;
    dfl_pht_spline *sp = fit.spline;
    cr_assert_eq(dfl_pht_field_new(&fit.spline, &f, NULL), DFL_OK);
    dfl_pht_val_opts go = {{0, 0, 0}, {1, 1, 0}, 41, 0.0};
    dfl_pht_val gv;
    cr_assert_eq(dfl_pht_validate_grid(&f, &s, &go, &gv, NULL), DFL_OK);
    size_t bad = 0;
    double x[2], g[2];
    for (int pass = 0; pass < 2; pass++) { /* nodes, then cell midpoints */
        const int n = pass ? 40 : 41;
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                x[0] = (i + 0.5 * pass) / 40.0;
                x[1] = (j + 0.5 * pass) / 40.0;
                const double val = dfl_field_eval1(&f, x, g);
                bad += !isfinite(val) || !isfinite(g[0]) || !isfinite(g[1]);
            }
    }
    (void)sp;
    cr_assert(bad > 0, "the poisoned cell holds grid points");
    cr_expect_eq(gv.nonfinite, bad);
    cr_expect(isinf(gv.all.max) && isinf(gv.all.gmax) && isinf(gv.all.mean), "max %g gmax %g mean %g",
              gv.all.max, gv.all.gmax, gv.all.mean);
    dfl_field_destroy(&f);
    dfl_pht_fit_free(&fit);
    dfl_pht_source_free(src);
    dfl_shape_free(&s);
}
