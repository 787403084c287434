/* The shape interface in use (shape.c): footpoints of SDF input, Hermite
 * data against closed forms, the kind table. */
#include <criterion/criterion.h>

#include <math.h>
#include <string.h>

#include "core/vec.h"
#include "core/rng.h"
#include "geom/shape.h"
#include "geom/shape_check.h"

static const double TC[3] = {0.1, -0.1, 0.2}, TR = 0.6, Tr = 0.25;
static const double C2[2] = {0.1, -0.2}, R2 = 0.7;
static const double C3[3] = {0.1, -0.2, 0.05}, R3 = 0.6;

Test(shape, footpoint_of_sdf_input)
{
    dfl_shape s;
    double ax[3] = {1, 2, 2};
    cr_assert_eq(dfl_shape_torus(TC, ax, TR, Tr, &s, NULL), DFL_OK);
    for (int t = 0; t < 50; t++) {
        double x[3] = {sc_urand(-1, 1), sc_urand(-1, 1), sc_urand(-1, 1)}, p[3], g[3];
        dfl_err err;
        cr_assert_eq(dfl_shape_footpoint(&s, x, p, &err), DFL_OK, "%s", err.msg);
        double d = dfl_shape_eval1(&s, x, g);
        double u[3] = {x[0] - p[0], x[1] - p[1], x[2] - p[2]};
        cr_assert(fabs(dfl_shape_eval1(&s, p, NULL)) < 1e-13);
        cr_assert(fabs(sqrt(dfl_vecn_dot(3, u, u)) - fabs(d)) < 1e-12);
    }
    dfl_shape_free(&s);
}

/* Hermite data of a sphere: H = (I - n n^T)/|u|, d_xyz = 3 u_x u_y u_z/|u|^5
 * (differentiate x/|u| in y, then -x y/|u|^3 in z); of a circle likewise. */
Test(shape, hermite_derivatives_closed_form)
{
    dfl_shape s;
    cr_assert_eq(dfl_shape_sphere(C3, R3, &s, NULL), DFL_OK);
    for (int t = 0; t < 20; t++) {
        double x[3] = {sc_urand(-1, 1), sc_urand(-1, 1), sc_urand(-1, 1)};
        double u[3] = {x[0] - C3[0], x[1] - C3[1], x[2] - C3[2]}, l = sqrt(dfl_vecn_dot(3, u, u));
        dfl_shape_derivs D;
        cr_assert_eq(dfl_shape_derivs_at(&s, x, &D, NULL), DFL_OK);
        cr_assert(fabs(D.d - (l - R3)) < 1e-15);
        for (int i = 0; i < 3; i++) {
            cr_assert(fabs(D.g[i] - u[i] / l) < 1e-15);
            for (int j = 0; j < 3; j++) {
                double want = ((i == j) - u[i] * u[j] / (l * l)) / l;
                cr_assert(fabs(D.H[3 * i + j] - want) < 1e-13 * (1 + fabs(want)), "H%d%d", i, j);
            }
        }
        double want = 3 * u[0] * u[1] * u[2] / pow(l, 5);
        cr_assert(fabs(D.dxyz - want) < 1e-12 * (1 + fabs(want)), "%.17g vs %.17g", D.dxyz, want);
    }
    dfl_shape_free(&s);
    cr_assert_eq(dfl_shape_circle(C2, R2, &s, NULL), DFL_OK);
    double x[2] = {0.4, 0.9}, u[2] = {x[0] - C2[0], x[1] - C2[1]}, l = hypot(u[0], u[1]);
    dfl_shape_derivs D;
    cr_assert_eq(dfl_shape_derivs_at(&s, x, &D, NULL), DFL_OK);
    cr_assert(fabs(D.H[1] + u[0] * u[1] / (l * l * l)) < 1e-14);
    cr_assert(fabs(D.H[0] - u[1] * u[1] / (l * l * l)) < 1e-14);
    dfl_shape_free(&s);
}

/* The kind table: codes and names from one list, names unique. */
Test(shape, kind_table)
{
    for (int k = 0; k < DFL_SHAPE_KIND_COUNT; k++) {
        const char *name = dfl_shape_kind_name((dfl_shape_kind)k);
        cr_assert_not_null(name);
        dfl_shape_kind got = (dfl_shape_kind)DFL_SHAPE_KIND_COUNT;
        cr_assert_eq(dfl_shape_kind_parse(name, &got, NULL), DFL_OK, "%s", name);
        cr_assert_eq(got, k, "%s", name);
        for (int j = 0; j < k; j++) cr_assert_str_neq(name, dfl_shape_kind_names[j]);
    }
    cr_assert_str_eq(dfl_shape_kind_name(DFL_SHAPE_CIRCLE), "circle");
    cr_assert_str_eq(dfl_shape_kind_name(DFL_SHAPE_ELLIPSE), "ellipse");
    cr_assert_str_eq(dfl_shape_kind_name(DFL_SHAPE_CSG), "csg");
    cr_assert_str_eq(dfl_shape_kind_name((dfl_shape_kind)-1), "?");
    dfl_shape_kind got = DFL_SHAPE_MESH;
    cr_assert_eq(dfl_shape_kind_parse("Circle", &got, NULL), DFL_E_INPUT);
    cr_assert_eq(got, DFL_SHAPE_MESH);
}

/* dfl_shape_hessian: the closed forms agree with the polarized jets
 * (dfl_jets_polarize) at random points off the medial sets, and a kind
 * without a closed form (box) goes through the jets. */
Test(shape, hessian_closed_forms_match_the_jets)
{
    const double c[3] = {0.1, 0, -0.1}, ax[3] = {0.2, 1, 0.3}, n[3] = {1, 2, 2}, h[3] = {0.3, 0.4, 0.5};
    dfl_shape s[6], a, b;
    cr_assert_eq(dfl_shape_sphere(c, 0.5, &s[0], NULL), DFL_OK);
    cr_assert_eq(dfl_shape_torus(c, ax, 0.6, 0.25, &s[1], NULL), DFL_OK);
    cr_assert_eq(dfl_shape_cylinder(c, ax, 0.3, &s[2], NULL), DFL_OK);
    cr_assert_eq(dfl_shape_plane(3, c, n, &s[3], NULL), DFL_OK);
    cr_assert_eq(dfl_shape_box(3, c, h, &s[4], NULL), DFL_OK);
    cr_assert_eq(dfl_shape_sphere(c, 0.4, &a, NULL), DFL_OK);
    cr_assert_eq(dfl_shape_torus(c, ax, 0.6, 0.2, &b, NULL), DFL_OK);
    cr_assert_eq(dfl_shape_csg(DFL_CSG_DIFFERENCE, 0, &a, &b, &s[5], NULL), DFL_OK);
    uint64_t seed = 3;
    for (int k = 0; k < 6; k++)
        for (int t = 0; t < 50; t++) {
            double x[3], H[9];
            for (int j = 0; j < 3; j++) x[j] = dfl_rng_splitmix(&seed, -1, 1);
            cr_assert_eq(dfl_shape_hessian(&s[k], x, H, NULL), DFL_OK);
            dfl_shape_derivs der;
            cr_assert_eq(dfl_shape_derivs_at(&s[k], x, &der, NULL), DFL_OK);
            for (int j = 0; j < 9; j++)
                cr_assert(fabs(H[j] - der.H[j]) < 1e-9 * (1 + fabs(der.H[j])),
                          "shape %d: H[%d] %g vs %g", k, j, H[j], der.H[j]);
        }
    for (int k = 0; k < 6; k++) dfl_shape_free(&s[k]);
    double H[9], x[3] = {0, 0, 0};
    dfl_shape c2;
    const double cc[2] = {0, 0};
    cr_assert_eq(dfl_shape_circle(cc, 1, &c2, NULL), DFL_OK);
    cr_assert_eq(dfl_shape_hessian(&c2, x, H, NULL), DFL_E_INPUT);
    dfl_shape_free(&c2);
}
