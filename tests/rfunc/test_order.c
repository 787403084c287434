/* bs04 sec. 2.3: normalization orders of joined fields, measured with jets
 * at interior points of the parts (away from the joins), for every join,
 * trim and p = 1..12.
 *
 * Predictions (join.h, trim.h).  At an interior point x of part i, along its
 * unit normal, h_i = s + T s^7 + ... with T = 0 for eq. 4 and
 * T = 1/(32 t0^2) for eq. 5 (t0 = trim value of part i at x); the other
 * parts are positive.
 *   R-equivalence:   u = h_i (1 + C h_i^p)^(-1/p) = h_i - (C/p) h_i^(p+1) + ...
 *                    C = sum_(j != i) h_j(x)^(-p);
 *   corrected:       the same with C - sum_v qt_v(x)^(-p), qt_v = max(q_v, h
 *                    of v's two segments) (the guard of join.h);
 *   R-conjunction:   u = h_i - (B/p) h_i^p + ...,  B = u_(i-1)(x)^(1-p)
 *                    (the fold of the parts before i, if any) + sum_(j > i)
 *                    h_j(x)^(1-p).
 * So the first non-zero coefficient after s^1 is at k = p+1 (R-conjunction:
 * k = p) unless the eq. 5 term s^7 comes first; both add when they meet.
 * The test asserts d1 = 1, zero coefficients below k, and the predicted
 * value at k: that is order p (requiv), p - 1 (rconj), capped at 6 by the
 * smooth trim. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rfunc/join.h"
#include "rfunc/rfield.h"
#include "rfunc/segment.h"
#include "rfunc/tri3d.h"
#include "rfunc_util.h"

#define K_JET 14

static const dfl_rfunc_trim trims[4] = {DFL_RFUNC_TRIM_DISK, DFL_RFUNC_TRIM_DISK_SMOOTH,
                                        DFL_RFUNC_TRIM_STRIP, DFL_RFUNC_TRIM_STRIP_SMOOTH};
static const dfl_rfunc_join joins[3] = {DFL_RFUNC_REQUIV, DFL_RFUNC_RCONJ,
                                        DFL_RFUNC_REQUIV_CORRECTED};

/* Predicted (k, coefficient of s^k) of the first non-zero term after s. */
static void predict(dfl_rfunc_join join, int p, double joinsum, double T, int *k, double *c)
{
    const int kj = join == DFL_RFUNC_RCONJ ? p : p + 1;
    const double cj = -joinsum / p;
    if (joinsum == 0.0) {
        /* The join term vanishes identically (corrected join whose guards
         * cancel every other part): u = h_i, only the trim term remains. */
        *k = T == 0.0 ? K_JET + 1 : 7;
        *c = T;
    } else if (T == 0.0 || kj < 7) {
        *k = kj;
        *c = cj;
    } else if (kj == 7) {
        *k = 7;
        *c = cj + T;
    } else {
        *k = 7;
        *c = T;
    }
}

/* scale (may be NULL): a jet whose coefficients bound the size of terms
 * that cancel in j (rounding residue ~ 1e-16 of them). */
static void check_jet(const dfl_jet *j, int k, double c, const dfl_jet *scale, const char *what)
{
    const int kk = k > K_JET ? K_JET : k;
    cr_assert(dfl_jet_order(j) >= kk, "%s: jet order %d < %d", what, dfl_jet_order(j), kk);
    cr_assert(fabs(dfl_jet_coeff(j, 0)) <= 1e-15, "%s: u(x) = %g", what, dfl_jet_coeff(j, 0));
    cr_assert(fabs(dfl_jet_deriv(j, 1) - 1.0) <= 1e-12, "%s: d1 = %.17g", what,
              dfl_jet_deriv(j, 1));
    if (k > K_JET) { /* normalized beyond the jet's order */
        for (int m = 2; m <= K_JET; m++)
            cr_assert(fabs(dfl_jet_coeff(j, m)) <=
                          1e-9 + (scale ? 1e-12 * fabs(dfl_jet_coeff(scale, m)) : 0.0),
                      "%s: coefficient %d = %g", what, m, dfl_jet_coeff(j, m));
        return;
    }
    cr_assert(fabs(c) > 1e-12, "%s: predicted coefficient vanishes", what);
    for (int m = 2; m < k; m++)
        cr_assert(fabs(dfl_jet_coeff(j, m)) <= 1e-9 * (1 + fabs(c)),
                  "%s: coefficient %d = %g should vanish (order %d)", what, m,
                  dfl_jet_coeff(j, m), k - 1);
    cr_assert(fabs(dfl_jet_coeff(j, k) - c) <= 1e-8 * fabs(c),
              "%s: coefficient %d = %.17g, predicted %.17g", what, k, dfl_jet_coeff(j, k), c);
}

static void polyline_orders(int dim, const double *v, size_t n, bool closed)
{
    const size_t nseg = closed ? n : n - 1;
    dfl_rfunc_seg *segs = calloc(nseg, sizeof *segs);
    for (int it = 0; it < 4; it++) {
        const dfl_rfunc_trim trim = trims[it];
        const int smooth = trim == DFL_RFUNC_TRIM_DISK_SMOOTH || trim == DFL_RFUNC_TRIM_STRIP_SMOOTH;
        for (size_t i = 0; i < nseg; i++)
            cr_assert_eq(dfl_rfunc_seg_init(dim, v + i * dim, v + ((i + 1) % n) * dim, trim,
                                            &segs[i], NULL),
                         DFL_OK);
        for (int ij = 0; ij < 3; ij++)
            for (int p = 1; p <= 12; p++) {
                dfl_field f;
                dfl_err err;
                dfl_status st = dfl_rfield_polyline(dim, v, n, closed, joins[ij], p, trim, &f, &err);
                if (joins[ij] == DFL_RFUNC_RCONJ && p == 1) {
                    /* a + b - (a + b) = 0: rejected, not a field. */
                    cr_assert_eq(st, DFL_E_INPUT);
                    continue;
                }
                cr_assert_eq(st, DFL_OK, "%s", err.msg);
                dfl_field fr;
                cr_assert_eq(dfl_rfield_polyline(dim, v, n, closed, DFL_RFUNC_REQUIV, p, trim, &fr,
                                                 &err),
                             DFL_OK);
                for (size_t i = 0; i < nseg; i++)
                    for (int il = 0; il < 2; il++) {
                        const double l = il ? 0.6 : 0.35;
                        const dfl_rfunc_seg *s = &segs[i];
                        double x[3] = {0, 0, 0}, nn[3] = {0, 0, 0};
                        for (int j = 0; j < dim; j++) x[j] = s->a[j] + l * (s->b[j] - s->a[j]);
                        if (dim == 2) {
                            nn[0] = s->n1[0];
                            nn[1] = s->n1[1];
                        } else {
                            const double w = 0.3 + 0.7 * l;
                            for (int j = 0; j < 3; j++)
                                nn[j] = cos(w) * s->n1[j] + sin(w) * s->n2[j];
                        }
                        /* Join sums of the prediction, from the parts' values. */
                        double sum = 0.0, sumabs = 0.0;
                        if (joins[ij] == DFL_RFUNC_RCONJ) {
                            if (i > 0) {
                                dfl_rfunc_acc acc;
                                dfl_rfunc_acc_begin(&acc, DFL_RFUNC_RCONJ, p, dim, 0);
                                for (size_t jj = 0; jj < i; jj++)
                                    dfl_rfunc_acc_add(&acc, dfl_rfunc_seg_eval(&segs[jj], x, NULL),
                                                      NULL);
                                sum += pow(dfl_rfunc_acc_end(&acc, NULL), 1 - p);
                            }
                            for (size_t jj = i + 1; jj < nseg; jj++)
                                sum += pow(dfl_rfunc_seg_eval(&segs[jj], x, NULL), 1 - p);
                        } else {
                            for (size_t jj = 0; jj < nseg; jj++)
                                if (jj != i) {
                                    const double t = pow(dfl_rfunc_seg_eval(&segs[jj], x, NULL), -p);
                                    sum += t;
                                    sumabs += t;
                                }
                            /* Guarded vertex terms max(q_v, h_prev, h_next)^-p. */
                            if (joins[ij] == DFL_RFUNC_REQUIV_CORRECTED)
                                for (size_t vv = closed ? 0 : 1; vv < (closed ? n : n - 1); vv++) {
                                    double q = 0;
                                    for (int j = 0; j < dim; j++)
                                        q += (x[j] - v[vv * dim + j]) * (x[j] - v[vv * dim + j]);
                                    q = sqrt(q);
                                    const size_t sp = vv == 0 ? n - 1 : vv - 1;
                                    q = fmax(q, dfl_rfunc_seg_eval(&segs[sp], x, NULL));
                                    q = fmax(q, dfl_rfunc_seg_eval(&segs[vv], x, NULL));
                                    sum -= pow(q, -p);
                                    sumabs += pow(q, -p);
                                }
                        }
                        if (fabs(sum) <= 1e-12 * sumabs) sum = 0.0;
                        const double t0 = dfl_rfunc_seg_trim(s, x, NULL);
                        int k;
                        double c;
                        predict(joins[ij], p, sum, smooth ? 1.0 / (32 * t0 * t0) : 0.0, &k, &c);
                        dfl_jet j;
                        cr_assert_eq(dfl_field_jet(&f, x, nn, K_JET, &j, &err), DFL_OK, "%s",
                                     err.msg);
                        char what[160];
                        snprintf(what, sizeof what, "dim %d %s %s %s p=%d seg %zu l=%g", dim,
                                 closed ? "closed" : "open", dfl_rfunc_join_name(joins[ij]),
                                 dfl_rfunc_trim_name(trim), p, i, l);
                        /* The corrected join cancels the plain R-equivalence's
                         * terms: their size scales the rounding residue. */
                        dfl_jet jr;
                        cr_assert_eq(dfl_field_jet(&fr, x, nn, K_JET, &jr, &err), DFL_OK);
                        check_jet(&j, k, c, &jr, what);
                    }
                dfl_field_destroy(&f);
                dfl_field_destroy(&fr);
            }
    }
    free(segs);
}

Test(rfunc_order, polyline_2d_open)
{
    const double v[] = {0.0, 0.0, 1.0, 0.2, 1.6, 1.0, 2.5, 1.1, 3.0, 0.3};
    polyline_orders(2, v, 5, false);
}

Test(rfunc_order, polyline_2d_closed)
{
    const double v[] = {0.0, 0.0, 1.2, -0.1, 1.5, 0.9, 0.4, 1.3};
    polyline_orders(2, v, 4, true);
}

Test(rfunc_order, polyline_3d_open)
{
    const double v[] = {0.0, 0.0, 0.0, 1.0, 0.2, 0.3, 1.5, 1.0, -0.2, 2.2, 1.3, 0.4};
    polyline_orders(3, v, 4, false);
}

/* Two triangles sharing an edge, R-equivalence: order p (eq. 4) or
 * min(p, 6) (eq. 5), both trims, at interior points along the normal. */
Test(rfunc_order, triangles_requiv)
{
    const double A[3] = {0, 0, 0}, B[3] = {1, 0, 0.1}, C[3] = {0.2, 1, 0}, D[3] = {1.2, 0.9, 0.5};
    const double *tri[2][3] = {{A, B, C}, {B, D, C}};
    for (int opt = 0; opt < 4; opt++) {
        dfl_rfunc_tri_opts o = dfl_rfunc_tri_defaults();
        o.trim = opt & 1 ? DFL_RFUNC_TRI_PRISM : DFL_RFUNC_TRI_CONDITIONAL;
        o.smooth = opt >> 1;
        dfl_rfunc_tri t[2];
        for (int i = 0; i < 2; i++)
            cr_assert_eq(dfl_rfunc_tri_init(tri[i][0], tri[i][1], tri[i][2], &o, &t[i], NULL),
                         DFL_OK);
        for (int p = 1; p <= 12; p++) {
            dfl_rfield *r;
            dfl_field f;
            cr_assert_eq(dfl_rfield_new(3, DFL_RFUNC_REQUIV, p, &r, NULL), DFL_OK);
            for (int i = 0; i < 2; i++)
                cr_assert_eq(dfl_rfield_add_triangle(r, tri[i][0], tri[i][1], tri[i][2], &o, NULL),
                             DFL_OK);
            cr_assert_eq(dfl_rfield_finish(&r, &f, NULL), DFL_OK);
            for (int i = 0; i < 2; i++) {
                double x[3];
                for (int j = 0; j < 3; j++)
                    x[j] = 0.5 * tri[i][0][j] + 0.3 * tri[i][1][j] + 0.2 * tri[i][2][j];
                const double other = dfl_rfunc_tri_eval(&t[1 - i], x, NULL);
                const double t0 = dfl_rfunc_tri_trim_eval(&t[i], x, NULL);
                int k;
                double c;
                predict(DFL_RFUNC_REQUIV, p, pow(other, -p), o.smooth ? 1 / (32 * t0 * t0) : 0.0,
                        &k, &c);
                dfl_jet j;
                dfl_err err;
                cr_assert_eq(dfl_field_jet(&f, x, t[i].n, K_JET, &j, &err), DFL_OK, "%s", err.msg);
                char what[96];
                snprintf(what, sizeof what, "triangles opt %d p=%d tri %d", opt, p, i);
                check_jet(&j, k, c, NULL, what);
            }
            dfl_field_destroy(&f);
        }
    }
}
