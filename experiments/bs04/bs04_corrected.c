/* bs04 study 7: the corrected join (eq. 20, Fig. 14) beside R-equivalence.
 *
 * Two segments of length L share the vertex O at the angle alpha (vjoin.h).
 * Their fields (exact distances, as eq. 20's derivation assumes, or a
 * library trim) are joined by R-equivalence (eq. 6) and by the corrected
 * R-equivalence (eq. 20 with q = |x - O|).  Measured:
 *   in the hatched sector (closest point of both segments is O, computed
 *     exactly: x . e1 <= 0 and x . e2 <= 0), sampled in polar coordinates
 *     (sector_nr radii up to sector_rmax L times sector_nt directions at
 *     the midpoints of equal angular steps; for alpha = 180 degrees the
 *     sector is the line x . e1 = 0, sampled on its two rays):
 *     max and min of | |grad u| - 1 |, and max |u - q| / q.  Theory for
 *     exact parts: h1 = h2 = q there, so eq. 6 gives u = 2^(-1/p) q,
 *     |grad u| = 2^(-1/p) (defect 1 - 2^(-1/p)), and eq. 20 gives u = q,
 *     |grad u| = 1 (defect 0);
 *   elsewhere, on the [grid], against the exact distance d to the union:
 *     "band": nodes with 0 < d <= band and |x - O| >= vertex_radius (near
 *     regular points, where both joins are normalized to order p), and
 *     "vertex": nodes with |x - O| < vertex_radius outside the hatched
 *     sector (the convex sector's bulge, which eq. 20 does not remove);
 *     max and mean | |grad u| - 1 | and max |u - d|.
 * Keys ([study]): alpha (degrees, sweep), length (1), parts (exact | disk |
 *   disk_smooth | strip | strip_smooth), p, sector_nr (40), sector_nt (21),
 *   sector_rmax (0.5, relative to L), band (0.1 L), vertex_radius (0.25 L);
 *   [grid] n, lo, hi (2D); [output] vti, exr, compress, half.
 * Three joins per point: eq. 6 (correction "none"), dflab's guarded eq. 20
 * (correction "guarded") and bs04's eq. 20 as printed ("eq20", NaN where
 * its radicand <= 0; NaN nodes and samples are counted, not measured).
 * Extra keys: case_theta (80 degrees), case_r (0.5 L), onset_rmax (10 L).
 * Extra columns: correction, sector_undefined, undefined_count and
 *   undefined_share (grid), onset_radius (eq20: first NaN on the hatched
 *   bisector, bisected, / L) and onset_radius_theory (disk parts: the
 *   closed form of rfunc/join.h), reflex_linf (max |u - d| off the convex
 *   sector), case_u and case_d (u / r and d / r at case_theta, case_r).
 * Rows: one per join (requiv, requiv_corrected): alpha, p, parts, join,
 *   sector_points, sector_gdef_max / _min, sector_gdef_theory (exact
 *   parts), sector_gdef_at_rmin (max over the innermost ring, r = rmax L /
 *   nr), sector_value_relerr_max (|u - q| / q), sector_part_gdef_max (max
 *   ||grad h_i| - 1| in the sector), band_ and vertex_ count, gdef_max,
 *   gdef_mean, linf.  Files: requiv<tag>.vti
 * /.exr, corrected<tag>.vti/.exr and eq20<tag>.vti/.exr (value, gradient,
 * grad_norm, error = u - d, reference = d).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/experiment.h"
#include "field/sample.h"
#include "harness/field_out.h"
#include "cfg/field_cost.h"
#include "cfg/grid_cfg.h"
#include "bs04/vjoin.h"
#include "core/vec.h"

typedef struct cj_keys {
    dfl_vjoin vj;
    long p, nr, nt;
    double rmax, band, vradius;
    double case_theta, case_r, onset_rmax;
    dfl_grid grid;
    dfl_field_write_opts oo;
} cj_keys;

static dfl_status read_keys(const dfl_cfg *cfg, cj_keys *k, dfl_err *err)
{
    dfl_status st;
    memset(k, 0, sizeof *k);
    if ((st = dfl_vjoin_from_cfg(cfg, "study", &k->vj, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "p", 2, 1, DFL_RFUNC_P_MAX, &k->p, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "sector_nr", 40, 1, 100000, &k->nr, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "sector_nt", 21, 1, 100000, &k->nt, err))) return st;
    if ((st = dfl_cfg_double_opt(cfg, "study", "sector_rmax", 0.5, 1e-9, 100, &k->rmax, err)))
        return st;
    if ((st = dfl_cfg_double_opt(cfg, "study", "band", 0.1, 1e-9, 100, &k->band, err))) return st;
    if ((st = dfl_cfg_double_opt(cfg, "study", "vertex_radius", 0.25, 0, 100, &k->vradius, err)))
        return st;
    if ((st = dfl_cfg_double_opt(cfg, "study", "case_theta", 80, 0, 360, &k->case_theta, err)))
        return st;
    if ((st = dfl_cfg_double_opt(cfg, "study", "case_r", 0.5, 1e-9, 100, &k->case_r, err)))
        return st;
    if ((st = dfl_cfg_double_opt(cfg, "study", "onset_rmax", 10, 1e-6, 1000, &k->onset_rmax, err)))
        return st;
    if ((st = dfl_grid_from_cfg(cfg, "grid", 2, &k->grid, err))) return st;
    return dfl_field_out_from_cfg(cfg, &k->oo, err);
}

typedef struct sector_stats {
    long count, undefined;
    double gdef_max, gdef_min, gdef_rmin, verr_max, part_gdef_max;
} sector_stats;

/* Sector samples (exact geometry, see the header) into pts (room for
 * 2 * nr * max(nt, 2) doubles); returns how many pass the exact hatched
 * test (all in exact arithmetic; rounding of cos/sin may drop some). */
static size_t sector_points(const cj_keys *k, double *pts)
{
    double t0, t1;
    int nrays;
    dfl_vjoin_hatched_range(&k->vj, &t0, &t1, &nrays);
    size_t m = 0;
    const long nt = nrays == 2 ? 2 : k->nt;
    for (long a = 0; a < nt; a++) {
        double c, s;
        if (nrays == 2) {
            /* the normal of segment 1, both ways: exact coordinates */
            c = -k->vj.e1[1] * (a ? -1.0 : 1.0);
            s = k->vj.e1[0] * (a ? -1.0 : 1.0);
        } else {
            const double t = t0 + (t1 - t0) * ((double)a + 0.5) / (double)nt;
            c = cos(t);
            s = sin(t);
        }
        for (long j = 1; j <= k->nr; j++) {
            const double r = k->rmax * k->vj.length * (double)j / (double)k->nr;
            const double x[2] = {r * c, r * s};
            if (!dfl_vjoin_hatched(&k->vj, x)) continue;
            pts[2 * m] = x[0];
            pts[2 * m + 1] = x[1];
            m++;
        }
    }
    return m;
}

static void measure_sector(const cj_keys *k, const dfl_field *f, size_t m, const double *pts,
                           double *val, double *grad, sector_stats *ss)
{
    f->ops->eval(f->ctx, m, pts, val, grad);
    memset(ss, 0, sizeof *ss);
    ss->count = (long)m;
    ss->gdef_min = m ? INFINITY : NAN;
    /* the innermost ring: nominal radius rmax L / nr (up to rounding) */
    const double r1 = k->rmax * k->vj.length / (double)k->nr * (1.0 + 1e-9);
    for (size_t i = 0; i < m; i++) {
        const double *x = pts + 2 * i;
        const double q = hypot(x[0], x[1]);
        if (isnan(val[i])) {
            /* eq. 20 undefined (correction = eq20): counted, not measured */
            ss->undefined++;
            continue;
        }
        const double gdef = fabs(hypot(grad[2 * i], grad[2 * i + 1]) - 1.0);
        double h[2], gh[4];
        dfl_vjoin_parts(&k->vj, x, h, gh);
        ss->gdef_max = fmax(ss->gdef_max, gdef);
        ss->gdef_min = fmin(ss->gdef_min, gdef);
        ss->verr_max = fmax(ss->verr_max, fabs(val[i] - q) / q);
        ss->part_gdef_max = fmax(ss->part_gdef_max, fmax(fabs(hypot(gh[0], gh[1]) - 1.0),
                                                         fabs(hypot(gh[2], gh[3]) - 1.0)));
        if (q <= r1) ss->gdef_rmin = fmax(ss->gdef_rmin, gdef);
    }
}

typedef struct region_stats {
    long count;
    double gdef_max, gdef_mean, linf;
} region_stats;

static void region_add(region_stats *r, double gdef, double err)
{
    r->count++;
    r->gdef_max = fmax(r->gdef_max, gdef);
    r->gdef_mean += gdef;
    r->linf = fmax(r->linf, fabs(err));
}

/* Grid regions of the header: band (near regular points) and vertex. */
/* 1 when x lies in the closed convex sector between the segments (the
 * smaller angle alpha'); the reflex side is its complement. */
static bool in_convex(const dfl_vjoin *vj, const double *x)
{
    const double c1 = vj->e1[0] * x[1] - vj->e1[1] * x[0];
    const double c2 = vj->e2[0] * x[1] - vj->e2[1] * x[0];
    return vj->alpha <= DFL_PI ? c1 >= 0.0 && c2 <= 0.0 : c1 <= 0.0 && c2 >= 0.0;
}

typedef struct grid_extra {
    long undefined;   /* nodes where u is NaN (eq. 20 undefined) */
    double reflex_linf; /* max |u - d| over defined nodes off the convex sector */
} grid_extra;

static void measure_grid(const cj_keys *k, const double *u, const double *gu, const double *d,
                         region_stats *band, region_stats *vert, grid_extra *ge)
{
    memset(band, 0, sizeof *band);
    memset(vert, 0, sizeof *vert);
    memset(ge, 0, sizeof *ge);
    const size_t m = dfl_grid_size(&k->grid);
    const double L = k->vj.length;
    for (size_t i = 0; i < m; i++) {
        double x[3];
        dfl_grid_node(&k->grid, i, x);
        if (isnan(u[i])) {
            ge->undefined++;
            continue;
        }
        if (!(d[i] > 0.0)) continue; /* on the set: gradient is a convention */
        if (!in_convex(&k->vj, x)) ge->reflex_linf = fmax(ge->reflex_linf, fabs(u[i] - d[i]));
        const double gdef = fabs(hypot(gu[2 * i], gu[2 * i + 1]) - 1.0);
        const double rv = hypot(x[0], x[1]);
        if (rv >= k->vradius * L && d[i] <= k->band * L)
            region_add(band, gdef, u[i] - d[i]);
        else if (rv < k->vradius * L && !dfl_vjoin_hatched(&k->vj, x))
            region_add(vert, gdef, u[i] - d[i]);
    }
    band->gdef_mean = band->count ? band->gdef_mean / (double)band->count : NAN;
    vert->gdef_mean = vert->count ? vert->gdef_mean / (double)vert->count : NAN;
    if (!band->count) band->gdef_max = band->linf = NAN;
    if (!vert->count) vert->gdef_max = vert->linf = NAN;
}

/* Onset radius / L of eq. 20's undefined region on the bisector of the
 * hatched sector: the first of 4000 radii up to onset_rmax L where u is
 * NaN, refined by bisection (60 steps); NaN when u is defined on the whole
 * scan.  The closed form (disk trim, rfunc/join.h): h_i = q sqrt(1 + 2 a
 * rho + rho^2) with a = cos(alpha'/2) on the bisector, radicand 0 at
 * rho* = sqrt(a^2 + 2^(2/p) - 1) - a. */
static double onset_measured(const cj_keys *k, const dfl_field *f)
{
    double t0, t1;
    int nrays;
    dfl_vjoin_hatched_range(&k->vj, &t0, &t1, &nrays);
    const double t = 0.5 * (t0 + t1), L = k->vj.length;
    const double c = nrays == 2 ? -k->vj.e1[1] : cos(t), s = nrays == 2 ? k->vj.e1[0] : sin(t);
    const int n = 4000;
    double lo = 0.0, hi = NAN;
    for (int i = 1; i <= n && isnan(hi); i++) {
        const double r = k->onset_rmax * L * i / n, x[2] = {r * c, r * s};
        if (isnan(dfl_field_eval1(f, x, NULL))) hi = r;
        else lo = r;
    }
    if (isnan(hi)) return NAN;
    for (int it = 0; it < 60; it++) {
        const double r = 0.5 * (lo + hi), x[2] = {r * c, r * s};
        if (isnan(dfl_field_eval1(f, x, NULL))) hi = r;
        else lo = r;
    }
    return 0.5 * (lo + hi) / L;
}

static double onset_theory(const cj_keys *k)
{
    if (k->vj.parts != 1 + DFL_RFUNC_TRIM_DISK) return NAN;
    const double ac = fmin(k->vj.alpha, 2.0 * DFL_PI - k->vj.alpha);
    const double a = cos(0.5 * ac);
    return sqrt(a * a + pow(2.0, 2.0 / (double)k->p) - 1.0) - a;
}

typedef struct variant_stats {
    sector_stats ss;
    region_stats band, vert;
    grid_extra ge;
    double onset, case_u, case_d;
} variant_stats;

static dfl_status put_row(dfl_table *t, const cj_keys *k, dfl_rfunc_join join,
                          const char *corr, const variant_stats *vs, dfl_err *err)
{
    const sector_stats *ss = &vs->ss;
    const region_stats *band = &vs->band, *vert = &vs->vert;
    const int p = (int)k->p;
    const double theory = join == DFL_RFUNC_REQUIV ? 1.0 - pow(2.0, -1.0 / p) : 0.0;
    const bool eq20 = strcmp(corr, "eq20") == 0;
    dfl_status st = dfl_table_row(t, err);
    if (!st) st = dfl_table_set_double(t, "alpha", k->vj.alpha_deg, err);
    if (!st) st = dfl_table_set_int(t, "p", p, err);
    if (!st) st = dfl_table_set_string(t, "parts", dfl_vjoin_part_names[k->vj.parts], err);
    if (!st) st = dfl_table_set_string(t, "join", dfl_rfunc_join_name(join), err);
    if (!st) st = dfl_table_set_string(t, "correction", corr, err);
    if (!st) st = dfl_table_set_int(t, "sector_points", ss->count, err);
    if (!st) st = dfl_table_set_double(t, "sector_gdef_max", ss->gdef_max, err);
    if (!st) st = dfl_table_set_double(t, "sector_gdef_min", ss->gdef_min, err);
    if (!st) st = dfl_table_set_double(t, "sector_gdef_theory", theory, err);
    if (!st) st = dfl_table_set_double(t, "sector_gdef_at_rmin", ss->gdef_rmin, err);
    if (!st) st = dfl_table_set_double(t, "sector_value_relerr_max", ss->verr_max, err);
    if (!st) st = dfl_table_set_double(t, "sector_part_gdef_max", ss->part_gdef_max, err);
    if (!st) st = dfl_table_set_int(t, "band_count", band->count, err);
    if (!st) st = dfl_table_set_double(t, "band_gdef_max", band->gdef_max, err);
    if (!st) st = dfl_table_set_double(t, "band_gdef_mean", band->gdef_mean, err);
    if (!st) st = dfl_table_set_double(t, "band_linf", band->linf, err);
    if (!st) st = dfl_table_set_int(t, "vertex_count", vert->count, err);
    if (!st) st = dfl_table_set_double(t, "vertex_gdef_max", vert->gdef_max, err);
    if (!st) st = dfl_table_set_double(t, "vertex_gdef_mean", vert->gdef_mean, err);
    if (!st) st = dfl_table_set_double(t, "vertex_linf", vert->linf, err);
    const double m = (double)dfl_grid_size(&k->grid);
    if (!st) st = dfl_table_set_int(t, "sector_undefined", ss->undefined, err);
    if (!st) st = dfl_table_set_int(t, "undefined_count", vs->ge.undefined, err);
    if (!st) st = dfl_table_set_double(t, "undefined_share", (double)vs->ge.undefined / m, err);
    if (!st) st = dfl_table_set_double(t, "onset_radius", eq20 ? vs->onset : NAN, err);
    if (!st) st = dfl_table_set_double(t, "onset_radius_theory", eq20 ? onset_theory(k) : NAN, err);
    if (!st) st = dfl_table_set_double(t, "reflex_linf", vs->ge.reflex_linf, err);
    if (!st) st = dfl_table_set_double(t, "case_u", vs->case_u, err);
    if (!st) st = dfl_table_set_double(t, "case_d", vs->case_d, err);
    return st;
}

static dfl_status cj_run(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_table *table,
                         dfl_err *err)
{
    cj_keys k;
    dfl_field f = {0};
    double *spts = NULL, *sval = NULL, *sgrad = NULL;
    dfl_field_bufs b = {0};
    dfl_status st = read_keys(cfg, &k, err);
    if (st == DFL_OK) st = dfl_cfg_check_used(cfg, err);
    if (st != DFL_OK) return st;

    const size_t ns = (size_t)k.nr * (size_t)(k.nt > 2 ? k.nt : 2);
    const size_t m = dfl_grid_size(&k.grid);
    spts = malloc(2 * ns * sizeof *spts);
    sval = malloc(ns * sizeof *sval);
    sgrad = malloc(2 * ns * sizeof *sgrad);
    const bool grid_ok = dfl_field_bufs_alloc(&b, m, 2, true);
    if (!spts || !sval || !sgrad || !grid_ok) {
        st = dfl_err_set(err, DFL_E_NOMEM, "out of memory for %zu grid nodes", m);
        goto done;
    }
    const size_t nsec = sector_points(&k, spts);
    /* the exact distance to the union: the reference of both images */
    for (size_t i = 0; i < m; i++) {
        double x[3];
        dfl_grid_node(&k.grid, i, x);
        b.ref[i] = dfl_vjoin_dist(&k.vj, x, NULL);
    }
    /* eq. 6, dflab's guarded eq. 20, bs04's eq. 20 as printed */
    static const dfl_rfunc_join joins[3] = {DFL_RFUNC_REQUIV, DFL_RFUNC_REQUIV_CORRECTED,
                                            DFL_RFUNC_REQUIV_CORRECTED};
    static const dfl_rfunc_correction corrs[3] = {DFL_RFUNC_CORR_GUARDED, DFL_RFUNC_CORR_GUARDED,
                                                  DFL_RFUNC_CORR_EQ20};
    static const char *const cnames[3] = {"none", "guarded", "eq20"};
    static const char *const stems[3] = {"requiv", "corrected", "eq20"};
    const double th = k.case_theta * (DFL_PI / 180.0), rc = k.case_r * k.vj.length;
    const double xc[2] = {rc * cos(th), rc * sin(th)};
    for (int j = 0; j < 3 && st == DFL_OK; j++) {
        st = dfl_vjoin_field_corr(&k.vj, joins[j], corrs[j], (int)k.p, &f, err);
        if (st != DFL_OK) break;
        variant_stats vs;
        memset(&vs, 0, sizeof vs);
        measure_sector(&k, &f, nsec, spts, sval, sgrad, &vs.ss);
        vs.onset = j == 2 ? onset_measured(&k, &f) : NAN;
        vs.case_u = dfl_field_eval1(&f, xc, NULL) / rc;
        vs.case_d = dfl_vjoin_dist(&k.vj, xc, NULL) / rc;
        st = dfl_field_sample(&f, &k.grid, ctx->threads, b.u, b.gu, err);
        if (st == DFL_OK) {
            measure_grid(&k, b.u, b.gu, b.ref, &vs.band, &vs.vert, &vs.ge);
            st = put_row(table, &k, joins[j], cnames[j], &vs, err);
        }
        if (st == DFL_OK) st = dfl_field_out_write(ctx, stems[j], &k.grid, b.u, b.gu, b.ref, &k.oo, err);
        dfl_field_destroy(&f);
    }
done:
    free(spts), free(sval), free(sgrad);
    dfl_field_bufs_free(&b);
    dfl_field_destroy(&f);
    return st;
}

/* Peak memory: the sector samples, sector_nr x max(sector_nt, 2) points
 * with value and gradient (40 bytes each), the grid's samples (u, grad u,
 * d: 32 bytes a node) and the writer's buffers, all held together.  Work:
 * three joins, each evaluated (two parts, CHEAP each, and
 * DFL_RFUNC_EVAL_UNITS; the part gradients once more at the sector) at
 * every sector sample and grid node, and written; d once per node. */
static dfl_status cj_estimate(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_cost *c,
                              dfl_err *err)
{
    (void)ctx;
    cj_keys k;
    dfl_status st = read_keys(cfg, &k, err);
    if (st) return st;
    const double ns = (double)k.nr * (double)(k.nt > 2 ? k.nt : 2);
    const double m = (double)dfl_grid_size(&k.grid);
    dfl_cost_add_bytes(c, "study", k.nr >= k.nt ? "sector_nr" : "sector_nt", 40 * ns,
                       "%.3g sector samples", ns);
    dfl_cost_add_bytes(c, "grid", "n", 32 * m + dfl_field_out_bytes(&k.oo, m),
                       "the samples and files of %d^2 nodes", k.grid.n[0]);
    dfl_cost_add_work(c, "study", k.nr >= k.nt ? "sector_nr" : "sector_nt", DFL_COST_CHEAP,
                      3 * (4 + DFL_RFUNC_EVAL_UNITS) * ns, "3 joins at %.3g sector samples", ns);
    dfl_cost_add_work(c, "grid", "n", DFL_COST_CHEAP,
                      3 * (2 + DFL_RFUNC_EVAL_UNITS) * m + m + 3 * dfl_field_out_units(&k.oo, m),
                      "3 joins at %.3g nodes and their files", m);
    return DFL_OK;
}

DFL_STUDY_DEFINE_ESTIMATED(bs04_corrected, cj_run, cj_estimate,
                 "bs04 Fig. 14, eq. 20: corrected join, |grad u| = 1 in the hatched sector");
