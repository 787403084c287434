/* Named implicit surfaces: the torus quartic, Goursat's family and the
 * genus-2 lemniscate tube, built as dfl_poly3 and handed to
 * dfl_implicit_new. */
#include "geom/implicit_impl.h"

#include <math.h>
#include <string.h>

/* Deterministic right-handed frame with w as third row (dfl_vec3_tangent_basis
 * completes it). */
static void frame_rows(const double w[3], double Q[9])
{
    dfl_vec3_tangent_basis(w, Q, Q + 3);
    memcpy(Q + 6, w, 3 * sizeof *w);
}

static int poly_to_terms(const dfl_poly3 *P, dfl_monomial *t)
{
    for (int k = 0; k < P->n; k++) {
        t[k].c = P->c[k];
        memcpy(t[k].e, P->e[k], sizeof t[k].e);
    }
    return P->n;
}

dfl_status dfl_implicit_torus(const double c[3], const double axis[3], double R, double r,
                              const dfl_implicit_options *opt, dfl_implicit **out, dfl_err *err)
{
    if (!(R > 0.0) || !(r > 0.0) || !(r < R) || !isfinite(R))
        return dfl_err_set(err, DFL_E_INPUT, "implicit torus: need 0 < minor < major, got %g, %g",
                           r, R);
    double an = sqrt(dfl_vec3_dot(axis, axis));
    if (!(an > 0.0) || !isfinite(an))
        return dfl_err_set(err, DFL_E_INPUT, "implicit torus: axis is the zero vector");
    double w[3] = {axis[0] / an, axis[1] / an, axis[2] / an}, Q[9];
    frame_rows(w, Q);
    /* (u^2 + v^2 + w^2 + R^2 - r^2)^2 - 4 R^2 (u^2 + v^2) */
    dfl_poly3 a, a2;
    memset(&a, 0, sizeof a);
    dfl_poly3_term(&a, 1, 2, 0, 0);
    dfl_poly3_term(&a, 1, 0, 2, 0);
    dfl_poly3_term(&a, 1, 0, 0, 2);
    dfl_poly3_term(&a, R * R - r * r, 0, 0, 0);
    dfl_poly3_mul(&a, &a, &a2);
    dfl_poly3_term(&a2, -4 * R * R, 2, 0, 0);
    dfl_poly3_term(&a2, -4 * R * R, 0, 2, 0);
    dfl_monomial t[DFL_IMPLICIT_MAX_TERMS];
    int n = poly_to_terms(&a2, t);
    double m = 1.05 * (R + r), lo[3] = {-m, -m, -1.05 * r}, hi[3] = {m, m, 1.05 * r};
    return dfl_implicit_new(n, t, c, Q, lo, hi, opt, out, err);
}

dfl_status dfl_implicit_goursat(const double centre[3], double a, double b, double c,
                                const dfl_implicit_options *opt, dfl_implicit **out,
                                dfl_err *err)
{
    if (!(a > -1.0 / 3.0) || !isfinite(a) || !isfinite(b) || !isfinite(c))
        return dfl_err_set(err, DFL_E_INPUT, "implicit goursat: need a > -1/3, got %g", a);
    /* x^4 + y^4 + z^4 >= |q|^4 / 3, so g >= al rho^4 + b rho^2 + c with
     * al = 1/3 + a > 0: the zero set lies in rho^2 <= (-b + sqrt(b^2 - 4 al c)) / (2 al). */
    double al = 1.0 / 3.0 + a, disc = b * b - 4.0 * al * c;
    if (disc < 0.0 || (-b + sqrt(disc)) <= 0.0)
        return dfl_err_set(err, DFL_E_INPUT,
                           "implicit goursat: a = %g, b = %g, c = %g give an empty surface", a, b,
                           c);
    double rho = sqrt((-b + sqrt(disc)) / (2.0 * al)) * 1.02;
    dfl_poly3 r2, r4, g;
    memset(&r2, 0, sizeof r2);
    dfl_poly3_term(&r2, 1, 2, 0, 0);
    dfl_poly3_term(&r2, 1, 0, 2, 0);
    dfl_poly3_term(&r2, 1, 0, 0, 2);
    dfl_poly3_mul(&r2, &r2, &r4);
    memset(&g, 0, sizeof g);
    dfl_poly3_term(&g, 1, 4, 0, 0);
    dfl_poly3_term(&g, 1, 0, 4, 0);
    dfl_poly3_term(&g, 1, 0, 0, 4);
    dfl_poly3_axpy(a, &r4, &g);
    dfl_poly3_axpy(b, &r2, &g);
    dfl_poly3_term(&g, c, 0, 0, 0);
    dfl_monomial t[DFL_IMPLICIT_MAX_TERMS];
    int n = poly_to_terms(&g, t);
    double lo[3] = {-rho, -rho, -rho}, hi[3] = {rho, rho, rho};
    return dfl_implicit_new(n, t, centre, NULL, lo, hi, opt, out, err);
}

dfl_status dfl_implicit_genus2(const double centre[3], double eps, const dfl_implicit_options *opt,
                               dfl_implicit **out, dfl_err *err)
{
    if (!(eps > 0.0) || !(eps < 0.25))
        return dfl_err_set(err, DFL_E_INPUT, "implicit genus2: need 0 < eps < 1/4, got %g", eps);
    /* L = (x^2 + y^2)^2 - x^2 + y^2 */
    dfl_poly3 r2, L, L2;
    memset(&r2, 0, sizeof r2);
    dfl_poly3_term(&r2, 1, 2, 0, 0);
    dfl_poly3_term(&r2, 1, 0, 2, 0);
    dfl_poly3_mul(&r2, &r2, &L);
    dfl_poly3_term(&L, -1, 2, 0, 0);
    dfl_poly3_term(&L, 1, 0, 2, 0);
    dfl_poly3_mul(&L, &L, &L2);
    dfl_poly3_term(&L2, 1, 0, 0, 2);
    dfl_poly3_term(&L2, -eps * eps, 0, 0, 0);
    dfl_monomial t[DFL_IMPLICIT_MAX_TERMS];
    int n = poly_to_terms(&L2, t);
    /* |L| <= eps and L >= r^4 - r^2 give r^2 <= (1 + sqrt(1 + 4 eps)) / 2 */
    double rm = sqrt(0.5 * (1.0 + sqrt(1.0 + 4.0 * eps))) * 1.02;
    double lo[3] = {-rm, -rm, -1.05 * eps}, hi[3] = {rm, rm, 1.05 * eps};
    return dfl_implicit_new(n, t, centre, NULL, lo, hi, opt, out, err);
}

dfl_status dfl_implicit_sphere(const double c[3], double r, const dfl_implicit_options *opt,
                               dfl_implicit **out, dfl_err *err)
{
    if (!(r > 0.0) || !isfinite(r))
        return dfl_err_set(err, DFL_E_INPUT, "implicit sphere: need radius > 0, got %g", r);
    /* |q|^2 - r^2: the sphere, but not its distance (|grad| = 2 |q|) */
    dfl_poly3 g;
    memset(&g, 0, sizeof g);
    dfl_poly3_term(&g, 1, 2, 0, 0);
    dfl_poly3_term(&g, 1, 0, 2, 0);
    dfl_poly3_term(&g, 1, 0, 0, 2);
    dfl_poly3_term(&g, -r * r, 0, 0, 0);
    dfl_monomial t[DFL_IMPLICIT_MAX_TERMS];
    int n = poly_to_terms(&g, t);
    double m = 1.05 * r, lo[3] = {-m, -m, -m}, hi[3] = {m, m, m};
    return dfl_implicit_new(n, t, c, NULL, lo, hi, opt, out, err);
}

dfl_status dfl_implicit_ellipsoid(const double c[3], const double semi[3], double k,
                                  const dfl_implicit_options *opt, dfl_implicit **out,
                                  dfl_err *err)
{
    for (int j = 0; j < 3; j++)
        if (!(semi[j] > 0.0) || !isfinite(semi[j]))
            return dfl_err_set(err, DFL_E_INPUT, "implicit ellipsoid: semi-axes must be > 0");
    if (!(k >= 0.0) || !isfinite(k))
        return dfl_err_set(err, DFL_E_INPUT, "implicit ellipsoid: scramble k = %g, expected >= 0",
                           k);
    /* E = sum q_j^2 / a_j^2 - 1 times phi = 1 + k (u^2 + v^4 + u^2 w^2) >= 1:
     * the same zero set and inside, a gradient far from unit length */
    dfl_poly3 e, phi, g;
    memset(&e, 0, sizeof e);
    dfl_poly3_term(&e, 1 / (semi[0] * semi[0]), 2, 0, 0);
    dfl_poly3_term(&e, 1 / (semi[1] * semi[1]), 0, 2, 0);
    dfl_poly3_term(&e, 1 / (semi[2] * semi[2]), 0, 0, 2);
    dfl_poly3_term(&e, -1, 0, 0, 0);
    memset(&phi, 0, sizeof phi);
    dfl_poly3_term(&phi, 1, 0, 0, 0);
    dfl_poly3_term(&phi, k, 2, 0, 0);
    dfl_poly3_term(&phi, k, 0, 4, 0);
    dfl_poly3_term(&phi, k, 2, 0, 2);
    dfl_poly3_mul(&e, &phi, &g);
    dfl_monomial t[DFL_IMPLICIT_MAX_TERMS];
    int n = poly_to_terms(&g, t);
    double lo[3], hi[3];
    for (int j = 0; j < 3; j++) {
        hi[j] = 1.05 * semi[j];
        lo[j] = -hi[j];
    }
    return dfl_implicit_new(n, t, c, NULL, lo, hi, opt, out, err);
}
