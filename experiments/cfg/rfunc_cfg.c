/* Config -> rfunc field.  The library reports degenerate geometry without
 * knowing where it came from; every such message is prefixed here with
 * file:line, [section] and key. */
#include "cfg/rfunc_cfg.h"

#include <ctype.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "cfg/curve_cfg.h"
#include "geom/polygonize.h"
#include "rfunc/rfield.h"

/* Polyline of the curve section named by [sec] curve, polygonized to eps.
 * *pts is malloc'ed; a closed curve (first point == last) drops the
 * repeated point and sets *closed. */
static dfl_status curve_polyline(const dfl_cfg *cfg, const char *sec, int *dim, double **pts,
                                 size_t *n, bool *closed, dfl_err *err)
{
    const char *csec, *kind;
    double eps;
    char w[600];
    dfl_status st;
    if ((st = dfl_cfg_string(cfg, sec, "curve", &csec, err))) return st;
    if ((st = dfl_cfg_double(cfg, sec, "eps", 1e-300, 1e300, &eps, err))) return st;
    if (dfl_cfg_has(cfg, sec, "closed"))
        return dfl_err_set(err, DFL_E_INPUT,
                           "%s: closed applies to vertices only (a curve's closedness comes"
                           " from the curve)",
                           dfl_cfg_where(cfg, sec, "closed", w, sizeof w));
    if (!dfl_cfg_has_section(cfg, csec))
        return dfl_err_set(err, DFL_E_INPUT, "%s: no section [%s]",
                           dfl_cfg_where(cfg, sec, "curve", w, sizeof w), csec);
    if ((st = dfl_cfg_string(cfg, csec, "kind", &kind, err))) return st;
    if (strcmp(kind, "bspline_curve") != 0)
        return dfl_err_set(err, DFL_E_INPUT,
                           "%s: expected a curve (kind = bspline_curve), section [%s] has"
                           " kind = %s",
                           dfl_cfg_where(cfg, sec, "curve", w, sizeof w), csec, kind);
    dfl_bspline c;
    if ((st = dfl_curve_from_cfg(cfg, csec, &c, err))) return st;
    dfl_polyline pl;
    memset(&pl, 0, sizeof pl);
    st = dfl_polygonize_curve(&c, eps, 0, &pl, err);
    dfl_bspline_free(&c);
    if (st != DFL_OK) return dfl_cfg_err_at(cfg, sec, "eps", st, err);
    size_t np = pl.n;
    *closed = false;
    if (np >= 4 && memcmp(pl.pts, pl.pts + (np - 1) * (size_t)pl.dim,
                          (size_t)pl.dim * sizeof *pl.pts) == 0) {
        *closed = true;
        np--;
    }
    *pts = malloc(np * (size_t)pl.dim * sizeof **pts);
    if (!*pts) {
        dfl_polyline_free(&pl);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    }
    memcpy(*pts, pl.pts, np * (size_t)pl.dim * sizeof **pts);
    *dim = pl.dim;
    *n = np;
    dfl_polyline_free(&pl);
    return DFL_OK;
}

dfl_status dfl_rfunc_field_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out,
                                    dfl_err *err)
{
    static const char *const joins[] = {"requiv", "rconj", "requiv_corrected"};
    static const char *const trims[] = {"disk", "disk_smooth", "strip", "strip_smooth"};
    char w[600];
    dfl_status st;
    int join, trim;
    long p;
    if ((st = dfl_cfg_enum_opt(cfg, sec, "join", joins, 3, 0, &join, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "p", 2, 1, DFL_RFUNC_P_MAX, &p, err))) return st;
    if ((st = dfl_cfg_enum_opt(cfg, sec, "trim", trims, 4, 0, &trim, err))) return st;
    if ((st = dfl_rfunc_join_check((dfl_rfunc_join)join, (int)p, err)))
        return dfl_cfg_err_at(cfg, sec, "p", st, err);

    const bool has_v = dfl_cfg_has(cfg, sec, "vertices"), has_c = dfl_cfg_has(cfg, sec, "curve");
    if (has_v == has_c)
        return dfl_err_set(err, DFL_E_INPUT,
                           "[%s]: kind = rfunc needs exactly one of 'vertices' (a polyline) or"
                           " 'curve' (a curve section), %s",
                           sec, has_v ? "both are given" : "neither is given");
    double *pts = NULL;
    size_t n = 0;
    int dim = 0;
    bool closed = false;
    const char *key = has_v ? "vertices" : "curve";
    if (has_v) {
        const char *raw;
        if ((st = dfl_cfg_bool_opt(cfg, sec, "closed", false, &closed, err))) return st;
        if ((st = dfl_cfg_string(cfg, sec, "vertices", &raw, err))) return st;
        dim = dfl_cfg_point_dim(raw);
        if (dim != 2 && dim != 3)
            return dfl_err_set(err, DFL_E_INPUT,
                               "%s: expected vertices of 2 or 3 numbers, the first has %d",
                               dfl_cfg_where(cfg, sec, "vertices", w, sizeof w), dim);
        if ((st = dfl_cfg_points(cfg, sec, "vertices", dim, closed ? 3 : 2, &pts, &n, err)))
            return st;
    } else {
        if ((st = curve_polyline(cfg, sec, &dim, &pts, &n, &closed, err))) return st;
    }
    st = dfl_rfield_polyline(dim, pts, n, closed, (dfl_rfunc_join)join, (int)p,
                             (dfl_rfunc_trim)trim, out, err);
    free(pts);
    if (st != DFL_OK) return dfl_cfg_err_at(cfg, sec, key, st, err);
    return DFL_OK;
}
