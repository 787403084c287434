/* Cubic curvature fit (proxy/curvfit.h).
 * - A cubic graph is reproduced exactly (the fit's space contains it).
 * - On a sphere and at a torus' equators the height function over the
 *   tangent plane is known in closed form and its cubic Taylor part is the
 *   quadratic one (the graphs are even in both tangent coordinates), so the
 *   fit's error is P times the remainder r_k = h(x_k) - T2(x_k) exactly: the
 *   tolerance is the derived bound |dA| <= sum_k |P_0k| |r_k| (likewise B,
 *   C), pushed to the eigenvalues by Weyl's inequality with the Frobenius
 *   norm, plus 1e-10 for the projections' rounding.
 * - On triangle meshes (a box): heights found by bracketing where Newton
 *   gives up (an edge: heights in closed form), nodes whose normal line
 *   misses the surface left out (a thin slab: the plane, or too few). */
#include <criterion/criterion.h>
#include <math.h>

#include "core/vec.h"
#include "geom/mesh.h"
#include "geom/mesh_fixtures.h"
#include "proxy/curvfit.h"

Test(curvfit, reproduces_a_cubic)
{
    dfl_curvfit F;
    cr_assert_eq(dfl_curvfit_init(5, 0.1, &F, NULL), DFL_OK);
    const double c[7] = {0.3, -0.2, 1.1, 0.05, -0.4, 0.7, 0.2};
    double z[DFL_CURVFIT_MAX_G * DFL_CURVFIT_MAX_G], got[7];
    for (int k = 0; k < F.npts; k++) {
        double x = F.xy[2 * k], y = F.xy[2 * k + 1];
        z[k] = c[0] * x * x / 2 + c[1] * x * y + c[2] * y * y / 2 + c[3] * x * x * x +
               c[4] * x * x * y + c[5] * x * y * y + c[6] * y * y * y;
    }
    dfl_curvfit_coeffs(&F, z, got);
    for (int a = 0; a < 7; a++) cr_assert(fabs(got[a] - c[a]) < 1e-10, "coef %d: %g", a, got[a]);
    dfl_err err;
    cr_assert_eq(dfl_curvfit_init(2, 0.1, &F, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_curvfit_init(5, 0, &F, &err), DFL_E_INPUT);
}

/* The derived tolerance for the remainders rem[k]. */
static double tolerance(const dfl_curvfit *F, const double *rem)
{
    double b[3] = {0, 0, 0};
    for (int a = 0; a < 3; a++)
        for (int k = 0; k < F->npts; k++) b[a] += fabs(F->pinv[a][k]) * fabs(rem[k]);
    return sqrt(b[0] * b[0] + 2 * b[1] * b[1] + b[2] * b[2]) + 1e-10;
}

Test(curvfit, sphere_within_the_truncation_bound)
{
    const double c[3] = {0, 0, 0}, r = 0.5;
    dfl_shape s;
    cr_assert_eq(dfl_shape_sphere(c, r, &s, NULL), DFL_OK);
    const int gs[3] = {3, 5, 9};
    const double hs[3] = {0.02, 0.01, 0.004};
    for (int t = 0; t < 3; t++) {
        dfl_curvfit F;
        cr_assert_eq(dfl_curvfit_init(gs[t], hs[t], &F, NULL), DFL_OK);
        double rem[DFL_CURVFIT_MAX_G * DFL_CURVFIT_MAX_G];
        for (int k = 0; k < F.npts; k++) {
            double rho2 = F.xy[2 * k] * F.xy[2 * k] + F.xy[2 * k + 1] * F.xy[2 * k + 1];
            rem[k] = -(r - sqrt(r * r - rho2)) + rho2 / (2 * r);
        }
        double tol = tolerance(&F, rem);
        cr_assert(tol < 1e-2);
        const double n[3] = {0.48, -0.6, 0.64}; /* unit */
        double p[3] = {r * n[0], r * n[1], r * n[2]};
        dfl_curvature cv;
        cr_assert_eq(dfl_curvfit_sdf(&F, &s, p, n, &cv), DFL_OK);
        cr_assert(fabs(cv.k1 - 1 / r) <= tol && fabs(cv.k2 - 1 / r) <= tol,
                  "g %d: %g %g, tol %g", gs[t], cv.k1, cv.k2, tol);
        /* and the error is the aliasing itself, not noise: P rem predicts it */
        double A = 0;
        for (int k = 0; k < F.npts; k++) A += F.pinv[0][k] * rem[k];
        cr_assert(fabs(cv.k2 - (1 / r - A)) < 1e-9, "%g vs %g", cv.k2, 1 / r - A);
    }
    dfl_shape_free(&s);
}

Test(curvfit, torus_equators_within_the_truncation_bound)
{
    const double c[3] = {0, 0, 0}, ax[3] = {0, 0, 1}, R = 0.6, r = 0.25;
    dfl_shape s;
    cr_assert_eq(dfl_shape_torus(c, ax, R, r, &s, NULL), DFL_OK);
    dfl_curvfit F;
    cr_assert_eq(dfl_curvfit_init(5, 0.01, &F, NULL), DFL_OK);
    for (int side = 0; side < 2; side++) {
        /* outer (side 0): p = (R + r, 0, 0), n = +x, kappa = 1/(R+r), 1/r;
         * inner: p = (R - r, 0, 0), n = -x, kappa = -1/(R-r), 1/r */
        double sg = side ? -1.0 : 1.0, x0 = R + sg * r;
        double p[3] = {x0, 0, 0}, n[3] = {sg, 0, 0}, b1[3], b2[3];
        dfl_vec3_tangent_basis(n, b1, b2);
        double ky = sg / (R + sg * r), kz = 1 / r;
        double rem[DFL_CURVFIT_MAX_G * DFL_CURVFIT_MAX_G];
        for (int k = 0; k < F.npts; k++) {
            double y = F.xy[2 * k] * b1[1] + F.xy[2 * k + 1] * b2[1];
            double z = F.xy[2 * k] * b1[2] + F.xy[2 * k + 1] * b2[2];
            double rho = R + sg * sqrt(r * r - z * z), xs = sqrt(rho * rho - y * y);
            double h = sg * (xs - x0);
            rem[k] = h - (-ky * y * y / 2 - kz * z * z / 2);
        }
        double tol = tolerance(&F, rem);
        cr_assert(tol < 2e-2 * kz, "tol %g", tol); /* a bound with content */
        dfl_curvature cv;
        cr_assert_eq(dfl_curvfit_sdf(&F, &s, p, n, &cv), DFL_OK);
        double lo = fmin(ky, kz), hi = fmax(ky, kz);
        cr_assert(fabs(cv.k1 - lo) <= tol && fabs(cv.k2 - hi) <= tol, "side %d: %g %g vs %g %g tol %g",
                  side, cv.k1, cv.k2, lo, hi, tol);
        /* the principal direction of 1/r is the z axis */
        cr_assert(fabs(fabs(cv.e2[2]) - 1) < 1e-6);
    }
    dfl_shape_free(&s);
}

/* ---- triangle meshes (dfl_curvfit_sdf's fallbacks, curvfit.h) ---- */

/* mf_cube scaled per axis by s: the box [-s, s]. */
static void box_shape(const double s[3], dfl_shape *out)
{
    dfl_trimesh m;
    mf_cube(&m);
    for (size_t i = 0; i < 3 * m.nverts; i++) m.verts[i] *= s[i % 3];
    cr_assert_eq(dfl_shape_mesh(&m, DFL_MESH_SIGNED, out, NULL), DFL_OK);
}

/* A footpoint on an edge of the box [-1/2, 1/2]^3 with the bisecting
 * normal n = (1, 1, 0) / sqrt 2: the mesh's gradient at p (distance 0) is
 * 0 / 0, so Newton gives up on that node at once and on nodes it lands on
 * the surface; the bracketing fallback must find every height.  Near the
 * edge the surface is max(x, y) = 1/2, so the node at tangent offset
 * e = u b1 + v b2 has height t = -sqrt 2 max(e_x, e_y) along n (exactly):
 * the curvature is the fit of those heights. */
Test(curvfit, a_mesh_edge_heights_by_bracketing)
{
    const double half[3] = {0.5, 0.5, 0.5}, p[3] = {0.5, 0.5, 0.05};
    const double r2 = sqrt(0.5), n[3] = {r2, r2, 0};
    dfl_shape s;
    box_shape(half, &s);
    dfl_curvfit F;
    cr_assert_eq(dfl_curvfit_init(5, 0.01, &F, NULL), DFL_OK);
    double b1[3], b2[3], z[DFL_CURVFIT_MAX_G * DFL_CURVFIT_MAX_G];
    dfl_vec3_tangent_basis(n, b1, b2);
    for (int k = 0; k < F.npts; k++) {
        const double ex = F.xy[2 * k] * b1[0] + F.xy[2 * k + 1] * b2[0];
        const double ey = F.xy[2 * k] * b1[1] + F.xy[2 * k + 1] * b2[1];
        z[k] = -sqrt(2.0) * fmax(ex, ey);
    }
    dfl_curvature want, got;
    dfl_curvfit_from_heights(&F, z, b1, b2, n, &want);
    cr_assert_eq(dfl_curvfit_sdf(&F, &s, p, n, &got), DFL_OK);
    cr_expect(fabs(got.k1 - want.k1) <= 1e-9 * (1 + fabs(want.k1)), "k1 %.17g, want %.17g", got.k1,
              want.k1);
    cr_expect(fabs(got.k2 - want.k2) <= 1e-9 * (1 + fabs(want.k2)), "k2 %.17g, want %.17g", got.k2,
              want.k2);
    /* a convex fold: the fit bends away from n across the edge */
    cr_expect_gt(want.k2, 1.0);
    dfl_shape_free(&s);
}

/* A thin slab [-1/2, 1/2] x [-hy, hy] x [-1/2, 1/2], footpoint at the
 * centre of its face x = 1/2, n = +x, a 7 x 7 grid of spacing 0.005
 * (offsets 0, +-0.005, +-0.01, +-0.015 along y and z: tangent_basis(+x)
 * spans them).  hy = 0.0125: the normal lines at y offset +-0.015 pass
 * beside the slab (no sign change within the reach), the other 35 nodes
 * meet the face at height 0: the fit of the nodes left is the plane,
 * curvatures 0 (to the heights' rounding).  hy = 0.003: only the 7 nodes at y offset 0 are
 * left, fewer than DFL_CURVFIT_MIN_NODES: DFL_E_NUMERIC, out untouched. */
Test(curvfit, nodes_whose_normal_line_misses_are_left_out)
{
    const double p[3] = {0.5, 0, 0}, n[3] = {1, 0, 0};
    dfl_curvfit F;
    cr_assert_eq(dfl_curvfit_init(7, 0.005, &F, NULL), DFL_OK);
    double b1[3], b2[3];
    dfl_vec3_tangent_basis(n, b1, b2);
    cr_assert(fabs(b1[0]) < 1e-15 && fabs(b2[0]) < 1e-15);
    cr_assert(fabs(fabs(b1[1]) + fabs(b2[1]) - 1) < 1e-15, "the grid's y offsets: 0.005 steps");
    dfl_shape s;
    const double wide[3] = {0.5, 0.0125, 0.5}, thin[3] = {0.5, 0.003, 0.5};
    box_shape(wide, &s);
    dfl_curvature c;
    cr_assert_eq(dfl_curvfit_sdf(&F, &s, p, n, &c), DFL_OK);
    /* heights 0 up to the mesh distance's rounding (< 1e-14 here); the
     * partial fit's weights are those of a subset, bounded like P's by the
     * derived tolerance of the full grid with a margin of 10 */
    double rem[DFL_CURVFIT_MAX_G * DFL_CURVFIT_MAX_G];
    for (int k = 0; k < F.npts; k++) rem[k] = 1e-13;
    const double tol = tolerance(&F, rem);
    cr_expect(fabs(c.k1) <= tol && fabs(c.k2) <= tol, "k1 %g k2 %g (tol %g)", c.k1, c.k2, tol);
    dfl_shape_free(&s);
    box_shape(thin, &s);
    c.k1 = 12345;
    cr_expect_eq(dfl_curvfit_sdf(&F, &s, p, n, &c), DFL_E_NUMERIC);
    cr_expect_eq(c.k1, 12345, "out untouched");
    dfl_shape_free(&s);
    /* a short square rod, |y|, |z| <= 0.0075: the 3 x 3 nodes at offsets 0,
     * +-0.005 are left, 9 < DFL_CURVFIT_MIN_NODES (their design alone is
     * regular: the rule, not a singular system, refuses them) */
    const double rod[3] = {0.5, 0.0075, 0.0075};
    box_shape(rod, &s);
    cr_expect_eq(dfl_curvfit_sdf(&F, &s, p, n, &c), DFL_E_NUMERIC);
    dfl_shape_free(&s);
}

/* A paraboloid z = c (x^2 + y^2) / 2 - e as f = z - c (x^2 + y^2) / 2 + e
 * (exact heights along the vertical lines), optionally with its sign
 * flipped above z = zj (f jumps there from +|f| to -|f|, as an open mesh's
 * winding number does across a sheet off the surface).  The gradient
 * (1, 0, 0) has no slope along n = +z, so Newton gives up on every node
 * and each height comes from bracket_root. */
typedef struct jump_para {
    double c, e, zj; /* zj = INFINITY: no jump */
} jump_para;

static void jump_para_eval(const void *impl, size_t m, const double *pts, double *val,
                           double *grad)
{
    const jump_para *J = impl;
    for (size_t i = 0; i < m; i++) {
        const double *x = pts + 3 * i;
        const double g = x[2] - J->c * (x[0] * x[0] + x[1] * x[1]) / 2 + J->e;
        val[i] = x[2] < J->zj ? g : -g;
        if (grad) grad[3 * i] = 1, grad[3 * i + 1] = 0, grad[3 * i + 2] = 0;
    }
}

static void jump_para_free(void *impl) { (void)impl; }

static const dfl_shape_ops jump_para_ops = {"jump_paraboloid", jump_para_eval, NULL,
                                            jump_para_free, NULL};

/* curvfit.h: a sign change where f jumps instead of passing 0 is no root:
 * the node is left out.  c = 10, e = 0.004, a 5 x 5 grid of spacing 0.005
 * at p = 0 (offsets r <= 0.01 sqrt 2, so c r^2 / 2 <= 0.001): the surface
 * lies at z = c r^2 / 2 - e in [-0.004, -0.003], below every node, where f
 * = e - c r^2 / 2 > 0.  Without the jump the ladder (rungs -h/2, +h/2, -h,
 * ...) first changes sign at -h = -0.005, below the surface: the bracket
 * holds the root and the heights are exact, so the result is the fit of
 * the exact heights (dfl_curvfit_from_heights of c r^2 / 2 - e).  With the
 * jump at zj = 0.001 the rung +h/2 = 0.0025 already changes sign (f < 0
 * above the sheet) while -h/2 does not (-0.0025 is above the surface):
 * every node brackets the jump, where |f| = 0.001 + e - c r^2 / 2 >=
 * 0.004, far above the converged bracket: all 25 nodes left out, fewer
 * than DFL_CURVFIT_MIN_NODES: DFL_E_NUMERIC, out untouched (before the
 * rule every node took the height 0.001). */
Test(curvfit, a_sign_jump_is_no_root)
{
    const double p[3] = {0, 0, 0}, n[3] = {0, 0, 1};
    dfl_curvfit F;
    cr_assert_eq(dfl_curvfit_init(5, 0.005, &F, NULL), DFL_OK);
    jump_para J = {10.0, 0.004, INFINITY};
    dfl_shape s = {3, &jump_para_ops, &J};
    double h[25], b1[3], b2[3];
    for (int k = 0; k < F.npts; k++) {
        const double x = F.xy[2 * k], y = F.xy[2 * k + 1];
        h[k] = J.c * (x * x + y * y) / 2 - J.e;
    }
    dfl_vec3_tangent_basis(n, b1, b2);
    dfl_curvature want, c;
    dfl_curvfit_from_heights(&F, h, b1, b2, n, &want);
    cr_assert_eq(dfl_curvfit_sdf(&F, &s, p, n, &c), DFL_OK);
    cr_expect(fabs(c.k1 - want.k1) < 1e-8 && fabs(c.k2 - want.k2) < 1e-8,
              "k1 %.17g k2 %.17g, the exact heights' fit %.17g %.17g", c.k1, c.k2, want.k1,
              want.k2);
    J.zj = 0.001;
    c.k1 = 12345;
    cr_expect_eq(dfl_curvfit_sdf(&F, &s, p, n, &c), DFL_E_NUMERIC, "k1 %g k2 %g", c.k1, c.k2);
    cr_expect_eq(c.k1, 12345, "out untouched");
}
