/* `[field] kind = pht` (pht_cfg.h). */
#include "cfg/pht_cfg.h"

#include <math.h>
#include <string.h>

#include "cfg/shape_cfg.h"
#include "pht/pht_field.h"

static const char *const split_names[] = {
#define X(code, name) name,
    DFL_PHT_SPLITS(X)
#undef X
};
static const char *const est_names[] = {
#define X(code, name) name,
    DFL_PHT_ESTIMATORS(X)
#undef X
};

static dfl_status box_from_cfg(const dfl_cfg *cfg, const char *sec, int dim, double *lo,
                               double *hi, dfl_err *err)
{
    const double zero[3] = {0, 0, 0}, one[3] = {1, 1, 1};
    dfl_status st;
    if ((st = dfl_cfg_vec_opt(cfg, sec, "lo", dim, zero, lo, err))) return st;
    if ((st = dfl_cfg_vec_opt(cfg, sec, "hi", dim, one, hi, err))) return st;
    for (int j = 0; j < dim; j++)
        if (!(lo[j] < hi[j]))
            return dfl_cfg_reject(cfg, sec, dfl_cfg_has(cfg, sec, "hi") ? "hi" : "lo", err,
                                  "the box needs lo < hi on every axis (axis %d: %g, %g)", j,
                                  lo[j], hi[j]);
    return DFL_OK;
}

dfl_status dfl_pht_opts_from_cfg(const dfl_cfg *cfg, const char *sec, int dim,
                                 dfl_pht_fit_opts *o, dfl_err *err)
{
    dfl_pht_fit_opts r;
    dfl_pht_fit_opts_default(dim, &r);
    dfl_status st;
    int split, est;
    long maxl, samples, seed;
    double eps;
    bool grade, peaks;
    /* the smallest eps accepted: 1e-300 (a target, with max_level as the cap) */
    if ((st = dfl_cfg_double_opt(cfg, sec, "eps", r.eps, 1e-300, INFINITY, &eps, err)))
        return st;
    if (!(eps > 0))
        return dfl_cfg_reject(cfg, sec, "eps", err, "eps = %g, expected a target error > 0", eps);
    if ((st = dfl_cfg_enum_opt(cfg, sec, "split", split_names, DFL_PHT_SPLIT_COUNT, r.split,
                               &split, err)))
        return st;
    long lmax = split == DFL_PHT_SPLIT_BINARY ? (long)dim * DFL_TMESH_MAX_LEVEL
                                              : DFL_TMESH_MAX_LEVEL;
    if ((st = dfl_cfg_int_opt(cfg, sec, "max_level", r.max_level, 0, lmax, &maxl, err)))
        return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "samples", r.samples, 1, 4096, &samples, err)))
        return st;
    if ((st = dfl_cfg_enum_opt(cfg, sec, "estimator", est_names, DFL_PHT_EST_COUNT, r.estimator,
                               &est, err)))
        return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "seed", (long)r.seed, 0, 0x7fffffffL, &seed, err)))
        return st;
    if ((st = dfl_cfg_bool_opt(cfg, sec, "grade", true, &grade, err))) return st;
    if ((st = dfl_cfg_bool_opt(cfg, sec, "peaks", true, &peaks, err))) return st;
    if ((st = box_from_cfg(cfg, sec, dim, r.lo, r.hi, err))) return st;
    r.eps = eps;
    r.split = (dfl_pht_split)split;
    r.max_level = (int)maxl;
    r.samples = (int)samples;
    r.estimator = (dfl_pht_estimator)est;
    r.seed = (uint64_t)seed;
    r.grade = grade;
    r.peaks = peaks;
    *o = r;
    return DFL_OK;
}

/* Whether the shape's distance is signed with an inside near the box, from
 * at most two evaluations (a grid of probes missed small shapes between its
 * points and cost 33^3 slow footpoints on implicit surfaces).  At the box
 * centre c: d(c) < 0 is inside.  d(c) >= the half diagonal puts the whole
 * box in the ball around c that no surface enters: no inside in the box.
 * Otherwise the nearest surface point is q = c - d(c) grad d(c); a step a
 * little past it, x = c - (d(c) + t) grad d(c), is inside for any closed
 * curve or surface (its distance is signed), while an unsigned distance
 * (an open curve) stays >= 0 there.  So a closed shape that meets the box
 * is never refused, whatever its size or the box's. */
static int has_inside(const dfl_shape *s, const double *lo, const double *hi)
{
    const int dim = s->dim;
    double c[3] = {0, 0, 0}, g[3] = {0, 0, 0}, half2 = 0;
    for (int j = 0; j < dim; j++) {
        c[j] = 0.5 * lo[j] + 0.5 * hi[j];
        const double h = 0.5 * hi[j] - 0.5 * lo[j];
        half2 += h * h;
    }
    const double d = dfl_shape_eval1(s, c, g);
    if (d < 0.0) return 1;
    if (!(d < sqrt(half2))) return 0;
    double gn = 0;
    for (int j = 0; j < dim; j++) gn += g[j] * g[j];
    gn = sqrt(gn);
    if (!(gn > 0) || !isfinite(gn)) return 0;
    /* past the surface by a small share of the distance (at least of the
     * box), far below any feature a fit at max_level 30 resolves */
    const double t = 1e-6 * fmax(d, sqrt(half2) * 1e-6);
    double x[3];
    for (int j = 0; j < dim; j++) x[j] = c[j] - (d + t) * g[j] / gn;
    return dfl_shape_eval1(s, x, NULL) < 0.0;
}

dfl_status dfl_pht_source_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_shape *shape,
                                   dfl_pht_source **src, dfl_err *err)
{
    const char *shsec;
    dfl_status st;
    if ((st = dfl_cfg_string_opt(cfg, sec, "shape", "shape", &shsec, err))) return st;
    if (!dfl_cfg_has_section(cfg, shsec))
        return dfl_cfg_reject(cfg, sec, "shape", err, "no section [%s] for the shape", shsec);
    dfl_shape s;
    if ((st = dfl_shape_from_cfg(cfg, shsec, &s, err))) return st;
    dfl_pht_source *p = NULL;
    dfl_err e2;
    if (dfl_pht_source_new(&s, &p, &e2) != DFL_OK) {
        dfl_shape_free(&s);
        return dfl_cfg_reject(cfg, shsec, "kind", err, "%s", e2.msg);
    }
    double lo[3], hi[3];
    if ((st = box_from_cfg(cfg, sec, s.dim, lo, hi, err))) goto fail;
    if (!has_inside(&s, lo, hi)) {
        int curve = strcmp(s.ops->kind, "bspline_curve") == 0;
        st = dfl_cfg_reject(cfg, shsec, curve ? "closed" : "kind", err,
                            "the shape has no inside in the box (d >= 0 past its nearest point to the box centre): "
                            "PHT fits need a signed distance of a closed curve or surface%s",
                            curve ? " (an open curve's distance is unsigned: set closed = true)"
                                  : "");
        goto fail;
    }
    /* the source points at its shape: rebuild it on the caller's copy */
    dfl_pht_source_free(p);
    p = NULL;
    *shape = s;
    if ((st = dfl_pht_source_new(shape, src, err)) != DFL_OK) {
        dfl_shape_free(shape);
        return st;
    }
    return DFL_OK;
fail:
    dfl_pht_source_free(p);
    dfl_shape_free(&s);
    return st;
}

dfl_status dfl_pht_field_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out,
                                  dfl_err *err)
{
    dfl_shape shape;
    dfl_pht_source *src;
    dfl_status st = dfl_pht_source_from_cfg(cfg, sec, &shape, &src, err);
    if (st != DFL_OK) return st;
    dfl_pht_fit_opts o;
    dfl_pht_fit fit;
    memset(&fit, 0, sizeof fit);
    if ((st = dfl_pht_opts_from_cfg(cfg, sec, shape.dim, &o, err))) goto done;
    if ((st = dfl_pht_fit_run(src, &o, &fit, err))) {
        dfl_err_prefix(err, "[%s] kind = pht", sec);
        goto done;
    }
    st = dfl_pht_field_new(&fit.spline, out, err);
done:
    dfl_pht_fit_free(&fit);
    dfl_pht_source_free(src);
    dfl_shape_free(&shape);
    return st;
}
