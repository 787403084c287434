/* Hermite data of an SDF (hermite.h).
 *
 * Derivation of sjp10's eq. 2-7 (the extracted text lost eq. 2-4) and how
 * dflab evaluates them.  In the paper's sign (d > 0 inside) let x have the
 * unique footpoint p(x) on Gamma and r = |x - p| = d(x).
 *   eq. 2   d_i = (x_i - p_i) / r.
 *           Differentiate r^2 = (x - p).(x - p): 2 r r_i = 2 (x_i - p_i)
 *           - 2 (x - p).p_{,i}, and (x - p) is normal to Gamma at p while
 *           p_{,i} = dp/dx_i is tangent, so the second term vanishes.
 *   eq. 3   d_ij = (delta_ij - dp_i/dx_j) / r - (x_i - p_i)(x_j - p_j) / r^3
 *           (quotient rule on eq. 2 with r_j = d_j).
 *   eq. 4/5 d_ijk = -(d^2 p_i / dx_j dx_k) / r
 *                   - [ (delta_ij - dp_i/dx_j)(x_k - p_k) + (delta_ik - dp_i/dx_k)(x_j - p_j)
 *                       + (delta_jk - dp_j/dx_k)(x_i - p_i) ] / r^3
 *                   + 3 (x_i - p_i)(x_j - p_j)(x_k - p_k) / r^5,
 *           one more quotient rule (the printed eq. 5 is this, symmetrized).
 *   eq. 6   curves p = c(t(x)), t the footpoint parameter: dp/dx_j = c'(t) dt/dx_j.
 *   eq. 7   t solves h(u, x) = (c(u) - x).c'(u) = 0 (eq. 10); implicit
 *           differentiation h_u dt/dx_j + h_{x_j} = 0 gives
 *           dt/dx_j = c'_j(t) / (|c'|^2 + (c - x).c''), and one more
 *           differentiation gives d^2 t / dx_j dx_k for the mixed derivatives.
 *   Surfaces g(p) = 0 with grad g(p) x (p - x) = 0 (eq. 8): the same implicit
 *   differentiation of the system (g(p), grad g(p) x (p - x)) = 0 in x.
 * Substituting, eq. 3 collapses to the closed forms geom states with the
 * curvature convention of geom/curvature.h (dflab sign d < 0 inside,
 * outward normal N, kappa > 0 on a convex curve): 2D Hess d = kappa /
 * (1 + kappa d) T T^T, 3D Hess d = sum_i kappa_i / (1 + kappa_i d) e_i e_i^T;
 * in the paper's sign every datum changes sign.
 *
 * dflab does not code eq. 3-7 by hand: geom follows the footpoint through
 * the Newton iteration in truncated Taylor arithmetic (exact jets of
 * s -> d(x + s v), geom/curve_sdf.h and geom/implicit.h), which is eq. 6-7
 * differentiated to any order.  The mixed partials come from jets along
 * diagonal directions by polarization:
 *   2D  D2_{(1,1)} - D2_{(1,-1)} = 4 d_xy;
 *   3D  with E1..E4 = (1,1,1), (1,1,-1), (1,-1,1), (-1,1,1) and
 *       D2_e = sum_ij e_i e_j d_ij:
 *       d_xy = (D2_1 + D2_2 - D2_3 - D2_4) / 8, d_xz = (D2_1 - D2_2 + D2_3 - D2_4) / 8,
 *       d_yz = (D2_1 - D2_2 - D2_3 + D2_4) / 8,
 *       d_xyz = (D3_1 - D3_2 - D3_3 - D3_4) / 24 (the 1/24 sum of geom/shape.h),
 *   so 2 jets of order 2 (2D) or 4 jets of order 3 (3D) per vertex.
 *   This is not geom's dfl_jets_polarize (dfl_shape_derivs_at), which takes
 *   the Hessian from jets along e_i and e_i + e_k (3 jets in 2D, 6 + 4 in
 *   3D): the two agree to rounding but not bit for bit (d_xy = (a - b) / 4
 *   versus (D2_{e1+e2} - D2_{e1} - D2_{e2}) / 2; switching changed every
 *   CSV of configs/paper/sjp10/sjp10_offsets.ini), so the paper studies'
 *   outputs keep this scheme.  d_xyz is the same sum in both.
 * Implicit surfaces use dfl_implicit_sdf_derivs (one footpoint, then jets
 * from it).
 *
 * Footpoints: geom's solvers are more robust than the paper's bare Newton
 * (Sec. 4.2).  Curves: the paper starts Newton on h(u) from the k <= 3
 * nearest of N uniform samples; geom ranks the discrete local minima of
 * |x - C| over 16 samples per knot span, refines 4 candidates by Newton
 * with step halving (Gauss-Newton where h' <= 0) and detects medial ties.
 * Implicit: the paper alternates tangent-plane projection and a Newton
 * projection from polygon-mesh vertices without step control; geom starts
 * from every surface sample within the distance bound (thinned) and runs a
 * Riemannian Newton on the surface with retraction, keeping the nearest.
 * Where the paper's Newton converges to the nearest footpoint both agree to
 * rounding; where it would converge to a farther local footpoint (near the
 * medial axis, from a poor start), geom does not. */
#include "pht/hermite.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/implicit.h"

struct dfl_pht_source {
    const dfl_shape *shape;
    const dfl_implicit *imp;   /* non-NULL for implicit surfaces */
};

dfl_status dfl_pht_source_new(const dfl_shape *shape, dfl_pht_source **out, dfl_err *err)
{
    if (!shape || !shape->ops)
        return dfl_err_set(err, DFL_E_INPUT, "PHT source: no shape");
    const char *kind = shape->ops->kind ? shape->ops->kind : "?";
    if (shape->dim != 2 && shape->dim != 3)
        return dfl_err_set(err, DFL_E_INPUT, "PHT source: shape '%s' has dimension %d", kind,
                           shape->dim);
    if (!shape->ops->jet)
        return dfl_err_set(err, DFL_E_INPUT,
                           "PHT source: shape '%s' has no SDF derivatives (Hermite data need "
                           "value, first and mixed derivatives)",
                           kind);
    if (strcmp(kind, "segment") == 0)
        return dfl_err_set(err, DFL_E_INPUT,
                           "PHT source: shape 'segment' has an unsigned distance (a signed "
                           "distance of a closed curve or surface is needed)");
    dfl_pht_source *s = calloc(1, sizeof *s);
    if (!s) return dfl_err_set(err, DFL_E_NOMEM, "PHT source: out of memory");
    s->shape = shape;
    s->imp = dfl_implicit_of_shape(shape);
    *out = s;
    return DFL_OK;
}

void dfl_pht_source_free(dfl_pht_source *src) { free(src); }

int dfl_pht_source_dim(const dfl_pht_source *src) { return src->shape->dim; }
const dfl_shape *dfl_pht_source_shape(const dfl_pht_source *src) { return src->shape; }

/* The probe of dfl_pht_source_check_signed.  Why it decides: from the box
 * centre c the nearest surface point is q = c - d(c) grad d(c); a point a
 * little past it, x = c - (d(c) + t) grad d(c), is inside (d < 0) for any
 * closed curve or surface once t is below the local feature size, while an
 * unsigned distance (an open curve, a segment) is >= 0 everywhere.  The
 * first step, t = 1e-6 max(d(c), 1e-6 half diagonal), is the one the
 * experiments' check took (pht_cfg.c, sjp10); smaller steps (down to
 * rounding of q) follow only when it lands outside, for a shape much
 * smaller than its distance from c.  A grid of probes (an earlier check)
 * missed small shapes between its points and cost 33^3 footpoints on
 * implicit surfaces. */
static int signed_probe(const dfl_shape *s, const double *lo, const double *hi)
{
    const int dim = s->dim;
    double c[3] = {0, 0, 0}, g[3] = {0, 0, 0}, half2 = 0, cmax = 0;
    for (int j = 0; j < dim; j++) {
        c[j] = 0.5 * lo[j] + 0.5 * hi[j];
        const double h = 0.5 * hi[j] - 0.5 * lo[j];
        half2 += h * h;
        cmax = fmax(cmax, fabs(c[j]));
    }
    const double d = dfl_shape_eval1(s, c, g);
    if (d < 0.0) return 1;
    if (!isfinite(d)) return 0;
    double gn = 0;
    for (int j = 0; j < dim; j++) gn += g[j] * g[j];
    gn = sqrt(gn);
    if (!(gn > 0) || !isfinite(gn)) return 0;
    const double floor = 1e-13 * (cmax + d);
    for (double t = 1e-6 * fmax(d, sqrt(half2) * 1e-6);; t *= 1e-3) {
        double x[3];
        for (int j = 0; j < dim; j++) x[j] = c[j] - (d + t) * g[j] / gn;
        if (dfl_shape_eval1(s, x, NULL) < 0.0) return 1;
        if (!(t * 1e-3 > floor)) return 0;
    }
}

dfl_status dfl_pht_source_check_signed(const dfl_pht_source *src, const double *lo,
                                       const double *hi, dfl_err *err)
{
    if (signed_probe(src->shape, lo, hi)) return DFL_OK;
    return dfl_err_set(err, DFL_E_INPUT,
                       "PHT source: shape '%s' has no inside (d >= 0 just past its nearest "
                       "point to the box centre): PHT fits need a signed distance of a closed "
                       "curve or surface (an open curve's distance is unsigned)",
                       src->shape->ops->kind ? src->shape->ops->kind : "?");
}

static dfl_status hermite_exact(const dfl_pht_source *src, const double *x, double *out,
                                int *flags, dfl_err *err);

static dfl_status jet2(const dfl_shape *s, const double *x, const double *e, int K, double *D,
                       dfl_err *err)
{
    dfl_jet j;
    dfl_status st = s->ops->jet(s->impl, x, e, K, &j, err);
    if (st != DFL_OK) return st;
    for (int k = 2; k <= K; k++) D[k - 2] = dfl_jet_deriv(&j, k);
    return DFL_OK;
}

dfl_status dfl_pht_hermite(const dfl_pht_source *src, const double *x, double *data, int *flags,
                           dfl_err *err)
{
    const dfl_shape *s = src->shape;
    double out[DFL_PHT_NDATA_MAX];
    int fl = 0;
    dfl_status st = hermite_exact(src, x, out, &fl, err);
    if (st == DFL_E_NUMERIC) {
        /* a focal or medial point: d is not differentiable here, so any data
         * are a choice; take the one-sided gradient of eval and no twist */
        double g[3];
        memset(out, 0, sizeof out);
        out[0] = dfl_shape_eval1(s, x, g);
        out[1] = g[0];
        out[2] = g[1];
        if (s->dim == 3) out[4] = g[2];
        fl = DFL_PHT_HERMITE_FALLBACK | DFL_PHT_HERMITE_MEDIAL;
        st = DFL_OK;
        dfl_err_clear(err);
    }
    if (st != DFL_OK) return st;
    int nd = DFL_PHT_NDATA(s->dim);
    for (int b = 0; b < nd; b++)
        if (!isfinite(out[b]))
            return dfl_err_set(err, DFL_E_NUMERIC,
                               "PHT source: Hermite data of '%s' not finite at a vertex",
                               s->ops->kind);
    memcpy(data, out, (size_t)nd * sizeof *out);
    if (flags) *flags = fl;
    return DFL_OK;
}

static dfl_status hermite_exact(const dfl_pht_source *src, const double *x, double *out,
                                int *flags, dfl_err *err)
{
    const dfl_shape *s = src->shape;
    int fl = 0;
    dfl_status st;
    if (src->imp) {
        dfl_sdf_derivs D;
        if ((st = dfl_implicit_sdf_derivs(src->imp, x, &D, err)) != DFL_OK) return st;
        out[0] = D.d;
        out[1] = D.g[0];
        out[2] = D.g[1];
        out[3] = D.H[1];
        out[4] = D.g[2];
        out[5] = D.H[2];
        out[6] = D.H[5];
        out[7] = D.dxyz;
        /* a footpoint tie (e.g. on the torus' axis, where a whole circle
         * ties) gives jets of one arbitrary branch, or none: use the
         * fallback there */
        if (D.foot.medial)
            return dfl_err_set(err, DFL_E_NUMERIC, "PHT source: medial footpoint tie");
    } else if (s->dim == 2) {
        double g[2], a[1], b[1];
        out[0] = dfl_shape_eval1(s, x, g);
        out[1] = g[0];
        out[2] = g[1];
        const double e1[2] = {1, 1}, e2[2] = {1, -1};
        if ((st = jet2(s, x, e1, 2, a, err)) != DFL_OK) return st;
        if ((st = jet2(s, x, e2, 2, b, err)) != DFL_OK) return st;
        out[3] = 0.25 * (a[0] - b[0]);
    } else {
        static const double E[4][3] = {{1, 1, 1}, {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}};
        double g[3], D[4][2];
        out[0] = dfl_shape_eval1(s, x, g);
        for (int m = 0; m < 4; m++)
            if ((st = jet2(s, x, E[m], 3, D[m], err)) != DFL_OK) return st;
        out[1] = g[0];
        out[2] = g[1];
        out[4] = g[2];
        out[3] = (D[0][0] + D[1][0] - D[2][0] - D[3][0]) / 8.0;
        out[5] = (D[0][0] - D[1][0] + D[2][0] - D[3][0]) / 8.0;
        out[6] = (D[0][0] - D[1][0] - D[2][0] + D[3][0]) / 8.0;
        out[7] = (D[0][1] - D[1][1] - D[2][1] - D[3][1]) / 24.0;
    }
    for (int b = 0; b < DFL_PHT_NDATA(s->dim); b++)
        if (!isfinite(out[b]))
            return dfl_err_set(err, DFL_E_NUMERIC, "PHT source: derivatives not finite");
    *flags = fl;
    return DFL_OK;
}

void dfl_pht_source_eval(const dfl_pht_source *src, size_t m, const double *pts, double *val,
                         double *grad)
{
    dfl_shape_eval(src->shape, m, pts, val, grad);
}
