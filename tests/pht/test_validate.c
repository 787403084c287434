/* Validation (pht/validate.c): the medial band of a circle is the disc of
 * radius w around its centre (its medial axis is the centre, and there the
 * normal-line distance is the Euclidean one); the exact field validates to
 * zero; fitted circle and sphere meet eps at 10^4 random points off the
 * medial axis; the field adapter and its jets. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

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
