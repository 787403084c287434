/* The triangle kernel: R-equivalence of rfunc/tri3d.h triangles with one
 * eq. 4 trim (prism, or conditional with k = 2). */
#include <math.h>
#include <stdlib.h>

#include "rfunc/batch_impl.h"
#include "rfunc/rfield.h"

/* Rvachev's R0-conjunction x ^ y = x + y - sqrt(x^2 + y^2 + c) as
 * rfunc/trim.c's dfl_rfunc_conj0 computes it (without cancellation for
 * x + y > 0), with its partials.  r^2 below 1e-280 (a point on a vertex
 * line of the prism, where the reciprocal square root estimate is not
 * valid) poisons *bad so that the point falls back. */
DFL_INLINE double conj0_l(double x, double y, double c, double *dx, double *dy, double *dc,
                          double *bad)
{
    const double r2 = x * x + y * y + c;
    const double rr = rsqrt_newton(r2);
    const double r = r2 * rr, s = x + y;
    *bad += r2 < 1e-280 ? NAN : 0.0;
    *dx = 1.0 - x * rr;
    *dy = 1.0 - y * rr;
    *dc = -0.5 * rr;
    return s > 0.0 ? (2.0 * x * y - c) / (s + r) : s - r;
}

/* A triangle of rfunc/tri3d.h with eq. 4: f = (x - V_0).n, p_i = (x - V_i).m_i,
 * t = (p_0 ^ p_1) ^ p_2 (conditional: c = a f^2 under both roots), h grad h
 * = f n - mt grad t. */
DFL_INLINE void tri_term(double x, double y, double z, const dfl_rfunc_batch *b, size_t k,
                         int p, int cond, double *S, double *Vx, double *Vy, double *Vz)
{
    const double *T = b->tri + 24 * k;
    const double *n = T, *V0 = T + 3, *m0 = T + 6, *V1 = T + 9, *m1 = T + 12, *V2 = T + 15,
                 *m2 = T + 18;
    const double f = (x - V0[0]) * n[0] + (y - V0[1]) * n[1] + (z - V0[2]) * n[2];
    const double p0 = (x - V0[0]) * m0[0] + (y - V0[1]) * m0[1] + (z - V0[2]) * m0[2];
    const double p1 = (x - V1[0]) * m1[0] + (y - V1[1]) * m1[1] + (z - V1[2]) * m1[2];
    const double p2 = (x - V2[0]) * m2[0] + (y - V2[1]) * m2[1] + (z - V2[2]) * m2[2];
    const double c = cond ? b->ca * f * f : 0.0, dcdf = cond ? 2.0 * b->ca * f : 0.0;
    double ax, ay, ac, bx, by, bc, bad = 0.0;
    const double t1 = conj0_l(p0, p1, c, &ax, &ay, &ac, &bad);
    const double t = conj0_l(t1, p2, c, &bx, &by, &bc, &bad);
    const double cn = (bx * ac + bc) * dcdf;
    const double mt = 0.5 * (fabs(t) - t);
    const double q = pow_term(f * f + mt * mt, p, S);
    *S += bad;
    for (int j = 0; j < 3; j++) {
        const double gt = bx * (ax * m0[j] + ay * m1[j]) + by * m2[j] + cn * n[j];
        const double g = f * n[j] - mt * gt;
        if (j == 0) *Vx += q * g;
        else if (j == 1) *Vy += q * g;
        else *Vz += q * g;
    }
}

DFL_INLINE void sums_tri_p(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out,
                           const int p, const int cond)
{
    const size_t n = b->n;
    for (size_t i0 = 0; i0 < m; i0 += LANES) {
        const size_t c = m - i0 < LANES ? m - i0 : LANES;
        double X[LANES], Y[LANES], Z[LANES], S[LANES] = {0}, Vx[LANES] = {0}, Vy[LANES] = {0},
                                             Vz[LANES] = {0};
        for (size_t l = 0; l < LANES; l++) {
            const size_t i = i0 + (l < c ? l : c - 1);
            X[l] = pts[3 * i];
            Y[l] = pts[3 * i + 1];
            Z[l] = pts[3 * i + 2];
        }
        for (size_t k = 0; k < n; k++) {
#pragma omp simd
            for (int l = 0; l < LANES; l++)
                tri_term(X[l], Y[l], Z[l], b, k, p, cond, &S[l], &Vx[l], &Vy[l], &Vz[l]);
        }
        for (size_t l = 0; l < c; l++) {
            out[4 * (i0 + l)] = S[l];
            out[4 * (i0 + l) + 1] = Vx[l];
            out[4 * (i0 + l) + 2] = Vy[l];
            out[4 * (i0 + l) + 3] = Vz[l];
        }
    }
}

DFL_CLONES
void dfl_rfunc_batch_sums_tri(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    switch (b->p * 2 + b->cond) {
    case 4: sums_tri_p(b, m, pts, out, 2, 0); break;
    case 5: sums_tri_p(b, m, pts, out, 2, 1); break;
    default:
        if (b->cond) sums_tri_p(b, m, pts, out, b->p, 1);
        else sums_tri_p(b, m, pts, out, b->p, 0);
        break;
    }
}

dfl_status dfl_rfunc_batch_triangles(const dfl_rfunc_tri *t, size_t n, int p,
                                     dfl_rfunc_batch **out, dfl_err *err)
{
    if (n < 2) return dfl_err_set(err, DFL_E_INPUT, "batch: %zu triangles (need at least 2)", n);
    const dfl_rfunc_tri_opts o = t[0].o;
    for (size_t k = 0; k < n; k++)
        if (t[k].o.smooth || t[k].o.trim != o.trim || t[k].o.a != o.a ||
            (o.trim == DFL_RFUNC_TRI_CONDITIONAL && t[k].o.k != 2))
            return dfl_err_set(err, DFL_E_INPUT,
                               "batch: triangles need one eq. 4 trim (conditional with k = 2)");
    dfl_rfield *r;
    dfl_status st = dfl_rfield_new(3, DFL_RFUNC_REQUIV, p, &r, err);
    if (st != DFL_OK) return st;
    dfl_rfield_set_fast(r, false);
    for (size_t k = 0; k < n && st == DFL_OK; k++)
        st = dfl_rfield_add_triangle(r, t[k].v[0], t[k].v[1], t[k].v[2], &t[k].o, err);
    dfl_field ref = {0};
    if (st == DFL_OK) st = dfl_rfield_finish(&r, &ref, err);
    else dfl_rfield_free(r);
    if (st != DFL_OK) return st;
    double *tri = malloc(24 * n * sizeof *tri);
    if (!tri) {
        dfl_field_destroy(&ref);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory for %zu triangles", n);
    }
    dfl_rfunc_batch *b;
    if ((st = dfl_rfunc_batch_alloc(3, p, n, &ref, &b, err)) != DFL_OK) {
        free(tri);
        return st;
    }
    b->tris = 1;
    b->cond = o.trim == DFL_RFUNC_TRI_CONDITIONAL;
    b->ca = o.a;
    b->tri = tri;
    for (size_t k = 0; k < n; k++) {
        double *T = tri + 24 * k;
        memcpy(T, t[k].n, 3 * sizeof *T);
        for (int i = 0; i < 3; i++) {
            memcpy(T + 3 + 6 * i, t[k].v[i], 3 * sizeof *T);
            memcpy(T + 6 + 6 * i, t[k].m[i], 3 * sizeof *T);
        }
    }
    *out = b;
    return DFL_OK;
}

