/* Config -> rfunc field.  The library reports degenerate geometry without
 * knowing where it came from; every such message is prefixed here with
 * file:line, [section] and key. */
#include "cfg/rfunc_cfg.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cfg/curve_cfg.h"
#include "rfunc/rfield.h"

/* The curve named by [sec] curve, polygonized to [sec] eps, into the spec:
 * the curve, its polyline and the vertices (a closed curve, first point ==
 * last, drops the repeated point and sets closed). */
static dfl_status curve_polyline(const dfl_cfg *cfg, const char *sec, dfl_rfunc_field_spec *s,
                                 dfl_err *err)
{
    const char *kind;
    dfl_status st;
    if ((st = dfl_cfg_string(cfg, sec, "curve", &s->curve, err))) return st;
    if ((st = dfl_cfg_double(cfg, sec, "eps", 1e-300, 1e300, &s->eps, err))) return st;
    if (dfl_cfg_has(cfg, sec, "closed"))
        return dfl_cfg_reject(cfg, sec, "closed", err,
                              "closed applies to vertices only (a curve's closedness comes from"
                              " the curve)");
    if (!dfl_cfg_has_section(cfg, s->curve))
        return dfl_cfg_reject(cfg, sec, "curve", err, "no section [%s]", s->curve);
    if ((st = dfl_cfg_string(cfg, s->curve, "kind", &kind, err))) return st;
    if (strcmp(kind, "bspline_curve") != 0)
        return dfl_cfg_reject(cfg, sec, "curve", err,
                              "expected a curve (kind = bspline_curve), section [%s] has kind = %s",
                              s->curve, kind);
    if ((st = dfl_curve_from_cfg(cfg, s->curve, &s->bspline, err))) return st;
    if ((st = dfl_polygonize_curve(&s->bspline, s->eps, 0, &s->pl, err)))
        return dfl_cfg_err_at(cfg, sec, "eps", st, err);
    const dfl_polyline *pl = &s->pl;
    size_t np = pl->n;
    const size_t dim = (size_t)pl->dim;
    if (np >= 4 && memcmp(pl->pts, pl->pts + (np - 1) * dim, dim * sizeof *pl->pts) == 0) {
        s->closed = true;
        np--;
    }
    s->v = malloc(np * dim * sizeof *s->v);
    if (!s->v) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    memcpy(s->v, pl->pts, np * dim * sizeof *s->v);
    s->dim = pl->dim;
    s->n = np;
    return DFL_OK;
}

static dfl_status vertex_polyline(const dfl_cfg *cfg, const char *sec, dfl_rfunc_field_spec *s,
                                  dfl_err *err)
{
    const char *raw;
    dfl_status st;
    if ((st = dfl_cfg_bool_opt(cfg, sec, "closed", false, &s->closed, err))) return st;
    if ((st = dfl_cfg_string(cfg, sec, "vertices", &raw, err))) return st;
    s->dim = dfl_cfg_point_dim(raw);
    if (s->dim != 2 && s->dim != 3)
        return dfl_cfg_reject(cfg, sec, "vertices", err,
                              "expected vertices of 2 or 3 numbers, the first has %d", s->dim);
    return dfl_cfg_points(cfg, sec, "vertices", s->dim, s->closed ? 3 : 2, &s->v, &s->n, err);
}

/* The keys of the header into *s (which may own memory on failure). */
static dfl_status read_spec(const dfl_cfg *cfg, const char *sec, dfl_rfunc_field_spec *s,
                            dfl_err *err)
{
    long p;
    dfl_status st;
    if ((st = dfl_rfunc_join_from_cfg(cfg, sec, &s->join, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "p", 2, 1, DFL_RFUNC_P_MAX, &p, err))) return st;
    s->p = (int)p;
    if ((st = dfl_rfunc_trim_from_cfg(cfg, sec, &s->trim, err))) return st;
    int corr;
    if ((st = dfl_cfg_enum_opt(cfg, sec, "correction", dfl_rfunc_correction_names,
                               DFL_RFUNC_CORRECTION_COUNT, DFL_RFUNC_CORR_GUARDED, &corr, err)))
        return st;
    s->corr = (dfl_rfunc_correction)corr;
    const bool has_v = dfl_cfg_has(cfg, sec, "vertices"), has_c = dfl_cfg_has(cfg, sec, "curve");
    if (has_v == has_c) {
        char w[600];
        /* both: name where the curve was given (the later addition, often a --set) */
        if (has_v) dfl_cfg_where(cfg, sec, "curve", w, sizeof w);
        else snprintf(w, sizeof w, "[%s]", sec);
        return dfl_err_set(err, DFL_E_INPUT,
                           "%s: kind = rfunc needs exactly one of 'vertices' (a polyline) or"
                           " 'curve' (a curve section), %s",
                           w, has_v ? "both are given" : "neither is given");
    }
    return has_v ? vertex_polyline(cfg, sec, s, err) : curve_polyline(cfg, sec, s, err);
}

dfl_status dfl_rfunc_spec_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_rfunc_field_spec *out,
                                   dfl_err *err)
{
    dfl_rfunc_field_spec s;
    memset(&s, 0, sizeof s);
    dfl_status st = read_spec(cfg, sec, &s, err);
    if (st != DFL_OK) dfl_rfunc_spec_free(&s); /* zeroes it */
    *out = s;
    return st;
}

dfl_status dfl_rfunc_field_from_spec(const dfl_cfg *cfg, const char *sec,
                                     const dfl_rfunc_field_spec *spec, dfl_field *out,
                                     dfl_err *err)
{
    dfl_status st = dfl_rfunc_join_check(spec->join, spec->p, err);
    if (st != DFL_OK) return dfl_cfg_err_at(cfg, sec, "p", st, err);
    dfl_rfield *r = NULL;
    st = dfl_rfield_new(spec->dim, spec->join, spec->p, &r, err);
    if (st != DFL_OK) return dfl_cfg_err_at(cfg, sec, "p", st, err);
    dfl_rfield_set_correction(r, spec->corr);
    st = dfl_rfield_add_polyline(r, spec->v, spec->n, spec->closed, spec->trim, err);
    if (st != DFL_OK) {
        dfl_rfield_free(r);
        return dfl_cfg_err_at(cfg, sec, spec->curve ? "curve" : "vertices", st, err);
    }
    st = dfl_rfield_finish(&r, out, err);
    if (st != DFL_OK) return dfl_cfg_err_at(cfg, sec, spec->curve ? "curve" : "vertices", st, err);
    return DFL_OK;
}

void dfl_rfunc_spec_free(dfl_rfunc_field_spec *spec)
{
    free(spec->v);
    dfl_bspline_free(&spec->bspline);
    dfl_polyline_free(&spec->pl);
    memset(spec, 0, sizeof *spec);
}

dfl_status dfl_rfunc_field_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out,
                                    dfl_err *err)
{
    dfl_rfunc_field_spec spec;
    dfl_status st = dfl_rfunc_spec_from_cfg(cfg, sec, &spec, err);
    if (st != DFL_OK) return st;
    st = dfl_rfunc_field_from_spec(cfg, sec, &spec, out, err);
    dfl_rfunc_spec_free(&spec);
    return st;
}

dfl_status dfl_rfunc_join_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_rfunc_join *join,
                                   dfl_err *err)
{
    int j;
    dfl_status st = dfl_cfg_enum_opt(cfg, sec, "join", dfl_rfunc_join_names,
                                     DFL_RFUNC_JOIN_COUNT, DFL_RFUNC_REQUIV, &j, err);
    if (st == DFL_OK) *join = (dfl_rfunc_join)j;
    return st;
}

dfl_status dfl_rfunc_join_p_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_rfunc_join *join,
                                     int *p, dfl_err *err)
{
    dfl_rfunc_join j;
    long pp;
    dfl_status st;
    if ((st = dfl_rfunc_join_from_cfg(cfg, sec, &j, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "p", 2, 1, DFL_RFUNC_P_MAX, &pp, err))) return st;
    if ((st = dfl_rfunc_join_check(j, (int)pp, err))) return dfl_cfg_err_at(cfg, sec, "p", st, err);
    *join = j;
    *p = (int)pp;
    return DFL_OK;
}

dfl_status dfl_rfunc_trim_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_rfunc_trim *trim,
                                   dfl_err *err)
{
    int t;
    dfl_status st = dfl_cfg_enum_opt(cfg, sec, "trim", dfl_rfunc_trim_names,
                                     DFL_RFUNC_TRIM_COUNT, DFL_RFUNC_TRIM_DISK, &t, err);
    if (st == DFL_OK) *trim = (dfl_rfunc_trim)t;
    return st;
}

dfl_status dfl_rfunc_tri_opts_from_cfg(const dfl_cfg *cfg, const char *sec, bool smooth_key,
                                       dfl_rfunc_tri_opts *out, dfl_err *err)
{
    int trim;
    double a;
    long k;
    bool smooth = false;
    dfl_status st;
    if ((st = dfl_cfg_enum_opt(cfg, sec, "tri_trim", dfl_rfunc_tri_trim_names,
                               DFL_RFUNC_TRI_TRIM_COUNT, DFL_RFUNC_TRI_CONDITIONAL, &trim, err)))
        return st;
    if ((st = dfl_cfg_double_opt(cfg, sec, "a", 0.2, 1e-12, 1e12, &a, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "k", 2, 2, 64, &k, err))) return st;
    if (smooth_key && (st = dfl_cfg_bool_opt(cfg, sec, "smooth", false, &smooth, err))) return st;
    dfl_rfunc_tri_opts o = dfl_rfunc_tri_defaults();
    o.trim = (dfl_rfunc_tri_trim)trim;
    o.a = a;
    o.k = (int)k;
    if (smooth_key) o.smooth = smooth;
    *out = o;
    return DFL_OK;
}
