/* sjp10 Sec. 5, Fig. 3: trimmed offsets as level sets f = delta of the
 * fitted PHT spline, against the exact offsets {d = delta} of the true
 * SDF, beside the untrimmed offset curves c(u) + delta N(u) and their
 * swallow-tails (what trimming removes).
 *
 * Measures.  Level sets come from marching squares (2D; and on a cutting
 * plane in 3D) or marching cubes (3D, over a cutting region) on the spline
 * sampled at grid nodes, every vertex then moved onto f = delta along its
 * grid edge (field/isoline.h, 40 Illinois steps), so the measured error is
 * the spline's, not the marching's.  Error of a vertex x: |d(x) - delta|,
 * which for a signed distance is exactly the distance from x to the true
 * trimmed offset {d = delta} (1-Lipschitz, unit speed along the footpoint
 * segment).  exact_lines counts the components of {d = delta} on the same
 * grid (marching squares on the exact SDF) for a topology check.
 * Untrimmed offsets (geom/offset.h; closed B-spline curves only): cusps,
 * swallow-tails (arcs where 1 + kappa delta < 0), self-intersections of
 * the sampled offset, and the share of its samples that lie closer to the
 * curve than |delta| (|d(o)| < |delta| (1 - 1e-6)): the part a trimmed
 * offset drops.
 *
 * Keys.  [study]
 *   cases = <section> ...   case sections: 2D or 3D by their shape
 *   fit   = <section>       2D fit options (pht_cfg.h)
 *   fit3  = <section>       3D fit options (lo/hi replaced by the case's)
 *   refine = 40             Illinois steps per vertex
 * A 2D case: shape (closed planar curve or circle), deltas (dflab sign:
 *   < 0 inside), grid_n (201), offset_samples (4000; used for B-spline
 *   curves only).
 * A 3D case: shape, ref (default shape), deltas, lo, hi (the fit's box),
 *   grid_n (41; nodes per axis of the cutting region), cut_lo, cut_hi (the region), plane_axis
 *   (0..2), plane_at (the cutting plane; isolines on it).
 * Rows: one per case and delta.  Files per case: <case>_isolines.vtp
 * (2D: all deltas, point data "delta"), <case>_untrimmed.vtp (point data
 * delta, removed), 3D: <case>_isosurfaces.vtp and <case>_plane.vtp.
 * Signs: dflab's delta < 0 is an inner offset; sjp10's delta is -delta.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <omp.h>

#include "cfg/curve_cfg.h"
#include "cfg/field_cost.h"
#include "cfg/list_cfg.h"
#include "cfg/pht_cfg.h"
#include "cfg/shape_cfg.h"
#include "field/isoline.h"
#include "field/sample.h"
#include "geom/offset.h"
#include "geom/polygon.h"
#include "io/vtk.h"
#include "pht/pht_field.h"
#include "sjp10/sjp10.h"
#include "sjp10/sjp10_common.h"

typedef struct ocase {
    char name[DFL_SECTION_NAME_LEN];
    const char *shape_sec;
    dfl_shape shape, ref;
    int have_shape, have_ref, have_curve, dim;
    dfl_pht_source *src;
    dfl_bspline curve;
    double *deltas;
    size_t ndeltas;
    long grid_n, offset_samples, plane_axis;
    double cut_lo[3], cut_hi[3], plane_at, lo[3], hi[3];
} ocase;

typedef struct okeys {
    ocase c[SJP10_MAX_CASES];
    int ncases;
    dfl_pht_fit_opts fit2, fit3;
    long refine;
} okeys;

/* Polylines and triangles of several level sets in one PolyData. */
typedef struct polyacc {
    size_t np, nl, nconn, nt, capp, capl, capc, capt;
    double *pts, *delta, *flag;
    size_t *off, *conn, *tris;
} polyacc;

static void keys_free(void *keys)
{
    okeys *k = keys;
    for (int i = 0; i < k->ncases; i++) {
        ocase *c = &k->c[i];
        dfl_pht_source_free(c->src);
        if (c->have_shape) dfl_shape_free(&c->shape);
        if (c->have_ref) dfl_shape_free(&c->ref);
        if (c->have_curve) dfl_bspline_free(&c->curve);
        free(c->deltas);
    }
}

static void acc_free(polyacc *a)
{
    free(a->pts), free(a->delta), free(a->flag), free(a->off), free(a->conn), free(a->tris);
    memset(a, 0, sizeof *a);
}

static int grow(void **p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap) return 0;
    size_t c = *cap ? *cap : 1024;
    while (c < need) c *= 2;
    void *q = realloc(*p, c * elem);
    if (!q) return -1;
    *p = q;
    *cap = c;
    return 0;
}

/* Appends n points (3 coordinates) tagged with delta and flag[i] (NULL: 0). */
static int acc_points(polyacc *a, size_t n, const double *pts, double delta, const double *flag)
{
    size_t c1 = a->capp, c2 = a->capp, c3 = a->capp;
    if (grow((void **)&a->pts, &c1, a->np + n, 3 * sizeof(double)) ||
        grow((void **)&a->delta, &c2, a->np + n, sizeof(double)) ||
        grow((void **)&a->flag, &c3, a->np + n, sizeof(double)))
        return -1;
    a->capp = c1;
    if (n) memcpy(a->pts + 3 * a->np, pts, 3 * n * sizeof *pts); /* an empty level set: pts may be NULL */
    for (size_t i = 0; i < n; i++) {
        a->delta[a->np + i] = delta;
        a->flag[a->np + i] = flag ? flag[i] : 0.0;
    }
    a->np += n;
    return 0;
}

/* Appends the lines and triangles of iso (its points already appended at base). */
static int acc_iso(polyacc *a, const dfl_iso *iso, size_t base)
{
    if (grow((void **)&a->off, &a->capl, a->nl + iso->nlines + 2, sizeof(size_t)) ||
        grow((void **)&a->conn, &a->capc, a->nconn + (iso->nlines ? iso->line_offsets[iso->nlines] : 0) + 1,
             sizeof(size_t)) ||
        grow((void **)&a->tris, &a->capt, 3 * (a->nt + iso->ntris) + 1, sizeof(size_t)))
        return -1;
    if (a->nl == 0) a->off[0] = 0;
    for (size_t l = 0; l < iso->nlines; l++) {
        for (size_t q = iso->line_offsets[l]; q < iso->line_offsets[l + 1]; q++)
            a->conn[a->nconn++] = base + iso->line_conn[q];
        a->off[++a->nl] = a->nconn;
    }
    for (size_t t = 0; t < 3 * iso->ntris; t++) a->tris[3 * a->nt + t] = base + iso->tris[t];
    a->nt += iso->ntris;
    return 0;
}

static dfl_status acc_write(const dfl_study_ctx *ctx, const char *stem, const polyacc *a,
                            const char *flag_name, dfl_err *err)
{
    dfl_vtk_array arr[2] = {{"delta", 1, a->delta}, {flag_name ? flag_name : "flag", 1, a->flag}};
    dfl_vtp_data d = {.npoints = a->np, .points = a->pts, .nlines = a->nl,
                      .line_offsets = a->nl ? a->off : NULL, .line_conn = a->conn,
                      .ntris = a->nt, .tris = a->tris, .point_arrays = a->np ? arr : NULL,
                      .narrays = a->np ? (flag_name ? 2 : 1) : 0};
    char path[4400];
    dfl_study_path(ctx, stem, "vtp", path, sizeof path);
    return dfl_vtp_write(path, &d, 1, err);
}

/* A case's level sets over all its offsets go into one file per kind,
 * <case>_<what>.vtp, which every row of the case names in its column
 * <what>_vtp ("" where the case has none: present false). */
static dfl_status put_vtp(dfl_table *t, const dfl_study_ctx *ctx, const ocase *c, const char *what,
                          bool present, dfl_err *err)
{
    char col[64], stem[96];
    snprintf(col, sizeof col, "%s_vtp", what);
    snprintf(stem, sizeof stem, "%s_%s", c->name, what);
    return dfl_study_put_file(t, col, ctx, stem, "vtp", present, err);
}

/* After the offsets (st their status): <case>_<what>.vtp from acc when
 * present and all went well; acc is freed either way. */
static dfl_status write_vtp(const dfl_study_ctx *ctx, const ocase *c, const char *what,
                            polyacc *acc, const char *flag_name, bool present, dfl_status st,
                            dfl_err *err)
{
    char stem[96];
    snprintf(stem, sizeof stem, "%s_%s", c->name, what);
    if (!st && present) st = acc_write(ctx, stem, acc, flag_name, err);
    acc_free(acc);
    return st;
}

static dfl_status read_case(const dfl_cfg *cfg, ocase *c, dfl_err *err)
{
    const char *sec = c->name, *rsec;
    dfl_status st;
    if (!dfl_cfg_has_section(cfg, sec))
        return dfl_cfg_reject(cfg, "study", "cases", err, "no section [%s]", sec);
    if ((st = dfl_cfg_string(cfg, sec, "shape", &c->shape_sec, err))) return st;
    if (!dfl_cfg_has_section(cfg, c->shape_sec))
        return dfl_cfg_reject(cfg, sec, "shape", err, "no section [%s]", c->shape_sec);
    if ((st = dfl_shape_from_cfg(cfg, c->shape_sec, &c->shape, err))) return st;
    c->have_shape = 1;
    c->dim = c->shape.dim;
    if ((st = sjp10_source_new(cfg, c->shape_sec, &c->shape, &c->src, err))) return st;
    if ((st = dfl_cfg_doubles(cfg, sec, "deltas", 1, &c->deltas, &c->ndeltas, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "grid_n", c->dim == 2 ? 201 : 41, 3, 2001, &c->grid_n, err)))
        return st;
    if (c->dim == 2) {
        const char *kind;
        if ((st = dfl_cfg_string(cfg, c->shape_sec, "kind", &kind, err))) return st;
        if (strcmp(kind, "bspline_curve") == 0) {
            if ((st = dfl_curve_section_from_cfg(cfg, c->shape_sec, &c->curve, err))) return st;
            c->have_curve = 1;
        }
        return dfl_cfg_int_opt(cfg, sec, "offset_samples", 4000, 8, 10000000, &c->offset_samples, err);
    }
    if ((st = dfl_cfg_string_opt(cfg, sec, "ref", c->shape_sec, &rsec, err))) return st;
    if (!dfl_cfg_has_section(cfg, rsec))
        return dfl_cfg_reject(cfg, sec, "ref", err, "no section [%s]", rsec);
    if ((st = dfl_shape_from_cfg(cfg, rsec, &c->ref, err))) return st;
    c->have_ref = 1;
    if ((st = dfl_cfg_vec(cfg, sec, "lo", 3, c->lo, err))) return st;
    if ((st = dfl_cfg_vec(cfg, sec, "hi", 3, c->hi, err))) return st;
    for (int j = 0; j < 3; j++)
        if (!(c->lo[j] < c->hi[j])) return dfl_cfg_reject(cfg, sec, "hi", err, "expected hi > lo");
    if ((st = dfl_cfg_vec(cfg, sec, "cut_lo", 3, c->cut_lo, err))) return st;
    if ((st = dfl_cfg_vec(cfg, sec, "cut_hi", 3, c->cut_hi, err))) return st;
    for (int j = 0; j < 3; j++)
        if (!(c->cut_lo[j] < c->cut_hi[j]))
            return dfl_cfg_reject(cfg, sec, "cut_hi", err, "expected cut_hi > cut_lo");
    if ((st = dfl_cfg_int(cfg, sec, "plane_axis", 0, 2, &c->plane_axis, err))) return st;
    return dfl_cfg_double(cfg, sec, "plane_at", -1e300, 1e300, &c->plane_at, err);
}

static dfl_status read_keys(const dfl_cfg *cfg, void *keys, dfl_err *err)
{
    okeys *k = keys;
    char names[SJP10_MAX_CASES][DFL_SECTION_NAME_LEN];
    dfl_status st = dfl_section_names_from_cfg(cfg, "study", "cases", SJP10_MAX_CASES, names,
                                               &k->ncases, "case section", err);
    if (st) return st;
    for (int i = 0; i < k->ncases; i++) memcpy(k->c[i].name, names[i], DFL_SECTION_NAME_LEN);
    for (int i = 0; i < k->ncases; i++)
        if ((st = read_case(cfg, &k->c[i], err))) return st;
    int need2 = 0, need3 = 0;
    for (int i = 0; i < k->ncases; i++) *(k->c[i].dim == 2 ? &need2 : &need3) = 1;
    if (need2) {
        if ((st = sjp10_fit_from_cfg(cfg, "fit", 2, &k->fit2, err))) return st;
    }
    if (need3) {
        if ((st = sjp10_fit_from_cfg(cfg, "fit3", 3, &k->fit3, err))) return st;
    }
    return dfl_cfg_int_opt(cfg, "study", "refine", 40, 0, 200, &k->refine, err);
}

/* max and mean of |d(x) - delta| over the iso's points (ref: the exact SDF). */
static void iso_error(const dfl_shape *ref, const dfl_iso *iso, double delta, int threads,
                      double *emax, double *emean)
{
    const int dim = ref->dim;
    const size_t n = iso->npoints;
    *emax = n ? 0.0 : NAN;
    *emean = n ? 0.0 : NAN;
    if (!n) return;
    double *x = malloc(n * (size_t)dim * sizeof *x), *d = malloc(n * sizeof *d);
    double *g = malloc(n * (size_t)dim * sizeof *g);
    if (!x || !d || !g) {
        *emax = *emean = NAN;
        free(x), free(d), free(g);
        return;
    }
    for (size_t i = 0; i < n; i++)
        for (int j = 0; j < dim; j++) x[i * dim + j] = iso->points[3 * i + j];
    sjp10_shape_eval(ref, n, x, d, g, threads);
    double s = 0;
    for (size_t i = 0; i < n; i++) {
        const double e = fabs(d[i] - delta);
        *emax = fmax(*emax, e);
        s += e;
    }
    *emean = s / (double)n;
    free(x), free(d), free(g);
}

static dfl_status row_start(dfl_table *t, const ocase *c, double delta, dfl_err *err)
{
    dfl_status st = dfl_table_row(t, err);
    if (!st) st = dfl_table_set_string(t, "case", c->name, err);
    if (!st) st = dfl_table_set_int(t, "dim", c->dim, err);
    if (!st) st = dfl_table_set_double(t, "delta", delta, err);
    if (!st) st = dfl_table_set_double(t, "sjp10_delta", -delta, err);
    return st;
}

static dfl_status put_fit_cols(dfl_table *t, const dfl_pht_fit_opts *o, const dfl_pht_fit *fit,
                               dfl_err *err)
{
    dfl_status st = dfl_table_set_double(t, "eps", o->eps, err);
    if (!st) st = sjp10_put_fit(t, fit, NULL, o->eps, err);
    return st;
}

/* Untrimmed offset of a B-spline case: counts, removed share, samples. */
static dfl_status untrimmed(const ocase *c, double delta, int threads, polyacc *acc,
                            dfl_offset_counts *cnt, double *removed, dfl_err *err)
{
    dfl_offset o;
    const int orient = dfl_polygon_orientation(c->curve.cp, c->curve.nuser) > 0 ? 1 : -1;
    dfl_status st = dfl_offset_curve(&c->curve, orient, delta, (size_t)c->offset_samples, &o, err);
    if (st) return st;
    st = dfl_offset_count(&o, cnt, err);
    const size_t n = o.n;
    double *d = malloc(n * sizeof *d), *g = malloc(2 * n * sizeof *g), *p3 = malloc(3 * n * sizeof *p3);
    double *flag = malloc(n * sizeof *flag);
    if (!st && (!d || !g || !p3 || !flag)) st = dfl_err_set(err, DFL_E_NOMEM, "sjp10_offsets: out of memory");
    if (!st) {
        sjp10_shape_eval(&c->shape, n, o.pts, d, g, threads);
        size_t rem = 0;
        for (size_t i = 0; i < n; i++) {
            flag[i] = fabs(d[i]) < fabs(delta) * (1 - 1e-6);
            rem += flag[i] != 0.0;
            p3[3 * i] = o.pts[2 * i], p3[3 * i + 1] = o.pts[2 * i + 1], p3[3 * i + 2] = 0;
        }
        *removed = (double)rem / (double)n;
        const size_t base = acc->np;
        if (acc_points(acc, n, p3, delta, flag) ||
            grow((void **)&acc->off, &acc->capl, acc->nl + 2, sizeof(size_t)) ||
            grow((void **)&acc->conn, &acc->capc, acc->nconn + n + 1, sizeof(size_t))) {
            st = dfl_err_set(err, DFL_E_NOMEM, "sjp10_offsets: out of memory");
        } else {
            if (acc->nl == 0) acc->off[0] = 0;
            for (size_t i = 0; i <= n; i++) acc->conn[acc->nconn++] = base + i % n;
            acc->off[++acc->nl] = acc->nconn;
        }
    }
    free(d), free(g), free(p3), free(flag);
    dfl_offset_free(&o);
    return st;
}

static dfl_status run_2d(const okeys *k, const ocase *c, const dfl_study_ctx *ctx, dfl_table *t,
                         dfl_err *err)
{
    const dfl_pht_fit_opts *o = &k->fit2;
    dfl_pht_fit fit;
    dfl_field f = {0};
    dfl_status st = dfl_pht_fit_run(c->src, o, &fit, err);
    if (st) return dfl_err_prefix(err, "[%s]", c->name);
    st = dfl_pht_field_new(&fit.spline, &f, err);
    dfl_grid g = {2, {(int)c->grid_n, (int)c->grid_n, 1}, {o->lo[0], o->lo[1], 0}, {o->hi[0], o->hi[1], 0}};
    const size_t m = dfl_grid_size(&g);
    double *v = malloc(m * sizeof *v), *dv = malloc(m * sizeof *dv), *xy = malloc(2 * m * sizeof *xy);
    double *dg = malloc(2 * m * sizeof *dg);
    polyacc iso_acc = {0}, un_acc = {0};
    if (!st && (!v || !dv || !xy || !dg)) st = dfl_err_set(err, DFL_E_NOMEM, "sjp10_offsets: out of memory");
    if (!st) st = dfl_field_sample(&f, &g, ctx->threads, v, NULL, err);
    if (!st) {
        for (size_t i = 0; i < m; i++) dfl_grid_node(&g, i, xy + 2 * i);
        sjp10_shape_eval(&c->shape, m, xy, dv, dg, ctx->threads);
    }
    for (size_t l = 0; l < c->ndeltas && !st; l++) {
        const double delta = c->deltas[l];
        dfl_iso iso = {0}, ex = {0};
        double emax, emean, removed = NAN;
        dfl_offset_counts cnt = {0};
        const double t0 = omp_get_wtime();
        st = dfl_iso_lines(&g, v, delta, &iso, err);
        if (!st) st = dfl_iso_refine(&iso, &f, delta, (int)k->refine, err);
        const double t_iso = omp_get_wtime() - t0;
        if (!st) st = dfl_iso_lines(&g, dv, delta, &ex, err);
        if (!st) iso_error(&c->shape, &iso, delta, ctx->threads, &emax, &emean);
        if (!st && acc_points(&iso_acc, iso.npoints, iso.points, delta, NULL))
            st = dfl_err_set(err, DFL_E_NOMEM, "sjp10_offsets: out of memory");
        if (!st && acc_iso(&iso_acc, &iso, iso_acc.np - iso.npoints))
            st = dfl_err_set(err, DFL_E_NOMEM, "sjp10_offsets: out of memory");
        if (!st && c->have_curve) st = untrimmed(c, delta, ctx->threads, &un_acc, &cnt, &removed, err);
        if (!st) st = row_start(t, c, delta, err);
        if (!st) st = put_fit_cols(t, o, &fit, err);
        if (!st) st = dfl_table_set_int(t, "iso_points", (long)iso.npoints, err);
        if (!st) st = dfl_table_set_int(t, "iso_lines", (long)iso.nlines, err);
        if (!st) st = dfl_table_set_int(t, "iso_closed", (long)iso.nclosed, err);
        if (!st) st = dfl_table_set_int(t, "exact_lines", (long)ex.nlines, err);
        if (!st) st = dfl_table_set_double(t, "err_max", emax, err);
        if (!st) st = dfl_table_set_double(t, "err_mean", emean, err);
        if (!st) st = dfl_table_set_double(t, "t_iso", t_iso, err);
        if (!st) st = dfl_table_set_int(t, "untrimmed", c->have_curve, err);
        if (!st) st = dfl_table_set_int(t, "cusps", c->have_curve ? (long)cnt.cusps : -1, err);
        if (!st) st = dfl_table_set_int(t, "swallow_tails", c->have_curve ? (long)cnt.swallow_tails : -1, err);
        if (!st) st = dfl_table_set_int(t, "self_intersections", c->have_curve ? (long)cnt.self_intersections : -1, err);
        if (!st) st = dfl_table_set_double(t, "reversed_fraction", c->have_curve ? cnt.reversed_fraction : NAN, err);
        if (!st) st = dfl_table_set_double(t, "removed_fraction", removed, err);
        if (!st) st = put_vtp(t, ctx, c, "isolines", true, err);
        if (!st) st = put_vtp(t, ctx, c, "untrimmed", c->have_curve, err);
        dfl_iso_free(&iso);
        dfl_iso_free(&ex);
    }
    st = write_vtp(ctx, c, "isolines", &iso_acc, NULL, true, st, err);
    st = write_vtp(ctx, c, "untrimmed", &un_acc, "removed", c->have_curve, st, err);
    free(v), free(dv), free(xy), free(dg);
    dfl_field_destroy(&f);
    dfl_pht_fit_free(&fit);
    return st;
}

/* The in-plane axes of a plane normal to axis (dfl_grid_plane's order). */
static void plane_axes(int axis, int *a0, int *a1)
{
    *a0 = axis == 0 ? 1 : 0;
    *a1 = axis == 2 ? 1 : 2;
}

static dfl_status run_3d(const okeys *k, const ocase *c, const dfl_study_ctx *ctx, dfl_table *t,
                         dfl_err *err)
{
    dfl_pht_fit_opts box = k->fit3;
    memcpy(box.lo, c->lo, sizeof box.lo);
    memcpy(box.hi, c->hi, sizeof box.hi);
    const dfl_pht_fit_opts *o = &box;
    dfl_pht_fit fit;
    dfl_field f = {0};
    dfl_status st = dfl_pht_fit_run(c->src, o, &fit, err);
    if (st) return dfl_err_prefix(err, "[%s]", c->name);
    st = dfl_pht_field_new(&fit.spline, &f, err);
    const int n = (int)c->grid_n;
    dfl_grid g = {3, {n, n, n}, {c->cut_lo[0], c->cut_lo[1], c->cut_lo[2]},
                  {c->cut_hi[0], c->cut_hi[1], c->cut_hi[2]}};
    int a0, a1;
    plane_axes((int)c->plane_axis, &a0, &a1);
    dfl_grid gp;
    const int np2[2] = {2 * n - 1, 2 * n - 1};
    const double plo[2] = {c->cut_lo[a0], c->cut_lo[a1]}, phi[2] = {c->cut_hi[a0], c->cut_hi[a1]};
    dfl_grid_plane((int)c->plane_axis, c->plane_at, np2, plo, phi, &gp);
    const size_t m = dfl_grid_size(&g), mp = dfl_grid_size(&gp);
    double *v = malloc(m * sizeof *v), *vp = malloc(mp * sizeof *vp);
    polyacc sacc = {0}, pacc = {0};
    if (!st && (!v || !vp)) st = dfl_err_set(err, DFL_E_NOMEM, "sjp10_offsets: out of memory");
    if (!st) st = dfl_field_sample(&f, &g, ctx->threads, v, NULL, err);
    if (!st) st = dfl_field_sample(&f, &gp, ctx->threads, vp, NULL, err);
    for (size_t l = 0; l < c->ndeltas && !st; l++) {
        const double delta = c->deltas[l];
        dfl_iso s = {0}, p = {0};
        double smax, smean, pmax, pmean;
        const double t0 = omp_get_wtime();
        st = dfl_iso_surface(&g, v, delta, &s, err);
        if (!st) st = dfl_iso_refine(&s, &f, delta, (int)k->refine, err);
        const double t_iso = omp_get_wtime() - t0;
        if (!st) st = dfl_iso_lines(&gp, vp, delta, &p, err);
        if (!st) st = dfl_iso_refine(&p, &f, delta, (int)k->refine, err);
        if (!st) iso_error(&c->ref, &s, delta, ctx->threads, &smax, &smean);
        if (!st) iso_error(&c->ref, &p, delta, ctx->threads, &pmax, &pmean);
        if (!st && (acc_points(&sacc, s.npoints, s.points, delta, NULL) ||
                    acc_iso(&sacc, &s, sacc.np - s.npoints) ||
                    acc_points(&pacc, p.npoints, p.points, delta, NULL) ||
                    acc_iso(&pacc, &p, pacc.np - p.npoints)))
            st = dfl_err_set(err, DFL_E_NOMEM, "sjp10_offsets: out of memory");
        if (!st) st = row_start(t, c, delta, err);
        if (!st) st = put_fit_cols(t, o, &fit, err);
        if (!st) st = dfl_table_set_int(t, "iso_points", (long)s.npoints, err);
        if (!st) st = dfl_table_set_int(t, "iso_triangles", (long)s.ntris, err);
        if (!st) st = dfl_table_set_double(t, "err_max", smax, err);
        if (!st) st = dfl_table_set_double(t, "err_mean", smean, err);
        if (!st) st = dfl_table_set_double(t, "t_iso", t_iso, err);
        if (!st) st = dfl_table_set_int(t, "plane_points", (long)p.npoints, err);
        if (!st) st = dfl_table_set_int(t, "plane_lines", (long)p.nlines, err);
        if (!st) st = dfl_table_set_double(t, "plane_err_max", pmax, err);
        if (!st) st = dfl_table_set_double(t, "plane_err_mean", pmean, err);
        if (!st) st = put_vtp(t, ctx, c, "isosurfaces", true, err);
        if (!st) st = put_vtp(t, ctx, c, "plane", true, err);
        dfl_iso_free(&s);
        dfl_iso_free(&p);
    }
    st = write_vtp(ctx, c, "isosurfaces", &sacc, NULL, true, st, err);
    st = write_vtp(ctx, c, "plane", &pacc, NULL, true, st, err);
    free(v), free(vp);
    dfl_field_destroy(&f);
    dfl_pht_fit_free(&fit);
    return st;
}

static dfl_status run_cases(void *keys, const dfl_study_ctx *ctx, dfl_table *t, dfl_err *err)
{
    const okeys *k = keys;
    dfl_status st = DFL_OK;
    for (int i = 0; i < k->ncases && !st; i++)
        st = k->c[i].dim == 2 ? run_2d(k, &k->c[i], ctx, t, err) : run_3d(k, &k->c[i], ctx, t, err);
    return st;
}

static const sjp10_study OFFSETS = {sizeof(okeys), read_keys, run_cases, keys_free};

static dfl_status offsets_run(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_table *table,
                              dfl_err *err)
{
    okeys k;
    return sjp10_run(&OFFSETS, &k, cfg, ctx, table, err);
}

/* Peak memory: the cases run one after another; a case holds its fit
 * (bounded by max_level of [fit] or [fit3], sjp10_fit_cost), its samples
 * (2D: grid_n^2 nodes of v, d, their points and gradients, 48 bytes; 3D:
 * grid_n^3 values and the plane's (2 grid_n - 1)^2, 8 bytes) and its level
 * sets.  Those are bounded by the grid, not the curve: marching squares puts
 * at most one vertex on each of the 2 edges a node owns, marching cubes on
 * the 6-tetrahedron split on each of 7 edges a node owns and at most 12
 * triangles in a cube.  Per offset the level set itself (a vertex: point,
 * edge ends and connectivity, 120 bytes; a triangle 24) and, kept for the
 * file over all offsets, its copy (a vertex 48 bytes, a triangle 24);
 * untrimmed offsets (B-spline curves): offset_samples points (120 bytes
 * while measured, 48 kept per offset).  Work: the fit, per node one
 * spline evaluation (DECODE) and in 2D the exact SDF (the shape's class),
 * per level-set vertex refine evaluations and one exact distance, per
 * offset sample one exact distance.  The shapes are not built. */
static dfl_status offsets_estimate(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_cost *c,
                                   dfl_err *err)
{
    (void)ctx;
    char names[SJP10_MAX_CASES][DFL_SECTION_NAME_LEN];
    int n = 0, need2 = 0, need3 = 0;
    okeys k;
    memset(&k, 0, sizeof k);
    dfl_status st = dfl_section_names_from_cfg(cfg, "study", "cases", SJP10_MAX_CASES, names, &n,
                                               "case section", err);
    for (int i = 0; i < n && !st; i++) {
        const char *shape;
        if (!dfl_cfg_has_section(cfg, names[i]) || !dfl_cfg_has(cfg, names[i], "shape") ||
            dfl_cfg_string(cfg, names[i], "shape", &shape, NULL))
            continue; /* the run names it */
        *(dfl_shape_dim_guess(cfg, shape) == 2 ? &need2 : &need3) = 1;
    }
    if (!st && need2) st = sjp10_fit_from_cfg(cfg, "fit", 2, &k.fit2, err);
    if (!st && need3) st = sjp10_fit_from_cfg(cfg, "fit3", 3, &k.fit3, err);
    if (!st) st = dfl_cfg_int_opt(cfg, "study", "refine", 40, 0, 200, &k.refine, err);
    const char *f2 = "fit", *f3 = "fit3";
    if (!st && need2) dfl_cfg_string(cfg, "study", "fit", &f2, NULL);
    if (!st && need3) dfl_cfg_string(cfg, "study", "fit3", &f3, NULL);
    f2 = dfl_cfg_section_name(cfg, f2), f3 = dfl_cfg_section_name(cfg, f3);
    for (int i = 0; i < n && !st; i++) {
        const char *sec = dfl_cfg_section_name(cfg, names[i]), *shape, *kind = "";
        double *deltas = NULL;
        size_t nd = 0;
        long gn, samples = 0;
        if (!sec || !dfl_cfg_has(cfg, sec, "shape") || dfl_cfg_string(cfg, sec, "shape", &shape, NULL))
            continue;
        const int dim = dfl_shape_dim_guess(cfg, shape);
        const dfl_cost_class cls = dfl_shape_cost_class(cfg, shape);
        if ((st = dfl_cfg_doubles(cfg, sec, "deltas", 1, &deltas, &nd, err))) break;
        free(deltas);
        if ((st = dfl_cfg_int_opt(cfg, sec, "grid_n", dim == 2 ? 201 : 41, 3, 2001, &gn, err)))
            break;
        if (dim == 2 && dfl_cfg_has(cfg, shape, "kind")) dfl_cfg_string(cfg, shape, "kind", &kind, NULL);
        if (dim == 2 && !strcmp(kind, "bspline_curve") &&
            (st = dfl_cfg_int_opt(cfg, sec, "offset_samples", 4000, 8, 10000000, &samples, err)))
            break;
        const double g = (double)gn, D = (double)nd, refine = (double)k.refine;
        dfl_cost one;
        memset(&one, 0, sizeof one);
        sjp10_fit_cost(dim == 2 ? &k.fit2 : &k.fit3, dim, -1, cls, 0, dim == 2 ? f2 : f3,
                       "max_level", &one);
        if (dim == 2) {
            const double nodes = g * g, pts = 2 * nodes;
            dfl_cost_add_bytes(&one, sec, "grid_n", 48 * nodes + 120 * pts + 48 * pts * D,
                               "%ld^2 samples and the level sets on them", gn);
            dfl_cost_add_bytes(&one, sec, "offset_samples", (120 + 48 * D) * (double)samples,
                               "untrimmed offsets of %ld samples", samples);
            dfl_cost_add_work(&one, sec, "grid_n", DFL_COST_DECODE, nodes + pts * D * refine,
                              "%ld^2 samples and the level sets' refinement", gn);
            dfl_cost_add_work(&one, sec, "grid_n", cls, nodes + pts * D,
                              "%ld^2 exact samples and errors", gn);
            dfl_cost_add_work(&one, sec, "offset_samples", cls, (double)samples * D,
                              "%ld untrimmed offset samples", samples);
        } else {
            const double nodes = g * g * g, plane = (2 * g - 1) * (2 * g - 1);
            const double pts = 7 * nodes + 2 * plane, tris = 12 * nodes;
            dfl_cost_add_bytes(&one, sec, "grid_n",
                               8 * (nodes + plane) + 120 * pts + 24 * tris + (48 * pts + 24 * tris) * D,
                               "%ld^3 samples and the level sets on them", gn);
            dfl_cost_add_work(&one, sec, "grid_n", DFL_COST_DECODE,
                              nodes + plane + pts * D * refine,
                              "%ld^3 samples and the level sets' refinement", gn);
            dfl_cost_add_work(&one, sec, "grid_n", cls, pts * D, "the level sets' errors");
        }
        dfl_cost_add_step(c, &one);
    }
    return st;
}

DFL_STUDY_DEFINE_ESTIMATED(sjp10_offsets, offsets_run, offsets_estimate,
                 "sjp10 Sec. 5 / Fig. 3: trimmed offsets as level sets of the PHT fit vs untrimmed offsets");
