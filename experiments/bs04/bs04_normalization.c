/* bs04 normalization-order table (Sec. 2.3, eq. 6-7, trims eq. 4-5): the
 * order to which a joined polyline field is normalized, measured with exact
 * jets, beside the order the theory predicts.  One sweep point = one
 * (join, p, trim); one CSV row per point.
 *
 * Keys.  [field] is the polyline field of experiments/cfg/rfunc_cfg.h,
 * whose parsed description (dfl_rfunc_field_spec) also gives the
 * measurement its segments: kind = rfunc, vertices (2D, required: `curve`
 * is not accepted), closed, join, p, trim.
 * [study]:
 *   fractions = 0.2 0.35 0.5 0.65 0.8   interior points x = a + l (b - a) of
 *               every segment, l in (0, 1); rays along +n and -n
 *   K         = 16     jet order (2..24); must exceed the predicted order
 *                      to see the first non-zero coefficient
 *   tol       = 1e-9   zero test of field/normorder.h, length scale
 *                      L = the segment's length
 *   fan       = 9      rays per free end point, spread over the open
 *                      half-plane of outward directions (Rvachev's
 *                      generalized normals, bs04 Fig. 3a)
 *
 * Theory (derivations; coefficients are Taylor coefficients a_k = d_k/k!
 * along the unit normal at an interior point x of segment i, s >= 0; the
 * expansions are those of rfunc/join.h and rfunc/trim.h):
 *   trim:  for t > 0 eq. 4 is h_i = |f| exactly: along the normal f = +-s
 *          and t stays positive (disk: t = t0 - s^2/d; strip: t constant),
 *          so h_i = s to every order; eq. 5 gives
 *          h_i = s + s^7/(32 t0^2) + O(s^8) (t0 = t(x)): order 6 at most.
 *          The trims themselves (disk, strip) therefore limit nothing at
 *          interior points; only the smooth composition (eq. 5) does.
 *   requiv (eq. 6): u = h_i (1 + C h_i^p)^(-1/p), C = sum_(j != i) h_j^(-p):
 *          a_(p+1) = -C/p: order p.
 *   corrected (eq. 20, with the guard of join.h): the same with
 *          C = sum_(j != i) h_j^(-p) - sum_v max(q_v, h_prev, h_next)^(-p).
 *   rconj (eq. 7, left fold): c ^ h = h - h^p c^(1-p)/p + ... for c > 0, and
 *          the fold carries it: a_p = -B/p, B = u_(i-1)^(1-p) (fold of
 *          parts 0..i-1, absent for i = 0) + sum_(j > i) h_j^(1-p):
 *          order p - 1 (p >= 2; for p = 1, a ^ b = 0 identically).
 *   Combined: k_join = p + 1 (p for rconj); with eq. 5 the first non-zero
 *   coefficient is at min(k_join, 7), both adding when k_join = 7.  The
 *   table's order_theory = min(order_join, 6 for *_smooth trims).
 * End points (free ends of open polylines), direction w with w . e_out > 0:
 *   disk:  h = s sqrt(1 + 2 s we/d + s^2/d^2) = s + (we/d) s^2 + ...;
 *   strip: h = s + (we^3 / (2d)) s^2 + ...;   (we = w . e_out)
 *   so d1 = 1 (bs04 Sec. 2.1: normalized at end points in the generalized
 *   sense) but only to order 1; the joins only add terms of order >= p + 1.
 * Along the segment's normal at a free end (t = 0 there): strip: p1 = 0
 *   on the whole normal line, t = 0, h = |f| = s: the join's order; disk:
 *   t = -s^2/d, h = sqrt(s^2 + s^4/d^2) = s + s^3/(2 d^2): order 2; eq. 5
 *   adds g = O(s^2) to both: order 2 (end_normal_a3()).  The join's term
 *   is predicted as at interior points, per ray: the corrected join's guard
 *   may cancel it exactly (every qt_v picks a part's field beyond its end,
 *   the sums telescope to C = 0), which raises the order there.
 * Joining points (interior vertices; all vertices of a closed polyline),
 * along the outer bisector w = -(a1 + a2)/|a1 + a2| (a1, a2 unit vectors to
 * the neighbours): both adjacent fields are s + O(s^2) (w points away from
 * both segments), the others positive, so
 *   requiv d1 = (1 + 1)^(-1/p) = 2^(-1/p),  rconj d1 = 2 - 2^(1/p),
 *   corrected: the guard is max(h_i, h_j) (> q = s), u = min(h_i, h_j)
 *   (1 + O(s^p)): d1 = 1 but a_2 = min(we/d) > 0, order 1 (trimmed fields
 *   are not exact beyond their end points).
 * Rows (one per sweep point): join, p, trim, status (ok | n/a), note, K,
 * rays, order_join, order_theory, trim_limit (6 for eq. 5, empty: none),
 * measured_order (min over the interior rays), measured_order_max, capped
 * (1: every coefficient up to K vanished), match, first_k / first_deriv /
 * first_coef (first non-zero at the ray of the minimum; ties: the first
 * ray), first_k_theory / first_coef_theory (predicted there), at_segment /
 * at_fraction / at_side (that ray), coef_relerr_max (max over all rays of
 * the predicted coefficient's relative error), d1_maxdev, end_* (free ends,
 * fan: d1 range, min order, theory 1), end_normal_order_min / _theory
 * (along the end's normal), joint_* (outer bisectors: d1 range and theory,
 * max order and theory).  rconj with p = 1 gives a row with status n/a and
 * an empty measured_order instead of failing the sweep.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/vec.h"
#include "harness/experiment.h"
#include "cfg/field_cfg.h"
#include "cfg/field_cost.h"
#include "cfg/rfunc_cfg.h"
#include "field/normorder.h"
#include "rfunc/join.h"
#include "rfunc/segment.h"

#define NORM_MAX_FRAC 64

typedef struct norm_keys {
    dfl_rfunc_field_spec spec; /* [field] as parsed; owns v */
    dfl_rfunc_join join;       /* the spec's values, for short */
    dfl_rfunc_trim trim;
    long p;
    bool closed;
    const double *v;           /* 2n vertex coordinates */
    size_t n;
    double *frac;
    size_t nfrac;
    long K, fan;
    double tol;
} norm_keys;

/* Theory of one interior ray. */
typedef struct theory {
    int k;              /* first non-zero coefficient; 0: beyond every order */
    double coef;
} theory;

/* Measured extremes over a set of rays. */
typedef struct extremes {
    int n;
    int omin, omax;
    double d1min, d1max;
} extremes;

static void ext_init(extremes *e)
{
    e->n = 0;
    e->omin = 1 << 30;
    e->omax = -(1 << 30);
    e->d1min = INFINITY;
    e->d1max = -INFINITY;
}

static void ext_add(extremes *e, const dfl_normorder *r)
{
    e->n++;
    if (r->order < e->omin) e->omin = r->order;
    if (r->order > e->omax) e->omax = r->order;
    if (r->d1 < e->d1min) e->d1min = r->d1;
    if (r->d1 > e->d1max) e->d1max = r->d1;
}

static dfl_status read_keys(const dfl_cfg *cfg, norm_keys *k, dfl_err *err)
{
    const dfl_field_kind *kind;
    dfl_status st;
    memset(k, 0, sizeof *k);
    if ((st = dfl_field_kind_from_cfg(cfg, "field", &kind, err))) return st;
    if (kind->build != dfl_rfunc_field_from_cfg)
        return dfl_cfg_reject(cfg, "field", "kind", err,
                              "bs04_normalization needs kind = rfunc, got '%s'", kind->name);
    if ((st = dfl_rfunc_spec_from_cfg(cfg, "field", &k->spec, err))) return st;
    if (k->spec.curve)
        return dfl_cfg_reject(cfg, "field", "curve", err,
                              "bs04_normalization measures at the segments of [field] vertices;"
                              " give vertices, not a curve");
    if (k->spec.dim != 2)
        return dfl_cfg_reject(cfg, "field", "vertices", err,
                              "bs04_normalization measures planar polylines, expected points of 2"
                              " numbers, got %d", k->spec.dim);
    k->join = k->spec.join;
    k->trim = k->spec.trim;
    k->p = k->spec.p;
    k->closed = k->spec.closed;
    k->v = k->spec.v;
    k->n = k->spec.n;
    if ((st = dfl_cfg_doubles(cfg, "study", "fractions", 1, &k->frac, &k->nfrac, err))) return st;
    if (k->nfrac > NORM_MAX_FRAC)
        return dfl_cfg_reject(cfg, "study", "fractions", err, "at most %d fractions",
                              NORM_MAX_FRAC);
    for (size_t i = 0; i < k->nfrac; i++)
        if (!(k->frac[i] > 0.0 && k->frac[i] < 1.0))
            return dfl_cfg_reject(cfg, "study", "fractions", err,
                                  "expected fractions strictly between 0 and 1 (interior points),"
                                  " got %g", k->frac[i]);
    if ((st = dfl_cfg_int_opt(cfg, "study", "K", 16, 2, DFL_JET_MAX, &k->K, err))) return st;
    if ((st = dfl_cfg_double_opt(cfg, "study", "tol", 1e-9, 1e-15, 1e-2, &k->tol, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, "study", "fan", 9, 1, 1000, &k->fan, err))) return st;
    return DFL_OK;
}

/* Predicted first non-zero coefficient along the normal at x on segment i
 * (see the top): the join's term (k_join, J) and the part's own term
 * (kown, T; T = 0: none), which add when they meet. */
static theory predict(const norm_keys *k, const dfl_rfunc_seg *seg, size_t nseg, size_t i,
                      const double *x, int kown, double T)
{
    const int p = (int)k->p;
    double sum = 0.0, sumabs = 0.0;
    int kj;
    if (k->join == DFL_RFUNC_RCONJ) {
        kj = p;
        if (i > 0) {
            dfl_rfunc_acc acc;
            dfl_rfunc_acc_begin(&acc, DFL_RFUNC_RCONJ, p, 2, 0);
            for (size_t j = 0; j < i; j++)
                dfl_rfunc_acc_add(&acc, dfl_rfunc_seg_eval(&seg[j], x, NULL), NULL);
            sum += pow(dfl_rfunc_acc_end(&acc, NULL), 1.0 - p);
        }
        for (size_t j = i + 1; j < nseg; j++)
            sum += pow(dfl_rfunc_seg_eval(&seg[j], x, NULL), 1.0 - p);
        sumabs = sum;
    } else {
        kj = p + 1;
        for (size_t j = 0; j < nseg; j++)
            if (j != i) {
                const double t = pow(dfl_rfunc_seg_eval(&seg[j], x, NULL), -p);
                sum += t;
                sumabs += t;
            }
        if (k->join == DFL_RFUNC_REQUIV_CORRECTED) {
            const size_t n = k->n;
            for (size_t v = k->closed ? 0 : 1; v < (k->closed ? n : n - 1); v++) {
                const double *pv = k->v + 2 * v;
                double q = hypot(x[0] - pv[0], x[1] - pv[1]);
                q = fmax(q, dfl_rfunc_seg_eval(&seg[v == 0 ? n - 1 : v - 1], x, NULL));
                q = fmax(q, dfl_rfunc_seg_eval(&seg[v], x, NULL));
                sum -= pow(q, -p);
                sumabs += pow(q, -p);
            }
        }
    }
    /* The corrected join cancels exactly where every guard picks a part's
     * field (telescoping sum): then u = h_i along the ray. */
    const double J = fabs(sum) <= 1e-12 * sumabs ? 0.0 : -sum / p;
    theory th = {0, 0.0};
    if (J == 0.0) {
        if (T != 0.0) th = (theory){kown, T};
    } else if (T == 0.0 || kj < kown) {
        th = (theory){kj, J};
    } else if (kj == kown) {
        th = (theory){kj, J + T};
    } else {
        th = (theory){kown, T};
    }
    return th;
}

/* The part's own s^3 coefficient along its normal at an end point (t = 0
 * there; see the top).  disk, eq. 4: t = -s^2/d, h = sqrt(s^2 + s^4/d^2):
 * 1/(2 d^2).  eq. 5: g = sqrt(t^2 + f^4) - t = c s^2 with
 * c = sqrt(1/d^2 + 1) + 1/d (disk) or c = 1 (strip, t = 0), h =
 * sqrt(s^2 + c^2 s^4/4): c^2/8 (eq. 5 is not scale-invariant: f^4 and t^2
 * have different units).  strip, eq. 4: t = 0, h = |f|: none. */
static double end_normal_a3(int trim, double d)
{
    double c;
    switch (trim) {
    case DFL_RFUNC_TRIM_DISK:
        return 1.0 / (2.0 * d * d);
    case DFL_RFUNC_TRIM_DISK_SMOOTH:
        c = sqrt(1.0 / (d * d) + 1.0) + 1.0 / d;
        return c * c / 8.0;
    case DFL_RFUNC_TRIM_STRIP_SMOOTH:
        return 1.0 / 8.0;
    default:
        return 0.0;
    }
}

/* The row's identity, also when nothing is swept. */
static dfl_status put_ids(dfl_table *t, const norm_keys *k, dfl_err *err)
{
    dfl_status st = dfl_table_set_string(t, "join", dfl_rfunc_join_name((dfl_rfunc_join)k->join), err);
    if (!st) st = dfl_table_set_int(t, "p", k->p, err);
    if (!st) st = dfl_table_set_string(t, "trim", dfl_rfunc_trim_name((dfl_rfunc_trim)k->trim), err);
    return st;
}

static dfl_status put_na_row(dfl_table *t, const norm_keys *k, dfl_err *err)
{
    dfl_status st = dfl_table_row(t, err);
    if (!st) st = put_ids(t, k, err);
    if (!st) st = dfl_table_set_string(t, "status", "n/a", err);
    if (!st)
        st = dfl_table_set_string(t, "note",
                                  "p >= 2 required: eq. 7 with p = 1 is a + b - (a + b) = 0", err);
    if (!st) st = dfl_table_set_int(t, "K", k->K, err);
    return st;
}

/* Jet along dir into *j (may be NULL) and its order (sigma = +1: the
 * fields are unsigned). */
static dfl_status measure(const dfl_field *f, const double *x, const double *dir, int K,
                          double L, double tol, dfl_normorder *r, dfl_jet *jout, dfl_err *err)
{
    dfl_jet j;
    dfl_status st = dfl_field_jet(f, x, dir, K, &j, err);
    if (st == DFL_OK) st = dfl_normorder_measure(&j, 1.0, L, tol, r, err);
    if (st == DFL_OK && jout) *jout = j;
    if (st != DFL_OK) dfl_err_prefix(err, "jet at (%g, %g) along (%g, %g)", x[0], x[1], dir[0], dir[1]);
    return st;
}

/* The polyline's segments as library parts, for the theory (the field
 * builder has accepted the same geometry). */
static dfl_status make_segments(const norm_keys *k, dfl_rfunc_seg **out, size_t *nseg,
                                dfl_err *err)
{
    const size_t ns = k->closed ? k->n : k->n - 1;
    dfl_rfunc_seg *seg = calloc(ns, sizeof *seg);
    if (!seg) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    dfl_status st = DFL_OK;
    for (size_t i = 0; i < ns && st == DFL_OK; i++)
        st = dfl_rfunc_seg_init(2, k->v + 2 * i, k->v + 2 * ((i + 1) % k->n), k->trim, &seg[i],
                                err);
    if (st != DFL_OK) {
        free(seg);
        return st;
    }
    *out = seg;
    *nseg = ns;
    return DFL_OK;
}

/* Interior rays: the minimum order over them and where it is reached. */
typedef struct interior {
    extremes ext;
    dfl_normorder rmin;  /* the ray of the minimum (ties: the first) */
    theory thmin;        /* predicted there */
    size_t at_seg;
    double at_frac, at_side;
    double d1dev;        /* max |d1 - 1| */
    double relerr;       /* max relative error of the predicted coefficient */
    int capped_min;
} interior;

/* Rays along +n and -n at the fractions of every segment. */
static dfl_status interior_rays(const norm_keys *k, const dfl_field *f, const dfl_rfunc_seg *seg,
                                size_t nseg, interior *out, dfl_err *err)
{
    const int K = (int)k->K;
    interior r;
    memset(&r, 0, sizeof r);
    ext_init(&r.ext);
    dfl_status st = DFL_OK;
    for (size_t i = 0; i < nseg && st == DFL_OK; i++)
        for (size_t l = 0; l < k->nfrac && st == DFL_OK; l++)
            for (int side = 1; side >= -1 && st == DFL_OK; side -= 2) {
                const dfl_rfunc_seg *s = &seg[i];
                const double x[2] = {s->a[0] + k->frac[l] * (s->b[0] - s->a[0]),
                                     s->a[1] + k->frac[l] * (s->b[1] - s->a[1])};
                const double dir[2] = {side * s->n1[0], side * s->n1[1]};
                dfl_normorder m;
                dfl_jet j;
                if ((st = measure(f, x, dir, K, s->d, k->tol, &m, &j, err))) break;
                double T = 0.0;
                if (dfl_rfunc_trim_smooth(k->trim)) {
                    const double t0 = dfl_rfunc_seg_trim(s, x, NULL);
                    T = 1.0 / (32.0 * t0 * t0);
                }
                const theory th = predict(k, seg, nseg, i, x, 7, T);
                if (th.k >= 1 && th.k <= K) {
                    const double e = fabs(dfl_jet_coeff(&j, th.k) - th.coef) / fabs(th.coef);
                    if (!(e <= r.relerr)) r.relerr = e; /* NAN propagates */
                }
                if (fabs(m.d1 - 1.0) > r.d1dev) r.d1dev = fabs(m.d1 - 1.0);
                if (m.order < r.ext.omin) {
                    r.rmin = m;
                    r.thmin = th;
                    r.at_seg = i;
                    r.at_frac = k->frac[l];
                    r.at_side = side;
                    r.capped_min = m.capped;
                }
                ext_add(&r.ext, &m);
            }
    if (st == DFL_OK) *out = r;
    return st;
}

/* Free end points (open polylines): a fan of outward directions. */
static dfl_status end_fan_rays(const norm_keys *k, const dfl_field *f, const dfl_rfunc_seg *seg,
                               size_t nseg, extremes *out, dfl_err *err)
{
    dfl_status st = DFL_OK;
    ext_init(out);
    if (k->closed) return DFL_OK;
    for (int e = 0; e < 2 && st == DFL_OK; e++) {
        const dfl_rfunc_seg *s = &seg[e ? nseg - 1 : 0];
        const double *x = e ? s->b : s->a;
        const double eo[2] = {e ? s->e[0] : -s->e[0], e ? s->e[1] : -s->e[1]};
        for (long m = 0; m < k->fan && st == DFL_OK; m++) {
            const double ph = -DFL_PI / 2 + DFL_PI * ((double)m + 0.5) / (double)k->fan;
            const double dir[2] = {cos(ph) * eo[0] + sin(ph) * s->n1[0],
                                   cos(ph) * eo[1] + sin(ph) * s->n1[1]};
            dfl_normorder r;
            if ((st = measure(f, x, dir, (int)k->K, s->d, k->tol, &r, NULL, err))) break;
            ext_add(out, &r);
        }
    }
    return st;
}

/* Free end points along the segment's normal (both sides), and the
 * predicted minimum order there (*theory_min; 1 << 30 when none). */
static dfl_status end_normal_rays(const norm_keys *k, const dfl_field *f,
                                  const dfl_rfunc_seg *seg, size_t nseg, extremes *out,
                                  int *theory_min, dfl_err *err)
{
    const int K = (int)k->K;
    dfl_status st = DFL_OK;
    ext_init(out);
    *theory_min = 1 << 30;
    if (k->closed) return DFL_OK;
    for (int e = 0; e < 4 && st == DFL_OK; e++) {
        const size_t i = e & 1 ? nseg - 1 : 0;
        const dfl_rfunc_seg *s = &seg[i];
        const double *x = e & 1 ? s->b : s->a;
        const double sg = e & 2 ? -1.0 : 1.0;
        const double dir[2] = {sg * s->n1[0], sg * s->n1[1]};
        dfl_normorder r;
        if ((st = measure(f, x, dir, K, s->d, k->tol, &r, NULL, err))) break;
        ext_add(out, &r);
        const theory th = predict(k, seg, nseg, i, x, 3, end_normal_a3(k->trim, s->d));
        const int o = th.k ? th.k - 1 : K;
        if (o < *theory_min) *theory_min = o;
    }
    return st;
}

/* Joining points: the outer bisector of every vertex with an outer side. */
static dfl_status joint_rays(const norm_keys *k, const dfl_field *f, extremes *out, dfl_err *err)
{
    dfl_status st = DFL_OK;
    ext_init(out);
    for (size_t v = k->closed ? 0 : 1; v < (k->closed ? k->n : k->n - 1) && st == DFL_OK; v++) {
        const double *pv = k->v + 2 * v;
        const double *pa = k->v + 2 * (v == 0 ? k->n - 1 : v - 1),
                     *pb = k->v + 2 * ((v + 1) % k->n);
        double a1[2] = {pa[0] - pv[0], pa[1] - pv[1]}, a2[2] = {pb[0] - pv[0], pb[1] - pv[1]};
        const double l1 = hypot(a1[0], a1[1]), l2 = hypot(a2[0], a2[1]);
        double w[2] = {-(a1[0] / l1 + a2[0] / l2), -(a1[1] / l1 + a2[1] / l2)};
        const double wl = hypot(w[0], w[1]);
        if (!(wl > 1e-9)) continue; /* a straight continuation: no outer side */
        w[0] /= wl;
        w[1] /= wl;
        dfl_normorder r;
        if ((st = measure(f, pv, w, (int)k->K, fmin(l1, l2), k->tol, &r, NULL, err))) break;
        ext_add(out, &r);
    }
    return st;
}

static dfl_status norm_run(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_table *table,
                           dfl_err *err)
{
    (void)ctx;
    norm_keys k;
    dfl_field f = {0};
    dfl_rfunc_seg *seg = NULL;
    dfl_status st = read_keys(cfg, &k, err);
    const int na = st == DFL_OK && k.join == DFL_RFUNC_RCONJ && k.p == 1;
    if (st == DFL_OK && !na) st = dfl_rfunc_field_from_spec(cfg, "field", &k.spec, &f, err);
    if (st == DFL_OK) st = dfl_cfg_check_used(cfg, err);
    if (st != DFL_OK) goto done;
    if (na) {
        st = put_na_row(table, &k, err);
        goto done;
    }

    size_t nseg = 0;
    interior ir;
    extremes en, enn, jo;
    int enn_theory;
    if ((st = make_segments(&k, &seg, &nseg, err))) goto done;
    if ((st = interior_rays(&k, &f, seg, nseg, &ir, err))) goto done;
    if ((st = end_fan_rays(&k, &f, seg, nseg, &en, err))) goto done;
    if ((st = end_normal_rays(&k, &f, seg, nseg, &enn, &enn_theory, err))) goto done;
    if ((st = joint_rays(&k, &f, &jo, err))) goto done;

    /* the row's values */
    const int p = (int)k.p, K = (int)k.K;
    const int order_join = k.join == DFL_RFUNC_RCONJ ? p - 1 : p;
    const int trim_limit = dfl_rfunc_trim_smooth(k.trim) ? 6 : 0; /* 0: none */
    const int order_theory = trim_limit && trim_limit < order_join ? trim_limit : order_join;
    const extremes in = ir.ext;
    const dfl_normorder rmin = ir.rmin;
    const theory thmin = ir.thmin;
    const size_t at_seg = ir.at_seg;
    const double at_frac = ir.at_frac, at_side = ir.at_side, d1dev = ir.d1dev, relerr = ir.relerr;
    const int capped_min = ir.capped_min;
    const double joint_d1 = k.join == DFL_RFUNC_REQUIV ? pow(2.0, -1.0 / p)
                            : k.join == DFL_RFUNC_RCONJ ? 2.0 - pow(2.0, 1.0 / p)
                                                        : 1.0;
    const int joint_order = k.join == DFL_RFUNC_REQUIV_CORRECTED ? 1 : 0;
    const int match = in.omin == order_theory || (capped_min && order_theory >= in.omin);

    st = dfl_table_row(table, err);
#define SETI(c, v) \
    if (!st) st = dfl_table_set_int(table, c, (long)(v), err)
#define SETD(c, v) \
    if (!st) st = dfl_table_set_double(table, c, v, err)
    if (!st) st = put_ids(table, &k, err);
    if (!st) st = dfl_table_set_string(table, "status", "ok", err);
    if (!st) st = dfl_table_set_string(table, "note", capped_min ? "normalized to every order the jet knows (>= K)" : "", err);
    SETI("K", K);
    SETI("rays", in.n);
    SETI("order_join", order_join);
    if (trim_limit) SETI("trim_limit", trim_limit);
    SETI("order_theory", order_theory);
    SETI("measured_order", in.omin);
    SETI("measured_order_max", in.omax);
    SETI("capped", capped_min);
    SETI("match", match);
    if (!capped_min) {
        SETI("first_k", rmin.k);
        SETD("first_deriv", rmin.deriv);
        SETD("first_coef", rmin.coef);
    }
    if (thmin.k >= 1) {
        SETI("first_k_theory", thmin.k);
        SETD("first_coef_theory", thmin.coef);
    }
    SETI("at_segment", at_seg);
    SETD("at_fraction", at_frac);
    SETI("at_side", at_side);
    SETD("coef_relerr_max", relerr);
    SETD("d1_maxdev", d1dev);
    if (en.n) {
        SETI("end_rays", en.n);
        SETD("end_d1_min", en.d1min);
        SETD("end_d1_max", en.d1max);
        SETI("end_order_min", en.omin);
        SETI("end_order_theory", 1);
    }
    if (enn.n) {
        SETI("end_normal_order_min", enn.omin);
        SETI("end_normal_order_theory", enn_theory > K ? K : enn_theory);
    }
    if (jo.n) {
        SETI("joint_rays", jo.n);
        SETD("joint_d1_min", jo.d1min);
        SETD("joint_d1_max", jo.d1max);
        SETD("joint_d1_theory", joint_d1);
        SETI("joint_order_max", jo.omax);
        SETI("joint_order_theory", joint_order);
    }
#undef SETI
#undef SETD
done:
    free(seg);
    dfl_rfunc_spec_free(&k.spec);
    free(k.frac);
    dfl_field_destroy(&f);
    return st;
}

/* Peak memory: nothing in proportion to a key beyond the field ([field]'s
 * parts) and one library segment per part (144 bytes); jets hold K + 1
 * coefficients.  Work: rays along both normals at every fraction of every
 * segment, fan rays per free end, 4 end normals and one per joint; each a
 * jet of order K of the join of all parts (K^2 CHEAP per part, the Taylor
 * products) and the theory's sums over the parts (one CHEAP each). */
static dfl_status norm_estimate(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_cost *c,
                                dfl_err *err)
{
    double parts = 0;
    const char *key;
    norm_keys k;
    memset(&k, 0, sizeof k);
    dfl_status st = dfl_study_estimate_default(cfg, ctx, c, err);
    if (!st && dfl_cfg_has(cfg, "field", "vertices"))
        st = dfl_rfunc_parts_bound(cfg, "field", &parts, &key, err);
    if (!st) st = dfl_cfg_doubles(cfg, "study", "fractions", 1, &k.frac, &k.nfrac, err);
    if (!st) st = dfl_cfg_int_opt(cfg, "study", "K", 16, 2, DFL_JET_MAX, &k.K, err);
    if (!st) st = dfl_cfg_int_opt(cfg, "study", "fan", 9, 1, 1000, &k.fan, err);
    if (!st) {
        const double rays = parts * ((double)k.nfrac * 2 + 1) + 2.0 * (double)k.fan + 4;
        dfl_cost_add_bytes(c, "field", "vertices", 144 * parts, "%.3g library segments", parts);
        dfl_cost_add_work(c, "field", "vertices", DFL_COST_CHEAP,
                          rays * (parts * ((double)k.K * (double)k.K + 1) + DFL_RFUNC_EVAL_UNITS),
                          "%.3g rays of jets of order %ld over %.3g parts", rays, k.K, parts);
    }
    free(k.frac);
    return st;
}

DFL_STUDY_DEFINE_ESTIMATED(bs04_normalization, norm_run, norm_estimate,
                 "bs04: normalization order of joined segment fields by jets, join x p x trim");
