/* Tiny dense linear algebra: LU with partial pivoting for small square
 * systems, and the eigen-decomposition of a symmetric 2x2 matrix.
 *
 *   dfl_lu_factor(n, A, piv, tol, err)   A = P L U in place (row-major n x n)
 *   dfl_lu_solve(n, A, piv, b)           solves with the factors, b in place
 *   dfl_sym2_eigen(a, b, c, lo, hi, th)  [[a, b], [b, c]] = R diag(hi, lo) R^T
 *
 * Sizes are the caller's (meant for n <= ~10: no blocking, no scaling);
 * nothing allocates; the functions are pure and thread-safe.  The
 * operation order is part of the contract: dflab's footpoint jets and
 * curvatures are computed with exactly these loops, and results are
 * reproduced bit for bit. */
#ifndef DFL_CORE_LINALG_H
#define DFL_CORE_LINALG_H

#include "core/status.h"

/* LU factorization with partial pivoting of the row-major n x n matrix A
 * (n >= 1), in place: on return the strict lower triangle holds L's
 * multipliers (unit diagonal implied), the upper triangle U, and piv[k] the
 * row swapped with row k at step k (whole rows are swapped, multipliers
 * included).  A pivot is accepted only if |pivot| > tol * max |A_ij| (of
 * the input): DFL_E_NUMERIC "singular matrix" otherwise, also for the zero
 * or a non-finite matrix; A is then partly overwritten.  err may be NULL. */
dfl_status dfl_lu_factor(int n, double *A, int *piv, double tol, dfl_err *err);

/* Solves A x = b with the factors of dfl_lu_factor; x overwrites b (n
 * doubles).  The permutation is applied to all of b before the forward
 * substitution (the factors refer to the final row order). */
void dfl_lu_solve(int n, const double *A, const int *piv, double *b);

/* Eigen-decomposition of the symmetric [[a, b], [b, c]]: eigenvalues
 * lo <= hi, with the unit eigenvector (cos th, sin th) of hi and
 * (-sin th, cos th) of lo, th = atan2(2b, a - c) / 2 in [-pi/2, pi/2].
 * Computed as m -+ r with m = (a + c)/2, r = hypot((a - c)/2, b): the angle
 * form stays accurate near a double eigenvalue, where the eigenvectors are
 * arbitrary. */
void dfl_sym2_eigen(double a, double b, double c, double *lo, double *hi, double *th);

#endif
