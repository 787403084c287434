/* bs04 study 3: gradient bounds at the joining point of two segments
 * (Fig. 4-5, eq. 13-14).
 *
 * Two segments of length L meet at the vertex O at the angle alpha
 * (vjoin.h); their fields (exact distances or a library trim) are joined by
 * R-equivalence (eq. 6) or, as an extension, R-conjunction (eq. 7).  On
 * circles of radius r around O, |grad u| of the joined field is measured
 * at `samples` directions and compared with
 *   the paper's band (eq. 13 with eq. 14):  |F1 - F2| <= |grad u| <= F1 + F2
 *     at phi = atan2(h2, h1) of each point;
 *   the same band widened by the parts' own normalization defect at that
 *     point, |F1 g1 - F2 g2| <= |grad u| <= F1 g1 + F2 g2 (g_i = |grad h_i|;
 *     the triangle inequality, exact for any parts; it is the paper's band
 *     for exact distances, and trimmed parts have g_i = 1 + O(r / L)).
 * The minimum is located (coarse scan + golden section) and compared with
 * the bisector of the convex sector and with the closed-form minimum of
 * gradbound.h (exact parts: exact at every r < L; trims: the r -> 0 limit).
 *
 * Keys ([study]):
 *   alpha    = 90         degrees in (0, 360) (sweep)
 *   length   = 1          segment length L
 *   parts    = exact      exact | disk | disk_smooth | strip | strip_smooth
 *   join     = requiv     requiv | rconj
 *   p        = 2          join order (rconj: >= 2)
 *   radii    = 1e-3 1e-2  circle radii relative to L (each in (0, 0.5]); one row each
 *   samples  = 3600       directions per circle, theta_k = 2 pi (k + 1/2) / samples
 *   fd_rel   = 1e-5       central-difference step relative to r for the
 *                         finite-difference cross-check of |grad u|
 *   profile_alpha = ...   optional: angles (degrees) whose circle profiles
 *                         are written to profile<tag>.csv
 *   profile_samples = 360 directions per radius in a profile (divides samples)
 *   fig5_p   = 2 7 12     orders of the Fig. 5 table (written at sweep point 0)
 *   fig5_nphi = 91        phi values in [0, 90] degrees in that table
 * Rows (one per radius): alpha, p, join, parts, r_rel, r, samples, on_set
 * (samples on a segment, skipped), grad_min / grad_max (measured; the
 * minimum refined by golden section), theta_min_deg, bisector_deg,
 * theta_min_err_deg, min_on_bisector (error < 1e-3 degrees), grad_bisector
 * (measured there), grad_bisector_theory, grad_min_theory and
 * min_regime_theory (bisector | mixed; gradbound.h), lower_min / upper_max
 * (the paper's band at the samples), violations (widened band),
 * violations_paper (unwidened), excess_paper_max, part_gdef_max (max
 * ||grad h_i| - 1|), fd_maxdiff (max ||grad u| - central differences|),
 * sum_min_phi_deg, sum_min, diff_at_45 (eq. 14 at this join and p).
 * Files: fig5_bounds.csv (join, p, phi_deg, F1, F2, lower, upper; written at
 * sweep point 0), fig5_claims.csv (join, p, sum_min_phi_deg, sum_min,
 * sum_min_theory, diff_at_45, sum_max, diff_max, sum_at_0, sum_at_90),
 * profile<tag>.csv (r_rel, theta_deg, phi_deg, h1, h2, grad_norm, lower,
 * upper, lower_parts, upper_parts, hatched).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/vec.h"
#include "harness/experiment.h"
#include "cfg/field_cost.h"
#include "rfunc/gradbound.h"
#include "bs04/vjoin.h"

static const double DEG = 180.0 / DFL_PI;
/* Rounding allowance of the band tests: F_i (pow) and |grad u| (the
 * field's own arithmetic) each carry a few ulps. */
static const double BAND_TOL = 1e-12;

/* eq. 13-14 have two arguments: the study offers the first two joins of
 * rfunc/join.h's list (requiv, rconj) under their names there. */
#define GB_NJOINS 2
_Static_assert(DFL_RFUNC_REQUIV == 0 && DFL_RFUNC_RCONJ == 1, "requiv, rconj lead the join list");
static const char *const *const join_names = dfl_rfunc_join_names;
static dfl_rfunc_join join_of(int j) { return (dfl_rfunc_join)j; }

typedef struct gb_keys {
    dfl_vjoin vj;
    double alpha_deg;
    long p;
    int join;                /* index into join_names */
    double *radii;
    size_t nradii;
    long samples;
    double fd_rel;
    double *profile_alpha;
    size_t nprofile;
    long profile_samples;
    double *fig5_p;
    size_t nfig5;
    long fig5_nphi;
} gb_keys;

static void keys_free(gb_keys *k)
{
    free(k->radii);
    free(k->profile_alpha);
    free(k->fig5_p);
}

static dfl_status read_keys(const dfl_cfg *cfg, gb_keys *k, dfl_err *err)
{
    dfl_status st;
    memset(k, 0, sizeof *k);
    if ((st = dfl_vjoin_from_cfg(cfg, "study", &k->vj, err))) return st;
    k->alpha_deg = k->vj.alpha_deg;
    if ((st = dfl_cfg_enum_opt(cfg, "study", "join", join_names, GB_NJOINS, 0, &k->join, err)))
        return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "p", 2, 1, DFL_RFUNC_P_MAX, &k->p, err))) return st;
    if ((st = dfl_gradbound_check(join_of(k->join), (int)k->p, err)))
        return dfl_cfg_err_at(cfg, "study", "p", st, err);
    if ((st = dfl_cfg_doubles(cfg, "study", "radii", 1, &k->radii, &k->nradii, err))) return st;
    for (size_t i = 0; i < k->nradii; i++)
        if (!(k->radii[i] > 0.0 && k->radii[i] <= 0.5))
            return dfl_cfg_reject(cfg, "study", "radii", err,
                                  "radius %g (relative to the length): expected (0, 0.5]",
                                  k->radii[i]);
    if ((st = dfl_cfg_int_opt(cfg, "study", "samples", 3600, 8, 10000000, &k->samples, err)))
        return st;
    if ((st = dfl_cfg_double_opt(cfg, "study", "fd_rel", 1e-5, 1e-9, 1e-2, &k->fd_rel, err)))
        return st;
    if (dfl_cfg_has(cfg, "study", "profile_alpha")) {
        if ((st = dfl_cfg_doubles(cfg, "study", "profile_alpha", 0, &k->profile_alpha,
                                  &k->nprofile, err)))
            return st;
    }
    if ((st = dfl_cfg_int_opt(cfg, "study", "profile_samples", 360, 2, 10000000,
                              &k->profile_samples, err)))
        return st;
    if (k->samples % k->profile_samples != 0)
        return dfl_cfg_reject(cfg, "study", "profile_samples", err,
                              "%ld does not divide samples = %ld", k->profile_samples, k->samples);
    if ((st = dfl_cfg_doubles(cfg, "study", "fig5_p", 1, &k->fig5_p, &k->nfig5, err))) return st;
    for (size_t i = 0; i < k->nfig5; i++)
        if (!(k->fig5_p[i] >= 2 && k->fig5_p[i] <= DFL_RFUNC_P_MAX) ||
            k->fig5_p[i] != floor(k->fig5_p[i]))
            return dfl_cfg_reject(cfg, "study", "fig5_p", err,
                                  "order %g: expected integers in [2, %d] (the table has"
                                  " R-conjunction too)", k->fig5_p[i], DFL_RFUNC_P_MAX);
    if ((st = dfl_cfg_int_opt(cfg, "study", "fig5_nphi", 91, 2, 100000, &k->fig5_nphi, err)))
        return st;
    return DFL_OK;
}

/* Fig. 5: the bounds vs phi, and the paper's claims about them. */
static dfl_status write_fig5(const dfl_study_ctx *ctx, const gb_keys *k, dfl_err *err)
{
    dfl_table *tb = dfl_table_new(), *tc = dfl_table_new();
    dfl_status st = tb && tc ? DFL_OK : dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    for (int j = 0; j < GB_NJOINS && st == DFL_OK; j++)
        for (size_t i = 0; i < k->nfig5 && st == DFL_OK; i++) {
            const int p = (int)k->fig5_p[i];
            for (long m = 0; m < k->fig5_nphi && st == DFL_OK; m++) {
                const double phi_deg = 90.0 * (double)m / (double)(k->fig5_nphi - 1);
                double F1, F2, lo, hi;
                dfl_gradbound_partials(join_of(j), p, phi_deg / DEG, &F1, &F2);
                dfl_gradbound_band(F1, F2, 1.0, 1.0, &lo, &hi);
                st = dfl_table_row(tb, err);
                if (!st) st = dfl_table_set_string(tb, "join", join_names[j], err);
                if (!st) st = dfl_table_set_int(tb, "p", p, err);
                if (!st) st = dfl_table_set_double(tb, "phi_deg", phi_deg, err);
                if (!st) st = dfl_table_set_double(tb, "F1", F1, err);
                if (!st) st = dfl_table_set_double(tb, "F2", F2, err);
                if (!st) st = dfl_table_set_double(tb, "lower", lo, err);
                if (!st) st = dfl_table_set_double(tb, "upper", hi, err);
            }
            double phi_min, smax, dmax, F1, F2, S0a, S0b, S9a, S9b;
            const double smin = dfl_gradbound_sum_min(join_of(j), p, &phi_min, &smax, &dmax);
            dfl_gradbound_partials(join_of(j), p, 0.25 * DFL_PI, &F1, &F2);
            dfl_gradbound_partials(join_of(j), p, 0.0, &S0a, &S0b);
            dfl_gradbound_partials(join_of(j), p, 0.5 * DFL_PI, &S9a, &S9b);
            if (!st) st = dfl_table_row(tc, err);
            if (!st) st = dfl_table_set_string(tc, "join", join_names[j], err);
            if (!st) st = dfl_table_set_int(tc, "p", p, err);
            if (!st) st = dfl_table_set_double(tc, "sum_min_phi_deg", phi_min * DEG, err);
            if (!st) st = dfl_table_set_double(tc, "sum_min", smin, err);
            if (!st)
                st = dfl_table_set_double(tc, "sum_min_theory",
                                          j == 0 ? pow(2.0, -1.0 / p) : 2.0 - pow(2.0, 1.0 / p),
                                          err);
            if (!st) st = dfl_table_set_double(tc, "diff_at_45", F1 - F2, err);
            if (!st) st = dfl_table_set_double(tc, "sum_max", smax, err);
            if (!st) st = dfl_table_set_double(tc, "diff_max", dmax, err);
            if (!st) st = dfl_table_set_double(tc, "sum_at_0", S0a + S0b, err);
            if (!st) st = dfl_table_set_double(tc, "sum_at_90", S9a + S9b, err);
        }
    /* one file for the whole sweep: no tag */
    dfl_study_ctx c0 = *ctx;
    c0.tag = "";
    char path[4096];
    if (st == DFL_OK)
        st = dfl_table_write_csv(tb, dfl_study_path(&c0, "fig5_bounds", "csv", path, sizeof path),
                                 err);
    if (st == DFL_OK)
        st = dfl_table_write_csv(tc, dfl_study_path(&c0, "fig5_claims", "csv", path, sizeof path),
                                 err);
    dfl_table_free(tb);
    dfl_table_free(tc);
    return st;
}

/* |grad u| at direction theta on the circle of radius r (slow path). */
typedef struct circ {
    const dfl_field *f;
    double r;
} circ;

static double circ_grad(void *ctx, double theta)
{
    const circ *c = ctx;
    const double x[2] = {c->r * cos(theta), c->r * sin(theta)};
    double g[2];
    dfl_field_eval1(c->f, x, g);
    return hypot(g[0], g[1]);
}

/* Angular distance (radians, in [0, pi]) between two directions. */
static double ang_dist(double a, double b)
{
    double d = fmod(fabs(a - b), 2.0 * DFL_PI);
    return d > DFL_PI ? 2.0 * DFL_PI - d : d;
}

typedef struct circle_stats {
    long on_set;
    double gmin, gmax, theta_min;
    double lower_min, upper_max;
    long viol, viol_paper;
    double excess_max, part_gdef_max, fd_maxdiff;
} circle_stats;

/* Workspace for one circle, allocated once per run. */
typedef struct circle_ws {
    double *pts, *val, *grad;     /* samples */
    double *fpts, *fval;          /* 4 shifted copies for finite differences */
} circle_ws;

static dfl_status measure_circle(const gb_keys *k, const dfl_field *f, double r, circle_ws *ws,
                                 dfl_table *prof, circle_stats *cs, dfl_err *err)
{
    const size_t n = (size_t)k->samples;
    const double hfd = k->fd_rel * r;
    const dfl_rfunc_join join = join_of(k->join);
    for (size_t i = 0; i < n; i++) {
        const double t = 2.0 * DFL_PI * ((double)i + 0.5) / (double)n;
        double *x = ws->pts + 2 * i;
        x[0] = r * cos(t);
        x[1] = r * sin(t);
        for (int s = 0; s < 4; s++) {
            double *y = ws->fpts + 2 * (4 * i + (size_t)s);
            y[0] = x[0] + (s == 0 ? hfd : s == 1 ? -hfd : 0.0);
            y[1] = x[1] + (s == 2 ? hfd : s == 3 ? -hfd : 0.0);
        }
    }
    f->ops->eval(f->ctx, n, ws->pts, ws->val, ws->grad);
    f->ops->eval(f->ctx, 4 * n, ws->fpts, ws->fval, NULL);
    memset(cs, 0, sizeof *cs);
    cs->gmin = INFINITY;
    cs->lower_min = INFINITY;
    size_t imin = 0;
    const size_t stride = n / (size_t)k->profile_samples;
    dfl_status st = DFL_OK;
    for (size_t i = 0; i < n && st == DFL_OK; i++) {
        const double *x = ws->pts + 2 * i;
        double h[2], gh[4];
        dfl_vjoin_parts(&k->vj, x, h, gh);
        if (h[0] == 0.0 || h[1] == 0.0) {
            cs->on_set++; /* u = 0 there, its gradient is a convention */
            continue;
        }
        const double G = hypot(ws->grad[2 * i], ws->grad[2 * i + 1]);
        const double g1 = hypot(gh[0], gh[1]), g2 = hypot(gh[2], gh[3]);
        const double phi = atan2(h[1], h[0]);
        double F1, F2, lo, hi, lo1, hi1;
        dfl_gradbound_partials(join, (int)k->p, phi, &F1, &F2);
        dfl_gradbound_band(F1, F2, 1.0, 1.0, &lo, &hi);
        dfl_gradbound_band(F1, F2, g1, g2, &lo1, &hi1);
        if (G < cs->gmin) cs->gmin = G, imin = i;
        cs->gmax = fmax(cs->gmax, G);
        cs->lower_min = fmin(cs->lower_min, lo);
        cs->upper_max = fmax(cs->upper_max, hi);
        if (G < lo1 - BAND_TOL || G > hi1 + BAND_TOL) cs->viol++;
        if (G < lo - BAND_TOL || G > hi + BAND_TOL) cs->viol_paper++;
        cs->excess_max = fmax(cs->excess_max, fmax(lo - G, G - hi));
        cs->part_gdef_max = fmax(cs->part_gdef_max, fmax(fabs(g1 - 1.0), fabs(g2 - 1.0)));
        const double *fv = ws->fval + 4 * i, *fp = ws->fpts + 8 * i;
        /* the step actually taken after rounding of the coordinates */
        const double gx = (fv[0] - fv[1]) / (fp[0] - fp[2]);
        const double gy = (fv[2] - fv[3]) / (fp[5] - fp[7]);
        cs->fd_maxdiff = fmax(cs->fd_maxdiff, fabs(hypot(gx, gy) - G));
        if (prof && i % stride == stride / 2) {
            const double t = 2.0 * DFL_PI * ((double)i + 0.5) / (double)n;
            st = dfl_table_row(prof, err);
            if (!st) st = dfl_table_set_double(prof, "r_rel", r / k->vj.length, err);
            if (!st) st = dfl_table_set_double(prof, "theta_deg", t * DEG, err);
            if (!st) st = dfl_table_set_double(prof, "phi_deg", phi * DEG, err);
            if (!st) st = dfl_table_set_double(prof, "h1", h[0], err);
            if (!st) st = dfl_table_set_double(prof, "h2", h[1], err);
            if (!st) st = dfl_table_set_double(prof, "grad_norm", G, err);
            if (!st) st = dfl_table_set_double(prof, "lower", lo, err);
            if (!st) st = dfl_table_set_double(prof, "upper", hi, err);
            if (!st) st = dfl_table_set_double(prof, "lower_parts", lo1, err);
            if (!st) st = dfl_table_set_double(prof, "upper_parts", hi1, err);
            if (!st) st = dfl_table_set_int(prof, "hatched", dfl_vjoin_hatched(&k->vj, x), err);
        }
    }
    if (st != DFL_OK) return st;
    if (!isfinite(cs->gmin))
        return dfl_err_set(err, DFL_E_NUMERIC, "bs04_gradbounds: every sample lies on the set");
    /* refine the minimum between the neighbouring samples */
    const double dt = 2.0 * DFL_PI / (double)n;
    const double t0 = 2.0 * DFL_PI * ((double)imin + 0.5) / (double)n;
    circ c = {f, r};
    double gref;
    const double tref = dfl_gradbound_golden(circ_grad, &c, t0 - dt, t0 + dt, 1e-12, &gref);
    cs->theta_min = t0;
    if (gref < cs->gmin) {
        cs->gmin = gref;
        cs->theta_min = fmod(tref + 2.0 * DFL_PI, 2.0 * DFL_PI);
    }
    return DFL_OK;
}

static dfl_status put_row(dfl_table *t, const gb_keys *k, double r, const circle_stats *cs,
                          const dfl_field *f, dfl_err *err)
{
    const dfl_rfunc_join join = join_of(k->join);
    const int p = (int)k->p;
    const double bis = dfl_vjoin_bisector(&k->vj);
    double dmin = ang_dist(cs->theta_min, bis);
    if (fabs(k->vj.alpha - DFL_PI) < 1e-15)
        dmin = fmin(dmin, ang_dist(cs->theta_min, bis + DFL_PI));
    circ c = {f, r};
    const double gbis = circ_grad(&c, bis);
    int where;
    const double gth = dfl_gradbound_vertex_min(join, p, k->vj.alpha, &where, NULL);
    double phi_min;
    const double smin = dfl_gradbound_sum_min(join, p, &phi_min, NULL, NULL);
    double F1, F2;
    dfl_gradbound_partials(join, p, 0.25 * DFL_PI, &F1, &F2);
    dfl_status st = dfl_table_row(t, err);
    if (!st) st = dfl_table_set_double(t, "alpha", k->alpha_deg, err);
    if (!st) st = dfl_table_set_int(t, "p", p, err);
    if (!st) st = dfl_table_set_string(t, "join", join_names[k->join], err);
    if (!st) st = dfl_table_set_string(t, "parts", dfl_vjoin_part_names[k->vj.parts], err);
    if (!st) st = dfl_table_set_double(t, "r_rel", r / k->vj.length, err);
    if (!st) st = dfl_table_set_double(t, "r", r, err);
    if (!st) st = dfl_table_set_int(t, "samples", k->samples, err);
    if (!st) st = dfl_table_set_int(t, "on_set", cs->on_set, err);
    if (!st) st = dfl_table_set_double(t, "grad_min", cs->gmin, err);
    if (!st) st = dfl_table_set_double(t, "grad_max", cs->gmax, err);
    if (!st) st = dfl_table_set_double(t, "theta_min_deg", cs->theta_min * DEG, err);
    if (!st) st = dfl_table_set_double(t, "bisector_deg", bis * DEG, err);
    if (!st) st = dfl_table_set_double(t, "theta_min_err_deg", dmin * DEG, err);
    if (!st) st = dfl_table_set_int(t, "min_on_bisector", dmin * DEG < 1e-3, err);
    if (!st) st = dfl_table_set_double(t, "grad_bisector", gbis, err);
    if (!st)
        st = dfl_table_set_double(t, "grad_bisector_theory",
                                  dfl_gradbound_bisector(join, p, k->vj.alpha), err);
    if (!st) st = dfl_table_set_double(t, "grad_min_theory", gth, err);
    if (!st)
        st = dfl_table_set_string(t, "min_regime_theory", where == 0 ? "bisector" : "mixed", err);
    if (!st) st = dfl_table_set_double(t, "lower_min", cs->lower_min, err);
    if (!st) st = dfl_table_set_double(t, "upper_max", cs->upper_max, err);
    if (!st) st = dfl_table_set_int(t, "violations", cs->viol, err);
    if (!st) st = dfl_table_set_int(t, "violations_paper", cs->viol_paper, err);
    if (!st) st = dfl_table_set_double(t, "excess_paper_max", fmax(cs->excess_max, 0.0), err);
    if (!st) st = dfl_table_set_double(t, "part_gdef_max", cs->part_gdef_max, err);
    if (!st) st = dfl_table_set_double(t, "fd_maxdiff", cs->fd_maxdiff, err);
    if (!st) st = dfl_table_set_double(t, "sum_min_phi_deg", phi_min * DEG, err);
    if (!st) st = dfl_table_set_double(t, "sum_min", smin, err);
    if (!st) st = dfl_table_set_double(t, "diff_at_45", F1 - F2, err);
    return st;
}

static dfl_status gb_run(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_table *table,
                         dfl_err *err)
{
    gb_keys k;
    dfl_field f = {0};
    circle_ws ws = {0};
    dfl_table *prof = NULL;
    dfl_status st = read_keys(cfg, &k, err);
    if (st == DFL_OK) st = dfl_cfg_check_used(cfg, err);
    if (st == DFL_OK) st = dfl_vjoin_field(&k.vj, join_of(k.join), (int)k.p, &f, err);
    if (st != DFL_OK) goto done;
    int want_profile = 0;
    for (size_t i = 0; i < k.nprofile; i++)
        if (fabs(k.profile_alpha[i] - k.alpha_deg) <= 1e-9) want_profile = 1;
    const size_t n = (size_t)k.samples;
    ws.pts = malloc(2 * n * sizeof *ws.pts);
    ws.val = malloc(n * sizeof *ws.val);
    ws.grad = malloc(2 * n * sizeof *ws.grad);
    ws.fpts = malloc(8 * n * sizeof *ws.fpts);
    ws.fval = malloc(4 * n * sizeof *ws.fval);
    if (want_profile) prof = dfl_table_new();
    if (!ws.pts || !ws.val || !ws.grad || !ws.fpts || !ws.fval || (want_profile && !prof)) {
        st = dfl_err_set(err, DFL_E_NOMEM, "out of memory for %zu samples", n);
        goto done;
    }
    for (size_t i = 0; i < k.nradii && st == DFL_OK; i++) {
        const double r = k.radii[i] * k.vj.length;
        circle_stats cs;
        st = measure_circle(&k, &f, r, &ws, prof, &cs, err);
        if (st == DFL_OK) st = put_row(table, &k, r, &cs, &f, err);
    }
    if (st == DFL_OK && ctx->point == 0) st = write_fig5(ctx, &k, err);
    if (st == DFL_OK && prof) {
        char path[4096];
        st = dfl_table_write_csv(prof, dfl_study_path(ctx, "profile", "csv", path, sizeof path),
                                 err);
    }
done:
    dfl_table_free(prof);
    free(ws.pts), free(ws.val), free(ws.grad), free(ws.fpts), free(ws.fval);
    dfl_field_destroy(&f);
    keys_free(&k);
    return st;
}

/* Peak memory: the circle's workspace, samples x (point, value, gradient,
 * 4 shifted points and their values: 17 doubles), reused by every radius;
 * with a profile, its table of profile_samples rows per radius, 11 cells
 * of about 64 bytes (a short string, its pointer, the allocator's header);
 * the Fig. 5 tables (2 joins x fig5_p x fig5_nphi rows of 10 cells) at the
 * first point.  Work per radius and sample: 5 evaluations of the
 * two-part join (2 + DFL_RFUNC_EVAL_UNITS CHEAP each) and the parts' own
 * and the bounds' (6). */
static dfl_status gb_estimate(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_cost *c,
                              dfl_err *err)
{
    gb_keys k;
    dfl_status st = read_keys(cfg, &k, err);
    if (!st) {
        const double n = (double)k.samples, radii = (double)k.nradii;
        int prof = 0;
        for (size_t i = 0; i < k.nprofile; i++)
            if (fabs(k.profile_alpha[i] - k.alpha_deg) <= 1e-9) prof = 1;
        dfl_cost_add_bytes(c, "study", "samples", 8 * 17 * n, "a circle of %ld samples",
                           k.samples);
        if (prof)
            dfl_cost_add_bytes(c, "study", "profile_samples",
                               64 * 11 * radii * (double)k.profile_samples,
                               "a profile of %.3g rows", radii * (double)k.profile_samples);
        if (ctx->point == 0)
            dfl_cost_add_bytes(c, "study", "fig5_nphi",
                               64 * 10 * 2 * (double)k.nfig5 * (double)k.fig5_nphi,
                               "the Fig. 5 table of %.3g rows",
                               2 * (double)k.nfig5 * (double)k.fig5_nphi);
        dfl_cost_add_work(c, "study", "samples", DFL_COST_CHEAP,
                          (5 * (2 + DFL_RFUNC_EVAL_UNITS) + 6) * n * radii,
                          "%.3g radii x %ld samples", radii, k.samples);
    }
    keys_free(&k);
    return st;
}

DFL_STUDY_DEFINE_ESTIMATED(bs04_gradbounds, gb_run, gb_estimate,
                 "bs04 Fig. 4-5, eq. 13-14: |grad u| on circles around a joining point vs the bounds");
