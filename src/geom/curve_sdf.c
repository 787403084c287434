/* Signed distance of a closed planar curve: sign by a certified polygon's
 * winding number, derivatives from the footpoint's curvature (formulas and
 * the curvature convention in curve_sdf.h). */
#include "geom/foot_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

dfl_status dfl_curve_sdf_new(const dfl_bspline *c, const dfl_foot_opts *opt, dfl_curve_sdf **out,
                             dfl_err *err)
{
    if (c->dim != 2)
        return dfl_err_set(err, DFL_E_INPUT,
                           "signed distance needs a planar curve, got dimension %d", c->dim);
    if (!dfl_bspline_is_closed(c, 1e-12))
        return dfl_err_set(err, DFL_E_INPUT,
                           "a closed curve is required for a signed distance (periodic, or with "
                           "first and last points equal)");
    dfl_curve_sdf *S = calloc(1, sizeof *S);
    if (!S) return dfl_err_set(err, DFL_E_NOMEM, "out of memory for a curve SDF");
    S->c = c;
    dfl_status st = dfl_curve_locator_new(c, opt, &S->L, err);
    if (st != DFL_OK) {
        free(S);
        return st;
    }
    double size = dfl_foot_extent(2, c->n, c->cp);
    if ((st = dfl_polygonize_curve(c, 1e-4 * size, 0, &S->poly, err)) != DFL_OK) {
        dfl_curve_sdf_free(S);
        return st;
    }
    /* close the polygon exactly (clamped curves meet within 1e-12) */
    memcpy(S->poly.pts + 2 * (S->poly.n - 1), S->poly.pts, 2 * sizeof(double));
    double area = 0.0;
    for (size_t i = 0; i + 1 < S->poly.n; i++) {
        const double *a = S->poly.pts + 2 * i, *b = a + 2;
        area += a[0] * b[1] - a[1] * b[0];
    }
    if (!(fabs(area) > 1e-10 * size * size)) {
        dfl_curve_sdf_free(S);
        return dfl_err_set(err, DFL_E_INPUT,
                           "degenerate closed curve: it encloses no area (signed area %g)",
                           0.5 * area);
    }
    S->orient = area > 0.0 ? 1 : -1;
    const size_t ne = S->poly.n - 1, nch = (ne + DFL_WINDING_CHUNK - 1) / DFL_WINDING_CHUNK;
    S->chunk_y = malloc((nch ? nch : 1) * 2 * sizeof(double));
    if (!S->chunk_y) {
        dfl_curve_sdf_free(S);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory for a curve SDF");
    }
    for (size_t j = 0; j < nch; j++) {
        const size_t e0 = j * DFL_WINDING_CHUNK;
        const size_t e1 = e0 + DFL_WINDING_CHUNK < ne ? e0 + DFL_WINDING_CHUNK : ne;
        double lo = S->poly.pts[2 * e0 + 1], hi = lo;
        for (size_t k = e0 + 1; k <= e1; k++) {
            lo = fmin(lo, S->poly.pts[2 * k + 1]);
            hi = fmax(hi, S->poly.pts[2 * k + 1]);
        }
        S->chunk_y[2 * j] = lo;
        S->chunk_y[2 * j + 1] = hi;
    }
    *out = S;
    return DFL_OK;
}

void dfl_curve_sdf_free(dfl_curve_sdf *S)
{
    if (!S) return;
    dfl_curve_locator_free(S->L);
    dfl_polyline_free(&S->poly);
    free(S->chunk_y);
    free(S);
}

int dfl_curve_sdf_orientation(const dfl_curve_sdf *S) { return S->orient; }

/* Winding number of the closed polygon around x (Sunday's crossing rule).
 * An edge counts only when one end has y <= x[1] and the other y > x[1],
 * so a chunk of edges whose ends all lie on one side (max y <= x[1] or
 * min y > x[1]) adds nothing and is skipped: the same count, from the few
 * chunks the line y = x[1] crosses. */
static int winding(const dfl_curve_sdf *S, const double *x)
{
    const dfl_polyline *p = &S->poly;
    const size_t ne = p->n - 1;
    int wn = 0;
    for (size_t i = 0; i < ne; i++) {
        if (i % DFL_WINDING_CHUNK == 0) {
            const double *cy = S->chunk_y + 2 * (i / DFL_WINDING_CHUNK);
            if (cy[1] <= x[1] || cy[0] > x[1]) {
                i += DFL_WINDING_CHUNK - 1;
                continue;
            }
        }
        const double *a = p->pts + 2 * i, *b = a + 2;
        double isl = (b[0] - a[0]) * (x[1] - a[1]) - (x[0] - a[0]) * (b[1] - a[1]);
        if (a[1] <= x[1]) {
            if (b[1] > x[1] && isl > 0.0) wn++;
        } else if (b[1] <= x[1] && isl < 0.0) {
            wn--;
        }
    }
    return wn;
}

void dfl_curve_sdf_from_foot(const dfl_curve_sdf *S, const double *x, const dfl_curve_foot *f,
                             int order, dfl_curve_sdf_val *o)
{
    const dfl_bspline *c = S->c;
    double D[4 * 2];
    dfl_bspline_eval(c, f->t, 3, D);
    const double *C1 = D + 2, *C2 = D + 4, *C3 = D + 6;
    double v = sqrt(C1[0] * C1[0] + C1[1] * C1[1]);
    double T[2] = {C1[0] / v, C1[1] / v};
    double N[2] = {S->orient * T[1], -S->orient * T[0]};
    double w[2] = {x[0] - f->p[0], x[1] - f->p[1]};
    int sign;
    if (f->dist > S->poly.bound) {
        o->winding = winding(S, x);
        sign = o->winding != 0 ? -1 : 1;
    } else {
        sign = N[0] * w[0] + N[1] * w[1] < 0.0 ? -1 : 1;
        o->winding = sign < 0 ? S->orient : 0;
    }
    memset(o->h, 0, sizeof o->h);
    memset(o->t3, 0, sizeof o->t3);
    o->d = sign * f->dist;
    o->t = f->t;
    o->foot[0] = f->p[0];
    o->foot[1] = f->p[1];
    o->flags = f->flags & (DFL_FOOT_MEDIAL | DFL_FOOT_FOCAL);
    double cr12 = C1[0] * C2[1] - C1[1] * C2[0], cr13 = C1[0] * C3[1] - C1[1] * C3[0];
    double dot12 = C1[0] * C2[0] + C1[1] * C2[1];
    /* dN/ds = kappa T with the outward N (curvature.h): o (C' x C'')/|C'|^3 */
    o->kappa = S->orient * cr12 / (v * v * v);
    o->kappa_s = S->orient * (cr13 / (v * v * v) - 3.0 * cr12 * dot12 / pow(v, 5)) / v;
    if ((f->flags & DFL_FOOT_END) && f->dist > 0.0) {
        /* footpoint at the joint of a clamped closed curve (a corner): there
         * d = sign |x - P| locally, whose derivatives are those of the
         * distance to the point P */
        double r = f->dist, u[2] = {w[0] / r, w[1] / r};
        o->g[0] = sign * u[0];
        o->g[1] = sign * u[1];
        if (order >= 2) {
            o->h[0] = sign * (1.0 - u[0] * u[0]) / r;
            o->h[1] = sign * (-u[0] * u[1]) / r;
            o->h[2] = sign * (1.0 - u[1] * u[1]) / r;
        }
        if (order >= 3) {
            /* d_ijk of |x - P|: (3 u_i u_j u_k - d_ij u_k - d_ik u_j - d_jk u_i) / r^2 */
            static const int I[4][3] = {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {1, 1, 1}};
            for (int q = 0; q < 4; q++) {
                int i = I[q][0], j = I[q][1], k = I[q][2];
                double val = 3.0 * u[i] * u[j] * u[k] - (i == j) * u[k] - (i == k) * u[j] -
                             (j == k) * u[i];
                o->t3[q] = sign * val / (r * r);
            }
        }
        return;
    }
    o->g[0] = N[0];
    o->g[1] = N[1];
    double g = 1.0 + o->kappa * o->d;
    if (fabs(g) < 1e-6) o->flags |= DFL_FOOT_FOCAL;
    if (order >= 2) {
        double a = o->kappa / g;
        o->h[0] = a * T[0] * T[0];
        o->h[1] = a * T[0] * T[1];
        o->h[2] = a * T[1] * T[1];
    }
    if (order >= 3) {
        double A = o->kappa_s / (g * g * g), B = -o->kappa * o->kappa / (g * g);
        static const int I[4][3] = {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {1, 1, 1}};
        for (int q = 0; q < 4; q++) {
            int i = I[q][0], j = I[q][1], k = I[q][2];
            o->t3[q] = A * T[i] * T[j] * T[k] +
                       B * (T[i] * T[j] * N[k] + T[i] * N[j] * T[k] + N[i] * T[j] * T[k]);
        }
    }
}

dfl_status dfl_curve_sdf_eval(const dfl_curve_sdf *S, const double x[2], int order,
                              dfl_curve_sdf_val *out, dfl_err *err)
{
    if (order < 0 || order > 3)
        return dfl_err_set(err, DFL_E_INPUT, "derivative order %d: expected 0..3", order);
    dfl_curve_foot f;
    dfl_status st = dfl_curve_footpoint(S->L, x, &f, err);
    if (st != DFL_OK) return st;
    dfl_curve_sdf_from_foot(S, x, &f, order, out);
    return DFL_OK;
}
