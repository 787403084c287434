/* CSG of SDFs (shape_csg.c): exact ops are min/max, smooth ops are the
 * polynomial smin, gradients and jets against finite differences. */
#include <criterion/criterion.h>

#include <math.h>
#include <string.h>

#include "core/vec.h"
#include "geom/shape.h"
#include "geom/shape_check.h"

/* Two balls of dimension dim (centres ca, cb, radii 0.5, 0.4) combined by
 * op into *s, and separate copies ra, rb of them as references.  The
 * children's structs must be zeroed (ownership taken). */
static void ball_pair(int dim, const double *ca, const double *cb, dfl_csg_op op, double k,
                      dfl_shape *s, dfl_shape *ra, dfl_shape *rb)
{
    dfl_shape a, b;
    dfl_status (*ball)(const double *, double, dfl_shape *, dfl_err *) =
        dim == 2 ? dfl_shape_circle : dfl_shape_sphere;
    cr_assert_eq(ball(ca, 0.5, &a, NULL), DFL_OK);
    cr_assert_eq(ball(cb, 0.4, &b, NULL), DFL_OK);
    cr_assert_eq(ball(ca, 0.5, ra, NULL), DFL_OK);
    cr_assert_eq(ball(cb, 0.4, rb, NULL), DFL_OK);
    cr_assert_eq(dfl_shape_csg(op, k, &a, &b, s, NULL), DFL_OK);
    cr_assert_null(a.impl);
    cr_assert_null(b.impl);
}

static void free3(dfl_shape *a, dfl_shape *b, dfl_shape *c)
{
    dfl_shape_free(a);
    dfl_shape_free(b);
    dfl_shape_free(c);
}

Test(shape_csg, csg_exact_ops_are_min_max)
{
    const double ca[2] = {-0.2, 0}, cb[2] = {0.25, 0.1};
    for (int op = DFL_CSG_UNION; op <= DFL_CSG_DIFFERENCE; op++) {
        dfl_shape s, ra, rb;
        ball_pair(2, ca, cb, (dfl_csg_op)op, 0, &s, &ra, &rb);
        for (int t = 0; t < 200; t++) {
            double x[2] = {sc_urand(-1, 1), sc_urand(-1, 1)};
            double da = dfl_shape_eval1(&ra, x, NULL), db = dfl_shape_eval1(&rb, x, NULL);
            double want = op == DFL_CSG_UNION ? fmin(da, db)
                        : op == DFL_CSG_INTERSECTION ? fmax(da, db) : fmax(da, -db);
            cr_assert(dfl_shape_eval1(&s, x, NULL) == want);
        }
        /* gradients and jets vs FD (values need no brute force: min/max) */
        sc_check_shape(&s, NULL, 0, NULL, 1, -1, 1, 20, 0, 1, 1);
        free3(&s, &ra, &rb);
    }
}

Test(shape_csg, csg_smooth_ops)
{
    /* smin closed-form properties */
    cr_assert(fabs(dfl_csg_smin(0.3, 0.3, 0.2) - (0.3 - 0.2 / 4)) < 1e-16);
    cr_assert(dfl_csg_smin(0.0, 0.5, 0.2) == 0.0);
    cr_assert(dfl_csg_smin(0.5, 0.0, 0.2) == 0.0);
    for (int t = 0; t < 1000; t++) {
        double a = sc_urand(-1, 1), b = sc_urand(-1, 1), k = sc_urand(0.01, 0.5);
        double m = dfl_csg_smin(a, b, k);
        cr_assert(m <= fmin(a, b) + 1e-16 && m >= fmin(a, b) - k / 4 - 1e-16);
    }
    const double ca[3] = {-0.2, 0, 0.1}, cb[3] = {0.25, 0.1, -0.1};
    for (int op = DFL_CSG_SMOOTH_UNION; op <= DFL_CSG_SMOOTH_DIFFERENCE; op++) {
        dfl_shape s, ra, rb;
        ball_pair(3, ca, cb, (dfl_csg_op)op, 0.3, &s, &ra, &rb);
        for (int t = 0; t < 200; t++) {
            double x[3] = {sc_urand(-1, 1), sc_urand(-1, 1), sc_urand(-1, 1)};
            double da = dfl_shape_eval1(&ra, x, NULL), db = dfl_shape_eval1(&rb, x, NULL);
            double want = op == DFL_CSG_SMOOTH_UNION ? dfl_csg_smin(da, db, 0.3)
                        : op == DFL_CSG_SMOOTH_INTERSECTION ? -dfl_csg_smin(-da, -db, 0.3)
                                                            : -dfl_csg_smin(-da, db, 0.3);
            cr_assert(fabs(dfl_shape_eval1(&s, x, NULL) - want) < 1e-15);
        }
        sc_check_shape(&s, NULL, 0, NULL, 1, -1, 1, 30, 0, 0, 1);
        free3(&s, &ra, &rb);
    }
}

Test(shape_csg, rejects_degenerate_input)
{
    dfl_shape s = {0};
    dfl_err err;
    double c[3] = {0, 0, 0};
    dfl_shape a, b;
    dfl_shape_circle(c, 1, &a, NULL);
    dfl_shape_sphere(c, 1, &b, NULL);
    cr_assert_eq(dfl_shape_csg(DFL_CSG_UNION, 0, &a, &b, &s, &err), DFL_E_INPUT);
    cr_assert_null(a.impl); /* ownership taken even on failure */
    dfl_shape_circle(c, 1, &a, NULL);
    dfl_shape_circle(c, 2, &b, NULL);
    cr_assert_eq(dfl_shape_csg(DFL_CSG_SMOOTH_UNION, 0, &a, &b, &s, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "k"));
}


/* Ties of the exact ops go to a (shape.h: deterministic on ties of
 * min/max): two equal circles mirrored in the y axis have bit-for-bit equal
 * values on it (|x - c| of (1, y) and (-1, y)), and union and intersection
 * take a's gradient there, whose x component has the sign of -c_a. */
Test(shape_csg, exact_ties_take_the_gradient_of_a)
{
    const double ca[2] = {-1, 0}, cb[2] = {1, 0};
    const dfl_csg_op ops[2] = {DFL_CSG_UNION, DFL_CSG_INTERSECTION};
    for (int i = 0; i < 2; i++) {
        dfl_shape a, b, s;
        cr_assert_eq(dfl_shape_circle(ca, 1.5, &a, NULL), DFL_OK);
        cr_assert_eq(dfl_shape_circle(cb, 1.5, &b, NULL), DFL_OK);
        cr_assert_eq(dfl_shape_csg(ops[i], 0, &a, &b, &s, NULL), DFL_OK);
        for (int k = -3; k <= 3; k++) {
            const double x[2] = {0, 0.7 * k};
            double g[2];
            dfl_shape_eval1(&s, x, g);
            /* a's gradient (x - ca)/|x - ca| for the union, the same for
             * the intersection (-min(-a, -b) takes -(-grad a)) */
            const double r = hypot(1.0, x[1]);
            cr_expect_float_eq(g[0], 1.0 / r, 1e-15, "op %d y %g: %g", i, x[1], g[0]);
            cr_expect_float_eq(g[1], x[1] / r, 1e-15, "op %d y %g", i, x[1]);
        }
        dfl_shape_free(&s);
    }
}
