#include "core/linalg.h"

#include <assert.h>
#include <math.h>

dfl_status dfl_lu_factor(int n, double *A, int *piv, double tol, dfl_err *err)
{
    assert(n >= 1);
    double amax = 0.0;
    for (int i = 0; i < n * n; i++) amax = fmax(amax, fabs(A[i]));
    /* written as !(x > y) so that NaN entries also count as singular */
    if (!(amax > 0.0)) return dfl_err_set(err, DFL_E_NUMERIC, "singular matrix (all zero)");
    for (int k = 0; k < n; k++) {
        int p = k;
        for (int i = k + 1; i < n; i++)
            if (fabs(A[n * i + k]) > fabs(A[n * p + k])) p = i;
        if (!(fabs(A[n * p + k]) > tol * amax))
            return dfl_err_set(err, DFL_E_NUMERIC, "singular matrix (pivot %d below %g of the "
                               "largest entry)", k, tol);
        piv[k] = p;
        if (p != k)
            for (int j = 0; j < n; j++) {
                double t = A[n * k + j];
                A[n * k + j] = A[n * p + j];
                A[n * p + j] = t;
            }
        for (int i = k + 1; i < n; i++) {
            double f = A[n * i + k] /= A[n * k + k];
            for (int j = k + 1; j < n; j++) A[n * i + j] -= f * A[n * k + j];
        }
    }
    return DFL_OK;
}

void dfl_lu_solve(int n, const double *A, const int *piv, double *b)
{
    for (int k = 0; k < n; k++) {
        if (piv[k] != k) {
            double t = b[k];
            b[k] = b[piv[k]];
            b[piv[k]] = t;
        }
    }
    for (int k = 0; k < n; k++)
        for (int i = k + 1; i < n; i++) b[i] -= A[n * i + k] * b[k];
    for (int i = n - 1; i >= 0; i--) {
        for (int j = i + 1; j < n; j++) b[i] -= A[n * i + j] * b[j];
        b[i] /= A[n * i + i];
    }
}

void dfl_sym2_eigen(double a, double b, double c, double *lo, double *hi, double *th)
{
    double m = 0.5 * (a + c), r = hypot(0.5 * (a - c), b);
    *lo = m - r;
    *hi = m + r;
    *th = 0.5 * atan2(2.0 * b, a - c);
}
