#include "geom/winding.h"

#include <math.h>

#include "core/vec.h"

double dfl_winding_triangle(const double *x, const double *a, const double *b, const double *c)
{
    double A[3], B[3], C[3], BxC[3];
    for (int j = 0; j < 3; j++) {
        A[j] = a[j] - x[j];
        B[j] = b[j] - x[j];
        C[j] = c[j] - x[j];
    }
    dfl_vec3_cross(B, C, BxC);
    const double la = dfl_vec3_norm(A), lb = dfl_vec3_norm(B), lc = dfl_vec3_norm(C);
    const double num = dfl_vec3_dot(A, BxC);
    const double den = la * lb * lc + dfl_vec3_dot(A, B) * lc + dfl_vec3_dot(A, C) * lb +
                       dfl_vec3_dot(B, C) * la;
    return atan2(num, den) / (2.0 * DFL_PI);
}

double dfl_winding_brute(const double *verts, const size_t *tris, size_t n, const double *x)
{
    double w = 0.0;
    for (size_t t = 0; t < n; t++)
        w += dfl_winding_triangle(x, verts + 3 * tris[3 * t], verts + 3 * tris[3 * t + 1],
                                  verts + 3 * tris[3 * t + 2]);
    return w;
}
