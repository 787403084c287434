#include "geom/ellipse.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>

#include "geom/shape_impl.h"

/* Root of G (see the header) by bisection; g = G(0) != 0.  The bracket:
 * G(z1 - 1) >= 0 because its second term is 1 there, and
 * G(|(r0 z0, z1)| - 1) <= 0 because both denominators are then at least
 * that norm.  Outside the ellipse (g > 0) the root is > 0, inside < 0, so
 * one end of the bracket tightens to 0. */
static double get_root(double r0, double z0, double z1, double g)
{
    const double n0 = r0 * z0;
    double s0 = z1 - 1.0, s1 = g < 0.0 ? 0.0 : hypot(n0, z1) - 1.0, s = 0.0;
    for (int i = 0; i < 2200; i++) {
        s = 0.5 * (s0 + s1);
        if (s == s0 || s == s1) break;
        const double q0 = n0 / (s + r0), q1 = z1 / (s + 1.0);
        const double gs = (q0 * q0 - 1.0) + q1 * q1;
        if (gs > 0.0)
            s0 = s;
        else if (gs < 0.0)
            s1 = s;
        else
            break;
    }
    return s;
}

/* First quadrant, e0 >= e1 > 0, y0, y1 >= 0: the footpoint (x0, x1). */
static void foot_q1(double e0, double e1, double y0, double y1, double *x0, double *x1)
{
    if (y1 > 0.0) {
        if (y0 > 0.0) {
            const double z0 = y0 / e0, z1 = y1 / e1;
            const double g = (z0 * z0 - 1.0) + z1 * z1;
            if (g != 0.0) {
                const double r0 = (e0 / e1) * (e0 / e1);
                const double sb = get_root(r0, z0, z1, g);
                *x0 = r0 * y0 / (sb + r0);
                *x1 = y1 / (sb + 1.0);
            } else {
                *x0 = y0;
                *x1 = y1;
            }
        } else {
            *x0 = 0.0;
            *x1 = e1;
        }
        return;
    }
    /* y1 == 0: on the major axis.  Inside the evolute's cusp (e0 y0 <
     * e0^2 - e1^2) the footpoint leaves the axis. */
    const double num = e0 * y0, den = e0 * e0 - e1 * e1;
    if (num < den) {
        const double xd = num / den;
        *x0 = e0 * xd;
        *x1 = e1 * sqrt(fmax(0.0, 1.0 - xd * xd));
    } else {
        *x0 = e0;
        *x1 = 0.0;
    }
}

double dfl_ellipse_sdist(double a, double b, const double *x, double *foot, double *grad)
{
    assert(a > 0.0 && b > 0.0 && isfinite(a) && isfinite(b));
    /* order the axes: e0 >= e1 (swap coordinates when b > a) */
    const int sw = b > a;
    const double e0 = sw ? b : a, e1 = sw ? a : b;
    const double px = sw ? x[1] : x[0], py = sw ? x[0] : x[1];
    double f0, f1;
    foot_q1(e0, e1, fabs(px), fabs(py), &f0, &f1);
    f0 = copysign(f0, px);
    f1 = copysign(f1, py);
    const double dist = hypot(px - f0, py - f1);
    const double inside = (px / e0) * (px / e0) + (py / e1) * (py / e1) < 1.0;
    /* outward normal at the footpoint: grad of x^2/e0^2 + y^2/e1^2 */
    double n0 = f0 / (e0 * e0), n1 = f1 / (e1 * e1);
    const double nn = hypot(n0, n1);
    assert(nn > 0.0);
    n0 /= nn;
    n1 /= nn;
    if (foot) {
        foot[0] = sw ? f1 : f0;
        foot[1] = sw ? f0 : f1;
    }
    if (grad) {
        grad[0] = sw ? n1 : n0;
        grad[1] = sw ? n0 : n1;
    }
    return inside ? -dist : dist;
}

/* ---- as a shape ---------------------------------------------------------- */

typedef struct ellipse {
    double c[2], a, b;
} ellipse;

static void ellipse_eval(const void *impl, size_t m, const double *pts, double *val,
                         double *grad)
{
    const ellipse *e = impl;
    for (size_t i = 0; i < m; i++) {
        const double u[2] = {pts[2 * i] - e->c[0], pts[2 * i + 1] - e->c[1]};
        val[i] = dfl_ellipse_sdist(e->a, e->b, u, NULL, grad ? grad + 2 * i : NULL);
    }
}

static const dfl_shape_ops ellipse_ops = {"ellipse", ellipse_eval, NULL, free, NULL};

dfl_status dfl_shape_ellipse(const double c[2], double a, double b, dfl_shape *out,
                             dfl_err *err)
{
    if (!finite_vec(2, c)) return dfl_err_set(err, DFL_E_INPUT, "ellipse: centre not finite");
    if (!(a > 0.0) || !isfinite(a) || !(b > 0.0) || !isfinite(b))
        return dfl_err_set(err, DFL_E_INPUT, "ellipse: semi-axes must be > 0, got %g and %g", a,
                           b);
    ellipse *e = calloc(1, sizeof *e);
    if (!e) return dfl_err_set(err, DFL_E_NOMEM, "ellipse: out of memory");
    e->c[0] = c[0];
    e->c[1] = c[1];
    e->a = a;
    e->b = b;
    return shape_set(2, &ellipse_ops, e, out);
}
