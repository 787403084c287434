/* bs04 appendix A: recursive normalization of a function that is not a
 * distance, the ellipse's f = x^2/a^2 + y^2/b^2 - 1, to order m (A.1, A.4;
 * rfunc/normalize.h), with the order measured by exact jets at boundary
 * points and the field compared with the exact signed distance to the
 * ellipse (geom/ellipse.h).  One sweep point = one (m, shape);
 * one CSV row per point.
 *
 * Keys.
 *   [field] kind = normalized (cfg/rfunc_cfg.h; the figure's field, so
 *           `dflab probe` evaluates it):
 *           implicit = implicit   the section of the implicit function
 *           m      = order, 1..6 (the cost grows like the Taylor degree
 *                    m(m+1)/2 to the power 2 dim, see normalize.h)
 *   [implicit] kind = ellipse, a, b      semi-axes (> 0) along x and y
 *   [study] points = 64       boundary points p_i = (a cos th, b sin th),
 *                             th = 2 pi (i + 1/2) / points; rays along the
 *                             outward normal (slope +1) and inward (-1)
 *           K      = 8        jet order (> m, <= 24)
 *           tol    = 1e-9     zero test of normorder.h with L = min(rho(p),
 *                             R): rho the local radius of curvature, R the
 *                             series' own scale (dfl_normorder_scale; the
 *                             recursion's coefficients grow far faster
 *                             than rho suggests, and so does their rounding)
 *           bands  = 0.02 0.05 0.1   grid metrics over the nodes with
 *                             |d| <= band, one set of columns per band
 *                             (increasing, > 0)
 *           deltas = 0.002 0.004 0.008   normal-line errors: for every p
 *                             and delta, |u(p +- delta nu) -+ delta|, max
 *                             over p (the exact distance along the normal is
 *                             delta: outside for a convex curve, inside while
 *                             delta < rho_min = min(a,b)^2 / max(a,b), as a
 *                             disk of that radius rolls freely inside
 *                             (Blaschke); enforced); line_slope is the least-squares slope of
 *                             log(error) against log(delta), m + 1 in theory
 *                             (u = s + a_(m+1) s^(m+1) + ...)
 *   [grid] (2D), [output] (field_out.h): the normalized field with the exact
 *   signed distance as reference -> normalized<tag>.vti/.exr.
 * Far from the curve the recursion diverges (f1^k D^k f(k-1) nests
 * derivatives of order up to m(m+1)/2 of a field whose normal direction is
 * singular at the centre, where grad f = 0): normalization is local (bs04
 * Sec. 1.2).  The band columns show where it helps; non-finite values are
 * counted (nonfinite_nodes) and enter linf as infinity.
 *
 * Rows: a, b, m, rays, order_theory = m, measured_order_min/max, match,
 * first_k, first_coef_min/max (|a_(m+1)| over the rays: non-zero),
 * d1_maxdev, line_delta_i / line_err_i, line_slope, line_slope_theory,
 * nodes, nonfinite_nodes, per band i: band_i, band_nodes_i, l1_band_i
 * (mean |u - d|), rms_band_i, linf_band_i, graddefect_mean_band_i,
 * graddefect_max_band_i (| |grad u| - 1 |), and vti.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/fit.h"
#include "geom/ellipse.h"
#include "core/vec.h"
#include "harness/experiment.h"
#include "field/sample.h"
#include "harness/field_out.h"
#include "cfg/field_cfg.h"
#include "cfg/field_cost.h"
#include "cfg/grid_cfg.h"
#include "cfg/rfunc_cfg.h"
#include "field/metrics.h"
#include "field/normorder.h"
#include "rfunc/normalize.h"

#define REC_MAX_DELTAS 8
#define REC_MAX_BANDS 8

typedef struct rec_keys {
    double a, b, tol;
    long m, points, K;
    double *deltas, *bands;
    size_t ndeltas, nbands;
    dfl_grid grid;
    dfl_field_write_opts out;
} rec_keys;

static dfl_status read_keys(const dfl_cfg *cfg, rec_keys *k, dfl_err *err)
{
    const dfl_field_kind *kind;
    const char *imp;
    dfl_status st;
    memset(k, 0, sizeof *k);
    if ((st = dfl_field_kind_from_cfg(cfg, "field", &kind, err))) return st;
    if (kind->build != dfl_rfunc_normalized_from_cfg)
        return dfl_cfg_reject(cfg, "field", "kind", err,
                              "bs04_recursive needs kind = normalized, got '%s'", kind->name);
    if ((st = dfl_rfunc_normalized_keys(cfg, "field", &imp, &k->a, &k->b, &k->m, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "points", 64, 1, 100000, &k->points, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "K", 8, 2, DFL_JET_MAX, &k->K, err))) return st;
    if (k->K <= k->m)
        return dfl_cfg_reject(cfg, "study", "K", err,
                              "the jet order must exceed m = %ld to see the first non-zero"
                              " coefficient, got %ld", k->m, k->K);
    if ((st = dfl_cfg_double_opt(cfg, "study", "tol", 1e-9, 1e-15, 1e-2, &k->tol, err))) return st;
    if ((st = dfl_cfg_doubles(cfg, "study", "bands", 1, &k->bands, &k->nbands, err))) return st;
    if (k->nbands > REC_MAX_BANDS)
        return dfl_cfg_reject(cfg, "study", "bands", err, "at most %d values", REC_MAX_BANDS);
    for (size_t i = 0; i < k->nbands; i++)
        if (!(k->bands[i] > 0.0) || (i > 0 && !(k->bands[i] > k->bands[i - 1])))
            return dfl_cfg_reject(cfg, "study", "bands", err,
                                  "expected increasing values > 0, got %g", k->bands[i]);
    if ((st = dfl_cfg_doubles(cfg, "study", "deltas", 2, &k->deltas, &k->ndeltas, err))) return st;
    /* rho >= rho_min = min(a, b)^2 / max(a, b) everywhere, and a disk of
     * radius rho_min rolls freely inside (Blaschke): below it every inward
     * normal segment of length delta ends at a point whose closest point is
     * p, so the exact distance along it is delta */
    const double rho_min = fmin(k->a, k->b) * fmin(k->a, k->b) / fmax(k->a, k->b);
    if (k->ndeltas > REC_MAX_DELTAS)
        return dfl_cfg_reject(cfg, "study", "deltas", err, "at most %d values", REC_MAX_DELTAS);
    for (size_t i = 0; i < k->ndeltas; i++)
        if (!(k->deltas[i] > 0.0 && k->deltas[i] < rho_min) ||
            (i > 0 && !(k->deltas[i] > k->deltas[i - 1])))
            return dfl_cfg_reject(cfg, "study", "deltas", err,
                                  "expected increasing values in (0, %g) (the smallest radius of"
                                  " curvature), got %g", rho_min, k->deltas[i]);
    if ((st = dfl_grid_from_cfg(cfg, "grid", 2, &k->grid, err))) return st;
    return dfl_field_out_from_cfg(cfg, &k->out, err);
}

/* Jets at the boundary points, both sides of the normal. */
typedef struct jet_stats {
    int omin, omax, kmin;    /* measured orders; k of the minimum */
    double cmin, cmax;       /* |a_(m+1)| over the rays of order m */
    double d1dev;            /* max |d1 - side| */
    double lerr[REC_MAX_DELTAS]; /* normal-line errors per delta */
} jet_stats;

static dfl_status boundary_jets(const rec_keys *k, const dfl_field *f, jet_stats *out,
                                dfl_err *err)
{
    const int m = (int)k->m, K = (int)k->K;
    int omin = 1 << 30, omax = -1, kmin = 0;
    double cmin = INFINITY, cmax = 0, d1dev = 0;
    double lerr[REC_MAX_DELTAS] = {0};
    dfl_status st = DFL_OK;
    for (long i = 0; i < k->points && st == DFL_OK; i++) {
        const double th = 2 * DFL_PI * ((double)i + 0.5) / (double)k->points;
        const double p[2] = {k->a * cos(th), k->b * sin(th)};
        double nu[2] = {p[0] / (k->a * k->a), p[1] / (k->b * k->b)};
        const double nn = hypot(nu[0], nu[1]);
        nu[0] /= nn;
        nu[1] /= nn;
        /* radius of curvature of (a cos th, b sin th): (a^2 s^2 + b^2 c^2)^(3/2) / (a b) */
        const double sp = hypot(k->a * sin(th), k->b * cos(th));
        const double rho = sp * sp * sp / (k->a * k->b);
        for (int side = 1; side >= -1 && st == DFL_OK; side -= 2) {
            const double dir[2] = {side * nu[0], side * nu[1]};
            dfl_jet j;
            dfl_normorder r;
            st = dfl_field_jet(f, p, dir, K, &j, err);
            if (st == DFL_OK)
                st = dfl_normorder_measure(&j, (double)side, fmin(rho, dfl_normorder_scale(&j)),
                                           k->tol, &r, err);
            if (st != DFL_OK) {
                dfl_err_prefix(err, "bs04_recursive: jet at (%g, %g)", p[0], p[1]);
                break;
            }
            if (r.order < omin) {
                omin = r.order;
                kmin = r.k;
            }
            if (r.order > omax) omax = r.order;
            if (!r.capped && r.order == m) {
                cmin = fmin(cmin, fabs(r.coef));
                cmax = fmax(cmax, fabs(r.coef));
            }
            d1dev = fmax(d1dev, fabs(r.d1 - side));
            for (size_t q = 0; q < k->ndeltas; q++) {
                const double dl = k->deltas[q];
                const double x[2] = {p[0] + side * dl * nu[0], p[1] + side * dl * nu[1]};
                const double e = fabs(dfl_field_eval1(f, x, NULL) - side * dl);
                if (!(e <= lerr[q])) lerr[q] = e; /* NAN propagates */
            }
        }
    }
    if (st != DFL_OK) return st;
    out->omin = omin, out->omax = omax, out->kmin = kmin;
    out->cmin = cmin, out->cmax = cmax, out->d1dev = d1dev;
    memcpy(out->lerr, lerr, sizeof lerr);
    return DFL_OK;
}

/* u, grad u on the grid, the exact signed distance d, and the number of
 * nodes where u or its gradient is not finite. */
static dfl_status sample_grid(const rec_keys *k, const dfl_field *f, int threads, double *u,
                              double *gu, double *d, long *nonfinite, dfl_err *err)
{
    const size_t nn = dfl_grid_size(&k->grid);
    dfl_status st = dfl_field_sample(f, &k->grid, threads, u, gu, err);
    if (st != DFL_OK) return st;
    long bad = 0;
    for (size_t i = 0; i < nn; i++) {
        double x[2];
        dfl_grid_node(&k->grid, i, x);
        d[i] = dfl_ellipse_sdist(k->a, k->b, x, NULL, NULL);
        if (!isfinite(u[i]) || !isfinite(gu[2 * i]) || !isfinite(gu[2 * i + 1])) bad++;
    }
    *nonfinite = bad;
    return DFL_OK;
}

static dfl_status rec_run(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_table *table,
                          dfl_err *err)
{
    rec_keys k;
    dfl_field f = {0};
    dfl_field_bufs b = {0};
    dfl_status st = read_keys(cfg, &k, err);
    /* the figure's field is [field]'s (what `dflab probe` evaluates) */
    if (st == DFL_OK) st = dfl_rfunc_normalized_from_cfg(cfg, "field", &f, err);
    if (st == DFL_OK) st = dfl_cfg_check_used(cfg, err);
    if (st != DFL_OK) goto done;

    const int m = (int)k.m, K = (int)k.K;
    jet_stats js;
    if ((st = boundary_jets(&k, &f, &js, err))) goto done;
    const int omin = js.omin, omax = js.omax, kmin = js.kmin;
    const double cmin = js.cmin, cmax = js.cmax, d1dev = js.d1dev;
    const double *lerr = js.lerr;

    /* the grid against the exact signed distance */
    const size_t nn = dfl_grid_size(&k.grid);
    if (!dfl_field_bufs_alloc(&b, nn, 2, true)) {
        st = dfl_err_set(err, DFL_E_NOMEM, "out of memory for %zu nodes", nn);
        goto done;
    }
    long nonfinite = 0;
    if ((st = sample_grid(&k, &f, ctx->threads, b.u, b.gu, b.ref, &nonfinite, err))) goto done;

    st = dfl_table_row(table, err);
#define SETI(c, v) \
    if (!st) st = dfl_table_set_int(table, c, (long)(v), err)
#define SETD(c, v) \
    if (!st) st = dfl_table_set_double(table, c, v, err)
    SETD("a", k.a);
    SETD("b", k.b);
    SETI("m", m);
    SETI("rays", 2 * k.points);
    SETI("K", K);
    SETI("order_theory", m);
    SETI("measured_order_min", omin);
    SETI("measured_order_max", omax);
    SETI("match", omin == m && omax == m);
    SETI("first_k", kmin);
    if (cmax > 0) {
        SETD("first_coef_min", cmin);
        SETD("first_coef_max", cmax);
    }
    SETD("d1_maxdev", d1dev);
    for (size_t q = 0; q < k.ndeltas; q++) {
        char c[32];
        snprintf(c, sizeof c, "line_delta_%zu", q + 1);
        SETD(c, k.deltas[q]);
        snprintf(c, sizeof c, "line_err_%zu", q + 1);
        SETD(c, lerr[q]);
    }
    SETD("line_slope", dfl_fit_loglog_slope(k.ndeltas, k.deltas, lerr));
    SETI("line_slope_theory", m + 1);
    SETI("nodes", nn);
    SETI("nonfinite_nodes", nonfinite);
    for (size_t q = 0; q < k.nbands && !st; q++) {
        /* far from the curve the recursion may overflow: such nodes enter
         * the band metrics as +inf (they are counted in nonfinite_nodes) */
        dfl_metrics bm;
        st = dfl_metrics_compute_saturating(nn, 2, b.u, b.gu, b.ref, k.bands[q], &bm, err);
        char c[48];
#define SETB(name, v)                                         \
    do {                                                      \
        snprintf(c, sizeof c, "%s_%zu", name, q + 1);         \
        SETD(c, v);                                           \
    } while (0)
        SETB("band", k.bands[q]);
        snprintf(c, sizeof c, "band_nodes_%zu", q + 1);
        SETI(c, bm.count);
        if (bm.count) {
            SETB("l1_band", bm.l1);
            SETB("rms_band", bm.rms);
            SETB("linf_band", bm.linf);
            SETB("graddefect_mean_band", bm.gdef_mean);
            SETB("graddefect_max_band", bm.gdef_max);
        }
#undef SETB
    }
    if (!st) st = dfl_study_put_file(table, "vti", ctx, "normalized", "vti", k.out.vti, err);
#undef SETI
#undef SETD
    if (st != DFL_OK) goto done;
    st = dfl_field_out_write(ctx, "normalized", &k.grid, b.u, b.gu, b.ref, &k.out, err);
done:
    dfl_field_bufs_free(&b);
    free(k.deltas);
    free(k.bands);
    dfl_field_destroy(&f);
    return st;
}

/* Peak memory: the grid's samples (u, grad u, the exact distance: 32 bytes
 * a node) and the writer's buffers (dfl_field_out_bytes); the jets hold a
 * few Taylor polynomials.  Work: the normalized field at every node
 * (dfl_field_eval_cost: (m (m + 1) / 2 + 2)^4 CHEAP) and an exact ellipse
 * distance and the files; per boundary point two jets of order K, each a recursion to
 * degree K + m (m + 1) / 2 + 1 in 2 variables, counted as (K + m (m + 1) /
 * 2 + 2)^4 CHEAP, and 2 x deltas field evaluations. */
static dfl_status rec_estimate(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_cost *c,
                               dfl_err *err)
{
    (void)ctx;
    rec_keys k;
    dfl_cost_class cls;
    double units;
    dfl_status st = read_keys(cfg, &k, err);
    if (!st) st = dfl_field_eval_cost(cfg, "field", &cls, &units, err);
    free(k.deltas), free(k.bands);
    if (st) return st;
    const double m = (double)dfl_grid_size(&k.grid), tri = k.m * (k.m + 1) / 2.0;
    dfl_cost_add_bytes(c, "grid", "n", 32 * m + dfl_field_out_bytes(&k.out, m),
                       "the samples and files of %d^2 nodes", k.grid.n[0]);
    dfl_cost_add_work(c, "grid", "n", cls, m * units, "%.3g nodes", m);
    dfl_cost_add_work(c, "grid", "n", DFL_COST_EXACT, m, "%.3g exact distances", m);
    dfl_cost_add_work(c, "grid", "n", DFL_COST_CHEAP, dfl_field_out_units(&k.out, m),
                      "the files of %.3g nodes", m);
    const double rays = 2.0 * (double)k.points;
    dfl_cost_add_work(c, "study", "points", DFL_COST_CHEAP,
                      rays * (pow(k.K + tri + 2, 4) + (double)k.ndeltas * units),
                      "%.3g rays of jets of order %ld", rays, k.K);
    return DFL_OK;
}

DFL_STUDY_DEFINE_ESTIMATED(bs04_recursive, rec_run, rec_estimate,
                 "bs04 app. A: recursive normalization of an ellipse's implicit function, m = 1..6");
