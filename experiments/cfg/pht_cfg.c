/* `[field] kind = pht` (pht_cfg.h). */
#include "cfg/pht_cfg.h"

#include <math.h>
#include <string.h>

#include "cfg/shape_cfg.h"
#include "pht/pht_field.h"

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
    if ((st = dfl_cfg_enum_opt(cfg, sec, "split", dfl_pht_split_names, DFL_PHT_SPLIT_COUNT, r.split,
                               &split, err)))
        return st;
    long lmax = split == DFL_PHT_SPLIT_BINARY ? (long)dim * DFL_TMESH_MAX_LEVEL
                                              : DFL_TMESH_MAX_LEVEL;
    if ((st = dfl_cfg_int_opt(cfg, sec, "max_level", r.max_level, 0, lmax, &maxl, err)))
        return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "samples", r.samples, 1, 4096, &samples, err)))
        return st;
    if ((st = dfl_cfg_enum_opt(cfg, sec, "estimator", dfl_pht_estimator_names, DFL_PHT_EST_COUNT, r.estimator,
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

/* 0 iff d at the box centre is >= the half diagonal (no inside, no
 * surface in the box); the sign itself is the library's test. */
static int box_meets_inside(const dfl_shape *s, const double *lo, const double *hi)
{
    double c[3] = {0, 0, 0}, half2 = 0;
    for (int j = 0; j < s->dim; j++) {
        c[j] = 0.5 * lo[j] + 0.5 * hi[j];
        const double h = 0.5 * hi[j] - 0.5 * lo[j];
        half2 += h * h;
    }
    return dfl_shape_eval1(s, c, NULL) < sqrt(half2);
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
    /* the library's sign test (pht/hermite.h, the fits' own), located at
     * the key to fix */
    if (dfl_pht_source_check_signed(p, lo, hi, &e2) != DFL_OK) {
        int curve = strcmp(s.ops->kind, "bspline_curve") == 0;
        st = dfl_cfg_reject(cfg, shsec, curve ? "closed" : "kind", err, "%s%s", e2.msg,
                            curve ? " (set closed = true)" : "");
        goto fail;
    }
    /* a config's policy beyond the library: a field whose box the shape
     * stays away from (d at the centre >= the half diagonal: the whole box
     * is outside) is a mistake, not a fit to make */
    if (!box_meets_inside(&s, lo, hi)) {
        st = dfl_cfg_reject(cfg, shsec, "kind", err,
                            "the shape has no inside in the box (its distance from the box "
                            "centre is at least the half diagonal): move the box or the shape");
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

dfl_status dfl_pht_field_target_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out,
                                         dfl_field_target *target, dfl_err *err)
{
    dfl_shape shape;
    dfl_pht_source *src;
    dfl_status st = dfl_pht_source_from_cfg(cfg, sec, &shape, &src, err);
    if (st != DFL_OK) return st;
    dfl_pht_fit_opts o;
    dfl_pht_fit fit;
    memset(&fit, 0, sizeof fit);
    if ((st = dfl_pht_opts_from_cfg(cfg, sec, shape.dim, &o, err))) goto done;
    if (dfl_cfg_validating(cfg)) { /* keys read and checked: no fit (io/config.h) */
        dfl_field_placeholder(shape.dim, out);
        dfl_field_target_none(target);
        goto done;
    }
    if ((st = dfl_pht_fit_run(src, &o, &fit, err))) {
        dfl_err_prefix(err, "[%s] kind = pht", sec);
        goto done;
    }
    if ((st = dfl_pht_field_new(&fit.spline, out, err)) == DFL_OK) {
        /* the fit's own record (pht/fit.h): converged iff no capped cell */
        target->value = o.eps;
        target->met = fit.converged ? 1 : 0;
        target->over = fit.capped;
    }
done:
    dfl_pht_fit_free(&fit);
    dfl_pht_source_free(src);
    dfl_shape_free(&shape);
    return st;
}

dfl_status dfl_pht_field_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out,
                                  dfl_err *err)
{
    dfl_field_target target;
    return dfl_pht_field_target_from_cfg(cfg, sec, out, &target, err);
}
