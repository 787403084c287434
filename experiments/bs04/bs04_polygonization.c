/* bs04 polygonization study: segment counts of certified polygonizations
 * (geom/polygonize.h) of the 'S' and 'W' B-splines against the maximum
 * deviation eps, with the fitted growth exponent and the paper's counts.
 *
 * Keys ([study]):
 *   curves     = S W          names of curve sections (kind = bspline_curve)
 *   eps        = 1e-2         maximum deviation (> 0); a comma list sweeps it
 *   fit_eps    = ...          blank-separated eps values (>= 2 distinct, > 0)
 *                             over which every row's fit_exponent is computed:
 *                             the least-squares slope of log(segments) against
 *                             log(eps) (smooth curves: -1/2)
 *   samples    = 16           samples per segment when measuring the deviation
 *   compress   = true         zlib-compressed .vtp
 *   paper_curve, paper_eps, paper_segments   the paper's counts (bs04 Sec.
 *                             2.4 for its 'S'), copied into paper_segments of
 *                             matching rows; paper_fit_exponent is their slope
 * Rows (one per curve and sweep point): curve, eps, segments, bound
 * (certified Hausdorff bound, <= eps), measured (dense sampling + local
 * maximization of the curve -> polyline distance), measured_over_eps,
 * fit_exponent, paper_segments, paper_fit_exponent, vtp.
 * Files: <curve>_polyline<tag>.vtp (points with the parameter t as point
 * data, one polyline; planar curves at z = 0).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bs04/bs04_space_util.h"
#include "core/fit.h"
#include "cfg/curve_cfg.h"
#include "cfg/list_cfg.h"
#include "harness/experiment.h"
#include "geom/polygonize.h"
#include "io/vtk.h"

#define MAX_CURVES 16
#define NAME_MAX_LEN DFL_SECTION_NAME_LEN

typedef struct study_keys {
    int ncurves;
    char names[MAX_CURVES][NAME_MAX_LEN];
    double eps;
    double *fit_eps;
    size_t nfit;
    long samples;
    bool compress;
    const char *paper_curve;
    double *paper_eps, *paper_seg;
    size_t npaper;
} study_keys;

static void keys_free(study_keys *k)
{
    free(k->fit_eps);
    free(k->paper_eps);
    free(k->paper_seg);
}

static dfl_status read_keys(const dfl_cfg *cfg, study_keys *k, dfl_err *err)
{
    dfl_status st;
    memset(k, 0, sizeof *k);
    if ((st = dfl_section_names_from_cfg(cfg, "study", "curves", MAX_CURVES, k->names,
                                         &k->ncurves, "curve section name", err)))
        return st;
    /* >= 1e-12: see the eps of experiments/cfg/rfunc_cfg.c (segment count
     * and coordinate rounding); smaller values fail for want of memory */
    if ((st = dfl_cfg_double(cfg, "study", "eps", 1e-12, 1e300, &k->eps, err))) return st;
    if ((st = dfl_cfg_doubles(cfg, "study", "fit_eps", 2, &k->fit_eps, &k->nfit, err))) return st;
    int distinct = 0;
    for (size_t i = 0; i < k->nfit; i++) {
        if (!(k->fit_eps[i] >= 1e-12))
            return dfl_cfg_reject(cfg, "study", "fit_eps", err,
                                  "expected values >= 1e-12 (as eps), got %g", k->fit_eps[i]);
        if (k->fit_eps[i] != k->fit_eps[0]) distinct = 1;
    }
    if (!distinct)
        return dfl_cfg_reject(cfg, "study", "fit_eps", err, "expected at least 2 distinct values");
    if ((st = dfl_cfg_int_opt(cfg, "study", "samples", 16, 2, 100000, &k->samples, err)))
        return st;
    if ((st = dfl_cfg_bool_opt(cfg, "study", "compress", true, &k->compress, err))) return st;
    if (dfl_cfg_has(cfg, "study", "paper_curve")) {
        size_t ns = 0;
        if ((st = dfl_cfg_string(cfg, "study", "paper_curve", &k->paper_curve, err))) return st;
        if ((st = dfl_cfg_doubles(cfg, "study", "paper_eps", 1, &k->paper_eps, &k->npaper, err)))
            return st;
        if ((st = dfl_cfg_doubles(cfg, "study", "paper_segments", 1, &k->paper_seg, &ns, err)))
            return st;
        if (ns != k->npaper)
            return dfl_cfg_reject(cfg, "study", "paper_segments", err,
                                  "expected %zu values (one per paper_eps)", k->npaper);
        for (size_t i = 0; i < ns; i++)
            if (!(k->paper_eps[i] > 0.0) || !(k->paper_seg[i] >= 1.0))
                return dfl_cfg_reject(cfg, "study", "paper_segments", err,
                                      "paper eps must be > 0 and segment counts >= 1");
    }
    return DFL_OK;
}

/* The polyline as VTK PolyData (z = 0 for planar curves) with its
 * parameters t as point data. */
static dfl_status write_vtp(const char *path, const dfl_polyline *p, int compress, dfl_err *err)
{
    const dfl_vtk_array arr = {"t", 1, p->t};
    return dfl_bs04_vtp_polyline(path, p->dim, p->n, p->pts, &arr, compress, err);
}

static dfl_status bs04_poly_run(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_table *table,
                                dfl_err *err)
{
    study_keys k;
    dfl_bspline curves[MAX_CURVES];
    dfl_polyline polys[MAX_CURVES];
    int nbuilt = 0, npoly = 0;
    memset(curves, 0, sizeof curves);
    memset(polys, 0, sizeof polys);
    dfl_status st = read_keys(cfg, &k, err);
    for (int c = 0; c < k.ncurves && st == DFL_OK; c++) {
        const char *sec = k.names[c];
        if (!dfl_cfg_has_section(cfg, sec)) {
            st = dfl_cfg_reject(cfg, "study", "curves", err, "no section [%s] for curve '%s'", sec,
                                sec);
            break;
        }
        if ((st = dfl_curve_section_from_cfg(cfg, sec, &curves[c], err))) break;
        nbuilt++;
    }
    /* every key read and validated before any computation or file */
    if (st == DFL_OK) st = dfl_cfg_check_used(cfg, err);
    double paper_fit = NAN;
    if (st == DFL_OK && k.npaper >= 2)
        paper_fit = dfl_fit_loglog_slope(k.npaper, k.paper_eps, k.paper_seg);
    for (int c = 0; c < k.ncurves && st == DFL_OK; c++) {
        /* fitted exponent over fit_eps */
        double *cnt = malloc(k.nfit * sizeof(double));
        if (!cnt) {
            st = dfl_err_set(err, DFL_E_NOMEM, "out of memory");
            break;
        }
        for (size_t i = 0; i < k.nfit && st == DFL_OK; i++) {
            dfl_polyline q;
            st = dfl_polygonize_curve(&curves[c], k.fit_eps[i], 0, &q, err);
            if (st != DFL_OK) {
                dfl_cfg_err_at(cfg, "study", "fit_eps", st, err);
                break;
            }
            cnt[i] = (double)(q.n - 1);
            dfl_polyline_free(&q);
        }
        double fit = st == DFL_OK ? dfl_fit_loglog_slope(k.nfit, k.fit_eps, cnt) : NAN;
        free(cnt);
        if (st != DFL_OK) break;
        st = dfl_polygonize_curve(&curves[c], k.eps, 0, &polys[c], err);
        if (st != DFL_OK) {
            dfl_cfg_err_at(cfg, "study", "eps", st, err);
            break;
        }
        npoly++;
        double meas;
        if ((st = dfl_polyline_deviation(&curves[c], &polys[c], (int)k.samples, &meas, err)))
            break;
        char stem[NAME_MAX_LEN + 16];
        snprintf(stem, sizeof stem, "%s_polyline", k.names[c]);
        double paper = NAN;
        if (k.paper_curve && strcmp(k.paper_curve, k.names[c]) == 0)
            for (size_t i = 0; i < k.npaper; i++)
                if (fabs(k.paper_eps[i] - k.eps) <= 1e-12 * k.eps) paper = k.paper_seg[i];
        st = dfl_table_row(table, err);
        if (!st) st = dfl_table_set_string(table, "curve", k.names[c], err);
        if (!st) st = dfl_table_set_double(table, "eps", k.eps, err);
        if (!st) st = dfl_table_set_int(table, "segments", (long)(polys[c].n - 1), err);
        if (!st) st = dfl_table_set_double(table, "bound", polys[c].bound, err);
        if (!st) st = dfl_table_set_double(table, "measured", meas, err);
        if (!st) st = dfl_table_set_double(table, "measured_over_eps", meas / k.eps, err);
        if (!st) st = dfl_table_set_double(table, "fit_exponent", fit, err);
        if (!st && !isnan(paper)) st = dfl_table_set_int(table, "paper_segments", (long)paper, err);
        if (!st && k.paper_curve && strcmp(k.paper_curve, k.names[c]) == 0)
            st = dfl_table_set_double(table, "paper_fit_exponent", paper_fit, err);
        if (!st) st = dfl_study_put_file(table, "vtp", ctx, stem, "vtp", true, err);
    }
    for (int c = 0; c < npoly && st == DFL_OK; c++) {
        char stem[NAME_MAX_LEN + 16], path[4096];
        snprintf(stem, sizeof stem, "%s_polyline", k.names[c]);
        st = write_vtp(dfl_study_path(ctx, stem, "vtp", path, sizeof path), &polys[c], k.compress,
                       err);
    }
    for (int c = 0; c < npoly; c++) dfl_polyline_free(&polys[c]);
    for (int c = 0; c < nbuilt; c++) dfl_bspline_free(&curves[c]);
    keys_free(&k);
    return st;
}

/* Peak memory: every curve's polyline at eps, all held until the .vtp
 * files are written, at most dfl_polygonize_curve_segments_bound points
 * each, 256 bytes a point: (dim + 2) doubles (point, t, bound) three times
 * over while the polygonizer's arrays double, the deviation search's
 * segment grid and the writer's copy (3D points, connectivity, zlib); and
 * one fit_eps polyline at a time beside them.  Work: a chord bound per
 * node of the subdivision tree (2 per segment, CHEAP) for eps and every
 * fit_eps, and the deviation: samples + 40 (the golden-section rounds)
 * distances to the polyline (EXACT) per segment. */
static dfl_status poly_estimate(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_cost *c,
                                dfl_err *err)
{
    (void)ctx;
    study_keys k;
    dfl_status st = read_keys(cfg, &k, err);
    double held = 0, fit = 0, tree = 0;
    for (int i = 0; i < k.ncurves && !st; i++) {
        dfl_bspline cv;
        if (!dfl_cfg_has_section(cfg, k.names[i])) continue; /* the run names it */
        if ((st = dfl_curve_section_from_cfg(cfg, k.names[i], &cv, err))) break;
        const double n = dfl_polygonize_curve_segments_bound(&cv, k.eps) + 1;
        held += n;
        tree += 2 * n;
        for (size_t j = 0; j < k.nfit; j++) {
            const double q = dfl_polygonize_curve_segments_bound(&cv, k.fit_eps[j]) + 1;
            fit = fmax(fit, q);
            tree += 2 * q;
        }
        dfl_bspline_free(&cv);
    }
    if (!st) {
        dfl_cost_add_bytes(c, "study", "eps", 256 * held, "polylines of up to %.3g points", held);
        dfl_cost_add_bytes(c, "study", "fit_eps", 96 * fit, "a polyline of up to %.3g points", fit);
        dfl_cost_add_work(c, "study", "eps", DFL_COST_CHEAP, tree, "%.3g chord bounds", tree);
        dfl_cost_add_work(c, "study", "samples", DFL_COST_EXACT, held * ((double)k.samples + 40),
                          "%.3g segments x %ld samples", held, k.samples);
    }
    keys_free(&k);
    return st;
}

DFL_STUDY_DEFINE_ESTIMATED(bs04_polygonization, bs04_poly_run, poly_estimate,
                 "bs04: certified polygonization of the S and W B-splines, segments vs eps");
