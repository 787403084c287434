/* B-spline curves.  One general (unclamped) representation serves clamped,
 * periodic and Bezier curves, so evaluation, blossoming and the algorithms
 * built on them (polygonization, footpoints) have a single code path. */
#include "geom/bspline.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define KMAX DFL_BSPLINE_MAX_ORDER

dfl_status dfl_bspline_check_knots(int order, size_t ncp, const double *knots, size_t nknots,
                                   int periodic, dfl_err *err)
{
    if (order < 2 || order > KMAX)
        return dfl_err_set(err, DFL_E_INPUT, "order %d out of range, expected 2..%d", order, KMAX);
    size_t want = periodic ? ncp + 1 : ncp + (size_t)order;
    if (nknots != want) {
        if (periodic)
            return dfl_err_set(err, DFL_E_INPUT,
                               "%zu knots given, expected %zu (closed curve: control points + 1 "
                               "breakpoints of one period)",
                               nknots, want);
        return dfl_err_set(err, DFL_E_INPUT,
                           "%zu knots given, expected %zu (control points %zu + order %d)", nknots,
                           want, ncp, order);
    }
    for (size_t i = 0; i < nknots; i++)
        if (!isfinite(knots[i]))
            return dfl_err_set(err, DFL_E_INPUT, "knot %zu is not finite", i);
    for (size_t i = 1; i < nknots; i++)
        if (knots[i] < knots[i - 1])
            return dfl_err_set(err, DFL_E_INPUT,
                               "knots must be non-decreasing, but knot %zu (%g) < knot %zu (%g)", i,
                               knots[i], i - 1, knots[i - 1]);
    /* multiplicities: a run of equal knots longer than allowed makes the
     * curve discontinuous (interior) or leaves an empty basis function.  For
     * a closed curve u_0 and u_m are the same periodic knot, so their runs
     * add up. */
    size_t run = 1, first_run = 0;
    for (size_t i = 1; i <= nknots; i++) {
        if (i < nknots && knots[i] == knots[i - 1]) {
            run++;
            continue;
        }
        size_t first = i - run;
        if (first == 0) first_run = run;
        size_t m = run, maxm = (size_t)order - 1;
        if (!periodic && (first == 0 || i == nknots)) maxm = (size_t)order;
        if (periodic && i == nknots && first > 0) m = run + first_run - 1;
        if (m > maxm)
            return dfl_err_set(err, DFL_E_INPUT,
                               "knot %g has multiplicity %zu, expected at most %zu (order %d%s)",
                               knots[first], m, maxm, order,
                               periodic ? ", periodic" : "");
        run = 1;
    }
    if (periodic) {
        if (!(knots[nknots - 1] > knots[0]))
            return dfl_err_set(err, DFL_E_INPUT, "closed curve: period (last - first knot) must be > 0");
    } else if (!(knots[ncp] > knots[order - 1])) {
        return dfl_err_set(err, DFL_E_INPUT, "empty parameter domain [knot %d, knot %zu]",
                           order - 1, ncp);
    }
    return DFL_OK;
}

dfl_status dfl_bspline_check_control(int dim, int order, size_t ncp, const double *cp,
                                     int periodic, dfl_err *err)
{
    if (dim < 1 || dim > 3)
        return dfl_err_set(err, DFL_E_INPUT, "dimension %d out of range, expected 1..3", dim);
    if (order < 2 || order > KMAX)
        return dfl_err_set(err, DFL_E_INPUT, "order %d out of range, expected 2..%d", order, KMAX);
    size_t need = periodic ? 3 : (size_t)order;
    if (ncp < need)
        return dfl_err_set(err, DFL_E_INPUT, "%zu control points given, expected at least %zu (%s)",
                           ncp, need, periodic ? "closed curve" : "the order");
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < ncp; i++)
        for (int j = 0; j < dim; j++) {
            double v = cp[i * (size_t)dim + (size_t)j];
            if (!isfinite(v))
                return dfl_err_set(err, DFL_E_INPUT, "control point %zu is not finite", i);
            if (v < lo[j]) lo[j] = v;
            if (v > hi[j]) hi[j] = v;
        }
    double ext = 0.0;
    for (int j = 0; j < dim; j++) ext = fmax(ext, hi[j] - lo[j]);
    if (!(ext > 0.0))
        return dfl_err_set(err, DFL_E_INPUT,
                           "degenerate control polygon: all %zu control points coincide", ncp);
    return DFL_OK;
}

static dfl_status alloc_curve(int dim, int order, size_t n, dfl_bspline *c, dfl_err *err)
{
    memset(c, 0, sizeof *c);
    c->cp = malloc(n * (size_t)dim * sizeof(double));
    c->knots = malloc((n + (size_t)order) * sizeof(double));
    if (!c->cp || !c->knots) {
        free(c->cp);
        free(c->knots);
        memset(c, 0, sizeof *c);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory for a B-spline curve");
    }
    c->dim = dim;
    c->order = order;
    c->n = n;
    return DFL_OK;
}

dfl_status dfl_bspline_init(int dim, int order, size_t ncp, const double *cp,
                            const double *knots, size_t nknots, dfl_bspline *out, dfl_err *err)
{
    dfl_status st = dfl_bspline_check_control(dim, order, ncp, cp, 0, err);
    if (st != DFL_OK) return st;
    if (knots && (st = dfl_bspline_check_knots(order, ncp, knots, nknots, 0, err)) != DFL_OK)
        return st;
    dfl_bspline c;
    if ((st = alloc_curve(dim, order, ncp, &c, err)) != DFL_OK) return st;
    memcpy(c.cp, cp, ncp * (size_t)dim * sizeof(double));
    if (knots) {
        memcpy(c.knots, knots, (ncp + (size_t)order) * sizeof(double));
    } else {
        /* clamped uniform: k-fold ends, unit interior spacing */
        size_t nk = ncp + (size_t)order;
        for (size_t i = 0; i < nk; i++) {
            double v = (double)i - (double)(order - 1);
            if (v < 0.0) v = 0.0;
            double vmax = (double)(ncp - (size_t)order + 1);
            if (v > vmax) v = vmax;
            c.knots[i] = v;
        }
    }
    c.nuser = ncp;
    c.closed = 0;
    c.t0 = c.knots[order - 1];
    c.t1 = c.knots[ncp];
    *out = c;
    return DFL_OK;
}

dfl_status dfl_bspline_init_periodic(int dim, int order, size_t ncp, const double *cp,
                                     const double *breaks, size_t nbreaks, dfl_bspline *out,
                                     dfl_err *err)
{
    dfl_status st = dfl_bspline_check_control(dim, order, ncp, cp, 1, err);
    if (st != DFL_OK) return st;
    if (breaks && (st = dfl_bspline_check_knots(order, ncp, breaks, nbreaks, 1, err)) != DFL_OK)
        return st;
    const size_t m = ncp, p = (size_t)order - 1;
    dfl_bspline c;
    if ((st = alloc_curve(dim, order, m + p, &c, err)) != DFL_OK) return st;
    for (size_t i = 0; i < m + p; i++)
        memcpy(c.cp + i * (size_t)dim, cp + (i % m) * (size_t)dim, (size_t)dim * sizeof(double));
    const double u0 = breaks ? breaks[0] : 0.0;
    const double T = breaks ? breaks[m] - breaks[0] : (double)m;
    /* tau_{p+j} = u_{j mod m} + floor(j/m) T, j = -p .. m+p (m >= 3 > 0) */
    for (size_t i = 0; i < m + 2 * p + 1; i++) {
        long j = (long)i - (long)p;
        long q = j >= 0 ? j / (long)m : -((-j + (long)m - 1) / (long)m);
        long r = j - q * (long)m;
        assert(r >= 0 && r < (long)m);
        double ur = breaks ? breaks[r] : (double)r;
        c.knots[i] = ur + (double)q * T;
    }
    c.nuser = m;
    c.closed = 1;
    c.t0 = c.knots[p];
    c.t1 = c.knots[m + p];
    assert(c.t0 == u0);
    (void)u0;
    *out = c;
    return DFL_OK;
}

dfl_status dfl_bspline_init_bezier(int dim, size_t ncp, const double *cp, dfl_bspline *out,
                                   dfl_err *err)
{
    if (ncp < 2 || ncp > KMAX)
        return dfl_err_set(err, DFL_E_INPUT, "Bezier curve: %zu control points, expected 2..%d",
                           ncp, KMAX);
    double knots[2 * KMAX];
    for (size_t i = 0; i < 2 * ncp; i++) knots[i] = i < ncp ? 0.0 : 1.0;
    return dfl_bspline_init(dim, (int)ncp, ncp, cp, knots, 2 * ncp, out, err);
}

dfl_status dfl_bspline_copy(const dfl_bspline *c, dfl_bspline *out, dfl_err *err)
{
    dfl_bspline d;
    dfl_status st = alloc_curve(c->dim, c->order, c->n, &d, err);
    if (st != DFL_OK) return st;
    memcpy(d.cp, c->cp, c->n * (size_t)c->dim * sizeof(double));
    memcpy(d.knots, c->knots, (c->n + (size_t)c->order) * sizeof(double));
    d.closed = c->closed;
    d.nuser = c->nuser;
    d.t0 = c->t0;
    d.t1 = c->t1;
    *out = d;
    return DFL_OK;
}

void dfl_bspline_free(dfl_bspline *c)
{
    if (!c) return;
    free(c->cp);
    free(c->knots);
    memset(c, 0, sizeof *c);
}

double dfl_bspline_wrap(const dfl_bspline *c, double t)
{
    if (!c->closed) return t < c->t0 ? c->t0 : (t > c->t1 ? c->t1 : t);
    if (t >= c->t0 && t < c->t1) return t;
    double T = c->t1 - c->t0;
    double r = fmod(t - c->t0, T);
    if (r < 0.0) r += T;
    double w = c->t0 + r;
    if (w >= c->t1) w = c->t0; /* rounding of r + T */
    return w;
}

int dfl_bspline_is_closed(const dfl_bspline *c, double tol)
{
    if (c->closed) return 1;
    double a[3], b[3];
    dfl_bspline_eval(c, c->t0, 0, a);
    dfl_bspline_eval(c, c->t1, 0, b);
    double ext = 0.0, gap = 0.0;
    for (int j = 0; j < c->dim; j++) {
        double lo = INFINITY, hi = -INFINITY;
        for (size_t i = 0; i < c->n; i++) {
            double v = c->cp[i * (size_t)c->dim + (size_t)j];
            lo = fmin(lo, v);
            hi = fmax(hi, v);
        }
        ext = fmax(ext, hi - lo);
        gap = fmax(gap, fabs(a[j] - b[j]));
    }
    return gap <= tol * (1.0 + ext);
}

size_t dfl_knot_span(const double *U, int order, size_t n, double t, int side)
{
    const size_t k1 = (size_t)order - 1;
    const double t0 = U[k1], t1 = U[n];
    if (t < t0) t = t0;
    if (t > t1) t = t1;
    if (side < 0 && t > t0) {
        /* smallest j >= k-1 with U[j+1] >= t, so U[j] < t <= U[j+1] */
        size_t lo = k1, hi = n - 1;
        while (lo < hi) {
            size_t mid = lo + (hi - lo) / 2;
            if (U[mid + 1] >= t) hi = mid;
            else lo = mid + 1;
        }
        return lo;
    }
    if (t >= t1) {
        size_t j = n - 1;
        while (j > k1 && !(U[j] < U[j + 1])) j--;
        return j;
    }
    /* largest j <= n-1 with U[j] <= t (then U[j+1] > t) */
    size_t lo = k1, hi = n - 1;
    while (lo < hi) {
        size_t mid = lo + (hi - lo + 1) / 2;
        if (U[mid] <= t) lo = mid;
        else hi = mid - 1;
    }
    return lo;
}

size_t dfl_bspline_span(const dfl_bspline *c, double t, int side)
{
    t = dfl_bspline_wrap(c, t);
    if (side < 0 && c->closed && t == c->t0) {
        /* t0 approached from the left is t1 of the previous period */
        size_t j = c->n - 1;
        while (j > (size_t)c->order - 1 && !(c->knots[j] < c->knots[j + 1])) j--;
        return j;
    }
    return dfl_knot_span(c->knots, c->order, c->n, t, side);
}

size_t dfl_bspline_span_count(const dfl_bspline *c)
{
    size_t cnt = 0;
    for (size_t j = (size_t)c->order - 1; j < c->n; j++)
        if (c->knots[j] < c->knots[j + 1]) cnt++;
    return cnt;
}

size_t dfl_bspline_span_index(const dfl_bspline *c, size_t s)
{
    for (size_t j = (size_t)c->order - 1; j < c->n; j++)
        if (c->knots[j] < c->knots[j + 1]) {
            if (s == 0) return j;
            s--;
        }
    assert(0 && "span index out of range");
    return c->n - 1;
}

/* Piegl & Tiller, The NURBS Book, algorithm A2.3 (DersBasisFuns). */
static inline __attribute__((always_inline)) void basis_body(const double *U, int order, size_t i,
                                                             double u, int nder, double *ders)
{
    const int p = order - 1;
    double ndu[KMAX][KMAX], left[KMAX], right[KMAX], a[2][KMAX];
    assert(order >= 1 && order <= KMAX && nder >= 0);
    assert(U[i] < U[i + 1]);
    ndu[0][0] = 1.0;
    for (int j = 1; j <= p; j++) {
        left[j] = u - U[i + 1 - (size_t)j];
        right[j] = U[i + (size_t)j] - u;
        double saved = 0.0;
        for (int r = 0; r < j; r++) {
            ndu[j][r] = right[r + 1] + left[j - r];
            double temp = ndu[r][j - 1] / ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    for (int j = 0; j <= p; j++) ders[j] = ndu[j][p];
    const int nd = nder < p ? nder : p;
    for (int r = 0; r <= p; r++) {
        int s1 = 0, s2 = 1;
        a[0][0] = 1.0;
        for (int k = 1; k <= nd; k++) {
            double d = 0.0;
            int rk = r - k, pk = p - k;
            if (r >= k) {
                a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
                d = a[s2][0] * ndu[rk][pk];
            }
            int j1 = rk >= -1 ? 1 : -rk;
            int j2 = (r - 1 <= pk) ? k - 1 : p - r;
            for (int j = j1; j <= j2; j++) {
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
                d += a[s2][j] * ndu[rk + j][pk];
            }
            if (r <= pk) {
                a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
                d += a[s2][k] * ndu[r][pk];
            }
            ders[k * order + r] = d;
            int tmp = s1;
            s1 = s2;
            s2 = tmp;
        }
    }
    double f = (double)p;
    for (int k = 1; k <= nd; k++) {
        for (int j = 0; j <= p; j++) ders[k * order + j] *= f;
        f *= (double)(p - k);
    }
    for (int k = nd + 1; k <= nder; k++)
        for (int j = 0; j <= p; j++) ders[k * order + j] = 0.0;
}

/* The cubic (order 4, every curve of the paper configs) with up to three
 * derivatives gets a copy of basis_body with constant loop bounds: the
 * same operations in the same order, so the same bytes, without the
 * general loop control (the basis is about a third of a curve distance's
 * Newton steps, and the distances are most of a curve's PHT fit). */
void dfl_bspline_basis(const double *U, int order, size_t i, double u, int nder, double *ders)
{
    if (order == 4) switch (nder) {
        case 0: basis_body(U, 4, i, u, 0, ders); return;
        case 1: basis_body(U, 4, i, u, 1, ders); return;
        case 2: basis_body(U, 4, i, u, 2, ders); return;
        case 3: basis_body(U, 4, i, u, 3, ders); return;
        default: break;
        }
    basis_body(U, order, i, u, nder, ders);
}

void dfl_bspline_eval_side(const dfl_bspline *c, double t, int side, int nder, double *out)
{
    const int k = c->order, dim = c->dim;
    double ders[(KMAX + 4) * KMAX];
    size_t span = dfl_bspline_span(c, t, side);
    double tw = dfl_bspline_wrap(c, t);
    if (c->closed && side < 0 && tw == c->t0) tw = c->t1;
    /* basis derivatives beyond the degree vanish; compute at most KMAX+3 */
    int nd = nder;
    if (nd > KMAX + 3) nd = KMAX + 3;
    dfl_bspline_basis(c->knots, k, span, tw, nd, ders);
    const double *P = c->cp + (span - (size_t)(k - 1)) * (size_t)dim;
    for (int r = 0; r <= nder; r++)
        for (int j = 0; j < dim; j++) {
            double s = 0.0;
            if (r <= nd)
                for (int i = 0; i < k; i++) s += ders[r * k + i] * P[i * dim + j];
            out[r * dim + j] = s;
        }
}

void dfl_bspline_eval(const dfl_bspline *c, double t, int nder, double *out)
{
    dfl_bspline_eval_side(c, t, 1, nder, out);
}

void dfl_blossom_bezier(const double *U, int order, size_t span, const double *cp_span, int dim,
                        double a, double b, double *bez)
{
    const int p = order - 1;
    double d[KMAX * 3];
    assert(order >= 1 && order <= KMAX && dim >= 1 && dim <= 3);
    for (int m = 0; m <= p; m++) {
        memcpy(d, cp_span, (size_t)order * (size_t)dim * sizeof(double));
        /* de Boor with argument u_r at level r: the blossom f(u_1..u_p),
         * here with p-m copies of a followed by m copies of b */
        for (int r = 1; r <= p; r++) {
            double ur = r <= p - m ? a : b;
            for (int i = p; i >= r; i--) {
                size_t gi = span - (size_t)p + (size_t)i;
                double t0 = U[gi], t1 = U[gi + (size_t)(p + 1 - r)];
                double al = (ur - t0) / (t1 - t0);
                for (int j = 0; j < dim; j++)
                    d[i * dim + j] = (1.0 - al) * d[(i - 1) * dim + j] + al * d[i * dim + j];
            }
        }
        memcpy(bez + m * dim, d + p * dim, (size_t)dim * sizeof(double));
    }
}

void dfl_bspline_span_bezier(const dfl_bspline *c, size_t span, double a, double b, double *bez)
{
    assert(span >= (size_t)c->order - 1 && span < c->n);
    dfl_blossom_bezier(c->knots, c->order, span,
                       c->cp + (span - (size_t)(c->order - 1)) * (size_t)c->dim, c->dim, a, b,
                       bez);
}

void dfl_bezier_split(const double *bez, int np, int dim, double s, double *left, double *right)
{
    double w[KMAX * 3];
    assert(np >= 1 && np <= KMAX);
    memcpy(w, bez, (size_t)np * (size_t)dim * sizeof(double));
    for (int j = 0; j < dim; j++) {
        left[j] = w[j];
        right[(np - 1) * dim + j] = w[(np - 1) * dim + j];
    }
    for (int r = 1; r < np; r++) {
        for (int i = 0; i < np - r; i++)
            for (int j = 0; j < dim; j++)
                w[i * dim + j] = (1.0 - s) * w[i * dim + j] + s * w[(i + 1) * dim + j];
        for (int j = 0; j < dim; j++) {
            left[r * dim + j] = w[j];
            right[(np - 1 - r) * dim + j] = w[(np - 1 - r) * dim + j];
        }
    }
}

void dfl_bezier_eval(const double *bez, int np, int dim, double s, double *out)
{
    double w[KMAX * 3];
    assert(np >= 1 && np <= KMAX);
    memcpy(w, bez, (size_t)np * (size_t)dim * sizeof(double));
    for (int r = 1; r < np; r++)
        for (int i = 0; i < np - r; i++)
            for (int j = 0; j < dim; j++)
                w[i * dim + j] = (1.0 - s) * w[i * dim + j] + s * w[(i + 1) * dim + j];
    memcpy(out, w, (size_t)dim * sizeof(double));
}
