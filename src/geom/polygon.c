#include "geom/polygon.h"

#include <math.h>

#include "geom/segdist.h"

double dfl_polygon_orientation(const double *v, size_t n)
{
    double a = 0;
    for (size_t i = 0; i < n; i++) {
        const double *p = v + 2 * i, *q = v + 2 * ((i + 1) % n);
        a += p[0] * q[1] - q[0] * p[1];
    }
    return a > 0 ? 1.0 : -1.0;
}

/* The edge distances are taken even once x is known to be outside only
 * one edge: the nearest edge need not be the violated one. */
double dfl_convex_polygon_dist(const double *v, size_t n, double orient, const double *x)
{
    int inside = 1;
    double d = INFINITY;
    for (size_t i = 0; i < n; i++) {
        const double *p = v + 2 * i, *q = v + 2 * ((i + 1) % n);
        const double cr = (q[0] - p[0]) * (x[1] - p[1]) - (q[1] - p[1]) * (x[0] - p[0]);
        if (orient * cr < 0) inside = 0;
        d = fmin(d, dfl_point_segment_dist(2, x, p, q));
    }
    return inside ? 0.0 : d;
}
