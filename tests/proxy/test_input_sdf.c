/* SDF proxy input: footpoints x - f grad f and analytic curvatures against
 * closed forms (sphere: kappa = +1/r both; cylinder: 0 and 1/r; plane: 0;
 * torus: 1/r across the tube and cos(th) / (R + r cos(th)) along it, th the
 * tube angle of the footpoint, outward normal). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

#include "core/rng.h"
#include "core/vec.h"
#include "geom/mesh.h"
#include "geom/mesh_fixtures.h"
#include "proxy/input_sdf.h"

static dfl_proxy_input make(dfl_shape *s, dfl_proxy_curv_method cm)
{
    dfl_proxy_input in;
    dfl_err err;
    dfl_curvfit_opts fit = {5, 0.01, 0, 0};
    cr_assert_eq(dfl_proxy_input_sdf(s, cm, &fit, &in, &err), DFL_OK, "%s", err.msg);
    cr_assert_null(s->impl);
    return in;
}

static void random_points(uint64_t seed, size_t m, double lo, double hi, double *x)
{
    for (size_t i = 0; i < 3 * m; i++) x[i] = dfl_rng_splitmix(&seed, lo, hi);
}

Test(input_sdf, sphere_footpoints_and_curvature)
{
    const double c[3] = {0.1, -0.05, 0.02}, r = 0.5;
    dfl_shape s;
    cr_assert_eq(dfl_shape_sphere(c, r, &s, NULL), DFL_OK);
    dfl_proxy_input in = make(&s, DFL_PROXY_CURV_ANALYTIC);
    enum { M = 200 };
    double x[3 * M];
    dfl_surfpoint o[M];
    random_points(7, M, -1, 1, x);
    cr_assert_eq(dfl_proxy_input_query(&in, M, x, 1, o, NULL), DFL_OK);
    cr_assert_eq(in.has_inside, 1);
    for (int i = 0; i < M; i++) {
        double q[3] = {x[3 * i] - c[0], x[3 * i + 1] - c[1], x[3 * i + 2] - c[2]};
        double l = dfl_vec3_norm(q);
        cr_assert(o[i].certified);
        cr_assert(fabs(o[i].d - (l - r)) < 1e-14);
        for (int j = 0; j < 3; j++) {
            cr_assert(fabs(o[i].p[j] - (c[j] + r * q[j] / l)) < 1e-14);
            cr_assert(fabs(o[i].n[j] - q[j] / l) < 1e-14);
            cr_assert(fabs(x[3 * i + j] - (o[i].p[j] + o[i].d * o[i].n[j])) < 1e-14);
        }
        cr_assert(fabs(o[i].curv.k1 - 1 / r) < 1e-9 && fabs(o[i].curv.k2 - 1 / r) < 1e-9,
                  "k = %g %g", o[i].curv.k1, o[i].curv.k2);
    }
    /* order 1: curvature skipped, NAN */
    cr_assert_eq(dfl_proxy_input_query(&in, 1, x, 0, o, NULL), DFL_OK);
    cr_assert(isnan(o[0].curv.k1));
    dfl_proxy_input_free(&in);
    dfl_proxy_input_free(&in);
}

Test(input_sdf, torus_curvature_closed_form)
{
    const double c[3] = {0, 0, 0}, ax[3] = {0, 0, 1}, R = 0.6, r = 0.25;
    dfl_shape s;
    cr_assert_eq(dfl_shape_torus(c, ax, R, r, &s, NULL), DFL_OK);
    dfl_proxy_input in = make(&s, DFL_PROXY_CURV_ANALYTIC);
    uint64_t seed = 11;
    for (int i = 0; i < 200; i++) {
        /* x = centre-circle point + (r + t) (cos th e_rho + sin th e_z) */
        double ph = dfl_rng_splitmix(&seed, 0, 2 * DFL_PI);
        double th = dfl_rng_splitmix(&seed, 0, 2 * DFL_PI);
        double t = dfl_rng_splitmix(&seed, -0.2, 0.3);
        double rho = R + (r + t) * cos(th);
        double x[3] = {rho * cos(ph), rho * sin(ph), (r + t) * sin(th)};
        dfl_surfpoint o;
        cr_assert_eq(dfl_proxy_input_query(&in, 1, x, 1, &o, NULL), DFL_OK);
        cr_assert(fabs(o.d - t) < 1e-13);
        double kt = 1 / r, kr = cos(th) / (R + r * cos(th));
        double lo = fmin(kt, kr), hi = fmax(kt, kr);
        cr_assert(fabs(o.curv.k1 - lo) < 1e-9 && fabs(o.curv.k2 - hi) < 1e-9,
                  "th %g: k = %g %g, want %g %g", th, o.curv.k1, o.curv.k2, lo, hi);
        /* the tube direction (kappa = 1/r) lies in the meridian plane */
        const double *et = kt < kr ? o.curv.e1 : o.curv.e2;
        double eph[3] = {-sin(ph), cos(ph), 0};
        cr_assert(fabs(dfl_vec3_dot(et, eph)) < 1e-8);
    }
    dfl_proxy_input_free(&in);
}

Test(input_sdf, cylinder_and_plane)
{
    const double p[3] = {0.1, 0.2, 0}, ax[3] = {1, 1, 0}, r = 0.3, nrm[3] = {0, 0, 2};
    dfl_shape s;
    cr_assert_eq(dfl_shape_cylinder(p, ax, r, &s, NULL), DFL_OK);
    dfl_proxy_input in = make(&s, DFL_PROXY_CURV_ANALYTIC);
    double x[3 * 50];
    dfl_surfpoint o[50];
    random_points(3, 50, -1, 1, x);
    cr_assert_eq(dfl_proxy_input_query(&in, 50, x, 1, o, NULL), DFL_OK);
    for (int i = 0; i < 50; i++) {
        cr_assert(fabs(o[i].curv.k1) < 1e-9 && fabs(o[i].curv.k2 - 1 / r) < 1e-9);
        /* zero-curvature direction = the axis */
        cr_assert(fabs(fabs(o[i].curv.e1[0] + o[i].curv.e1[1]) / sqrt(2) - 1) < 1e-9);
    }
    dfl_proxy_input_free(&in);
    cr_assert_eq(dfl_shape_plane(3, p, nrm, &s, NULL), DFL_OK);
    in = make(&s, DFL_PROXY_CURV_ANALYTIC);
    cr_assert_eq(dfl_proxy_input_query(&in, 50, x, 1, o, NULL), DFL_OK);
    for (int i = 0; i < 50; i++) {
        cr_assert(fabs(o[i].curv.k1) < 1e-12 && fabs(o[i].curv.k2) < 1e-12);
        cr_assert(fabs(o[i].p[2]) < 1e-15 && fabs(o[i].d - x[3 * i + 2]) < 1e-15);
    }
    dfl_proxy_input_free(&in);
}

Test(input_sdf, rejects_2d_shapes)
{
    const double c[2] = {0, 0};
    dfl_shape s;
    cr_assert_eq(dfl_shape_circle(c, 1, &s, NULL), DFL_OK);
    dfl_proxy_input in = {0};
    dfl_err err;
    cr_assert_eq(dfl_proxy_input_sdf(&s, DFL_PROXY_CURV_ANALYTIC, NULL, &in, &err), DFL_E_INPUT);
    cr_assert_null(s.impl);
    cr_assert_eq(dfl_proxy_input_query(&in, 0, NULL, 0, NULL, &err), DFL_E_INPUT);
}

/* A field that is not an SDF: k (|x - c| - r), |grad| = k.  The header's
 * rule: certified exactly when ||grad f| - 1| <= 1e-6. */
typedef struct scaled_sphere {
    double c[3], r, k;
} scaled_sphere;

static void scaled_eval(const void *impl, size_t m, const double *pts, double *val, double *grad)
{
    const scaled_sphere *s = impl;
    for (size_t i = 0; i < m; i++) {
        double v[3], l = 0;
        for (int j = 0; j < 3; j++) v[j] = pts[3 * i + j] - s->c[j], l += v[j] * v[j];
        l = sqrt(l);
        val[i] = s->k * (l - s->r);
        if (grad)
            for (int j = 0; j < 3; j++) grad[3 * i + j] = s->k * v[j] / l;
    }
}

static void scaled_free(void *impl) { free(impl); }

static const dfl_shape_ops scaled_ops = {"scaled_sphere", scaled_eval, NULL, scaled_free, NULL};

Test(input_sdf, non_sdf_is_not_certified)
{
    static const double ks[] = {1.0, 1 + 5e-7, 1 - 5e-7, 1 + 2e-6, 1 - 2e-6, 1 + 1e-3, 0.5, 2};
    static const int want[] = {1, 1, 1, 0, 0, 0, 0, 0};
    for (int q = 0; q < 8; q++) {
        scaled_sphere *ss = malloc(sizeof *ss);
        cr_assert_not_null(ss);
        *ss = (scaled_sphere){{0.1, -0.05, 0.02}, 0.5, ks[q]};
        dfl_shape s = {3, &scaled_ops, ss};
        dfl_proxy_input in = make(&s, DFL_PROXY_CURV_ANALYTIC);
        enum { M = 50 };
        double x[3 * M];
        dfl_surfpoint o[M];
        random_points(11, M, -1, 1, x);
        cr_assert_eq(dfl_proxy_input_query(&in, M, x, 0, o, NULL), DFL_OK);
        int n = 0;
        for (int i = 0; i < M; i++) n += o[i].certified;
        cr_expect_eq(n, want[q] ? M : 0, "|grad f| = %.9g: %d of %d certified", ks[q], n, M);
        dfl_proxy_input_free(&in);
    }
}

/* input_sdf.h: a failed curvature fit.  A short square rod of the box mesh
 * (|y|, |z| <= 0.0075) seen from x = (0.6, 0, 0): footpoint (0.5, 0, 0),
 * normal +x; on a 7 x 7 stencil of spacing 0.005 only 9 nodes meet the
 * rod, fewer than the fit's 10 (curvfit.h).  Without the fallback the
 * curvatures are NaN; with plane_fallback they are 0 in an orthonormal
 * tangent frame (e1 x e2 = n); certified = 0 both ways; the footpoint and
 * normal are the SDF's either way. */
Test(input_sdf, a_failed_fit_is_nan_or_with_the_fallback_the_tangent_plane)
{
    for (int fb = 0; fb <= 1; fb++) {
        dfl_trimesh m;
        mf_cube(&m);
        const double half[3] = {0.5, 0.0075, 0.0075};
        for (size_t i = 0; i < 3 * m.nverts; i++) m.verts[i] *= half[i % 3];
        dfl_shape s;
        cr_assert_eq(dfl_shape_mesh(&m, DFL_MESH_SIGNED, &s, NULL), DFL_OK);
        dfl_proxy_input in;
        const dfl_curvfit_opts fit = {7, 0.005, fb, 0};
        cr_assert_eq(dfl_proxy_input_sdf(&s, DFL_PROXY_CURV_FIT, &fit, &in, NULL), DFL_OK);
        const double x[3] = {0.6, 0, 0};
        dfl_surfpoint o;
        cr_assert_eq(dfl_proxy_input_query(&in, 1, x, 1, &o, NULL), DFL_OK);
        cr_expect(fabs(o.p[0] - 0.5) < 1e-15 && fabs(o.p[1]) < 1e-15 && fabs(o.p[2]) < 1e-15);
        cr_expect(fabs(o.n[0] - 1) < 1e-15);
        cr_expect_eq(o.certified, 0);
        if (!fb) {
            cr_expect(isnan(o.curv.k1) && isnan(o.curv.k2));
        } else {
            cr_expect(o.curv.k1 == 0 && o.curv.k2 == 0 && o.curv.K == 0 && o.curv.H == 0);
            double c[3];
            dfl_vec3_cross(o.curv.e1, o.curv.e2, c);
            for (int j = 0; j < 3; j++) cr_expect(fabs(c[j] - o.n[j]) < 1e-15, "e1 x e2 = n");
        }
        dfl_proxy_input_free(&in);
    }
}

/* input_sdf.h: focal_clamp.  A sphere of radius 1/2 seen from x inside,
 * at |d| = 0.4999 (just off the centre): p is the closest point only while
 * 1 + k d >= 0, i.e. k <= 1/|d| = 2.0004.  The cubic fit on a wide stencil
 * (5 x 5, spacing 0.05) overestimates the sphere's k = 2 by its quartic
 * term (z = -rho^2 / (2r) - rho^4 / (8 r^3) bends faster than the
 * quadratic): the premise, asserted, is k1, k2 > 1/|d| without the clamp.
 * With it both are exactly -1/d, and K, H follow. */
Test(input_sdf, focal_clamp_keeps_x_before_the_centre_of_curvature)
{
    double k[2][2], dq = 0;
    const double x[3] = {0.9999, 0, 0}, d = -0.4999;
    for (int fc = 0; fc <= 1; fc++) {
        const double c[3] = {1, 0, 0};
        dfl_shape s;
        cr_assert_eq(dfl_shape_sphere(c, 0.5, &s, NULL), DFL_OK);
        dfl_proxy_input in;
        const dfl_curvfit_opts fit = {5, 0.05, 0, fc};
        cr_assert_eq(dfl_proxy_input_sdf(&s, DFL_PROXY_CURV_FIT, &fit, &in, NULL), DFL_OK);
        dfl_surfpoint o;
        cr_assert_eq(dfl_proxy_input_query(&in, 1, x, 1, &o, NULL), DFL_OK);
        cr_assert(fabs(o.d - d) < 1e-12, "d %.17g", o.d);
        dq = o.d;
        k[fc][0] = o.curv.k1;
        k[fc][1] = o.curv.k2;
        if (fc) {
            cr_expect(o.curv.K == o.curv.k1 * o.curv.k2 && o.curv.H == 0.5 * (o.curv.k1 + o.curv.k2));
            cr_expect_eq(o.certified, 1, "the clamp is not a failure");
        }
        dfl_proxy_input_free(&in);
    }
    cr_assert(k[0][0] > -1 / d && k[0][1] > -1 / d, "premise: k %.17g %.17g, 1/|d| %.17g", k[0][0],
              k[0][1], -1 / d);
    cr_expect(k[1][0] == -1 / dq && k[1][1] == -1 / dq, "clamped: %.17g %.17g", k[1][0], k[1][1]);
}
