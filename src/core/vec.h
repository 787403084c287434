/* Small fixed-size vector helpers: dflab's one small-vector vocabulary
 * (3D unless the name says otherwise; vecn takes the length).
 *
 *   DFL_PI                      pi to double precision
 *   dfl_vecn_dot(n, a, b)       sum a[j] b[j], j = 0..n-1, summed from 0.0 in order
 *   dfl_vec3_dot(a, b)          a0 b0 + a1 b1 + a2 b2
 *   dfl_vec3_cross(a, b, c)     c = a x b
 *   dfl_vec3_norm(a)            |a|
 *   dfl_vec3_tangent_basis      orthonormal completion of a unit normal
 *
 * All inline, no allocation, no checks beyond what the comment states:
 * callers pass valid pointers to 3 (or n) doubles.  Output arguments may
 * not alias inputs unless stated.  The two dot products round differently
 * (vecn adds to 0.0 first, which turns a -0 product into +0): keep the one
 * a module's numbers were computed with. */
#ifndef DFL_CORE_VEC_H
#define DFL_CORE_VEC_H

#include <math.h>

#define DFL_PI 3.14159265358979323846

/* n >= 0; 0.0 for n == 0. */
static inline double dfl_vecn_dot(int n, const double *a, const double *b)
{
    double s = 0.0;
    for (int j = 0; j < n; j++) s += a[j] * b[j];
    return s;
}

static inline double dfl_vec3_dot(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* c = a x b (c must not alias a or b). */
static inline void dfl_vec3_cross(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

static inline double dfl_vec3_norm(const double *a) { return sqrt(dfl_vec3_dot(a, a)); }

/* Orthonormal t1, t2 with t1 x t2 = n for a unit n; deterministic (t1 is
 * the coordinate axis least aligned with n, made orthogonal to it). */
static inline void dfl_vec3_tangent_basis(const double n[3], double t1[3], double t2[3])
{
    double t[3] = {0, 0, 0};
    int k = 0;
    for (int j = 1; j < 3; j++)
        if (fabs(n[j]) < fabs(n[k])) k = j;
    t[k] = 1.0;
    double tn = dfl_vec3_dot(t, n);
    for (int j = 0; j < 3; j++) t1[j] = t[j] - tn * n[j];
    double l = dfl_vec3_norm(t1);
    for (int j = 0; j < 3; j++) t1[j] /= l;
    dfl_vec3_cross(n, t1, t2);
}

#endif
