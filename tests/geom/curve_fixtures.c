/* Curves shared by the footpoint tests (see curve_fixtures.h). */
#include "geom/curve_fixtures.h"

#include <criterion/criterion.h>
#include <math.h>

/* the 'S' of configs/shapes/S.ini (open, clamped cubic) */
static const double S_cp[] = {0.85, 0.85, 0.6, 1.0, 0.1, 0.95, 0.1, 0.6, 0.5,
                              0.5,  0.9,  0.4, 0.9, 0.05, 0.4, 0.0, 0.15, 0.15};

/* a closed periodic cubic symmetric about both axes: points on the x axis
 * inside it are on the medial axis */
static const double blob_cp[] = {2.0, 0.0,  1.6, 0.9,  0.0, 1.0,  -1.6, 0.9,
                                 -2.0, 0.0, -1.6, -0.9, 0.0, -1.0, 1.6, -0.9};

void cf_make_S(dfl_bspline *c)
{
    cr_assert_eq(dfl_bspline_init(2, 4, 9, S_cp, NULL, 0, c, NULL), DFL_OK);
}

void cf_make_blob(dfl_bspline *c)
{
    cr_assert_eq(dfl_bspline_init_periodic(2, 4, 8, blob_cp, NULL, 0, c, NULL), DFL_OK);
}

dfl_curve_sdf *cf_blob_sdf(dfl_bspline *c)
{
    cf_make_blob(c);
    dfl_curve_sdf *S = NULL;
    dfl_err err;
    cr_assert_eq(dfl_curve_sdf_new(c, NULL, &S, &err), DFL_OK, "%s", err.msg);
    return S;
}

void cf_make_space(dfl_bspline *c)
{
    double cp[7 * 3];
    for (int i = 0; i < 7; i++) {
        cp[3 * i] = 0.5 + 0.4 * cos(1.3 * i);
        cp[3 * i + 1] = 0.5 + 0.4 * sin(1.3 * i);
        cp[3 * i + 2] = i / 6.0;
    }
    cr_assert_eq(dfl_bspline_init(3, 4, 7, cp, NULL, 0, c, NULL), DFL_OK);
}

/* dense sampling (1e5) + golden-section refinement of the best sample */
double cf_brute_curve(const dfl_bspline *c, const double *x, double *tbest)
{
    const int N = 100000, dim = c->dim;
    double best = INFINITY;
    int kb = 0;
    for (int k = 0; k <= N; k++) {
        double t = c->t0 + (c->t1 - c->t0) * k / N, p[3], d = 0;
        dfl_bspline_eval(c, t, 0, p);
        for (int j = 0; j < dim; j++) d += (p[j] - x[j]) * (p[j] - x[j]);
        if (d < best) {
            best = d;
            kb = k;
        }
    }
    double lo = c->t0 + (c->t1 - c->t0) * (kb - 1) / N, hi = c->t0 + (c->t1 - c->t0) * (kb + 1) / N;
    if (!c->closed) {
        lo = fmax(lo, c->t0);
        hi = fmin(hi, c->t1);
    }
    const double gr = 0.5 * (sqrt(5.0) - 1.0);
    for (int it = 0; it < 200; it++) {
        double a = hi - gr * (hi - lo), b = lo + gr * (hi - lo), pa[3], pb[3], da = 0, db = 0;
        dfl_bspline_eval(c, a, 0, pa);
        dfl_bspline_eval(c, b, 0, pb);
        for (int j = 0; j < dim; j++) {
            da += (pa[j] - x[j]) * (pa[j] - x[j]);
            db += (pb[j] - x[j]) * (pb[j] - x[j]);
        }
        if (da < db) hi = b;
        else lo = a;
        double m = fmin(da, db);
        if (m < best) best = m;
    }
    if (tbest) *tbest = 0.5 * (lo + hi);
    return sqrt(best);
}

