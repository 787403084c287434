#include "geom/segdist.h"

#include <assert.h>
#include <math.h>
#include <string.h>

#include "core/hypot.h"

double dfl_segdist_eval(int dim, const double *a, const double *b, const double *x, double *grad)
{
    assert(dim == 2 || dim == 3);
    double ab[3] = {0, 0, 0}, xa[3] = {0, 0, 0}, w[3] = {0, 0, 0};
    double dot = 0.0, len2 = 0.0;
    for (int j = 0; j < dim; j++) {
        ab[j] = b[j] - a[j];
        xa[j] = x[j] - a[j];
        dot += xa[j] * ab[j];
        len2 += ab[j] * ab[j];
    }
    /* The end-point branches subtract the end point itself (not a + t ab
     * with t rounded to 0 or 1): see the header's bit-for-bit promise. */
    if (dot <= 0.0 || len2 == 0.0) {
        memcpy(w, xa, sizeof w);
    } else if (dot >= len2) {
        for (int j = 0; j < dim; j++) w[j] = x[j] - b[j];
    } else {
        const double t = dot / len2;
        for (int j = 0; j < dim; j++) w[j] = xa[j] - t * ab[j];
    }
    const double d = dfl_hypot_vec(dim, w);
    if (grad)
        for (int j = 0; j < dim; j++) grad[j] = d > 0.0 ? w[j] / d : 0.0;
    return d;
}

bool dfl_segdist_closest_is_start(int dim, const double *a, const double *b, const double *x)
{
    double dot = 0.0;
    for (int j = 0; j < dim; j++) dot += (x[j] - a[j]) * (b[j] - a[j]);
    return dot <= 0.0;
}

double dfl_segdist_residual(int dim, const double *a, const double *e, double ee,
                            const double *x, double *r)
{
    assert(dim >= 1 && dim <= 3);
    double w[3], we = 0.0;
    for (int j = 0; j < dim; j++) {
        w[j] = x[j] - a[j];
        we += w[j] * e[j];
    }
    double s = ee > 0.0 ? we / ee : 0.0;
    if (s < 0.0) s = 0.0;
    if (s > 1.0) s = 1.0;
    double d = 0.0;
    for (int j = 0; j < dim; j++) {
        r[j] = w[j] - s * e[j];
        d += r[j] * r[j];
    }
    return sqrt(d);
}

double dfl_point_segment_dist(int dim, const double *x, const double *a, const double *b)
{
    assert(dim >= 1 && dim <= 3);
    double e[3], r[3], ee = 0.0;
    for (int j = 0; j < dim; j++) {
        e[j] = b[j] - a[j];
        ee += e[j] * e[j];
    }
    return dfl_segdist_residual(dim, a, e, ee, x, r);
}

double dfl_point_segment_dist_hypot(const double *x, const double *a, const double *b)
{
    const double e[2] = {b[0] - a[0], b[1] - a[1]};
    double r[2];
    (void)dfl_segdist_residual(2, a, e, e[0] * e[0] + e[1] * e[1], x, r);
    return hypot(r[0], r[1]);
}
