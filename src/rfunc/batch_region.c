/* The convex-region kernel: R-equivalence of 2D convex polygons. */
#include <math.h>
#include <stdlib.h>

#include "rfunc/batch_impl.h"
#include "rfunc/rfield.h"

/* A convex region of rfunc/region.h: h^2 = sum_i max(-p_i, 0)^2 over its
 * edges, p_i = (x - V_i).m_i, h grad h = -sum_i max(-p_i, 0) m_i (0 inside,
 * where the point falls back: h^-p is infinite). */
DFL_INLINE void region_term(double x, double y, const dfl_rfunc_batch *b, size_t k, int p,
                            double *S, double *Vx, double *Vy)
{
    double h2 = 0.0, gx = 0.0, gy = 0.0;
    for (size_t e = b->roff[k]; e < b->roff[k + 1]; e++) {
        const double q = -((x - b->rv[2 * e]) * b->rm[2 * e] + (y - b->rv[2 * e + 1]) * b->rm[2 * e + 1]);
        const double mq = 0.5 * (q + fabs(q));
        h2 += mq * mq;
        gx -= mq * b->rm[2 * e];
        gy -= mq * b->rm[2 * e + 1];
    }
    const double q = pow_term(h2, p, S);
    *Vx += q * gx;
    *Vy += q * gy;
}

DFL_INLINE void sums_gen_p(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out,
                           const int p, const int dim, const int strip)
{
    (void)strip, (void)dim;
    DFL_BATCH_SUMS(b, m, pts, out, 2, region_term(X[l], Y[l], b, k, p, &S[l], &Vx[l], &Vy[l]));
}

#define DFL_GEN_CASES(dim, strip)                                  \
    switch (b->p) {                                                \
    case 1: sums_gen_p(b, m, pts, out, 1, dim, strip); break;      \
    case 2: sums_gen_p(b, m, pts, out, 2, dim, strip); break;      \
    case 3: sums_gen_p(b, m, pts, out, 3, dim, strip); break;      \
    case 4: sums_gen_p(b, m, pts, out, 4, dim, strip); break;      \
    case 7: sums_gen_p(b, m, pts, out, 7, dim, strip); break;      \
    case 12: sums_gen_p(b, m, pts, out, 12, dim, strip); break;    \
    default: sums_gen_p(b, m, pts, out, b->p, dim, strip); break;  \
    }

DFL_CLONES
void dfl_rfunc_batch_sums_reg(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    DFL_GEN_CASES(2, -2)
}

dfl_status dfl_rfunc_batch_regions(const dfl_rfunc_region *r, size_t n, int p,
                                   dfl_rfunc_batch **out, dfl_err *err)
{
    if (n < 2) return dfl_err_set(err, DFL_E_INPUT, "batch: %zu regions (need at least 2)", n);
    dfl_rfield *rf;
    dfl_status st = dfl_rfield_new(2, DFL_RFUNC_REQUIV, p, &rf, err);
    if (st != DFL_OK) return st;
    dfl_rfield_set_fast(rf, false);
    size_t ne = 0;
    for (size_t k = 0; k < n && st == DFL_OK; k++) {
        st = dfl_rfield_add_region(rf, r[k].v, r[k].n, err);
        ne += r[k].n;
    }
    dfl_field ref = {0};
    if (st == DFL_OK) st = dfl_rfield_finish(&rf, &ref, err);
    else dfl_rfield_free(rf);
    if (st != DFL_OK) return st;
    size_t *off = malloc((n + 1) * sizeof *off);
    double *ev = malloc(4 * ne * sizeof *ev);
    dfl_rfunc_batch *b = NULL;
    if (!off || !ev) {
        free(off), free(ev);
        dfl_field_destroy(&ref);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory for %zu regions", n);
    }
    if ((st = dfl_rfunc_batch_alloc(2, p, n, &ref, &b, err)) != DFL_OK) {
        free(off), free(ev);
        return st;
    }
    b->regions = 1;
    b->roff = off;
    b->rv = ev;
    b->rm = ev + 2 * ne;
    off[0] = 0;
    for (size_t k = 0; k < n; k++) {
        memcpy(b->rv + 2 * off[k], r[k].v, 2 * r[k].n * sizeof *ev);
        memcpy(b->rm + 2 * off[k], r[k].m, 2 * r[k].n * sizeof *ev);
        off[k + 1] = off[k] + r[k].n;
    }
    *out = b;
    return DFL_OK;
}

