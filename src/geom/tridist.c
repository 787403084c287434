#include "geom/tridist.h"

#include <math.h>

static double dist_to(const double *p, const double *q, double *qout, dfl_tri_feature f,
                      dfl_tri_feature *feat)
{
    double s = 0.0;
    for (int j = 0; j < 3; j++) s += (p[j] - q[j]) * (p[j] - q[j]);
    if (qout)
        for (int j = 0; j < 3; j++) qout[j] = q[j];
    if (feat) *feat = f;
    return sqrt(s);
}

double dfl_tridist_closest(const double *p, const double *a, const double *b, const double *c,
                           double *qout, dfl_tri_feature *feat)
{
    double ab[3], ac[3], ap[3], q[3];
    for (int j = 0; j < 3; j++) {
        ab[j] = b[j] - a[j];
        ac[j] = c[j] - a[j];
        ap[j] = p[j] - a[j];
    }
#define DOT(u, v) ((u)[0] * (v)[0] + (u)[1] * (v)[1] + (u)[2] * (v)[2])
    double d1 = DOT(ab, ap), d2 = DOT(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) return dist_to(p, a, qout, DFL_TRI_VERT_A, feat);
    double bp[3];
    for (int j = 0; j < 3; j++) bp[j] = p[j] - b[j];
    double d3 = DOT(ab, bp), d4 = DOT(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) return dist_to(p, b, qout, DFL_TRI_VERT_B, feat);
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
        double v = d1 / (d1 - d3);
        for (int j = 0; j < 3; j++) q[j] = a[j] + v * ab[j];
        return dist_to(p, q, qout, DFL_TRI_EDGE_AB, feat);
    }
    double cp[3];
    for (int j = 0; j < 3; j++) cp[j] = p[j] - c[j];
    double d5 = DOT(ab, cp), d6 = DOT(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) return dist_to(p, c, qout, DFL_TRI_VERT_C, feat);
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
        double w = d2 / (d2 - d6);
        for (int j = 0; j < 3; j++) q[j] = a[j] + w * ac[j];
        return dist_to(p, q, qout, DFL_TRI_EDGE_AC, feat);
    }
    double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
        double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        for (int j = 0; j < 3; j++) q[j] = b[j] + w * (c[j] - b[j]);
        return dist_to(p, q, qout, DFL_TRI_EDGE_BC, feat);
    }
    double den = 1.0 / (va + vb + vc);
    double v = vb * den, w = vc * den;
    for (int j = 0; j < 3; j++) q[j] = a[j] + ab[j] * v + ac[j] * w;
#undef DOT
    return dist_to(p, q, qout, DFL_TRI_FACE, feat);
}
