/* The B-spline basis straight from the definition: the independent
 * reference of the curve and surface tests (header-only). */
#ifndef DFL_TESTS_GEOM_BSPLINE_REF_H
#define DFL_TESTS_GEOM_BSPLINE_REF_H

#include <stddef.h>

/* Cox-de Boor N_{i,k}(t) over the knots U (order k, right-continuous),
 * valid for t in [tau_j, tau_{j+1}) of a non-empty span. */
static inline double ref_cox_de_boor(const double *U, size_t i, int k, double t)
{
    if (k == 1) return (U[i] <= t && t < U[i + 1]) ? 1.0 : 0.0;
    double a = 0.0, b = 0.0;
    double d1 = U[i + (size_t)k - 1] - U[i], d2 = U[i + (size_t)k] - U[i + 1];
    if (d1 > 0.0) a = (t - U[i]) / d1 * ref_cox_de_boor(U, i, k - 1, t);
    if (d2 > 0.0) b = (U[i + (size_t)k] - t) / d2 * ref_cox_de_boor(U, i + 1, k - 1, t);
    return a + b;
}

#endif
