/* hvb25 accuracy engine: a field (a proxy grid under one or several
 * decoding filters, a grid peer, any dfl_field) against a reference SDF on
 * a node grid (the paper's 217^3), in z slabs so that memory stays at a few
 * slabs whatever the grid.
 *
 * Per decoding it accumulates, over the whole grid, over the band
 * |d| <= band and over the points off the medial region (below), the
 * metrics of field/metrics.h (L1 = mean |e|, MSE, set beside the paper's undefined "L2", RMS,
 * Linf), combined slab after slab in slab order (count-weighted means, so
 * the result does not depend on the thread count), and the worst point.
 *
 * Error: e = u - ref where ref = d (the reference's signed distance) for
 * signed decodings and |d| for unsigned ones (the paper's output).
 * Non-finite u is an error of +inf (field/metrics.h): counted, in every
 * set its reference puts it in, never left out.
 *
 * Medial region: a point x whose exact footpoint p(x) = x - d grad d lies
 * farther than `medial` cell sizes from the exact footpoint of the centre
 * of the cell holding x: there the cell's proxy describes another part of
 * the surface (x and its cell centre lie on two sides of the medial axis /
 * cut locus).  On the concave side at depth delta below a surface of
 * curvature radius r the footpoint moves by the tangential offset times
 * r / (r - delta), so the region holds the points whose footpoint map
 * amplifies their offset from the cell centre beyond the threshold
 * (default 1 cell, hvb25_accuracy's `medial`): all points close enough to
 * the medial axis (delta -> r), few others.  Needs a cell grid (proxy or
 * grid peer); without one no point is medial.
 */
#ifndef DFL_EXPERIMENTS_HVB25_EVAL_H
#define DFL_EXPERIMENTS_HVB25_EVAL_H

#include <stddef.h>

#include "field/field.h"
#include "field/metrics.h"
#include "field/sample.h"
#include "io/config.h"
#include "io/table.h"
#include "proxy/filter.h"

#define HVB25_MAX_DECODINGS 4

/* key = nearest hermite ... (blank-separated filter names, at most
 * HVB25_MAX_DECODINGS; absent or empty: *n = 0) into f[0..*n-1]. */
dfl_status hvb25_filters_from_cfg(const dfl_cfg *cfg, const char *sec, const char *key,
                                  dfl_proxy_filter *f, int *n, dfl_err *err);

/* A proxy grid decoded with options o, as a dfl_field whose ctx is the
 * view itself (borrowed: the view and its grid must outlive the field;
 * nothing to destroy).  One grid, several decodings, no copies. */
typedef struct hvb25_view {
    const dfl_proxy_grid *g;
    dfl_proxy_filter_opts o;
} hvb25_view;
void hvb25_view_field(const hvb25_view *v, dfl_field *out);

typedef struct hvb25_cells {
    int n;                 /* cells per axis; 0: no cell grid */
    double lo[3], h[3];
} hvb25_cells;

typedef struct hvb25_acc_result {
    dfl_metrics all, band, off;     /* whole grid, band, off the medial region */
    size_t nonfinite, medial;       /* points with u not finite (error +inf); medial points */
    double worst[3], worst_d, worst_err, worst_jump;  /* argmax |e| (first in grid order) */
    double eval_seconds;            /* decoding time over the whole grid */
} hvb25_acc_result;

typedef struct hvb25_acc_spec {
    const dfl_field *field;         /* decoded as is when ndec == 0 */
    const dfl_proxy_grid *grid;     /* the proxy grid of field, or NULL */
    int ndec;                       /* proxy decodings to run instead (grid != NULL) */
    dfl_proxy_filter_opts dec[HVB25_MAX_DECODINGS];
    int field_signed;               /* signedness when ndec == 0 */
    hvb25_cells cells;
    const dfl_field *ref;           /* reference distance with gradient (3D) */
    dfl_grid eval;                  /* 3D node grid */
    double band, medial;            /* band half-width; medial threshold in cell sizes */
    int threads;
} hvb25_acc_spec;

/* Runs every decoding (max(ndec, 1) results into res[]).  DFL_E_NOMEM;
 * DFL_E_NUMERIC when the reference is not finite somewhere. */
dfl_status hvb25_acc_run(const hvb25_acc_spec *s, hvb25_acc_result *res, dfl_err *err);

/* Sets the result's cells with column suffix sfx "" in the table's current
 * row: metrics (all, _band, _off), nonfinite, medial, worst_*, eval_*. */
dfl_status hvb25_acc_put(dfl_table *t, const hvb25_acc_result *r, size_t npoints, dfl_err *err);

#endif
