/* bs04 Sec. 3.1 / Fig. 8: approximate distance fields of two space curves.
 * Each degree-3 B-spline is polygonized with certified maximum deviation
 * eps (geom/polygonize.h), its segments get the 3D segment field of eq. 4
 * (f = sqrt(s^2 + q^2) for the line, a sphere trim), and the fields are
 * joined (R-equivalence of order 2 in the paper).  The field is sampled on
 * a volume grid and on section planes, and compared with the exact
 * (unsigned) distance to the curve (footpoints, geom/footpoint.h).
 *
 * Keys ([study]):
 *   curves  = space1 space2      curve sections (kind = bspline_curve, 3D)
 *   eps     = 3e-3               polygonization bound (> 0)
 *   join, p                      joining operation (cfg/rfunc_cfg.h)
 *   trim    = disk               disk = sphere trim of eq. 3/4 (strip = slab)
 *   paper_segments = 56 90       bs04's counts, one per curve (optional)
 *   band    = 0.05               metrics also over |d| <= band
 *   volume  = true               sample [grid] (3D) and write <curve>_volume
 *   slices  = z 0.5; y 0.5       section planes (cfg/slice_cfg.h), slice_n,
 *                                slice_lo, slice_hi
 *   compress = true              zlib .vtp
 *   [grid] n, lo, hi             the volume grid   [output] see field_out.h
 * Rows (one per curve): curve, eps, segments, bound, paper_segments,
 * join, p, trim, metrics of u against the exact distance over the volume
 * (suffix "") and in the band ("_band"), |grad u| statistics in the band
 * ("_band": min, mean, max), the same for each slice ("_s<k>" and
 * "_s<k>_band"), and file names.
 * Files: <curve>_polyline.vtp, <curve>_volume.vti/.exr,
 * <curve>_slice<k>.vti/.exr.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bs04/bs04_space_util.h"
#include "cfg/rfunc_cfg.h"
#include "cfg/curve_cfg.h"
#include "cfg/list_cfg.h"
#include "harness/experiment.h"
#include "field/exact.h"
#include "field/metrics.h"
#include "field/sample.h"
#include "harness/field_out.h"
#include "geom/polygonize.h"
#include "cfg/field_cost.h"
#include "cfg/grid_cfg.h"
#include "rfunc/rfield.h"
#include "cfg/slice_cfg.h"

#define MAX_CURVES 8
#define NAME_LEN DFL_SECTION_NAME_LEN

typedef struct keys {
    int ncurves;
    char names[MAX_CURVES][NAME_LEN];
    double eps, band;
    dfl_rfunc_join join;
    int p;
    dfl_rfunc_trim trim;
    double *paper;
    size_t npaper;
    bool volume;
    dfl_grid grid;
    dfl_bs04_space_out so;     /* compress is read before the other keys */
} keys;

static dfl_status read_keys(const dfl_cfg *cfg, keys *k, dfl_err *err)
{
    dfl_status st;
    memset(k, 0, sizeof *k);
    if ((st = dfl_section_names_from_cfg(cfg, "study", "curves", MAX_CURVES, k->names,
                                         &k->ncurves, "curve section", err)))
        return st;
    if ((st = dfl_cfg_double(cfg, "study", "eps", 1e-9, 1e3, &k->eps, err))) return st;
    if ((st = dfl_rfunc_join_p_from_cfg(cfg, "study", &k->join, &k->p, err))) return st;
    if ((st = dfl_rfunc_trim_from_cfg(cfg, "study", &k->trim, err))) return st;
    if ((st = dfl_cfg_double_opt(cfg, "study", "band", 0.05, 0.0, 1e300, &k->band, err))) return st;
    if ((st = dfl_cfg_bool_opt(cfg, "study", "volume", true, &k->volume, err))) return st;
    if ((st = dfl_cfg_bool_opt(cfg, "study", "compress", true, &k->so.compress, err))) return st;
    if (dfl_cfg_has(cfg, "study", "paper_segments")) {
        if ((st = dfl_cfg_doubles(cfg, "study", "paper_segments", 1, &k->paper, &k->npaper, err)))
            return st;
        if (k->npaper != (size_t)k->ncurves)
            return dfl_cfg_reject(cfg, "study", "paper_segments", err,
                                  "expected %d values (one per curve)", k->ncurves);
    }
    /* [grid] is read whenever present, so that volume = false does not turn
     * its keys into "unknown key" errors */
    if ((k->volume || dfl_cfg_has_section(cfg, "grid")) &&
        (st = dfl_grid_from_cfg(cfg, "grid", 3, &k->grid, err)))
        return st;
    return dfl_bs04_space_out_from_cfg(cfg, false, &k->so, err);
}

/* The curve of section sec (3D required) and its exact distance field. */
static dfl_status load_curve(const dfl_cfg *cfg, const char *sec, dfl_bspline *c, dfl_field *exact,
                             dfl_err *err)
{
    dfl_status st;
    if (!dfl_cfg_has_section(cfg, sec))
        return dfl_cfg_reject(cfg, "study", "curves", err, "no section [%s]", sec);
    if ((st = dfl_curve_section_from_cfg(cfg, sec, c, err))) return st;
    if (c->dim != 3) {
        dfl_bspline_free(c);
        return dfl_cfg_reject(cfg, sec, "control", err,
                              "expected a space curve (3D control points)");
    }
    dfl_shape sh;
    if ((st = dfl_param_shape_from_cfg(cfg, sec, "bspline_curve", &sh, err))) {
        dfl_bspline_free(c);
        return st;
    }
    if ((st = dfl_field_exact_new(&sh, exact, err))) {
        dfl_shape_free(&sh);
        dfl_bspline_free(c);
    }
    return st;
}

/* Metrics of u against the exact distance d (all and |d| <= band) and
 * |grad u| in the band, into the row with suffix sfx. */
static dfl_status put_field(dfl_table *t, const char *sfx, size_t m, const double *u,
                            const double *gu, const double *d, double band, dfl_err *err)
{
    dfl_metrics all, inb;
    char s2[64];
    dfl_status st = dfl_metrics_compute(m, 3, u, gu, d, 0.0, &all, err);
    if (st == DFL_OK) st = dfl_metrics_compute(m, 3, u, gu, d, band, &inb, err);
    if (st != DFL_OK) return st;
    unsigned char *mask = malloc(m ? m : 1);
    if (!mask) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    for (size_t i = 0; i < m; i++) mask[i] = d[i] <= band;
    dfl_gradstat gs;
    dfl_metrics_gradstat(m, 3, gu, mask, &gs);
    free(mask);
    snprintf(s2, sizeof s2, "%s_band", sfx);
    st = dfl_metrics_put(t, sfx, &all, err);
    if (st == DFL_OK) st = dfl_metrics_put(t, s2, &inb, err);
    if (st == DFL_OK) st = dfl_metrics_put_gradstat(t, s2, &gs, err);
    return st;
}

/* u and the exact distance on grid g: the metrics into the row (suffix
 * sfx, put_field) and the field files <stem>. */
static dfl_status sample_grid(const keys *k, const dfl_field *f, const dfl_field *exact,
                              const dfl_grid *g, const char *sfx, const char *stem,
                              const dfl_study_ctx *ctx, dfl_table *table, dfl_err *err)
{
    const size_t m = dfl_grid_size(g);
    dfl_field_bufs b;
    dfl_status st = DFL_OK;
    if (!dfl_field_bufs_alloc(&b, m, 3, true))
        st = dfl_err_set(err, DFL_E_NOMEM, "out of memory for %zu samples", m);
    if (!st) st = dfl_field_sample(f, g, ctx->threads, b.u, b.gu, err);
    if (!st) st = dfl_field_sample(exact, g, ctx->threads, b.ref, NULL, err);
    if (!st) st = put_field(table, sfx, m, b.u, b.gu, b.ref, k->band, err);
    if (!st) st = dfl_field_out_write(ctx, stem, g, b.u, b.gu, b.ref, &k->so.out, err);
    dfl_field_bufs_free(&b);
    return st;
}

static dfl_status do_curve(const keys *k, int c, const dfl_bspline *curve, const dfl_field *exact,
                           const dfl_study_ctx *ctx, dfl_table *table, dfl_err *err)
{
    const char *name = k->names[c];
    char stem[NAME_LEN + 32], path[4400], sfx[32];
    dfl_polyline pl;
    dfl_field f = {0};
    dfl_status st = dfl_polygonize_curve(curve, k->eps, 0, &pl, err);
    if (st != DFL_OK) return st;
    /* a closed curve repeats its first point: drop it, close the polyline */
    size_t np = pl.n;
    const bool closed = curve->closed || (np >= 4 && memcmp(pl.pts, pl.pts + 3 * (np - 1),
                                                            3 * sizeof *pl.pts) == 0);
    if (closed) np--;
    st = dfl_rfield_polyline(3, pl.pts, np, closed, k->join, k->p, k->trim, &f, err);
    if (st != DFL_OK) goto done;
    const long segs = (long)(pl.n - 1);

    st = dfl_table_row(table, err);
    if (!st) st = dfl_table_set_string(table, "curve", name, err);
    if (!st) st = dfl_table_set_double(table, "eps", k->eps, err);
    if (!st) st = dfl_table_set_int(table, "segments", segs, err);
    if (!st) st = dfl_table_set_double(table, "bound", pl.bound, err);
    if (!st && k->paper) st = dfl_table_set_int(table, "paper_segments", (long)k->paper[c], err);
    if (!st) st = dfl_table_set_string(table, "join", dfl_rfunc_join_name(k->join), err);
    if (!st) st = dfl_table_set_int(table, "p", k->p, err);
    if (!st) st = dfl_table_set_string(table, "trim", dfl_rfunc_trim_name(k->trim), err);
    if (st) goto done;

    snprintf(stem, sizeof stem, "%s_polyline", name);
    st = dfl_bs04_vtp_polyline(dfl_study_path(ctx, stem, "vtp", path, sizeof path), 3, pl.n,
                               pl.pts, NULL, k->so.compress, err);
    if (!st) st = dfl_study_put_file(table, "vtp", ctx, stem, "vtp", true, err);
    if (!st && k->volume) {
        snprintf(stem, sizeof stem, "%s_volume", name);
        st = sample_grid(k, &f, exact, &k->grid, "", stem, ctx, table, err);
        if (!st && k->so.out.vti)
            st = dfl_study_put_file(table, "volume_vti", ctx, stem, "vti", true, err);
    }
    for (int s = 0; s < k->so.nslices && st == DFL_OK; s++) {
        const dfl_grid *sl = &k->so.slices[s];
        char col[32], desc[64];
        snprintf(sfx, sizeof sfx, "_s%d", s);
        snprintf(stem, sizeof stem, "%s_slice%d", name, s);
        st = sample_grid(k, &f, exact, sl, sfx, stem, ctx, table, err);
        snprintf(col, sizeof col, "slice%d", s);
        dfl_slice_label(sl, desc, sizeof desc);
        if (!st) st = dfl_table_set_string(table, col, desc, err);
    }
done:
    dfl_field_destroy(&f);
    dfl_polyline_free(&pl);
    return st;
}

static dfl_status space_run(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_table *table,
                            dfl_err *err)
{
    keys k;
    dfl_bspline curves[MAX_CURVES];
    dfl_field exact[MAX_CURVES];
    int nbuilt = 0;
    memset(curves, 0, sizeof curves);
    memset(exact, 0, sizeof exact);
    dfl_status st = read_keys(cfg, &k, err);
    for (int c = 0; c < k.ncurves && st == DFL_OK; c++) {
        st = load_curve(cfg, k.names[c], &curves[c], &exact[c], err);
        if (st == DFL_OK) nbuilt++;
    }
    if (st == DFL_OK) st = dfl_cfg_check_used(cfg, err);
    for (int c = 0; c < k.ncurves && st == DFL_OK; c++)
        st = do_curve(&k, c, &curves[c], &exact[c], ctx, table, err);
    for (int c = 0; c < nbuilt; c++) {
        dfl_field_destroy(&exact[c]);
        dfl_bspline_free(&curves[c]);
    }
    free(k.paper);
    return st;
}

/* Peak memory: the curves run one after another; a curve holds its field
 * (at most dfl_polygonize_curve_segments_bound segments at eps,
 * DFL_RFUNC_PART_BYTES each) and one grid at a time, the volume or a slice:
 * u, grad u, d and the band mask (41 bytes a node) and the writer's buffers.
 * Work per curve: u (dfl_field_eval_cost's rfunc: one CHEAP per segment and
 * DFL_RFUNC_EVAL_UNITS) and d (FOOTPOINT, on the curve) at every node of
 * the volume and the slices, and their files. */
static dfl_status space_estimate(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_cost *c,
                                 dfl_err *err)
{
    (void)ctx;
    keys k;
    dfl_status st = read_keys(cfg, &k, err);
    double vol = k.volume ? (double)dfl_grid_size(&k.grid) : 0, sl = 0, all = vol;
    for (int s = 0; s < k.so.nslices; s++) {
        sl = fmax(sl, (double)dfl_grid_size(&k.so.slices[s]));
        all += (double)dfl_grid_size(&k.so.slices[s]);
    }
    for (int i = 0; i < k.ncurves && !st; i++) {
        dfl_bspline cv;
        if (!dfl_cfg_has_section(cfg, k.names[i])) continue; /* the run names it */
        if ((st = dfl_curve_section_from_cfg(cfg, k.names[i], &cv, err))) break;
        const double parts = dfl_polygonize_curve_segments_bound(&cv, k.eps) + 1;
        dfl_bspline_free(&cv);
        dfl_cost one;
        memset(&one, 0, sizeof one);
        dfl_cost_add_bytes(&one, "study", "eps", parts * DFL_RFUNC_PART_BYTES,
                           "an R-function field of up to %.3g segments", parts);
        if (vol >= sl && vol > 0)
            dfl_cost_add_bytes(&one, "grid", "n", 41 * vol + dfl_field_out_bytes(&k.so.out, vol),
                               "a volume of %d^3 nodes and its files", k.grid.n[0]);
        else if (sl > 0)
            dfl_cost_add_bytes(&one, "study", "slice_n", 41 * sl + dfl_field_out_bytes(&k.so.out, sl),
                               "a section plane of %.3g nodes and its files", sl);
        dfl_cost_add_work(&one, vol >= sl ? "grid" : "study", vol >= sl ? "n" : "slice_n",
                          DFL_COST_CHEAP, all * (parts + DFL_RFUNC_EVAL_UNITS) +
                                              dfl_field_out_units(&k.so.out, all),
                          "u at %.3g nodes, %.3g segments", all, parts);
        dfl_cost_add_work(&one, vol >= sl ? "grid" : "study", vol >= sl ? "n" : "slice_n",
                          DFL_COST_FOOTPOINT, all, "%.3g exact distances", all);
        dfl_cost_add_step(c, &one);
    }
    free(k.paper);
    return st;
}

DFL_STUDY_DEFINE_ESTIMATED(bs04_spacecurves, space_run, space_estimate,
                 "bs04 Fig. 8: fields of polygonized space curves, volume and section planes");
