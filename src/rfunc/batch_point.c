/* The point-part kernel: R-equivalence of points, h = |x - c|. */
#include <math.h>
#include <stdlib.h>

#include "rfunc/batch_impl.h"
#include "rfunc/rfield.h"

/* A point part: h^2 = |x - c|^2, h grad h = x - c. */
DFL_INLINE void point_term(double x, double y, double z, const dfl_rfunc_batch *b, size_t k,
                           int p, int dim, double *S, double *Vx, double *Vy, double *Vz)
{
    const double wx = x - b->ax[k], wy = y - b->ay[k], wz = dim == 3 ? z - b->az[k] : 0.0;
    const double q = pow_term(wx * wx + wy * wy + wz * wz, p, S);
    *Vx += q * wx;
    *Vy += q * wy;
    *Vz += q * wz;
}

DFL_INLINE void sums_gen_p(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out,
                           const int p, const int dim, const int strip)
{
    (void)strip;
    if (dim == 2)
        DFL_BATCH_SUMS(b, m, pts, out, 2,
                       point_term(X[l], Y[l], 0.0, b, k, p, 2, &S[l], &Vx[l], &Vy[l], &Vz[l]));
    else
        DFL_BATCH_SUMS(b, m, pts, out, 3,
                       point_term(X[l], Y[l], Z[l], b, k, p, 3, &S[l], &Vx[l], &Vy[l], &Vz[l]));
}

DFL_INLINE void sums_points2_body(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    DFL_GEN_CASES(2, -1)
}
DFL_ISA_KERNEL(sums_points2, (const dfl_rfunc_batch *b, size_t m, const double *pts, double *out), (b, m, pts, out))

DFL_INLINE void sums_points3_body(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    DFL_GEN_CASES(3, -1)
}
DFL_ISA_KERNEL(sums_points3, (const dfl_rfunc_batch *b, size_t m, const double *pts, double *out), (b, m, pts, out))

void dfl_rfunc_batch_sums_pts(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    if (b->dim == 3) sums_points3(b, m, pts, out);
    else sums_points2(b, m, pts, out);
}

dfl_status dfl_rfunc_batch_points(int dim, const double *c, size_t n, int p,
                                  dfl_rfunc_batch **out, dfl_err *err)
{
    if (n < 2) return dfl_err_set(err, DFL_E_INPUT, "batch: %zu points (need at least 2)", n);
    dfl_rfield *r;
    dfl_status st = dfl_rfield_new(dim, DFL_RFUNC_REQUIV, p, &r, err);
    if (st != DFL_OK) return st;
    dfl_rfield_set_fast(r, false);
    for (size_t i = 0; i < n && st == DFL_OK; i++) st = dfl_rfield_add_point(r, c + (size_t)dim * i, err);
    dfl_field ref = {0};
    if (st == DFL_OK) st = dfl_rfield_finish(&r, &ref, err);
    else dfl_rfield_free(r);
    if (st != DFL_OK) return st;
    dfl_rfunc_batch *b;
    if ((st = dfl_rfunc_batch_alloc(dim, p, n, &ref, &b, err)) != DFL_OK) return st;
    b->points = 1;
    for (size_t k = 0; k < n; k++) {
        b->ax[k] = c[(size_t)dim * k];
        b->ay[k] = c[(size_t)dim * k + 1];
        b->az[k] = dim == 3 ? c[3 * k + 2] : 0.0;
    }
    *out = b;
    return DFL_OK;
}

