/* One corner evaluation (decode + distance + clip) serves all filters; the
 * blends only differ in their weight function, so trilinear and Hermite
 * share one loop with the weight picked once per batch. */
#include "proxy/filter.h"

#include <math.h>
#include <string.h>

#include "core/isa.h"
#include "core/vec.h"

DFL_NAMES_DEFINE(dfl_proxy_filter, DFL_PROXY_FILTER_LIST, DFL_PROXY_FILTER_COUNT,
                 dfl_proxy_filter_names, dfl_proxy_filter_name, dfl_proxy_filter_parse,
                 "filter")
DFL_NAMES_DEFINE(dfl_proxy_clip, DFL_PROXY_CLIP_LIST, DFL_PROXY_CLIP_COUNT, dfl_proxy_clip_names,
                 dfl_proxy_clip_name, dfl_proxy_clip_parse, "clip")

void dfl_proxy_filter_opts_default(dfl_proxy_filter f, const dfl_proxy_grid *g,
                                   dfl_proxy_filter_opts *o)
{
    o->filter = f;
    o->clip = f == DFL_PROXY_NEAREST ? dfl_proxy_cell_size(g) : 0.0;
    o->is_signed = 0;
    o->clip_kind = DFL_PROXY_CLIP_BOUND;
}

dfl_status dfl_proxy_filter_check(const dfl_proxy_grid *g, const dfl_proxy_filter_opts *o,
                                  dfl_err *err)
{
    if ((unsigned)o->filter >= DFL_PROXY_FILTER_COUNT)
        return dfl_err_set(err, DFL_E_INPUT, "proxy filter: unknown filter %d", (int)o->filter);
    if ((unsigned)o->clip_kind >= DFL_PROXY_CLIP_COUNT)
        return dfl_err_set(err, DFL_E_INPUT, "proxy filter: unknown clip %d", (int)o->clip_kind);
    if (!(o->clip >= 0) || !isfinite(o->clip))
        return dfl_err_set(err, DFL_E_INPUT, "proxy filter: clip radius %g (expected >= 0)",
                           o->clip);
    if (o->is_signed && !g->has_inside)
        return dfl_err_set(err, DFL_E_INPUT,
                           "proxy filter: signed output needs an input with an inside");
    return DFL_OK;
}

DFL_ISA_BODY double clipped(const dfl_proxy_geom *pgp, int order, dfl_proxy_clip kind,
                            double clip, const double x[3], double *grad)
{
    const dfl_proxy_geom *pg = pgp;
    double phi = dfl_proxy_geom_eval(pg, order, x, grad);
    if (clip > 0 && kind != DFL_PROXY_CLIP_OFF) {
        const double v[3] = {x[0] - pg->p[0], x[1] - pg->p[1], x[2] - pg->p[2]};
        const double r2 = dfl_vec3_dot(v, v);
        if (kind == DFL_PROXY_CLIP_BOUND) {
            /* |x - p| - rho > |phi|, without a square root when it is not */
            const double lim = clip + fabs(phi);
            if (r2 > lim * lim) {
                const double r = sqrt(r2), ball = r - clip;
                const double s = phi < 0 ? -1.0 : 1.0;
                phi = s * fmax(ball, fabs(phi));
                if (grad)
                    for (int j = 0; j < 3; j++) grad[j] = s * v[j] / r;
            }
        } else {
            /* max(phi, |x - p| - rho); the ball term wins only where
             * |x - p| > rho + phi, which needs rho + phi < |x - p| */
            const double lim = clip + phi;
            if (lim < 0 || r2 > lim * lim) {
                const double r = sqrt(r2), ball = r - clip;
                if (ball > phi) {
                    phi = ball;
                    if (grad)
                        for (int j = 0; j < 3; j++) grad[j] = r > 0 ? v[j] / r : 0.0;
                }
            }
        }
    }
    return phi;
}

double dfl_proxy_proxy_dist(const dfl_proxy_grid *g, size_t c, dfl_proxy_clip kind, double clip,
                            const double x[3], double *grad)
{
    dfl_proxy_geom pg;
    dfl_proxy_cell_decode(g, c, &pg);
    return clipped(&pg, g->order, kind, clip, x, grad);
}

/* D of cell (i, j, k) */
DFL_ISA_BODY double dist_ijk(const dfl_proxy_grid *g, size_t i, size_t j, size_t k,
                             const dfl_proxy_filter_opts *o, const double x[3], double *grad)
{
    dfl_proxy_geom pg;
    dfl_proxy_cell_decode_ijk(g, i, j, k, &pg);
    return clipped(&pg, g->order, o->clip_kind, o->clip, x, grad);
}

/* The cell of x per axis, clamped to the grid; a NaN coordinate takes cell
 * 0 on its axis (filter.h: its value is NaN). */
DFL_ISA_BODY void nearest_cell(const dfl_proxy_grid *g, const double x[3], size_t idx[3])
{
    for (int j = 0; j < 3; j++) {
        const double s = floor((x[j] - g->lo[j]) / g->h[j]);
        idx[j] = !(s >= 0) ? 0 : s > g->res - 1 ? (size_t)g->res - 1 : (size_t)s;
    }
}

/* weight of the upper neighbour and its derivative in t */
DFL_ISA_BODY void weight(dfl_proxy_filter f, int order, double t, double *w, double *dw)
{
    if (f == DFL_PROXY_TRILINEAR) {
        *w = t;
        *dw = 1.0;
    } else if (order == 1) {
        *w = t * t * (3.0 - 2.0 * t);
        *dw = 6.0 * t * (1.0 - t);
    } else {
        *w = t * t * t * (10.0 + t * (-15.0 + 6.0 * t));
        const double u = t * (1.0 - t);
        *dw = 30.0 * u * u;
    }
}

/* The blend's corners (lower i0, upper i1 per axis), weights w and their
 * derivatives dw at x. */
DFL_ISA_BODY void blend_setup(const dfl_proxy_grid *g, const dfl_proxy_filter_opts *o,
                              const double x[3], size_t i0[3], size_t i1[3], double w[3][2],
                              double dw[3][2])
{
    const size_t n = (size_t)g->res;
    for (int j = 0; j < 3; j++) {
        const double s = (x[j] - g->lo[j]) / g->h[j] - 0.5;
        double t, dt = 1.0 / g->h[j];
        if (g->res == 1) {
            i0[j] = 0;
            t = 0;
            dt = 0;
        } else if (!(s > 0)) { /* NaN too: cell 0, the value is NaN */
            i0[j] = 0;
            t = 0;
            dt = 0;
        } else if (s >= g->res - 1) {
            i0[j] = n - 2;
            t = 1;
            dt = 0;
        } else {
            double f = floor(s);
            if (f > g->res - 2) f = g->res - 2;
            i0[j] = (size_t)f;
            t = s - f;
        }
        i1[j] = g->res == 1 ? 0 : i0[j] + 1;
        double wt, dwt;
        weight(o->filter, g->order, t, &wt, &dwt);
        w[j][0] = 1.0 - wt;
        w[j][1] = wt;
        dw[j][0] = -dwt * dt;
        dw[j][1] = dwt * dt;
    }
}

DFL_ISA_BODY double blend(const dfl_proxy_grid *g, const dfl_proxy_filter_opts *o, const double x[3],
                    double *grad)
{
    size_t i0[3], i1[3];
    double w[3][2], dw[3][2];
    blend_setup(g, o, x, i0, i1, w, dw);
    double val = 0, gr[3] = {0, 0, 0};
    for (int q = 0; q < 8; q++) {
        const int a = q & 1, b = (q >> 1) & 1, c = (q >> 2) & 1;
        const double W = w[0][a] * w[1][b] * w[2][c];
        if (W == 0 && !grad) continue;
        double gd[3];
        double d = dist_ijk(g, a ? i1[0] : i0[0], b ? i1[1] : i0[1], c ? i1[2] : i0[2], o,
                            x, grad ? gd : NULL);
        if (!o->is_signed && d < 0) {
            d = -d;
            if (grad)
                for (int j = 0; j < 3; j++) gd[j] = -gd[j];
        }
        val += W * d;
        if (grad) {
            const double gw[3] = {dw[0][a] * w[1][b] * w[2][c], w[0][a] * dw[1][b] * w[2][c],
                                  w[0][a] * w[1][b] * dw[2][c]};
            for (int j = 0; j < 3; j++) gr[j] += W * gd[j] + d * gw[j];
        }
    }
    if (grad)
        for (int j = 0; j < 3; j++) grad[j] = gr[j];
    return val;
}

/* Queries per block of the batched nearest filter (SoA lanes). */
#define QL 8

/* The lane loop of nearest_block (order, pos, clipon constants at each
 * call): dfl_proxy_decode, dfl_proxy_geom_eval (decode.h), clipped above
 * and the fold of unsigned output (a negative value and its gradient
 * negated, NaN too, as !(phi >= 0)), written out on scalars in the same operations and order
 * (dot products left to right, the cross product of dfl_vec3_cross), so
 * that the lanes vectorize; tests/proxy and scripts/check_isa.py hold them
 * to the per-query bytes. */
DFL_ISA_BODY void nearest_lanes(const int order, const dfl_proxy_position pos, const int clipon,
                                const double clip, const int sgnd, const int wantg,
                                double (*S)[QL], double (*XC)[QL], double (*X)[QL],
                                const double *SIDE, double *V, double (*G)[QL])
{
#pragma omp simd
    for (int l = 0; l < QL; l++) {
        const int disp = pos == DFL_PROXY_DISPLACEMENT;
        const double d0 = disp ? S[0][l] : S[0][l] - XC[0][l],
                     d1 = disp ? S[1][l] : S[1][l] - XC[1][l],
                     d2 = disp ? S[2][l] : S[2][l] - XC[2][l];
        const double p0 = disp ? XC[0][l] + S[0][l] : S[0][l],
                     p1 = disp ? XC[1][l] + S[1][l] : S[1][l],
                     p2 = disp ? XC[2][l] + S[2][l] : S[2][l];
        const double dl = sqrt(d0 * d0 + d1 * d1 + d2 * d2);
        const double v0 = X[0][l] - p0, v1 = X[1][l] - p1, v2 = X[2][l] - p2;
        double phi, g0, g1, g2;
        if (order == 1) {
            const double f = -SIDE[l] / dl;
            const double n0 = f * d0, n1 = f * d1, n2 = f * d2;
            phi = v0 * n0 + v1 * n1 + v2 * n2;
            g0 = n0, g1 = n1, g2 = n2;
        } else {
            const double l0 = S[5][l], l1 = S[6][l], l2v = S[7][l];
            const double l2 = l0 * l0 + l1 * l1 + l2v * l2v;
            const double in = (l2 > 2.25 ? -1.0 : 1.0) / dl;
            const double n0 = in * d0, n1 = in * d1, n2 = in * d2;
            const double tn = l0 * n0 + l1 * n1 + l2v * n2;
            const double u0 = l0 - tn * n0, u1 = l1 - tn * n1, u2 = l2v - tn * n2;
            const double it = 1.0 / sqrt(u0 * u0 + u1 * u1 + u2 * u2);
            const double t0 = it * u0, t1 = it * u1, t2 = it * u2;
            const double b0 = n1 * t2 - n2 * t1, b1 = n2 * t0 - n0 * t2, b2 = n0 * t1 - n1 * t0;
            const double kr = S[3][l], kR = S[4][l];
            const double vn = v0 * n0 + v1 * n1 + v2 * n2;
            const double vt = v0 * t0 + v1 * t1 + v2 * t2, vb = v0 * b0 + v1 * b1 + v2 * b2;
            const double uR = 1.0 + kR * vn, wR = kR * vb;
            const double SR = sqrt(uR * uR + wR * wR);
            const double a = (kR * (vn * vn + vb * vb) + 2.0 * vn) / (1.0 + SR);
            const double ur = 1.0 + kr * a, wr = kr * vt;
            const double Sr = sqrt(ur * ur + wr * wr);
            phi = (kr * (a * a + vt * vt) + 2.0 * a) / (1.0 + Sr);
            const double iR = 1.0 / SR, ir = 1.0 / Sr;
            const double a0 = SR > 0 ? iR * (uR * n0 + wR * b0) : n0,
                         a1 = SR > 0 ? iR * (uR * n1 + wR * b1) : n1,
                         a2 = SR > 0 ? iR * (uR * n2 + wR * b2) : n2;
            g0 = Sr > 0 ? ir * (ur * a0 + wr * t0) : a0;
            g1 = Sr > 0 ? ir * (ur * a1 + wr * t1) : a1;
            g2 = Sr > 0 ? ir * (ur * a2 + wr * t2) : a2;
        }
        if (clipon) {
            const double ap = fabs(phi), lim = clip + ap, r2 = v0 * v0 + v1 * v1 + v2 * v2;
            const double r = sqrt(r2), ball = r - clip, sg = phi < 0 ? -1.0 : 1.0;
            const int far = r2 > lim * lim;
            g0 = far ? sg * v0 / r : g0;
            g1 = far ? sg * v1 / r : g1;
            g2 = far ? sg * v2 / r : g2;
            phi = far ? sg * (ball > ap ? ball : ap) : phi;
        }
        const int flip = !sgnd && !(phi >= 0);
        V[l] = flip ? -phi : phi;
        if (wantg) {
            /* else the gradient's divisions are dead code, phi unchanged */
            G[0][l] = flip ? -g0 : g0;
            G[1][l] = flip ? -g1 : g1;
            G[2][l] = flip ? -g2 : g2;
        }
    }
}

/* nearest_lanes with order, position, clip on/off and the gradient as
 * constants (one specialised lane loop each, no branch inside). */
DFL_ISA_BODY void run_lanes(const int order, const dfl_proxy_position pos, const double clip,
                            const int sgnd, const int wantg, double (*S)[QL], double (*XC)[QL],
                            double (*X)[QL], const double *SIDE, double *V, double (*G)[QL])
{
#define DFL_LANES(o_, p_, c_)                                                         \
    (wantg ? nearest_lanes(o_, p_, c_, clip, sgnd, 1, S, XC, X, SIDE, V, G)           \
           : nearest_lanes(o_, p_, c_, clip, sgnd, 0, S, XC, X, SIDE, V, G))
    if (order == 1 && pos == DFL_PROXY_DISPLACEMENT && clip > 0)
        DFL_LANES(1, DFL_PROXY_DISPLACEMENT, 1);
    else if (order == 1 && pos == DFL_PROXY_DISPLACEMENT)
        DFL_LANES(1, DFL_PROXY_DISPLACEMENT, 0);
    else if (order == 1 && clip > 0)
        DFL_LANES(1, DFL_PROXY_ABSOLUTE, 1);
    else if (order == 1)
        DFL_LANES(1, DFL_PROXY_ABSOLUTE, 0);
    else if (pos == DFL_PROXY_DISPLACEMENT && clip > 0)
        DFL_LANES(2, DFL_PROXY_DISPLACEMENT, 1);
    else if (pos == DFL_PROXY_DISPLACEMENT)
        DFL_LANES(2, DFL_PROXY_DISPLACEMENT, 0);
    else if (clip > 0)
        DFL_LANES(2, DFL_PROXY_ABSOLUTE, 1);
    else
        DFL_LANES(2, DFL_PROXY_ABSOLUTE, 0);
#undef DFL_LANES
}

/* The scalars of nb cells per query into lanes: cell q of query l
 * (cells[l nb + q], nb <= 8) to S[q][k][l], k < nscalar, and 0 for the
 * rest of DFL_PROXY_NSCALAR_MAX; dfl_proxy_cell_load's conversions straight
 * into the lanes, or for half storage with f16c one F16C block conversion
 * of the gathered halves (store.h: the same doubles). */
DFL_ISA_BODY void load_lanes(const dfl_proxy_grid *g, int f16c, const int nb, const size_t *cells,
                             double (*S)[DFL_PROXY_NSCALAR_MAX][QL])
{
    const int ns = g->nscalar;
    const size_t nsz = (size_t)ns;
    if (f16c) {
        uint16_t hb[8 * QL * DFL_PROXY_NSCALAR_MAX];
        double sc[8 * QL * DFL_PROXY_NSCALAR_MAX];
        const uint16_t *d = g->data;
        const size_t nc = (size_t)nb * QL;
        for (size_t j = 0; j < nc; j++) memcpy(hb + j * nsz, d + cells[j] * nsz, nsz * sizeof *hb);
        dfl_proxy_store_half_block(1, hb, nc * nsz, sc);
        for (size_t l = 0; l < QL; l++)
            for (int q = 0; q < nb; q++)
                for (int k = 0; k < ns; k++)
                    S[q][k][l] = sc[((size_t)nb * l + (size_t)q) * nsz + (size_t)k];
    } else {
        switch (g->storage) {
        case DFL_PROXY_DOUBLE:
            for (size_t l = 0; l < QL; l++)
                for (int q = 0; q < nb; q++) {
                    const double *cs = (const double *)g->data + cells[(size_t)nb * l + (size_t)q] * nsz;
                    for (int k = 0; k < ns; k++) S[q][k][l] = cs[k];
                }
            break;
        case DFL_PROXY_FLOAT:
            if (ns == 8) {
                /* order 2: a constant count, one vector conversion per cell */
                for (size_t l = 0; l < QL; l++)
                    for (int q = 0; q < nb; q++) {
                        const float *cs = (const float *)g->data + cells[(size_t)nb * l + (size_t)q] * 8;
                        for (int k = 0; k < 8; k++) S[q][k][l] = cs[k];
                    }
                break;
            }
            for (size_t l = 0; l < QL; l++)
                for (int q = 0; q < nb; q++) {
                    const float *cs = (const float *)g->data + cells[(size_t)nb * l + (size_t)q] * nsz;
                    for (int k = 0; k < ns; k++) S[q][k][l] = cs[k];
                }
            break;
        default:
            for (size_t l = 0; l < QL; l++)
                for (int q = 0; q < nb; q++) {
                    const uint16_t *cs = (const uint16_t *)g->data + cells[(size_t)nb * l + (size_t)q] * nsz;
                    for (int k = 0; k < ns; k++) S[q][k][l] = imath_half_to_float(cs[k]);
                }
        }
    }
    for (int q = 0; q < nb; q++)
        for (int k = ns; k < DFL_PROXY_NSCALAR_MAX; k++)
            for (size_t l = 0; l < QL; l++) S[q][k][l] = 0.0;
}

/* The nearest filter for c <= QL queries at x, across queries: the cells'
 * scalars are gathered into structure-of-arrays lanes (a short block
 * repeats its last query), then decoding, the proxy's distance, the clip
 * and the fold run in one lane loop (nearest_lanes), branch-free, so that
 * the compiler keeps QL queries in vector registers instead of one serial
 * chain of square roots and divisions per query.  Every lane computes what
 * one query at a time computed, operation for operation: the branches
 * become selects of values computed either way, and fmax(ball, |phi|) a
 * select (where the clip applies phi is finite and ball is not NaN, so
 * they agree); hence the same bytes.  The cell index runs across lanes too
 * (nearest_cell's clamp on the floored double, which is integral, so the
 * centre lo + (i + 0.5) h is nearest_cell's); order 2 has no sign byte. */
DFL_ISA_BODY void nearest_block(const dfl_proxy_grid *g, const dfl_proxy_filter_opts *o, int f16c,
                                size_t c, const double *x, double *val, double *grad)
{
    const int order = g->order;
    const dfl_proxy_position pos = g->position;
    /* the lanes compute the bound clip (or none): off is radius 0 */
    const double clip = o->clip_kind == DFL_PROXY_CLIP_OFF ? 0.0 : o->clip;
    double S[1][DFL_PROXY_NSCALAR_MAX][QL], XC[3][QL], X[3][QL], ID[3][QL], SIDE[QL], V[QL],
        G[3][QL];
    size_t cells[QL];
    const size_t n = (size_t)g->res;
    const double top = g->res - 1;
    for (int j = 0; j < 3; j++) {
        const double lo = g->lo[j], h = g->h[j];
        for (size_t l = 0; l < QL; l++) X[j][l] = x[3 * (l < c ? l : c - 1) + (size_t)j];
#pragma omp simd
        for (size_t l = 0; l < QL; l++) {
            const double s = floor((X[j][l] - lo) / h);
            const double id = !(s >= 0) ? 0.0 : s > top ? top : s;
            ID[j][l] = id;
            XC[j][l] = lo + (id + 0.5) * h;
        }
    }
    for (size_t l = 0; l < QL; l++)
        cells[l] = (size_t)ID[0][l] + n * ((size_t)ID[1][l] + n * (size_t)ID[2][l]);
    load_lanes(g, f16c, 1, cells, S);
    if (order == 1)
        for (size_t l = 0; l < QL; l++) SIDE[l] = g->side ? g->side[cells[l]] : 1;
    const int sgnd = o->is_signed;
    /* the uniform choices as constants, so that the lane loop has no branch */
    run_lanes(order, pos, clip, sgnd, grad != NULL, S[0], XC, X, SIDE, V, G);
    for (size_t l = 0; l < c; l++) {
        val[l] = V[l];
        if (grad)
            for (int j = 0; j < 3; j++) grad[3 * l + (size_t)j] = G[j][l];
    }
}

/* The blend filters (trilinear, Hermite) for c <= QL queries at x, across
 * queries as nearest_block does: per query blend_setup's corners and
 * weights; the 8 corners' scalars gathered into lanes (corner q of query l
 * in lane l of block q; a short block repeats its last query) and each
 * block run through nearest_lanes without the fold (clip bound or none;
 * dist_ijk's decoding, distance and clip, operation for operation); then
 * per query blend's sum, in blend's order with blend's fold (d < 0: a NaN
 * is not negated here) and its skip of zero weights without gradient (so
 * that 0 x inf adds no NaN).  Hence blend's bytes. */
DFL_ISA_BODY void blend_block(const dfl_proxy_grid *g, const dfl_proxy_filter_opts *o, int f16c,
                              size_t c, const double *x, double *val, double *grad)
{
    const int order = g->order, ns = g->nscalar;
    const dfl_proxy_position pos = g->position;
    const double clip = o->clip_kind == DFL_PROXY_CLIP_OFF ? 0.0 : o->clip;
    const size_t n = (size_t)g->res;
    double S[8][DFL_PROXY_NSCALAR_MAX][QL], XC[8][3][QL], X[3][QL], SIDE[8][QL], V[8][QL],
        G[8][3][QL], w[QL][3][2], dw[QL][3][2];
    size_t ids[2][3][QL], cells[QL][8]; /* ids: lower, upper corner index per axis */
    const size_t bytes = (size_t)ns * dfl_proxy_storage_size(g->storage);
    for (size_t l = 0; l < QL; l++) {
        const size_t i = l < c ? l : c - 1;
        size_t i0[3], i1[3];
        blend_setup(g, o, x + 3 * i, i0, i1, w[l], dw[l]);
        for (int j = 0; j < 3; j++) X[j][l] = x[3 * i + (size_t)j];
        for (int j = 0; j < 3; j++) ids[0][j][l] = i0[j], ids[1][j][l] = i1[j];
        for (int q = 0; q < 8; q++) {
            const size_t id0 = q & 1 ? i1[0] : i0[0], id1 = (q >> 1) & 1 ? i1[1] : i0[1],
                         id2 = (q >> 2) & 1 ? i1[2] : i0[2];
            cells[l][q] = id0 + n * (id1 + n * id2);
            /* the 64 cells' loads overlap (queries in no order miss the cache) */
            __builtin_prefetch((const char *)g->data + cells[l][q] * bytes);
        }
    }
    /* the corner centres: two per axis and query, each corner's row by its bit */
    double C[2][3][QL];
    for (int j = 0; j < 3; j++)
        for (size_t l = 0; l < QL; l++) {
            C[0][j][l] = g->lo[j] + ((double)ids[0][j][l] + 0.5) * g->h[j];
            C[1][j][l] = g->lo[j] + ((double)ids[1][j][l] + 0.5) * g->h[j];
        }
    for (int q = 0; q < 8; q++)
        for (int j = 0; j < 3; j++) memcpy(XC[q][j], C[(q >> j) & 1][j], sizeof XC[q][j]);
    load_lanes(g, f16c, 8, &cells[0][0], S);
    /* the sign byte: order 1 only (order 2 decodes its sign from L t) */
    if (order == 1)
        for (size_t l = 0; l < QL; l++)
            for (int q = 0; q < 8; q++) SIDE[q][l] = g->side ? g->side[cells[l][q]] : 1;
    for (int q = 0; q < 8; q++)
        run_lanes(order, pos, clip, 1, grad != NULL, S[q], XC[q], X, SIDE[q], V[q], G[q]);
    if (!grad) {
        /* blend's sum across queries: per lane the same products, folds,
         * skips (a select keeping the sum) and order of additions */
        double wv[3][2][QL], acc[QL];
        for (size_t l = 0; l < QL; l++) {
            acc[l] = 0;
            for (int j = 0; j < 3; j++) wv[j][0][l] = w[l][j][0], wv[j][1][l] = w[l][j][1];
        }
        const int fold = !o->is_signed;
        for (int q = 0; q < 8; q++) {
            const int a = q & 1, b = (q >> 1) & 1, cc = (q >> 2) & 1;
#pragma omp simd
            for (size_t l = 0; l < QL; l++) {
                const double W = wv[0][a][l] * wv[1][b][l] * wv[2][cc][l];
                const double d = fold && V[q][l] < 0 ? -V[q][l] : V[q][l];
                const double s = acc[l] + W * d;
                acc[l] = W == 0 ? acc[l] : s;
            }
        }
        for (size_t l = 0; l < c; l++) val[l] = acc[l];
        return;
    }
    for (size_t l = 0; l < c; l++) {
        double v = 0, gr[3] = {0, 0, 0};
        for (int q = 0; q < 8; q++) {
            const int a = q & 1, b = (q >> 1) & 1, cc = (q >> 2) & 1;
            const double W = w[l][0][a] * w[l][1][b] * w[l][2][cc];
            if (W == 0 && !grad) continue;
            double d = V[q][l], gd[3] = {0, 0, 0};
            if (grad)
                for (int j = 0; j < 3; j++) gd[j] = G[q][j][l];
            if (!o->is_signed && d < 0) {
                d = -d;
                for (int j = 0; j < 3; j++) gd[j] = -gd[j];
            }
            v += W * d;
            if (grad) {
                const double gw[3] = {dw[l][0][a] * w[l][1][b] * w[l][2][cc],
                                      w[l][0][a] * dw[l][1][b] * w[l][2][cc],
                                      w[l][0][a] * w[l][1][b] * dw[l][2][cc]};
                for (int j = 0; j < 3; j++) gr[j] += W * gd[j] + d * gw[j];
            }
        }
        val[l] = v;
        if (grad)
            for (int j = 0; j < 3; j++) grad[3 * l + (size_t)j] = gr[j];
    }
}

/* The query loop, compiled per ISA (core/isa.h): same bytes on each. */
DFL_ISA_BODY void queries_body(const dfl_proxy_grid *g, const dfl_proxy_filter_opts *o, size_t m,
                               const double *x, double *val, double *grad)
{
    /* half storage loads through F16C where the process may use it */
    const int f16c = g->storage == DFL_PROXY_HALF && dfl_proxy_store_has_f16c();
    if (o->filter == DFL_PROXY_NEAREST) {
        if (o->clip_kind == DFL_PROXY_CLIP_PAPER && o->clip > 0) {
            /* the paper's reading of the clip has no lane loop: one query
             * at a time, the same formula as dfl_proxy_proxy_dist */
            for (size_t i = 0; i < m; i++) {
                double *gi = grad ? grad + 3 * i : NULL;
                size_t c[3];
                nearest_cell(g, x + 3 * i, c);
                double v = dist_ijk(g, c[0], c[1], c[2], o, x + 3 * i, gi);
                if (!o->is_signed && !(v >= 0)) {
                    v = -v;
                    if (gi)
                        for (int j = 0; j < 3; j++) gi[j] = -gi[j];
                }
                val[i] = v;
            }
            return;
        }
        for (size_t i = 0; i < m; i += QL)
            nearest_block(g, o, f16c, m - i < QL ? m - i : QL, x + 3 * i, val + i,
                          grad ? grad + 3 * i : NULL);
        return;
    }
    if (o->clip_kind == DFL_PROXY_CLIP_PAPER && o->clip > 0) {
        for (size_t i = 0; i < m; i++) val[i] = blend(g, o, x + 3 * i, grad ? grad + 3 * i : NULL);
        return;
    }
    for (size_t i = 0; i < m; i += QL)
        blend_block(g, o, f16c, m - i < QL ? m - i : QL, x + 3 * i, val + i,
                    grad ? grad + 3 * i : NULL);
}
DFL_ISA_KERNEL(queries,
               (const dfl_proxy_grid *g, const dfl_proxy_filter_opts *o, size_t m,
                const double *x, double *val, double *grad),
               (g, o, m, x, val, grad))

void dfl_proxy_filter_eval(const dfl_proxy_grid *g, const dfl_proxy_filter_opts *o, size_t m,
                           const double *x, double *val, double *grad)
{
    queries(g, o, m, x, val, grad);
}
