#include "rfunc/mtaylor.h"

#include <assert.h>
#include <math.h>
#include <string.h>

size_t dfl_mt_size(int dim, int deg)
{
    assert(dim == 2 || dim == 3);
    const size_t n = (size_t)deg + 1;
    return dim == 2 ? n * (n + 1) / 2 : n * (n + 1) * (n + 2) / 6;
}

/* Offset of the degree-d block. */
static size_t off(int dim, int d) { return d == 0 ? 0 : dfl_mt_size(dim, d - 1); }

size_t dfl_mt_index(int dim, const int *e)
{
    if (dim == 2) return off(2, e[0] + e[1]) + (size_t)e[1];
    const int ee = e[1] + e[2];
    return off(3, e[0] + ee) + (size_t)ee * (ee + 1) / 2 + (size_t)e[2];
}

void dfl_mt_const(double a, dfl_mt *out)
{
    memset(out->c, 0, dfl_mt_size(out->dim, out->deg) * sizeof *out->c);
    out->c[0] = a;
}

void dfl_mt_copy(const dfl_mt *a, dfl_mt *out)
{
    assert(a->dim == out->dim && a->c != out->c);
    const size_t na = dfl_mt_size(a->dim, a->deg), no = dfl_mt_size(out->dim, out->deg);
    const size_t n = na < no ? na : no;
    memcpy(out->c, a->c, n * sizeof *out->c);
    if (no > n) memset(out->c + n, 0, (no - n) * sizeof *out->c);
}

void dfl_mt_axpy(const dfl_mt *a, double k, const dfl_mt *b, dfl_mt *out)
{
    assert(out->deg <= a->deg && out->deg <= b->deg);
    const size_t n = dfl_mt_size(out->dim, out->deg);
    for (size_t i = 0; i < n; i++) out->c[i] = a->c[i] + k * b->c[i];
}

void dfl_mt_scale(const dfl_mt *a, double k, dfl_mt *out)
{
    assert(out->deg <= a->deg);
    const size_t n = dfl_mt_size(out->dim, out->deg);
    for (size_t i = 0; i < n; i++) out->c[i] = k * a->c[i];
}

/* O += w A B for homogeneous blocks A (degree d1) and B (degree d2), O the
 * block of degree d1 + d2. */
static void hmul_acc(int dim, const double *A, int d1, const double *B, int d2, double w,
                     double *O)
{
    if (dim == 2) {
        for (int t1 = 0; t1 <= d1; t1++) {
            const double x = w * A[t1];
            if (x == 0.0) continue;
            for (int t2 = 0; t2 <= d2; t2++) O[t1 + t2] += x * B[t2];
        }
        return;
    }
    for (int e1 = 0; e1 <= d1; e1++)
        for (int l1 = 0; l1 <= e1; l1++) {
            const double x = w * A[e1 * (e1 + 1) / 2 + l1];
            if (x == 0.0) continue;
            for (int e2 = 0; e2 <= d2; e2++) {
                const int e = e1 + e2;
                double *o = O + e * (e + 1) / 2 + l1;
                const double *b = B + e2 * (e2 + 1) / 2;
                for (int l2 = 0; l2 <= e2; l2++) o[l2] += x * b[l2];
            }
        }
}

void dfl_mt_mul(const dfl_mt *a, const dfl_mt *b, dfl_mt *out)
{
    assert(a->dim == b->dim && a->dim == out->dim);
    assert(out->deg <= a->deg && out->deg <= b->deg);
    assert(out->c != a->c && out->c != b->c);
    const int dim = out->dim;
    memset(out->c, 0, dfl_mt_size(dim, out->deg) * sizeof *out->c);
    for (int d = 0; d <= out->deg; d++)
        for (int d1 = 0; d1 <= d; d1++)
            hmul_acc(dim, a->c + off(dim, d1), d1, b->c + off(dim, d - d1), d - d1, 1.0,
                     out->c + off(dim, d));
}

dfl_status dfl_mt_pow(const dfl_mt *a, double e, dfl_mt *out, dfl_err *err)
{
    assert(a->dim == out->dim && out->deg <= a->deg && out->c != a->c);
    const int dim = out->dim;
    const double a0 = a->c[0];
    if (!(a0 > 0.0) || !isfinite(a0))
        return dfl_err_set(err, DFL_E_NUMERIC,
                           "Taylor power: constant term %g is not positive", a0);
    memset(out->c, 0, dfl_mt_size(dim, out->deg) * sizeof *out->c);
    out->c[0] = pow(a0, e);
    const double inv = 1.0 / a0; /* g_j = a_j / a0 */
    for (int d = 1; d <= out->deg; d++)
        for (int j = 1; j <= d; j++)
            hmul_acc(dim, a->c + off(dim, j), j, out->c + off(dim, d - j), d - j,
                     ((e + 1.0) * j - d) * inv / d, out->c + off(dim, d));
    return DFL_OK;
}

void dfl_mt_deriv(const dfl_mt *a, int var, dfl_mt *out)
{
    assert(a->dim == out->dim && out->deg <= a->deg - 1 && out->c != a->c);
    assert(var >= 0 && var < a->dim);
    const int dim = a->dim;
    memset(out->c, 0, dfl_mt_size(dim, out->deg) * sizeof *out->c);
    for (int d = 1; d <= out->deg + 1; d++) {
        const double *A = a->c + off(dim, d);
        double *O = out->c + off(dim, d - 1);
        if (dim == 2) {
            /* (i, j) = (d - t, t) */
            for (int t = 0; t <= d; t++) {
                if (var == 0 && t <= d - 1) O[t] += (d - t) * A[t];
                if (var == 1 && t >= 1) O[t - 1] += t * A[t];
            }
            continue;
        }
        /* (i, j, l) = (d - e, e - l, l) */
        for (int e = 0; e <= d; e++)
            for (int l = 0; l <= e; l++) {
                const double x = A[e * (e + 1) / 2 + l];
                if (var == 0 && e <= d - 1) O[e * (e + 1) / 2 + l] += (d - e) * x;
                if (var == 1 && e - l >= 1) O[(e - 1) * e / 2 + l] += (e - l) * x;
                if (var == 2 && l >= 1) O[(e - 1) * e / 2 + l - 1] += l * x;
            }
    }
}

void dfl_mt_ray(const dfl_mt *a, const double *dir, int K, dfl_jet *out)
{
    if (K > a->deg) K = a->deg;
    if (K > DFL_JET_MAX) K = DFL_JET_MAX;
    const int dim = a->dim;
    double pw[3][DFL_JET_MAX + 1];
    for (int v = 0; v < dim; v++) {
        pw[v][0] = 1.0;
        for (int k = 1; k <= K; k++) pw[v][k] = pw[v][k - 1] * dir[v];
    }
    double c[DFL_JET_MAX + 1];
    for (int d = 0; d <= K; d++) {
        const double *A = a->c + off(dim, d);
        double s = 0.0;
        if (dim == 2) {
            for (int t = 0; t <= d; t++) s += A[t] * pw[0][d - t] * pw[1][t];
        } else {
            for (int e = 0; e <= d; e++)
                for (int l = 0; l <= e; l++)
                    s += A[e * (e + 1) / 2 + l] * pw[0][d - e] * pw[1][e - l] * pw[2][l];
        }
        c[d] = s;
    }
    dfl_jet_poly(c, K + 1, K, out);
}

static double binom(int n, int k)
{
    double r = 1.0;
    for (int i = 1; i <= k; i++) r = r * (n - k + i) / i;
    return r;
}

void dfl_mt_poly_expand(int nterms, const double *coef, const int *exps, const double *x,
                        dfl_mt *out)
{
    const int dim = out->dim;
    memset(out->c, 0, dfl_mt_size(dim, out->deg) * sizeof *out->c);
    for (int t = 0; t < nterms; t++) {
        const int *E = exps + t * dim;
        int b[3] = {0, 0, 0};
        const int e2 = dim == 3 ? E[2] : 0;
        /* (x + delta)^E = prod_i sum_b C(E_i, b) x_i^(E_i - b) delta_i^b */
        for (b[0] = 0; b[0] <= E[0]; b[0]++)
            for (b[1] = 0; b[1] <= E[1]; b[1]++)
                for (b[2] = 0; b[2] <= e2; b[2]++) {
                    if (b[0] + b[1] + b[2] > out->deg) continue;
                    double v = coef[t];
                    for (int i = 0; i < dim; i++)
                        v *= binom(E[i], b[i]) * pow(x[i], E[i] - b[i]);
                    out->c[dfl_mt_index(dim, b)] += v;
                }
    }
}
