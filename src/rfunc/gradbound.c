/* Derivations behind gradbound.h (the extracted paper text garbles eq. 14's
 * exponents; they are re-derived here).
 *
 * R-equivalence: F = (h1^-p + h2^-p)^(-1/p), dF/dh1 = h1^(-p-1) (h1^-p +
 * h2^-p)^(-(p+1)/p).  With h1 = rho c, h2 = rho s: h1^-p + h2^-p = rho^-p
 * (c^p + s^p) / (c s)^p, so dF/dh1 = c^(-p-1) (c s)^(p+1) / (c^p +
 * s^p)^((p+1)/p) = s^(p+1) / (c^p + s^p)^((p+1)/p): eq. 14.  F1 + F2 =
 * (|v|_(p+1) / |v|_p)^(p+1) for v = (c, s): 1 on the axes and smallest where
 * the components are equal (phi = pi/4), where it is 2^(-1/p).
 *
 * R-conjunction: dF/dh1 = 1 - (h1 / N)^(p-1) with h1 / N = c / (c^p +
 * s^p)^(1/p).  F1 + F2 = 2 - |v|_(p-1)^(p-1) / |v|_p^(p-1): the ratio of
 * norms is largest at equal components, so F1 + F2 is again smallest at
 * phi = pi/4 (2 - 2^(1/p)) and 1 on the axes.
 *
 * Regimes near a vertex (exact distances, vertex at the origin, x = q w
 * with |w| = 1).  Convex sector, both closest points interior: grad h_i
 * are the unit normals of the two carriers pointing to x; they enclose
 * pi - alpha', so |grad u|^2 = F1^2 + F2^2 - 2 F1 F2 cos(alpha'); on the
 * bisector h1 = h2, F1 = F2 = F(pi/4) and |grad u| = 2 F(pi/4)
 * sqrt((1 - cos alpha') / 2) = 2 F(pi/4) sin(alpha'/2).
 * Mixed regime: part A's closest point interior, B's the vertex.  In A's
 * frame (A along +x) x = q (cos t, sin t) with cos t > 0: h_A = q |sin t|,
 * grad h_A = (0, sign sin t), h_B = q, grad h_B = (cos t, sin t); their dot
 * product is |sin t| = s, and phi = atan2(h_B, h_A) = atan2(1, s) when A is
 * part 1 (the swapped case gives the same |grad u| since both joins are
 * symmetric in their arguments).  Available s: B's closest point is the
 * vertex iff x . e_B <= 0; with e_B at angle alpha' from A the directions
 * with cos t > 0 and cos(t - alpha') <= 0 are t in (-pi/2, alpha' - pi/2],
 * whose |sin t| fill [cos alpha', 1] for alpha' <= pi/2 and [0, 1] beyond.
 * Hatched sector: both gradients radial, phi = pi/4, |grad u| = 2 F(pi/4).
 */
#include "rfunc/gradbound.h"

#include <assert.h>
#include <math.h>

#include "core/vec.h"

dfl_status dfl_gradbound_check(dfl_rfunc_join join, int p, dfl_err *err)
{
    if (join != DFL_RFUNC_REQUIV && join != DFL_RFUNC_RCONJ)
        return dfl_err_set(err, DFL_E_INPUT,
                           "gradient bounds: eq. 13-14 apply to requiv and rconj (two"
                           " arguments), not to %s",
                           dfl_rfunc_join_name(join));
    return dfl_rfunc_join_check(join, p, err);
}

void dfl_gradbound_rconj_partials_polar(double phi, int p, double *F1, double *F2)
{
    assert(p >= 2);
    const double c = cos(phi), s = sin(phi);
    const double den = pow(pow(c, p) + pow(s, p), (p - 1.0) / p);
    *F1 = 1.0 - pow(c, p - 1) / den;
    *F2 = 1.0 - pow(s, p - 1) / den;
}

void dfl_gradbound_partials(dfl_rfunc_join join, int p, double phi, double *F1, double *F2)
{
    assert(join == DFL_RFUNC_REQUIV || join == DFL_RFUNC_RCONJ);
    if (join == DFL_RFUNC_REQUIV)
        dfl_rfunc_requiv_partials_polar(phi, p, F1, F2);
    else
        dfl_gradbound_rconj_partials_polar(phi, p, F1, F2);
}

void dfl_gradbound_band(double F1, double F2, double g1, double g2, double *lo, double *hi)
{
    *lo = fabs(F1 * g1 - F2 * g2);
    *hi = F1 * g1 + F2 * g2;
}

static double fold_alpha(double alpha)
{
    assert(alpha > 0.0 && alpha < 2.0 * DFL_PI);
    return alpha <= DFL_PI ? alpha : 2.0 * DFL_PI - alpha;
}

double dfl_gradbound_bisector(dfl_rfunc_join join, int p, double alpha)
{
    double F1, F2;
    dfl_gradbound_partials(join, p, 0.25 * DFL_PI, &F1, &F2);
    return (F1 + F2) * sin(0.5 * fold_alpha(alpha));
}

double dfl_gradbound_mixed(dfl_rfunc_join join, int p, double s)
{
    assert(s >= 0.0 && s <= 1.0);
    double F1, F2;
    dfl_gradbound_partials(join, p, atan2(1.0, s), &F1, &F2);
    return sqrt(F1 * F1 + F2 * F2 + 2.0 * F1 * F2 * s);
}

double dfl_gradbound_golden(double (*f)(void *ctx, double x), void *ctx, double a, double b,
                            double tol, double *fmin)
{
    assert(a <= b && tol > 0.0);
    const double ig = 0.5 * (sqrt(5.0) - 1.0);
    double c = b - ig * (b - a), d = a + ig * (b - a);
    double fc = f(ctx, c), fd = f(ctx, d);
    while (b - a > tol) {
        if (fc <= fd) {
            b = d;
            d = c;
            fd = fc;
            c = b - ig * (b - a);
            fc = f(ctx, c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + ig * (b - a);
            fd = f(ctx, d);
        }
    }
    const double x = fc <= fd ? c : d;
    if (fmin) *fmin = fc <= fd ? fc : fd;
    return x;
}

typedef struct jp {
    dfl_rfunc_join join;
    int p;
} jp;

static double mixed_fn(void *ctx, double s)
{
    const jp *j = ctx;
    return dfl_gradbound_mixed(j->join, j->p, s);
}

static double sum_fn(void *ctx, double phi)
{
    const jp *j = ctx;
    double F1, F2;
    dfl_gradbound_partials(j->join, j->p, phi, &F1, &F2);
    return F1 + F2;
}

/* Scan + golden section on [a, b] (unimodality is only needed near the
 * best scan point). */
static double scan_min(double (*f)(void *, double), void *ctx, double a, double b, int n,
                       double *xmin)
{
    assert(n >= 2);
    int kbest = 0;
    double fbest = INFINITY;
    const double hstep = (b - a) / (n - 1);
    for (int k = 0; k < n; k++) {
        const double fx = f(ctx, k == n - 1 ? b : a + k * hstep);
        if (fx < fbest) fbest = fx, kbest = k;
    }
    const double lo = kbest > 0 ? a + (kbest - 1) * hstep : a;
    const double hi = kbest < n - 1 ? a + (kbest + 1) * hstep : b;
    double fg;
    const double xg = dfl_gradbound_golden(f, ctx, lo, hi, 1e-12 * (1.0 + fabs(b - a)), &fg);
    if (fg <= fbest) {
        *xmin = xg;
        return fg;
    }
    *xmin = kbest == n - 1 ? b : a + kbest * hstep;
    return fbest;
}

double dfl_gradbound_vertex_min(dfl_rfunc_join join, int p, double alpha, int *where,
                                double *s_min)
{
    const double ap = fold_alpha(alpha);
    const double bis = dfl_gradbound_bisector(join, p, alpha);
    jp j = {join, p};
    double s;
    /* the hatched value is the mixed regime at s = 1, inside the scan */
    const double mix = scan_min(mixed_fn, &j, fmax(cos(ap), 0.0), 1.0, 2001, &s);
    if (s_min) *s_min = s;
    if (where) *where = bis <= mix + 1e-12 ? 0 : 1;
    return fmin(bis, mix);
}

double dfl_gradbound_sum_min(dfl_rfunc_join join, int p, double *phi_min, double *sum_max,
                             double *diff_max)
{
    jp j = {join, p};
    double smax = 0.0, dmax = 0.0;
    for (int k = 0; k <= 2000; k++) {
        double F1, F2;
        dfl_gradbound_partials(join, p, k == 2000 ? 0.5 * DFL_PI : k * (0.5 * DFL_PI / 2000), &F1,
                               &F2);
        smax = fmax(smax, F1 + F2);
        dmax = fmax(dmax, fabs(F1 - F2));
    }
    double phi;
    const double m = scan_min(sum_fn, &j, 0.0, 0.5 * DFL_PI, 2001, &phi);
    if (phi_min) *phi_min = phi;
    if (sum_max) *sum_max = smax;
    if (diff_max) *diff_max = dmax;
    return m;
}
