/* bs04 Sec. 4.2 / Fig. 13a: one approximate distance field for a 2D set of
 * heterogeneous dimension: a square region (dimension 2), a line segment
 * (1) and a point (0), each with its own field (rfunc/region.h,
 * rfunc/segment.h), joined by R-equivalence.
 *
 * Measured against the exact distance to the union, d = min(d_region (0
 * inside), d_segment, d_point), on [grid] (all samples, and the band
 * 0 < d <= band: the set itself, where u = 0 and the gradient is 0 by
 * convention, is left out), |grad u| in the band, and normalization at the
 * parts' regular boundary points: at offset delta along the outward normal
 * (the middle 80% of the square's edges, of the segment, a circle of
 * radius delta around the point) the part's own field is the exact
 * distance h_i = delta, so with the other fields h_j >= D there
 *     u = delta (1 + sum_j (delta/h_j)^p)^(-1/p),
 *     |u/delta - 1| <= (n - 1) (delta/D)^p / p,
 *     du/dh_i = (u/delta)^(p+1) = 1 - (p+1)/p sum_j (delta/h_j)^p + ...,
 *     ||grad u| - 1| <~ (p+1)/p (n - 1) (delta/D)^p
 * (the other parts add (u/h_j)^(p+1) |grad h_j|, of higher order): the rows
 * report the largest |u/delta - 1| and ||grad u| - 1| over those samples.
 *
 * Keys.  [field] kind = rfunc (rfunc_cfg.h; the field the figure shows,
 * so `dflab probe` evaluates it) with exactly these parts:
 *   region   = x y; x y; ...    convex polygon (>= 3 vertices)
 *   vertices = x y; x y         the segment's end points
 *   points   = x y              the point
 *   join, p                     (default requiv, 2)
 *   trim     = disk             the segment's trim
 * [study]:
 *   band    = 0.05
 *   delta   = 1e-4              normal offset of the boundary samples (> 0)
 *   boundary_samples = 200      per part
 *   compress = true             [grid] 2D   [output] see field_out.h
 * Rows: join, p, trim, metrics of u against d (all, _band), |grad u| in
 * the band, boundary_ratio_err, boundary_grad_err (max over all parts),
 * and per part (region, segment, point) the same with suffixes.
 * Files: hetero<tag>.vti/.exr (value, gradient, error = u - d, reference
 * d), parts<tag>.vtp (square outline, segment, point).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cfg/rfunc_cfg.h"
#include "core/vec.h"
#include "harness/experiment.h"
#include "field/metrics.h"
#include "field/sample.h"
#include "harness/field_out.h"
#include "cfg/field_cost.h"
#include "geom/polygon.h"
#include "geom/segdist.h"
#include "io/vtk.h"
#include "cfg/grid_cfg.h"
#include "cfg/list_cfg.h"
#include "rfunc/rfield.h"


typedef struct keys {
    dfl_rfunc_field_spec spec; /* [field], owns region */
    const double *region;
    size_t nreg;
    double seg[4], pt[2];
    dfl_rfunc_join join;
    int p;
    dfl_rfunc_trim trim;
    double band, delta;
    long nb;
    bool compress;
    dfl_grid grid;
    dfl_field_write_opts out;
} keys;

static dfl_status read_keys(const dfl_cfg *cfg, keys *k, dfl_err *err)
{
    dfl_status st;
    memset(k, 0, sizeof *k);
    if ((st = dfl_rfunc_spec_from_kind_cfg(cfg, "field", "bs04_hetero", &k->spec, err))) return st;
    const dfl_rfunc_field_spec *sp = &k->spec;
    if (sp->dim != 2 || sp->nregion < 3 || sp->n != 2 || sp->closed || sp->curve ||
        sp->npoints != 1 || sp->ntris)
        return dfl_err_set(err, DFL_E_INPUT,
                           "%s: [field] of bs04_hetero: expected a region, a segment (vertices"
                           " = 2 end points) and one point (points), nothing else",
                           dfl_cfg_path(cfg));
    if ((st = dfl_rfunc_join_check(sp->join, sp->p, err)))
        return dfl_cfg_err_at(cfg, "field", "p", st, err);
    k->region = sp->region;
    k->nreg = sp->nregion;
    memcpy(k->seg, sp->v, sizeof k->seg);
    memcpy(k->pt, sp->points, sizeof k->pt);
    k->join = sp->join;
    k->p = sp->p;
    k->trim = sp->trim;
    if ((st = dfl_cfg_double_opt(cfg, "study", "band", 0.05, 0.0, 1e300, &k->band, err))) return st;
    if ((st = dfl_cfg_double_opt(cfg, "study", "delta", 1e-4, 1e-12, 1.0, &k->delta, err)))
        return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "boundary_samples", 200, 1, 1000000, &k->nb, err)))
        return st;
    if ((st = dfl_cfg_bool_opt(cfg, "study", "compress", true, &k->compress, err))) return st;
    if ((st = dfl_grid_from_cfg(cfg, "grid", 2, &k->grid, err))) return st;
    return dfl_field_out_from_cfg(cfg, &k->out, err);
}

/* Exact distance to the union of the convex region (orientation o), the
 * segment, the point. */
static double exact_union(const keys *k, double o, const double *x)
{
    const double dr = dfl_convex_polygon_dist(k->region, k->nreg, o, x);
    if (dr == 0.0) return 0.0; /* in the region (or on its boundary) */
    const double ds = dfl_point_segment_dist(2, x, k->seg, k->seg + 2);
    const double dp = hypot(x[0] - k->pt[0], x[1] - k->pt[1]);
    return fmin(dr, fmin(ds, dp));
}

typedef struct bstat {
    double ratio, grad;
} bstat;

static void probe(const dfl_field *f, const double *x, double delta, bstat *b)
{
    double g[2];
    const double u = dfl_field_eval1(f, x, g);
    b->ratio = fmax(b->ratio, fabs(u / delta - 1.0));
    b->grad = fmax(b->grad, fabs(hypot(g[0], g[1]) - 1.0));
}

/* Samples at offset delta along the outward normals of the parts (see the
 * top): the region's edges (orientation o), both sides of the segment, a
 * circle around the point. */
static void boundary_probes(const keys *k, const dfl_field *f, double o, bstat *br, bstat *bs,
                            bstat *bp)
{
    *br = *bs = *bp = (bstat){0, 0};
    const size_t nb = (size_t)k->nb;
    for (size_t e = 0; e < k->nreg; e++) {
        const double *a = k->region + 2 * e, *b = k->region + 2 * ((e + 1) % k->nreg);
        const double L = hypot(b[0] - a[0], b[1] - a[1]);
        const double nx = o * (b[1] - a[1]) / L, ny = -o * (b[0] - a[0]) / L; /* outward */
        for (size_t i = 0; i < nb; i++) {
            /* the middle 80% of the edge: at the corners two half-planes
             * are violated and h is the corner distance (still exact for a
             * rectangle, but not at offset delta along one normal) */
            const double t = 0.1 + 0.8 * ((double)i + 0.5) / (double)nb;
            const double x[2] = {a[0] + t * (b[0] - a[0]) + k->delta * nx,
                                 a[1] + t * (b[1] - a[1]) + k->delta * ny};
            probe(f, x, k->delta, br);
        }
    }
    {
        const double *a = k->seg, *b = k->seg + 2;
        const double L = hypot(b[0] - a[0], b[1] - a[1]);
        const double nx = (b[1] - a[1]) / L, ny = -(b[0] - a[0]) / L;
        for (size_t i = 0; i < nb; i++) {
            const double t = 0.1 + 0.8 * ((double)i + 0.5) / (double)nb;
            for (int sgn = -1; sgn <= 1; sgn += 2) {
                const double x[2] = {a[0] + t * (b[0] - a[0]) + sgn * k->delta * nx,
                                     a[1] + t * (b[1] - a[1]) + sgn * k->delta * ny};
                probe(f, x, k->delta, bs);
            }
        }
    }
    for (size_t i = 0; i < nb; i++) {
        const double ph = 2 * DFL_PI * ((double)i + 0.5) / (double)nb;
        const double x[2] = {k->pt[0] + k->delta * cos(ph), k->pt[1] + k->delta * sin(ph)};
        probe(f, x, k->delta, bp);
    }
}

static dfl_status hetero_run(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_table *table,
                             dfl_err *err)
{
    keys k;
    dfl_field f = {0};
    dfl_field_bufs b = {0};
    double *outline = NULL;
    unsigned char *mask = NULL;
    char path[4400];
    /* the region, the segment and the point, in that order (rfunc_cfg.h) */
    dfl_status st = read_keys(cfg, &k, err);
    if (!st) st = dfl_rfunc_field_from_spec(cfg, "field", &k.spec, &f, err);
    if (!st) st = dfl_cfg_check_used(cfg, err);
    if (st) goto done;

    const size_t m = dfl_grid_size(&k.grid);
    mask = malloc(m);
    if (!dfl_field_bufs_alloc(&b, m, 2, true) || !mask) {
        st = dfl_err_set(err, DFL_E_NOMEM, "out of memory for %zu samples", m);
        goto done;
    }
    const double *u = b.u, *gu = b.gu, *d = b.ref;
    if ((st = dfl_field_sample(&f, &k.grid, ctx->threads, b.u, b.gu, err))) goto done;
    const double o = dfl_polygon_orientation(k.region, k.nreg);
    for (size_t i = 0; i < m; i++) {
        double x[2];
        dfl_grid_node(&k.grid, i, x);
        b.ref[i] = exact_union(&k, o, x);
        /* the band excludes the set itself (inside the region u = 0 and
         * the gradient is 0 by convention, not a normalization defect) */
        mask[i] = d[i] > 0.0 && d[i] <= k.band;
    }
    dfl_metrics all, inb;
    dfl_gradstat gs;
    if ((st = dfl_metrics_compute(m, 2, u, gu, d, 0.0, &all, err))) goto done;
    if ((st = dfl_metrics_compute_masked(m, 2, u, gu, d, mask, &inb, err))) goto done;
    dfl_metrics_gradstat(m, 2, gu, mask, &gs);
    bstat br, bs, bp;
    boundary_probes(&k, &f, o, &br, &bs, &bp);

    st = dfl_table_row(table, err);
    if (!st) st = dfl_table_set_string(table, "join", dfl_rfunc_join_name(k.join), err);
    if (!st) st = dfl_table_set_int(table, "p", k.p, err);
    if (!st) st = dfl_table_set_string(table, "trim", dfl_rfunc_trim_name(k.trim), err);
    if (!st) st = dfl_metrics_put(table, "", &all, err);
    if (!st) st = dfl_metrics_put(table, "_band", &inb, err);
    if (!st) st = dfl_metrics_put_gradstat(table, "_band", &gs, err);
    if (!st) st = dfl_table_set_double(table, "delta", k.delta, err);
    const double rmax = fmax(br.ratio, fmax(bs.ratio, bp.ratio));
    const double gmax = fmax(br.grad, fmax(bs.grad, bp.grad));
    if (!st) st = dfl_table_set_double(table, "boundary_ratio_err", rmax, err);
    if (!st) st = dfl_table_set_double(table, "boundary_grad_err", gmax, err);
    if (!st) st = dfl_table_set_double(table, "boundary_ratio_err_region", br.ratio, err);
    if (!st) st = dfl_table_set_double(table, "boundary_grad_err_region", br.grad, err);
    if (!st) st = dfl_table_set_double(table, "boundary_ratio_err_segment", bs.ratio, err);
    if (!st) st = dfl_table_set_double(table, "boundary_grad_err_segment", bs.grad, err);
    if (!st) st = dfl_table_set_double(table, "boundary_ratio_err_point", bp.ratio, err);
    if (!st) st = dfl_table_set_double(table, "boundary_grad_err_point", bp.grad, err);
    if (st) goto done;
    if ((st = dfl_field_out_write(ctx, "hetero", &k.grid, u, gu, d, &k.out, err))) goto done;

    /* the parts: the closed outline, the segment and the point as lines */
    const size_t np = k.nreg + 1 + 2 + 1;
    outline = malloc(3 * np * sizeof *outline);
    size_t conn[64], off[4];
    if (!outline || np > 64) {
        st = dfl_err_set(err, DFL_E_NOMEM, "out of memory (or a region of > 60 vertices)");
        goto done;
    }
    for (size_t i = 0; i < np; i++) {
        const double *src = i <= k.nreg ? k.region + 2 * (i % k.nreg)
                            : i < k.nreg + 3 ? k.seg + 2 * (i - k.nreg - 1)
                                             : k.pt;
        outline[3 * i] = src[0];
        outline[3 * i + 1] = src[1];
        outline[3 * i + 2] = 0.0;
        conn[i] = i;
    }
    off[0] = 0;
    off[1] = k.nreg + 1;
    off[2] = k.nreg + 3;
    off[3] = np;
    dfl_vtp_data vd = {np, outline, 3, off, conn, 0, NULL, NULL, 0};
    st = dfl_vtp_write(dfl_study_path(ctx, "parts", "vtp", path, sizeof path), &vd, k.compress, err);
done:
    dfl_field_destroy(&f);
    dfl_field_bufs_free(&b);
    free(mask), free(outline);
    dfl_rfunc_spec_free(&k.spec);
    return st;
}

/* Peak memory: the grid's samples (u, grad u, d and the band mask: 33
 * bytes a node) and the writer's buffers.  Work: the field (one CHEAP per
 * region edge, the segment and the point each, and DFL_RFUNC_EVAL_UNITS)
 * and d at every node, the file, and the field at boundary_samples probes
 * per region edge, segment and point. */
static dfl_status hetero_estimate(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_cost *c,
                                  dfl_err *err)
{
    (void)ctx;
    keys k;
    dfl_status st = read_keys(cfg, &k, err);
    if (!st) {
        const double m = (double)dfl_grid_size(&k.grid), parts = (double)k.nreg + 2;
        dfl_cost_add_bytes(c, "grid", "n", 33 * m + dfl_field_out_bytes(&k.out, m),
                           "the samples and files of %d^2 nodes", k.grid.n[0]);
        const double units = parts + DFL_RFUNC_EVAL_UNITS;
        dfl_cost_add_work(c, "grid", "n", DFL_COST_CHEAP,
                          (units + parts) * m + dfl_field_out_units(&k.out, m), "%.3g nodes", m);
        dfl_cost_add_work(c, "study", "boundary_samples", DFL_COST_CHEAP,
                          parts * units * (double)k.nb, "%ld boundary samples per part", k.nb);
    }
    dfl_rfunc_spec_free(&k.spec);
    return st;
}

DFL_STUDY_DEFINE_ESTIMATED(bs04_hetero, hetero_run, hetero_estimate,
                 "bs04 Fig. 13a: one field for a region, a segment and a point");
