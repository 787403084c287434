/* Rays and 1D searches along a planar curve (see curveprobe.h).
 *
 * Every search evaluates the field in batches of points along one ray or one
 * parameter interval, so the field's dispatch happens once per batch; the
 * batches live on the stack of the thread that owns the ray. */
#include "field/curveprobe.h"

#include "core/vec.h"

#include <assert.h>
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#define ARC_CHORDS 64   /* chords per knot span in the arc-length table */
#define SUB 16          /* subdivision factor of every refinement round */
#define VALID_CHUNK 256 /* rays per batch in dfl_curveprobe_valid */
#define MAX_SAMPLES 1024

void dfl_curveprobe_free(dfl_rayset *rs)
{
    if (!rs) return;
    free(rs->o);
    free(rs->v);
    free(rs->t);
    free(rs->kappa);
    free(rs->side);
    free(rs->kind);
    memset(rs, 0, sizeof *rs);
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static const double gx[3] = {-0.77459666924148338, 0.0, 0.77459666924148338};
static const double gw[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};

/* Arc length of c between t0 and t1 (one polynomial piece) by 3-point
 * Gauss-Legendre on the speed: error O(h^6). */
static double arc_gauss(const dfl_bspline *c, double t0, double t1)
{
    const double hw = 0.5 * (t1 - t0), mid = 0.5 * (t1 + t0);
    double len = 0.0;
    for (int g = 0; g < 3; g++) {
        double d[4];
        dfl_bspline_eval_side(c, mid + hw * gx[g], 1, 1, d);
        len += gw[g] * hw * hypot(d[2], d[3]);
    }
    return len;
}

/* Position, unit tangent and signed curvature at t (left-sided at t1). */
static int frame_at(const dfl_bspline *c, double t, double *P, double *T, double *kappa)
{
    double d[6];
    dfl_bspline_eval(c, t, 2, d);
    const double sp = hypot(d[2], d[3]);
    if (!(sp > 0.0) || !isfinite(sp)) return 0;
    P[0] = d[0], P[1] = d[1];
    T[0] = d[2] / sp, T[1] = d[3] / sp;
    /* curvature.h's kappa for n = (T_y, -T_x): dn/ds = kappa T, i.e.
     * dT/ds = kappa N with N = (-T_y, T_x) */
    *kappa = (d[2] * d[5] - d[3] * d[4]) / (sp * sp * sp);
    return 1;
}

static void put_ray(dfl_rayset *rs, size_t k, const double *P, const double *v, double t,
                    double kappa, int side, int kind)
{
    rs->o[2 * k] = P[0], rs->o[2 * k + 1] = P[1];
    rs->v[2 * k] = v[0], rs->v[2 * k + 1] = v[1];
    rs->t[k] = t;
    rs->kappa[k] = kappa;
    rs->side[k] = side;
    rs->kind[k] = kind;
}

/* The rays +N (side +1) and -N (side -1) of the given kind at parameter t,
 * as rays *k and *k + 1 (advancing *k); DFL_E_INPUT at a zero tangent. */
static dfl_status put_normal_pair(dfl_rayset *rs, size_t *k, const dfl_bspline *c, double t,
                                  int kind, dfl_err *err)
{
    double P[2], T[2], kap;
    if (!frame_at(c, t, P, T, &kap))
        return dfl_err_set(err, DFL_E_INPUT, "rays: zero tangent at t = %g", t);
    const double N[2] = {-T[1], T[0]}, mN[2] = {T[1], -T[0]};
    put_ray(rs, (*k)++, P, N, t, kap, 1, kind);
    put_ray(rs, (*k)++, P, mN, t, kap, -1, kind);
    return DFL_OK;
}

dfl_status dfl_curveprobe_rays(const dfl_bspline *c, size_t nside, size_t ncap,
                               const double *joint_t, size_t njoint, dfl_rayset *out,
                               dfl_err *err)
{
    memset(out, 0, sizeof *out);
    if (!c || c->dim != 2) return dfl_err_set(err, DFL_E_INPUT, "rays: a planar curve is required");
    if (nside < 2) return dfl_err_set(err, DFL_E_INPUT, "rays: expected >= 2 origins, got %zu", nside);
    if (njoint > 0 && !joint_t)
        return dfl_err_set(err, DFL_E_INPUT, "rays: joint parameters missing");
    const int open = !c->closed;
    const size_t ncaps = open ? ncap : 0;
    const size_t n = 2 * nside + 2 * ncaps + 2 * njoint;
    const size_t nspan = dfl_bspline_span_count(c);
    const size_t ntab = nspan * ARC_CHORDS + 1;
    double *tt = malloc(ntab * sizeof *tt), *ss = malloc(ntab * sizeof *ss);
    double *ak = malloc(2 * nside * sizeof *ak);
    out->o = malloc(2 * n * sizeof *out->o);
    out->v = malloc(2 * n * sizeof *out->v);
    out->t = malloc(n * sizeof *out->t);
    out->kappa = malloc(n * sizeof *out->kappa);
    out->side = malloc(n * sizeof *out->side);
    out->kind = malloc(n * sizeof *out->kind);
    dfl_status st = DFL_OK;
    if (!tt || !ss || !ak || !out->o || !out->v || !out->t || !out->kappa || !out->side ||
        !out->kind) {
        st = dfl_err_set(err, DFL_E_NOMEM, "rays: out of memory for %zu rays", n);
        goto done;
    }
    /* arc-length table: ARC_CHORDS intervals per non-empty span (each
     * inside one polynomial piece), integrated by arc_gauss */
    size_t m = 0;
    for (size_t s = 0; s < nspan; s++) {
        const size_t j = dfl_bspline_span_index(c, s);
        const double a = c->knots[j], b = c->knots[j + 1];
        for (int i = s ? 1 : 0; i <= ARC_CHORDS; i++) {
            const double t = i == ARC_CHORDS ? b : a + (b - a) * i / ARC_CHORDS;
            tt[m] = t;
            ss[m] = m ? ss[m - 1] + arc_gauss(c, tt[m - 1], t) : 0.0;
            m++;
        }
    }
    assert(m == ntab);
    const double L = ss[m - 1];
    if (!(L > 0.0)) {
        st = dfl_err_set(err, DFL_E_INPUT, "rays: the curve has zero length");
        goto done;
    }
    size_t k = 0, lo = 0;
    for (size_t i = 0; i < nside; i++) {
        const double target = L * (double)i / (double)(nside - 1);
        while (lo + 2 < m && ss[lo + 1] < target) lo++;
        const double ds = ss[lo + 1] - ss[lo];
        double w = ds > 0 ? (target - ss[lo]) / ds : 0.0;
        w = w < 0 ? 0 : w > 1 ? 1 : w;
        double t = i == nside - 1 ? c->t1 : tt[lo] + w * (tt[lo + 1] - tt[lo]);
        if (i == 0) t = c->t0;
        /* Newton on arc(tt[lo], t) = target - ss[lo] inside the interval */
        for (int it = 0; it < 3 && i > 0 && i < nside - 1; it++) {
            double d[4];
            dfl_bspline_eval_side(c, t, 1, 1, d);
            const double sp = hypot(d[2], d[3]);
            if (!(sp > 0.0)) break;
            t -= (ss[lo] + arc_gauss(c, tt[lo], t) - target) / sp;
            t = t < tt[lo] ? tt[lo] : t > tt[lo + 1] ? tt[lo + 1] : t;
        }
        if ((st = put_normal_pair(out, &k, c, t, DFL_RAY_SIDE, err)) != DFL_OK) goto done;
    }
    for (int e = 0; e < 2 && ncaps > 0; e++) {
        const double t = e ? c->t1 : c->t0;
        double P[2], T[2], kap;
        if (!frame_at(c, t, P, T, &kap)) {
            st = dfl_err_set(err, DFL_E_INPUT, "rays: zero tangent at t = %g", t);
            goto done;
        }
        const double N[2] = {-T[1], T[0]};
        const double To[2] = {e ? T[0] : -T[0], e ? T[1] : -T[1]};
        for (size_t j = 1; j <= ncaps; j++) {
            const double th = DFL_PI * (double)j / (double)(ncaps + 1);
            const double v[2] = {cos(th) * N[0] + sin(th) * To[0], cos(th) * N[1] + sin(th) * To[1]};
            put_ray(out, k++, P, v, t, kap, 0, DFL_RAY_CAP);
        }
    }
    for (size_t j = 0; j < njoint; j++) {
        const double t = dfl_bspline_wrap(c, joint_t[j]);
        if ((st = put_normal_pair(out, &k, c, t, DFL_RAY_JOINT, err)) != DFL_OK) goto done;
    }
    assert(k == n);
    out->n = n;
    /* curvature tertiles over the SIDE rays (each origin counted twice,
     * which leaves the quantiles unchanged) */
    for (size_t i = 0; i < 2 * nside; i++) ak[i] = fabs(out->kappa[i]);
    qsort(ak, 2 * nside, sizeof *ak, cmp_double);
    out->kflat = ak[(2 * nside - 1) / 3];
    out->kcurved = ak[2 * (2 * nside - 1) / 3];
done:
    free(tt);
    free(ss);
    free(ak);
    if (st != DFL_OK) dfl_curveprobe_free(out);
    return st;
}

/* exact(o_k + s_k v_k) >= s_k (1 - tol), in batches; s == NULL means
 * s_k = level for every ray. */
static dfl_status branch_test(const dfl_field *exact, const dfl_rayset *rs, double level,
                              const double *s, double tol, int threads, int *ok, dfl_err *err)
{
    if (!exact || exact->dim != 2)
        return dfl_err_set(err, DFL_E_INPUT, "rays: the exact field must be 2D");
    if (!(tol >= 0.0 && tol < 1.0))
        return dfl_err_set(err, DFL_E_INPUT, "rays: bad tolerance %g", tol);
    const size_t nchunk = (rs->n + VALID_CHUNK - 1) / VALID_CHUNK;
#pragma omp parallel for schedule(dynamic) num_threads(threads > 0 ? threads : omp_get_max_threads())
    for (size_t ch = 0; ch < nchunk; ch++) {
        double pts[2 * VALID_CHUNK], val[VALID_CHUNK];
        const size_t k0 = ch * VALID_CHUNK;
        const size_t cnt = rs->n - k0 < VALID_CHUNK ? rs->n - k0 : VALID_CHUNK;
        for (size_t i = 0; i < cnt; i++) {
            const double sk = s ? s[k0 + i] : level;
            for (int j = 0; j < 2; j++)
                pts[2 * i + j] = rs->o[2 * (k0 + i) + j] + (isnan(sk) ? 0.0 : sk) * rs->v[2 * (k0 + i) + j];
        }
        exact->ops->eval(exact->ctx, cnt, pts, val, NULL);
        for (size_t i = 0; i < cnt; i++) {
            const double sk = s ? s[k0 + i] : level;
            ok[k0 + i] = !isnan(sk) && val[i] >= sk * (1.0 - tol);
        }
    }
    return DFL_OK;
}

dfl_status dfl_curveprobe_valid(const dfl_field *exact, const dfl_rayset *rs, double level,
                                double tol, int threads, int *valid, dfl_err *err)
{
    if (!(level > 0.0) || !isfinite(level))
        return dfl_err_set(err, DFL_E_INPUT, "rays: bad level %g", level);
    return branch_test(exact, rs, level, NULL, tol, threads, valid, err);
}

dfl_status dfl_curveprobe_on_branch(const dfl_field *exact, const dfl_rayset *rs, const double *s,
                                    double tol, int threads, int *ok, dfl_err *err)
{
    return branch_test(exact, rs, 0.0, s, tol, threads, ok, err);
}

dfl_status dfl_curveprobe_cross(const dfl_field *u, const dfl_rayset *rs, double level,
                                const dfl_cross_opts *opt, int threads, double *s, dfl_err *err)
{
    if (!u || u->dim != 2) return dfl_err_set(err, DFL_E_INPUT, "rays: the field must be 2D");
    if (!(opt->smax > 0.0) || !isfinite(opt->smax) || opt->steps < 1 ||
        opt->steps > DFL_CROSS_MAX_STEPS || opt->rounds < 0 || opt->rounds > 40 ||
        !isfinite(level))
        return dfl_err_set(err, DFL_E_INPUT,
                           "rays: bad search (level %g, smax %g, steps %d, rounds %d)", level,
                           opt->smax, opt->steps, opt->rounds);
    const int steps = opt->steps;
#pragma omp parallel for schedule(dynamic, 8) num_threads(threads > 0 ? threads : omp_get_max_threads())
    for (size_t k = 0; k < rs->n; k++) {
        double pts[2 * (DFL_CROSS_MAX_STEPS + 1)], val[DFL_CROSS_MAX_STEPS + 1];
        const double *o = rs->o + 2 * k, *v = rs->v + 2 * k;
        for (int i = 0; i <= steps; i++) {
            const double si = opt->smax * i / steps;
            pts[2 * i] = o[0] + si * v[0];
            pts[2 * i + 1] = o[1] + si * v[1];
        }
        u->ops->eval(u->ctx, (size_t)steps + 1, pts, val, NULL);
        if (val[0] >= level) {
            s[k] = 0.0;
            continue;
        }
        int i = 1;
        while (i <= steps && !(val[i] >= level)) i++;
        if (i > steps) {
            s[k] = NAN;
            continue;
        }
        double a = opt->smax * (i - 1) / steps, fa = val[i - 1];
        double b = opt->smax * i / steps, fb = val[i];
        for (int r = 0; r < opt->rounds; r++) {
            for (int j = 1; j < SUB; j++) {
                const double sj = a + (b - a) * j / SUB;
                pts[2 * (j - 1)] = o[0] + sj * v[0];
                pts[2 * (j - 1) + 1] = o[1] + sj * v[1];
            }
            u->ops->eval(u->ctx, SUB - 1, pts, val, NULL);
            int j = 0;
            while (j < SUB - 1 && !(val[j] >= level)) j++;
            /* sub-sample j (point j+1 of the bracket) is the first one up */
            const double na = j == 0 ? a : a + (b - a) * j / SUB;
            const double nfa = j == 0 ? fa : val[j - 1];
            if (j < SUB - 1) {
                b = a + (b - a) * (j + 1) / SUB;
                fb = val[j];
            }
            a = na, fa = nfa;
        }
        double w = (isfinite(fa) && fb > fa) ? (level - fa) / (fb - fa) : 1.0;
        w = w < 0 ? 0 : w > 1 ? 1 : w;
        s[k] = a + w * (b - a);
    }
    return DFL_OK;
}

static void mean_add(double *sum, size_t *cnt, double r)
{
    *sum += r;
    (*cnt)++;
}

void dfl_curveprobe_stats(const dfl_rayset *rs, const double *s, const int *valid,
                          const int *branch, double level, dfl_ray_stats *out)
{
    memset(out, 0, sizeof *out);
    out->max = out->joint_max = out->side_max = out->cap_max = -INFINITY;
    out->min = INFINITY;
    out->argmax = (size_t)-1;
    double sum = 0, sflat = 0, scurv = 0, souter = 0, sinner = 0;
    size_t cnt = 0, nflat = 0, ncurv = 0, nouter = 0, ninner = 0;
    for (size_t k = 0; k < rs->n; k++) {
        if (valid && !valid[k]) continue;
        out->valid++;
        if (isnan(s[k])) {
            out->unresolved++;
            continue;
        }
        if (branch && !branch[k]) {
            out->beyond++;
            continue;
        }
        const double r = (s[k] - level) / level;
        if (r > out->max) out->max = r, out->argmax = k;
        if (r < out->min) out->min = r;
        mean_add(&sum, &cnt, r);
        if (rs->kind[k] == DFL_RAY_JOINT && r > out->joint_max) out->joint_max = r;
        if (rs->kind[k] == DFL_RAY_CAP && r > out->cap_max) out->cap_max = r;
        if (rs->kind[k] != DFL_RAY_SIDE) continue;
        if (r > out->side_max) out->side_max = r;
        const double ak = fabs(rs->kappa[k]);
        if (ak <= rs->kflat) mean_add(&sflat, &nflat, r);
        if (ak > rs->kcurved) {
            mean_add(&scurv, &ncurv, r);
            /* v = side N points to the centre of curvature iff kappa side > 0 */
            if (rs->kappa[k] * rs->side[k] > 0) mean_add(&sinner, &ninner, r);
            else mean_add(&souter, &nouter, r);
        }
    }
    out->mean = cnt ? sum / (double)cnt : NAN;
    out->merged = out->valid ? (double)(out->unresolved + out->beyond) / (double)out->valid : NAN;
    out->flat_mean = nflat ? sflat / (double)nflat : NAN;
    out->curved_mean = ncurv ? scurv / (double)ncurv : NAN;
    out->outer_mean = nouter ? souter / (double)nouter : NAN;
    out->inner_mean = ninner ? sinner / (double)ninner : NAN;
    if (!cnt) out->max = out->min = NAN;
    if (out->joint_max == -INFINITY) out->joint_max = NAN;
    if (out->side_max == -INFINITY) out->side_max = NAN;
    if (out->cap_max == -INFINITY) out->cap_max = NAN;
}

/* |u| at m curve parameters tp (positions into pts); best index. */
static int best_of(const dfl_field *u, const dfl_bspline *c, int m, const double *tp,
                   double *pts, double *val)
{
    for (int i = 0; i < m; i++) {
        double P[3];
        dfl_bspline_eval(c, tp[i], 0, P);
        pts[2 * i] = P[0], pts[2 * i + 1] = P[1];
    }
    u->ops->eval(u->ctx, (size_t)m, pts, val, NULL);
    int b = 0;
    for (int i = 1; i < m; i++)
        if (fabs(val[i]) > fabs(val[b]) || isnan(val[i])) b = i;
    return b;
}

dfl_status dfl_curveprobe_max(const dfl_field *u, const dfl_bspline *c, const double *t,
                              size_t n, int samples, int rounds, int threads, double *max,
                              double *tmax, dfl_err *err)
{
    if (!u || u->dim != 2 || c->dim != 2)
        return dfl_err_set(err, DFL_E_INPUT, "curve max: a 2D field and curve are required");
    if (n < 2 || samples < 2 || samples > MAX_SAMPLES || rounds < 0 || rounds > 40)
        return dfl_err_set(err, DFL_E_INPUT,
                           "curve max: bad arguments (%zu parameters, %d samples, %d rounds)", n,
                           samples, rounds);
    for (size_t i = 0; i + 1 < n; i++)
        if (!(t[i + 1] > t[i]))
            return dfl_err_set(err, DFL_E_INPUT, "curve max: parameters must increase");
    double *bv = malloc((n - 1) * sizeof *bv), *bt = malloc((n - 1) * sizeof *bt);
    if (!bv || !bt) {
        free(bv);
        free(bt);
        return dfl_err_set(err, DFL_E_NOMEM, "curve max: out of memory");
    }
#pragma omp parallel for schedule(dynamic) num_threads(threads > 0 ? threads : omp_get_max_threads())
    for (size_t i = 0; i < n - 1; i++) {
        double tp[MAX_SAMPLES + 1], pts[2 * (MAX_SAMPLES + 1)], val[MAX_SAMPLES + 1];
        const double a = t[i], b = t[i + 1];
        for (int j = 0; j <= samples; j++) tp[j] = j == samples ? b : a + (b - a) * j / samples;
        int j = best_of(u, c, samples + 1, tp, pts, val);
        double best = fabs(val[j]), tb = tp[j];
        double lo = tp[j > 0 ? j - 1 : 0], hi = tp[j < samples ? j + 1 : samples];
        for (int r = 0; r < rounds; r++) {
            for (int q = 0; q <= SUB; q++) tp[q] = q == SUB ? hi : lo + (hi - lo) * q / SUB;
            const int q = best_of(u, c, SUB + 1, tp, pts, val);
            if (fabs(val[q]) > best || isnan(val[q])) best = fabs(val[q]), tb = tp[q];
            const double h = (hi - lo) / SUB;
            lo = tb - h > lo ? tb - h : lo;
            hi = tb + h < hi ? tb + h : hi;
        }
        bv[i] = best, bt[i] = tb;
    }
    size_t ib = 0;
    for (size_t i = 1; i + 1 < n; i++)
        if (bv[i] > bv[ib] || isnan(bv[i])) ib = i;
    *max = bv[ib];
    if (tmax) *tmax = bt[ib];
    free(bv);
    free(bt);
    return DFL_OK;
}
