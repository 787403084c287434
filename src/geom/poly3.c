#include "geom/poly3.h"

#include <assert.h>
#include <string.h>

int dfl_poly3_term(dfl_poly3 *P, double c, int e0, int e1, int e2)
{
    assert(e0 >= 0 && e1 >= 0 && e2 >= 0);
    if (c == 0.0) return 1;
    for (int k = 0; k < P->n; k++) {
        if (P->e[k][0] == e0 && P->e[k][1] == e1 && P->e[k][2] == e2) {
            P->c[k] += c;
            return 1;
        }
    }
    if (P->n >= DFL_POLY3_MAX_TERMS || e0 + e1 + e2 > DFL_POLY3_MAX_DEGREE) return 0;
    P->c[P->n] = c;
    P->e[P->n][0] = e0;
    P->e[P->n][1] = e1;
    P->e[P->n][2] = e2;
    P->n++;
    if (e0 + e1 + e2 > P->deg) P->deg = e0 + e1 + e2;
    return 1;
}

int dfl_poly3_mul(const dfl_poly3 *A, const dfl_poly3 *B, dfl_poly3 *out)
{
    memset(out, 0, sizeof *out);
    for (int i = 0; i < A->n; i++)
        for (int j = 0; j < B->n; j++)
            if (!dfl_poly3_term(out, A->c[i] * B->c[j], A->e[i][0] + B->e[j][0],
                                A->e[i][1] + B->e[j][1], A->e[i][2] + B->e[j][2]))
                return 0;
    return 1;
}

int dfl_poly3_axpy(double k, const dfl_poly3 *A, dfl_poly3 *P)
{
    for (int i = 0; i < A->n; i++)
        if (!dfl_poly3_term(P, k * A->c[i], A->e[i][0], A->e[i][1], A->e[i][2])) return 0;
    return 1;
}

void dfl_poly3_deriv(const dfl_poly3 *P, int axis, dfl_poly3 *out)
{
    assert(axis >= 0 && axis < 3);
    memset(out, 0, sizeof *out);
    for (int k = 0; k < P->n; k++) {
        int e[3] = {P->e[k][0], P->e[k][1], P->e[k][2]};
        if (e[axis] == 0) continue;
        double c = P->c[k] * e[axis];
        e[axis]--;
        dfl_poly3_term(out, c, e[0], e[1], e[2]); /* a derivative has no more terms */
    }
}

/* Orders 0 to 2 (the implicit footpoints' hot path): the general loop
 * below written out, the same products in the same order, so the same
 * bits for every input, non-finite ones too.  Per axis and term,
 * D_m = e (e-1)..(e-m+1) q^(e-m) (0 when e < m); the factorial factor is
 * the general loop's product of small integers, exact in double, and
 * 1.0 * q^e is q^e.  H's lower triangle is its upper one: the general
 * loop forms H[3i + j] and H[3j + i] from the same factors in the same
 * order. */
static double eval_low(const dfl_poly3 *P, double (*pw)[DFL_POLY3_MAX_DEGREE + 1], int order,
                       double gr[3], double H[9])
{
    double g = 0.0, g0 = 0.0, g1 = 0.0, g2 = 0.0;
    double h00 = 0.0, h01 = 0.0, h02 = 0.0, h11 = 0.0, h12 = 0.0, h22 = 0.0;
    for (int k = 0; k < P->n; k++) {
        const int e0 = P->e[k][0], e1 = P->e[k][1], e2 = P->e[k][2];
        const double c = P->c[k];
        const double a0 = pw[0][e0], b0 = pw[1][e1], c0 = pw[2][e2];
        g += c * a0 * b0 * c0;
        if (order < 1) continue;
        const double a1 = e0 >= 1 ? (double)e0 * pw[0][e0 - 1] : 0.0;
        const double b1 = e1 >= 1 ? (double)e1 * pw[1][e1 - 1] : 0.0;
        const double c1 = e2 >= 1 ? (double)e2 * pw[2][e2 - 1] : 0.0;
        g0 += c * a1 * b0 * c0;
        g1 += c * a0 * b1 * c0;
        g2 += c * a0 * b0 * c1;
        if (order < 2) continue;
        const double a2 = e0 >= 2 ? (double)(e0 * (e0 - 1)) * pw[0][e0 - 2] : 0.0;
        const double b2 = e1 >= 2 ? (double)(e1 * (e1 - 1)) * pw[1][e1 - 2] : 0.0;
        const double c2 = e2 >= 2 ? (double)(e2 * (e2 - 1)) * pw[2][e2 - 2] : 0.0;
        h00 += c * a2 * b0 * c0;
        h01 += c * a1 * b1 * c0;
        h02 += c * a1 * b0 * c1;
        h11 += c * a0 * b2 * c0;
        h12 += c * a0 * b1 * c1;
        h22 += c * a0 * b0 * c2;
    }
    if (order >= 1) {
        gr[0] = g0;
        gr[1] = g1;
        gr[2] = g2;
    }
    if (order >= 2) {
        H[0] = h00, H[1] = h01, H[2] = h02;
        H[3] = h01, H[4] = h11, H[5] = h12;
        H[6] = h02, H[7] = h12, H[8] = h22;
    }
    return g;
}

double dfl_poly3_eval(const dfl_poly3 *P, const double q[3], int order, double gr[3],
                      double H[9], double T[27])
{
    assert(order >= 0 && order <= 3);
    double pw[3][DFL_POLY3_MAX_DEGREE + 1];
    for (int a = 0; a < 3; a++) {
        pw[a][0] = 1.0;
        for (int k = 1; k <= P->deg; k++) pw[a][k] = pw[a][k - 1] * q[a];
    }
    if (order <= 2) return eval_low(P, pw, order, gr, H);
    double g = 0.0;
    if (order >= 1) memset(gr, 0, 3 * sizeof *gr);
    if (order >= 2) memset(H, 0, 9 * sizeof *H);
    if (order >= 3) memset(T, 0, 27 * sizeof *T);
    for (int k = 0; k < P->n; k++) {
        /* D[a][m] = d^m/dq_a^m q_a^e_a */
        double D[3][4];
        for (int a = 0; a < 3; a++) {
            int e = P->e[k][a];
            double ff = 1.0;
            for (int m = 0; m <= order; m++) {
                D[a][m] = (e >= m) ? ff * pw[a][e - m] : 0.0;
                ff *= (double)(e - m);
            }
        }
        double c = P->c[k];
        g += c * D[0][0] * D[1][0] * D[2][0];
        if (order < 1) continue;
        for (int i = 0; i < 3; i++) {
            int m[3] = {0, 0, 0};
            m[i]++;
            gr[i] += c * D[0][m[0]] * D[1][m[1]] * D[2][m[2]];
            if (order < 2) continue;
            for (int j = 0; j < 3; j++) {
                int mj[3] = {m[0], m[1], m[2]};
                mj[j]++;
                H[3 * i + j] += c * D[0][mj[0]] * D[1][mj[1]] * D[2][mj[2]];
                if (order < 3) continue;
                for (int l = 0; l < 3; l++) {
                    int ml[3] = {mj[0], mj[1], mj[2]};
                    ml[l]++;
                    T[9 * i + 3 * j + l] += c * D[0][ml[0]] * D[1][ml[1]] * D[2][ml[2]];
                }
            }
        }
    }
    return g;
}

void dfl_poly3_eval_series(const dfl_poly3 *P, const dfl_series X[3], int K, dfl_series *out)
{
    dfl_series pw[3][DFL_POLY3_MAX_DEGREE + 1];
    for (int a = 0; a < 3; a++) {
        dfl_series_zero(&pw[a][0]);
        pw[a][0].c[0] = 1.0;
        for (int k = 1; k <= P->deg; k++) dfl_series_mul(&pw[a][k - 1], &X[a], K, &pw[a][k]);
    }
    dfl_series_zero(out);
    for (int t = 0; t < P->n; t++) {
        dfl_series m;
        dfl_series_mul(&pw[0][P->e[t][0]], &pw[1][P->e[t][1]], K, &m);
        dfl_series_mul(&m, &pw[2][P->e[t][2]], K, &m);
        dfl_series_axpy(P->c[t], &m, K, out);
    }
}
