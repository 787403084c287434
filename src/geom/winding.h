/* Generalized winding numbers of triangle soups (Jacobson, Kavan,
 * Sorkine-Hornung: "Robust inside-outside segmentation using generalized
 * winding numbers", ACM Transactions on Graphics 32(4), 33:1-12, 2013,
 * doi:10.1145/2461912.2461916): w(x) = sum over triangles of the signed
 * solid angle the triangle subtends at x, over 4 pi.  For a closed,
 * consistently oriented (counter-clockwise seen from outside) mesh w is 1
 * inside and 0 outside; for open meshes and soups it varies smoothly and
 * w > 1/2 is the robust "inside".
 *
 *   dfl_winding_triangle(x, a, b, c)        one triangle's signed solid angle / 4 pi
 *   dfl_winding_brute(verts, tris, n, x)    the exact sum over n triangles
 *
 * The solid angle is Van Oosterom and Strackee's closed form ("The solid
 * angle of a plane triangle", IEEE Trans. Biomedical Engineering 30(2),
 * 125-126, 1983, doi:10.1109/TBME.1983.325207):
 *   tan(Omega/2) = A.(B x C) / (|A||B||C| + (A.B)|C| + (A.C)|B| + (B.C)|A|)
 * with A = a - x, B = b - x, C = c - x, evaluated by atan2 so that Omega is
 * in (-2 pi, 2 pi]; positive when x sees the triangle counter-clockwise
 * (x on the side opposite to the normal (b - a) x (c - a)).  On the
 * triangle's plane (x in the triangle) the value is 0 or +-1/2 by the
 * atan2 of a zero numerator; at a vertex 0.  Pure and thread-safe. */
#ifndef DFL_GEOM_WINDING_H
#define DFL_GEOM_WINDING_H

#include <stddef.h>

/* Omega(x; a, b, c) / (4 pi), in (-1/2, 1/2]. */
double dfl_winding_triangle(const double *x, const double *a, const double *b, const double *c);

/* sum_{t < n} dfl_winding_triangle(x, verts[3 tris[3t]], ...), summed from
 * 0.0 in triangle order. */
double dfl_winding_brute(const double *verts, const size_t *tris, size_t n, const double *x);

#endif
