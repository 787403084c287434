#include "bs04/vjoin.h"

#include <assert.h>
#include <math.h>
#include <string.h>

#include "core/vec.h"
#include "rfunc/rfield.h"
#include "geom/segdist.h"
#include "rfunc/exact_polyline.h"

/* "exact", then the trims' names in their order (parts = 1 + trim). */
#define PART_NAME_(code, name, smooth, strip) [1 + code] = name,
const char *const dfl_vjoin_part_names[DFL_VJOIN_NPARTS] = {
    [0] = "exact", DFL_RFUNC_TRIM_LIST(PART_NAME_)};
#undef PART_NAME_

/* The trim of a trimmed part kind (parts >= 1). */
static dfl_rfunc_trim trim_of(int parts)
{
    assert(parts >= 1 && parts < DFL_VJOIN_NPARTS);
    return (dfl_rfunc_trim)(parts - 1);
}

dfl_status dfl_vjoin_init(double alpha_deg, double length, int parts, dfl_vjoin *out,
                          dfl_err *err)
{
    if (!(alpha_deg > 0.0 && alpha_deg < 360.0))
        return dfl_err_set(err, DFL_E_INPUT,
                           "angle %g degrees: expected 0 < alpha < 360 (0 and 360 make the"
                           " segments overlap)",
                           alpha_deg);
    if (!(length > 0.0) || !isfinite(length))
        return dfl_err_set(err, DFL_E_INPUT, "segment length %g: expected a finite value > 0",
                           length);
    if (parts < 0 || parts >= DFL_VJOIN_NPARTS)
        return dfl_err_set(err, DFL_E_INPUT, "unknown part kind %d", parts);
    dfl_vjoin vj;
    memset(&vj, 0, sizeof vj);
    vj.parts = parts;
    vj.alpha_deg = alpha_deg;
    vj.alpha = alpha_deg == 180.0 ? DFL_PI : alpha_deg * (DFL_PI / 180.0);
    vj.length = length;
    /* exact multiples of 90 degrees give exact coordinates, so that the
     * hatched test of collinear segments is not spoiled by cos(pi) */
    double c = cos(vj.alpha), s = sin(vj.alpha);
    if (alpha_deg == 90.0) c = 0.0, s = 1.0;
    if (alpha_deg == 180.0) c = -1.0, s = 0.0;
    if (alpha_deg == 270.0) c = 0.0, s = -1.0;
    vj.e1[0] = 1.0;
    vj.e1[1] = 0.0;
    vj.e2[0] = c;
    vj.e2[1] = s;
    vj.v[0] = length;
    vj.v[1] = 0.0;
    vj.v[2] = 0.0;
    vj.v[3] = 0.0;
    vj.v[4] = length * c;
    vj.v[5] = length * s;
    if (parts > 0) {
        dfl_status st = dfl_rfunc_seg_init(2, vj.v, vj.v + 2, trim_of(parts), &vj.seg[0], err);
        if (st == DFL_OK)
            st = dfl_rfunc_seg_init(2, vj.v + 2, vj.v + 4, trim_of(parts), &vj.seg[1], err);
        if (st != DFL_OK) return st;
    }
    *out = vj;
    return DFL_OK;
}

dfl_status dfl_vjoin_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_vjoin *out, dfl_err *err)
{
    double alpha, length;
    int parts;
    dfl_status st = dfl_cfg_double(cfg, sec, "alpha", 0.0, 360.0, &alpha, err);
    if (st == DFL_OK) st = dfl_cfg_double_opt(cfg, sec, "length", 1.0, 0.0, 1e300, &length, err);
    if (st == DFL_OK)
        st = dfl_cfg_enum_opt(cfg, sec, "parts", dfl_vjoin_part_names, DFL_VJOIN_NPARTS, 0,
                              &parts, err);
    if (st != DFL_OK) return st;
    st = dfl_vjoin_init(alpha, length, parts, out, err);
    if (st != DFL_OK) {
        const char *key = !(alpha > 0.0 && alpha < 360.0) ? "alpha"
                          : !(length > 0.0)               ? "length"
                                                          : "parts";
        dfl_cfg_err_at(cfg, sec, key, st, err);
    }
    return st;
}

dfl_status dfl_vjoin_field(const dfl_vjoin *vj, dfl_rfunc_join join, int p, dfl_field *out,
                           dfl_err *err)
{
    return dfl_vjoin_field_corr(vj, join, DFL_RFUNC_CORR_GUARDED, p, out, err);
}

dfl_status dfl_vjoin_field_corr(const dfl_vjoin *vj, dfl_rfunc_join join,
                                dfl_rfunc_correction corr, int p, dfl_field *out, dfl_err *err)
{
    if (vj->parts == 0)
        return dfl_rfunc_exact_polyline_field_corr(2, vj->v, 3, join, corr, p, out, err);
    dfl_rfield *r = NULL;
    dfl_status st = dfl_rfield_new(2, join, p, &r, err);
    if (st != DFL_OK) return st;
    dfl_rfield_set_correction(r, corr);
    st = dfl_rfield_add_polyline(r, vj->v, 3, false, trim_of(vj->parts), err);
    if (st != DFL_OK) {
        dfl_rfield_free(r);
        return st;
    }
    return dfl_rfield_finish(&r, out, err);
}

void dfl_vjoin_parts(const dfl_vjoin *vj, const double *x, double *h, double *g)
{
    if (vj->parts == 0) {
        h[0] = dfl_segdist_eval(2, vj->v, vj->v + 2, x, g);
        h[1] = dfl_segdist_eval(2, vj->v + 2, vj->v + 4, x, g ? g + 2 : NULL);
    } else {
        h[0] = dfl_rfunc_seg_eval(&vj->seg[0], x, g);
        h[1] = dfl_rfunc_seg_eval(&vj->seg[1], x, g ? g + 2 : NULL);
    }
}

double dfl_vjoin_dist(const dfl_vjoin *vj, const double *x, double *g)
{
    double g1[2], g2[2];
    const double d1 = dfl_segdist_eval(2, vj->v, vj->v + 2, x, g ? g1 : NULL);
    const double d2 = dfl_segdist_eval(2, vj->v + 2, vj->v + 4, x, g ? g2 : NULL);
    if (g) memcpy(g, d1 <= d2 ? g1 : g2, sizeof g1);
    return fmin(d1, d2);
}

bool dfl_vjoin_hatched(const dfl_vjoin *vj, const double *x)
{
    /* O is the origin: (x - O) . e_i */
    return dfl_vecn_dot(2, x, vj->e1) <= 0.0 && dfl_vecn_dot(2, x, vj->e2) <= 0.0;
}

void dfl_vjoin_hatched_range(const dfl_vjoin *vj, double *t0, double *t1, int *nrays)
{
    /* directions t with cos t <= 0 and cos(t - alpha) <= 0 */
    if (vj->alpha <= DFL_PI) {
        *t0 = vj->alpha + 0.5 * DFL_PI;
        *t1 = 1.5 * DFL_PI;
    } else {
        *t0 = 0.5 * DFL_PI;
        *t1 = vj->alpha - 0.5 * DFL_PI;
    }
    if (*t1 < *t0) *t1 = *t0; /* rounding at alpha = pi */
    *nrays = *t1 - *t0 <= 1e-15 ? 2 : 1;
    assert(*t0 >= 0.0 && *t0 < 2.0 * DFL_PI);
}

double dfl_vjoin_bisector(const dfl_vjoin *vj)
{
    return vj->alpha <= DFL_PI ? 0.5 * vj->alpha : 0.5 * vj->alpha + DFL_PI;
}
