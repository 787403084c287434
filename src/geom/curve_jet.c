/* Jets of the distance to a curve through its footpoint: the footpoint is
 * followed in Taylor arithmetic along the ray (curve_sdf.h). */
#include "geom/foot_internal.h"

#include <math.h>

#define KMAX DFL_BSPLINE_MAX_ORDER

/* sum_m a[m] delta^m / m!  for m = 0..M (Horner). */
static void taylor_compose(const double *a, int stride, int M, const dfl_jet *delta, int K,
                           dfl_jet *out)
{
    double fact[KMAX + 2];
    fact[0] = 1.0;
    for (int m = 1; m <= M; m++) fact[m] = fact[m - 1] * m;
    dfl_jet acc;
    dfl_jet_const(a[M * stride] / fact[M], K, &acc);
    for (int m = M - 1; m >= 0; m--) {
        dfl_jet_mul(&acc, delta, &acc);
        dfl_jet_add_const(&acc, a[m * stride] / fact[m], &acc);
    }
    *out = acc;
}

/* Jet of the footpoint branch through foot f: writes the residual jets
 * r_j(s) = C_j(t(s)) - x_j - s dir_j and C'_j(t(s)).  side: piece used. */
static dfl_status follow_foot(const dfl_bspline *c, const double *x, const double *dir, int K,
                              double t, int side, int fixed, dfl_jet *r, dfl_jet *c1,
                              dfl_jet *delta_out, dfl_err *err)
{
    const int dim = c->dim, p = c->order - 1;
    double D[(KMAX + 3) * 3];
    dfl_bspline_eval_side(c, t, side, p + 2, D);
    dfl_jet delta, X[3];
    dfl_jet_zero(&delta);
    for (int j = 0; j < dim; j++) dfl_jet_linear(x[j], dir[j], K, &X[j]);
    int iters = 0;
    while ((1 << iters) <= K + 1) iters++;
    iters += 1;
    if (fixed) iters = 0;
    dfl_jet C[3], C1[3], C2[3], R[3];
    for (int it = 0; it <= iters; it++) {
        for (int j = 0; j < dim; j++) {
            taylor_compose(D + j, dim, p, &delta, K, &C[j]);
            taylor_compose(D + dim + j, dim, p, &delta, K, &C1[j]);
            taylor_compose(D + 2 * dim + j, dim, p, &delta, K, &C2[j]);
            dfl_jet_sub(&C[j], &X[j], &R[j]);
        }
        if (it == iters) break;
        /* Newton on F = C'.(C - x): delta -= F / F' */
        dfl_jet F, Fp, tmp;
        dfl_jet_zero(&F);
        dfl_jet_zero(&Fp);
        for (int j = 0; j < dim; j++) {
            dfl_jet_mul(&C1[j], &R[j], &tmp);
            dfl_jet_add(&F, &tmp, &F);
            dfl_jet_mul(&C2[j], &R[j], &tmp);
            dfl_jet_add(&Fp, &tmp, &Fp);
            dfl_jet_mul(&C1[j], &C1[j], &tmp);
            dfl_jet_add(&Fp, &tmp, &Fp);
        }
        dfl_status st = dfl_jet_div(&F, &Fp, &tmp, err);
        if (st != DFL_OK) return st;
        dfl_jet_sub(&delta, &tmp, &delta);
        /* t* is the root: delta(0) = 0 exactly (drops rounding residue) */
        double a[DFL_JET_MAX + 1];
        a[0] = 0.0;
        for (int k = 1; k <= K; k++) {
            double v = dfl_jet_coeff(&delta, k);
            a[k] = isfinite(v) ? v : 0.0;
        }
        dfl_jet_poly(a, K + 1, K, &delta);
    }
    for (int j = 0; j < dim; j++) {
        r[j] = R[j];
        c1[j] = C1[j];
    }
    if (delta_out) *delta_out = delta;
    return DFL_OK;
}

static int is_knot(const dfl_bspline *c, double t)
{
    for (size_t i = 0; i < c->n + (size_t)c->order; i++)
        if (c->knots[i] == t) return 1;
    return 0;
}

/* sign of the first non-zero coefficient of delta (0 if none) */
static int lead_sign(const dfl_jet *d, int K)
{
    for (int k = 1; k <= K; k++) {
        double v = dfl_jet_coeff(d, k);
        if (isfinite(v) && fabs(v) > 0.0) return v > 0 ? 1 : -1;
    }
    return 0;
}

/* mode 0: unsigned |x - C|; mode 1: signed N.(x - C) with orientation o */
static dfl_status branch_jet(const dfl_bspline *c, const double *x, const double *dir, int K,
                             const dfl_curve_foot *f, int mode, int orient, int sign,
                             dfl_jet *out, dfl_err *err)
{
    const int dim = c->dim;
    dfl_jet r[3], c1[3], delta, acc, tmp;
    int fixed = (f->flags & DFL_FOOT_END) != 0;
    if (fixed && !c->closed) {
        /* the footpoint stays at the end while g'(t_end) pushes outward */
        double D[2 * 3];
        dfl_bspline_eval(c, f->t, 1, D);
        double g1 = 0.0;
        for (int j = 0; j < dim; j++) g1 += D[dim + j] * (D[j] - x[j]);
        /* first-order change of g' along dir: -C'.dir; stays if the sign holds */
        double dg = 0.0;
        for (int j = 0; j < dim; j++) dg -= D[dim + j] * dir[j];
        int at_start = f->t <= c->t0;
        double gs = g1 != 0.0 ? g1 : dg;
        fixed = at_start ? gs >= 0.0 : gs <= 0.0;
    }
    int side = 1;
    dfl_status st = follow_foot(c, x, dir, K, f->t, side, fixed, r, c1, &delta, err);
    if (st != DFL_OK) return st;
    if (!fixed && (is_knot(c, f->t) || (c->closed && f->t == c->t0)) && lead_sign(&delta, K) < 0) {
        side = -1;
        if ((st = follow_foot(c, x, dir, K, f->t, side, fixed, r, c1, &delta, err)) != DFL_OK)
            return st;
    }
    if (mode == 0 || fixed) {
        dfl_jet_zero(&acc);
        for (int j = 0; j < dim; j++) {
            dfl_jet_mul(&r[j], &r[j], &tmp);
            dfl_jet_add(&acc, &tmp, &acc);
        }
        if ((st = dfl_jet_sqrt(&acc, out, err)) != DFL_OK) return st;
        if (mode == 1 && sign < 0) dfl_jet_neg(out, out);
        return DFL_OK;
    }
    /* d = N.(x - C) = -N.r, N = orient (C'_y, -C'_x) / |C'| */
    dfl_jet v2, v, num;
    dfl_jet_mul(&c1[0], &c1[0], &v2);
    dfl_jet_mul(&c1[1], &c1[1], &tmp);
    dfl_jet_add(&v2, &tmp, &v2);
    if ((st = dfl_jet_sqrt(&v2, &v, err)) != DFL_OK) return st;
    dfl_jet_mul(&c1[1], &r[0], &num);
    dfl_jet_mul(&c1[0], &r[1], &tmp);
    dfl_jet_sub(&num, &tmp, &num);
    dfl_jet_scale(&num, -(double)orient, &num);
    return dfl_jet_div(&num, &v, out, err);
}

/* lexicographic comparison of jets (value first) with a small tolerance */
static int jet_cmp(const dfl_jet *a, const dfl_jet *b, int K)
{
    for (int k = 0; k <= K; k++) {
        double x = dfl_jet_coeff(a, k), y = dfl_jet_coeff(b, k);
        if (!isfinite(x) || !isfinite(y)) return 0;
        double tol = 1e-9 * (fabs(x) + fabs(y)) + 1e-13;
        if (x < y - tol) return -1;
        if (x > y + tol) return 1;
    }
    return 0;
}

dfl_status dfl_curve_dist_jet(const dfl_curve_locator *L, const dfl_curve_sdf *S, const double *x,
                              const double *dir, int K, dfl_jet *out, dfl_err *err)
{
    dfl_status st = dfl_jet_check_order(K, err);
    if (st != DFL_OK) return st;
    dfl_curve_foot fs[DFL_FOOT_MAX_CAND];
    dfl_err e2;
    int n = dfl_curve_footpoints(L, x, fs, DFL_FOOT_MAX_CAND, &e2);
    if (n < 1) return dfl_err_set(err, DFL_E_NUMERIC, "footpoint search failed: %s", e2.msg);
    int sign = 1, orient = 1, mode = S ? 1 : 0;
    if (S) {
        dfl_curve_sdf_val v;
        dfl_curve_sdf_from_foot(S, x, &fs[0], 0, &v);
        sign = v.d < 0.0 ? -1 : 1;
        orient = S->orient;
    }
    int nt = (fs[0].flags & DFL_FOOT_MEDIAL) ? n : 1;
    dfl_jet best;
    int have = 0;
    for (int q = 0; q < nt; q++) {
        if (q > 0 && !(fs[q].flags & DFL_FOOT_MEDIAL)) break;
        dfl_jet j;
        st = branch_jet(L->c, x, dir, K, &fs[q], mode, orient, sign, &j, err);
        if (st != DFL_OK) return st;
        /* d for s > 0 is the nearest branch: min of |.|, i.e. the smallest
         * jet outside and the largest (least negative) inside */
        if (!have || (sign > 0 ? jet_cmp(&j, &best, K) < 0 : jet_cmp(&j, &best, K) > 0)) best = j;
        have = 1;
    }
    *out = best;
    return DFL_OK;
}

dfl_status dfl_curve_sdf_jet(const dfl_curve_sdf *S, const double x[2], const double dir[2], int K,
                             dfl_jet *out, dfl_err *err)
{
    return dfl_curve_dist_jet(S->L, S, x, dir, K, out, err);
}
