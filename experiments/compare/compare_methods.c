/* compare_methods: every method on every shape at a sweep of resolutions,
 * measured by one protocol (compare_eval.h), one long CSV.
 *
 * Config:
 *   [study]   methods = <section> ...   the method sections, in row order
 *             shapes  = <section> ...   the shape sections
 *   [compare] the protocol (compare_eval.h), all optional:
 *             grid2d = 301, grid3d = 41 (nodes per axis), surface = 20000,
 *             medial_draws = 100000, band = 0.05, medial_band = 0.02,
 *             pairs = 20000, seed = 1, repeats = 3 (timed evaluations)
 *   a shape section: a [shape] (include = ...) plus lo, hi: the box of its
 *             error points, which every method with a box is given, and
 *             optionally max_values = K: on this shape each method runs
 *             its first K values only (method sections list them coarse
 *             to fine), the others give a skipped row saying so (a shape
 *             whose exact distance is dear: implicit footpoints)
 *   a method section: a [field] section of any kind of
 *             experiments/cfg/field_cfg.c (its keys as there) plus the
 *             study's own keys
 *       resolution = KEY          the field key swept (res, eps, max_level...);
 *                                 none: one row, no key set (kind = exact)
 *       values     = v1 v2 ...    its values (blank-separated), one row each
 *                                 (not with resolution = none)
 *       dims       = 2 3          the dimensions the method applies to
 *       shape_key  = shape        the field key that receives the shape
 *                                 section (rfunc: curve)
 *       shape_kinds = K ...       only shapes of these kinds (default any)
 *       skip_kinds = K ...        not shapes of these kinds (default none;
 *                                 e.g. input = sdf proxies on an implicit
 *                                 shape, which offers footpoints only)
 *       box        = lo hi        the field keys that receive the box; none:
 *                                 the method has no box (rfunc)
 *       distance   = signed | unsigned   what the field approximates: d, or
 *                                 |d| (bs04's R-function fields)
 *       faces      = none | count | size   what the value says of the
 *                                 method's cells, for the continuity pairs
 *                                 (compare_eval.h's cmp_planes): count: N
 *                                 cells per axis on the box (faces and
 *                                 centres at lo + k (hi - lo) / 2N); size:
 *                                 voxels of that size from the origin (k v / 2,
 *                                 OpenVDB); none (default): the dyadic planes
 *                                 only
 * For each (method, shape, value) the study builds the field from a copy of
 * the config in which [method] KEY = value, shape_key = the shape section
 * and the box keys are set, so a method is built by its kind's own factory
 * and reads its own keys; the copy's method section must then have no
 * unread key (a typo fails there, exit 2).  A method that does not apply to
 * a shape (dims, shape_kinds) gives a row whose `skipped` column says why
 * (and a line on stderr), not an error; so does a build that fails with
 * DFL_E_NUMERIC ("build failed: ...": e.g. a Taylor-2 grid peer whose cell
 * centre lies where the SDF's Hessian is not finite).
 *
 * Columns: method, kind, shape, dim, setting (KEY=value), skipped, bytes
 * (dfl_field_bytes; empty when the kind does not say), build_s,
 * queries_per_s, build_rss_growth (bytes: growth of the process's peak
 * resident set during the build, getrusage ru_maxrss; 0 when the build
 * stays under an earlier peak, so an upper bound only for the first
 * builds), count, l1, rms, linf, eikonal_mean, eikonal_max, band_count,
 * band_l1, band_rms, band_linf, off_count, off_l1, off_rms, off_linf,
 * grad_linf, c0_jump, c1_jump, nonfinite, the point counts of the
 * protocol (n_grid, n_surface, n_medial, n_pairs), and the build's own
 * target (field_cfg.h dfl_field_target; empty cells for a kind without
 * one): target (its tolerance, e.g. pht's eps), target_met (1: every
 * cell's estimate met it; 0: the build stopped short, e.g. at pht's
 * max_level), target_over (the cells left above it) and target_linf_met
 * (1: the row's own linf, over every error point of the protocol, is <=
 * target; 0: it is not, a non-finite value included).  The row says
 * whether eps was reached: a setting eps=1e-3 is a target, not a result;
 * target_met is the build's verdict from its own sample points,
 * target_linf_met the study's from its error points, and the two can
 * disagree (a fit's estimator samples a cell at a few points; a cone
 * point or a kink between them is where the error points find more).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <omp.h>
#include <sys/resource.h>

#include "cfg/field_cfg.h"
#include "cfg/field_cost.h"
#include "cfg/shape_cfg.h"
#include "compare/compare.h"
#include "compare/compare_eval.h"
#include "harness/experiment.h"

#define MAX_LIST 32
#define NAME_MAX_LEN 64

typedef struct words {
    size_t n;
    char w[MAX_LIST][NAME_MAX_LEN];
} words;

/* Blank-separated words of [sec] key (absent: def) into *out.  At most
 * MAX_LIST words of fewer than NAME_MAX_LEN bytes. */
static dfl_status words_from_cfg(const dfl_cfg *cfg, const char *sec, const char *key,
                                 const char *def, int required, words *out, dfl_err *err)
{
    const char *v;
    dfl_status st = required ? dfl_cfg_string(cfg, sec, key, &v, err)
                             : dfl_cfg_string_opt(cfg, sec, key, def, &v, err);
    if (st) return st;
    out->n = 0;
    for (const char *s = v; *s;) {
        s += strspn(s, " \t");
        const size_t len = strcspn(s, " \t");
        if (!len) break;
        if (out->n == MAX_LIST || len >= NAME_MAX_LEN)
            return dfl_cfg_reject(cfg, sec, key, err,
                                  "at most %d blank-separated words of < %d characters",
                                  MAX_LIST, NAME_MAX_LEN);
        memcpy(out->w[out->n], s, len);
        out->w[out->n++][len] = '\0';
        s += len;
    }
    if (required && out->n == 0)
        return dfl_cfg_reject(cfg, sec, key, err, "expected at least one word");
    return DFL_OK;
}

/* The study's keys of a method section. */
typedef struct method {
    const char *sec;
    const char *key;         /* resolution */
    words values, shape_kinds, skip_kinds, box;
    int dims;                /* bit 2: 2D, bit 3: 3D */
    const char *shape_key;
    int unsigned_ref;
    int faces;               /* 0 none, 1 count, 2 size */
} method;

static const char *const distance_names[] = {"signed", "unsigned"};
static const char *const faces_names[] = {"none", "count", "size"};

/* Every word of [sec] key is a shape kind (geom/shape.h's table): a typo
 * in shape_kinds or skip_kinds would silently select or skip nothing. */
static dfl_status kinds_known(const dfl_cfg *cfg, const char *sec, const char *key,
                              const words *w, dfl_err *err)
{
    for (size_t i = 0; i < w->n; i++) {
        dfl_shape_kind k;
        dfl_err e2;
        if (dfl_shape_kind_parse(w->w[i], &k, &e2) != DFL_OK)
            return dfl_cfg_reject(cfg, sec, key, err, "%s", e2.msg);
    }
    return DFL_OK;
}

static dfl_status method_from_cfg(const dfl_cfg *cfg, const char *sec, method *m, dfl_err *err)
{
    memset(m, 0, sizeof *m);
    m->sec = sec;
    if (!dfl_cfg_has_section(cfg, sec))
        return dfl_cfg_reject(cfg, "study", "methods", err, "no section [%s]", sec);
    words dims;
    int dist = 0;
    dfl_status st = dfl_cfg_string(cfg, sec, "resolution", &m->key, err);
    if (st) return st;
    if (strcmp(m->key, "none") == 0) {
        if (dfl_cfg_has(cfg, sec, "values"))
            return dfl_cfg_reject(cfg, sec, "values", err, "not with resolution = none");
        m->values.n = 1;
        m->values.w[0][0] = '\0';
    } else {
        st = words_from_cfg(cfg, sec, "values", NULL, 1, &m->values, err);
    }
    if (!st) st = words_from_cfg(cfg, sec, "dims", "2 3", 0, &dims, err);
    if (!st) st = dfl_cfg_string_opt(cfg, sec, "shape_key", "shape", &m->shape_key, err);
    if (!st) st = words_from_cfg(cfg, sec, "shape_kinds", "", 0, &m->shape_kinds, err);
    if (!st) st = words_from_cfg(cfg, sec, "skip_kinds", "", 0, &m->skip_kinds, err);
    if (!st) st = kinds_known(cfg, sec, "shape_kinds", &m->shape_kinds, err);
    if (!st) st = kinds_known(cfg, sec, "skip_kinds", &m->skip_kinds, err);
    if (!st) st = words_from_cfg(cfg, sec, "box", "lo hi", 0, &m->box, err);
    if (!st) st = dfl_cfg_enum_opt(cfg, sec, "distance", distance_names, 2, 0, &dist, err);
    if (!st) st = dfl_cfg_enum_opt(cfg, sec, "faces", faces_names, 3, 0, &m->faces, err);
    if (!st && m->faces && strcmp(m->key, "none") == 0)
        return dfl_cfg_reject(cfg, sec, "faces", err, "not with resolution = none");
    if (st) return st;
    m->unsigned_ref = dist == 1;
    for (size_t i = 0; i < dims.n; i++) {
        if (strcmp(dims.w[i], "2") && strcmp(dims.w[i], "3"))
            return dfl_cfg_reject(cfg, sec, "dims", err, "expected 2 and/or 3, got '%s'",
                                  dims.w[i]);
        m->dims |= 1 << (dims.w[i][0] - '0');
    }
    if (m->box.n == 1 && strcmp(m->box.w[0], "none") == 0) m->box.n = 0;
    else if (m->box.n != 2)
        return dfl_cfg_reject(cfg, sec, "box", err, "expected two key names (lo hi) or none");
    return DFL_OK;
}

/* Why method m does not apply to shape section ssec of dimension dim, or
 * NULL. */
static const char *not_applicable(const dfl_cfg *cfg, const method *m, const char *ssec, int dim,
                                  char *buf, size_t size)
{
    if (!(m->dims & (1 << dim))) {
        snprintf(buf, size, "the method applies to dims other than %d", dim);
        return buf;
    }
    const char *kind = "";
    dfl_cfg_string(cfg, ssec, "kind", &kind, NULL);
    for (size_t i = 0; i < m->skip_kinds.n; i++)
        if (strcmp(m->skip_kinds.w[i], kind) == 0) {
            snprintf(buf, size, "shape kind %s is in skip_kinds", kind);
            return buf;
        }
    if (m->shape_kinds.n) {
        for (size_t i = 0; i < m->shape_kinds.n; i++)
            if (strcmp(m->shape_kinds.w[i], kind) == 0) return NULL;
        snprintf(buf, size, "shape kind %s is not in shape_kinds", kind);
        return buf;
    }
    return NULL;
}

static dfl_status set_kv(dfl_cfg *w, const char *sec, const char *key, const char *val,
                         dfl_err *err)
{
    char a[512];
    snprintf(a, sizeof a, "%s.%s=%s", sec, key, val);
    return dfl_cfg_set(w, a, err);
}

static void fmt_box(int dim, const double *v, char *buf, size_t size)
{
    if (dim == 2) snprintf(buf, size, "%.17g %.17g", v[0], v[1]);
    else snprintf(buf, size, "%.17g %.17g %.17g", v[0], v[1], v[2]);
}

/* A copy of cfg with the method's keys set for shape ssec (box lo, hi) at
 * value v. */
static dfl_status method_copy(const dfl_cfg *cfg, const method *m, const char *ssec, int dim,
                              const double *lo, const double *hi, const char *v, dfl_cfg **out,
                              dfl_err *err)
{
    dfl_status st = dfl_cfg_sweep_point(cfg, 0, out, err);
    if (!st && strcmp(m->key, "none") != 0) st = set_kv(*out, m->sec, m->key, v, err);
    if (!st) st = set_kv(*out, m->sec, m->shape_key, ssec, err);
    if (!st && m->box.n) {
        char b[256];
        fmt_box(dim, lo, b, sizeof b);
        st = set_kv(*out, m->sec, m->box.w[0], b, err);
        fmt_box(dim, hi, b, sizeof b);
        if (!st) st = set_kv(*out, m->sec, m->box.w[1], b, err);
    }
    if (st) {
        dfl_cfg_free(*out);
        *out = NULL;
    }
    return st;
}

/* The shape of ssec and its box, read from a copy of cfg so that the
 * copy's section can be checked for unread keys; cfg then claims what the
 * copy read (ssec and the sections it follows: CSG operands, a mesh's
 * polygonized shape). */
static dfl_status shape_from_cfg(const dfl_cfg *cfg, const char *ssec, dfl_shape *shape,
                                 double *lo, double *hi, long *max_values, dfl_err *err)
{
    if (!dfl_cfg_has_section(cfg, ssec))
        return dfl_cfg_reject(cfg, "study", "shapes", err, "no section [%s]", ssec);
    dfl_cfg *w;
    dfl_status st = dfl_cfg_sweep_point(cfg, 0, &w, err);
    if (st) return st;
    st = dfl_shape_from_cfg(w, ssec, shape, err);
    if (!st) st = dfl_cfg_vec(w, ssec, "lo", shape->dim, lo, err);
    if (!st) st = dfl_cfg_vec(w, ssec, "hi", shape->dim, hi, err);
    if (!st) st = dfl_cfg_int_opt(w, ssec, "max_values", MAX_LIST, 1, MAX_LIST, max_values, err);
    for (int a = 0; !st && a < shape->dim; a++)
        if (!(lo[a] < hi[a])) st = dfl_cfg_reject(w, ssec, "hi", err, "expected hi > lo");
    if (!st) st = dfl_cfg_check_used_in(w, ssec, err);
    if (!st) dfl_cfg_claim_read(cfg, w);
    if (st && shape->ops) dfl_shape_free(shape);
    dfl_cfg_free(w);
    return st;
}

/* A failure of the copy that sets the method's value v: named at the
 * method's values key (the copy's own message names the set key). */
static dfl_status value_err(const dfl_cfg *cfg, const method *m, const char *v, dfl_status st,
                            dfl_err *err)
{
    if (st != DFL_E_INPUT || strcmp(m->key, "none") == 0) return st;
    char msg[DFL_ERR_MSG_MAX];
    snprintf(msg, sizeof msg, "%s", err ? err->msg : "");
    char w[1024];
    dfl_cfg_where(cfg, m->sec, "values", w, sizeof w);
    return dfl_err_set(err, st, "%s (value %s): %s", w, v, msg);
}

/* The keys the study sets in the copy w (method_copy) must be keys the
 * kind reads: a kind without a box (exact, rfunc) needs box = none, said so
 * at the method, not as an unknown key the user never wrote. */
static dfl_status study_keys_read(const dfl_cfg *w, const method *m, dfl_err *err)
{
    const char *kind = "";
    dfl_cfg_string(w, m->sec, "kind", &kind, NULL);
    for (size_t b = 0; b < m->box.n; b++)
        if (!dfl_cfg_used(w, m->sec, m->box.w[b]))
            return dfl_cfg_reject(w, m->sec, "box", err,
                                  "kind = %s reads no key '%s' for the box (set box = none, or "
                                  "name its box keys)",
                                  kind, m->box.w[b]);
    if (!dfl_cfg_used(w, m->sec, m->shape_key))
        return dfl_cfg_reject(w, m->sec, "shape_key", err,
                              "kind = %s reads no key '%s' for the shape", kind, m->shape_key);
    return DFL_OK;
}

/* A validation pass over one method copy w: the kind's factory reads
 * every key of the method section as the run will, builds nothing (io/
 * config.h dfl_cfg_validating), and the section must then have no unread
 * key, so that a typo in the last method is found before the first one
 * is built, not hours into the run. */
static dfl_status method_validate(dfl_cfg *w, const method *m, dfl_err *err)
{
    dfl_cfg_validate_only(w);
    method again; /* marks the study's own keys read in the copy */
    dfl_status st = method_from_cfg(w, m->sec, &again, err);
    dfl_field f = {0};
    if (!st) st = dfl_field_from_cfg(w, m->sec, &f, err);
    dfl_field_destroy(&f);
    if (!st) st = study_keys_read(w, m, err);
    if (!st) st = dfl_cfg_check_used_in(w, m->sec, err);
    return st;
}

typedef struct study_cfg {
    words methods, shapes;
    method m[MAX_LIST];
    cmp_points_opts po;
    int repeats;
} study_cfg;

static dfl_status protocol_from_cfg(const dfl_cfg *cfg, cmp_points_opts *o, int *repeats,
                                    dfl_err *err)
{
    const char *s = "compare";
    long g2, g3, ns, nd, np, seed, rep;
    dfl_status st = dfl_cfg_int_opt(cfg, s, "grid2d", 301, 2, 4001, &g2, err);
    if (!st) st = dfl_cfg_int_opt(cfg, s, "grid3d", 41, 2, 401, &g3, err);
    if (!st) st = dfl_cfg_int_opt(cfg, s, "surface", 20000, 0, 10000000, &ns, err);
    if (!st) st = dfl_cfg_int_opt(cfg, s, "medial_draws", 100000, 0, 100000000, &nd, err);
    if (!st) st = dfl_cfg_int_opt(cfg, s, "pairs", 20000, 0, 10000000, &np, err);
    if (!st) st = dfl_cfg_int_opt(cfg, s, "seed", 1, 0, 1L << 62, &seed, err);
    if (!st) st = dfl_cfg_int_opt(cfg, s, "repeats", 3, 1, 100, &rep, err);
    if (!st) st = dfl_cfg_double_opt(cfg, s, "band", 0.05, 1e-12, 1e6, &o->band, err);
    if (!st)
        st = dfl_cfg_double_opt(cfg, s, "medial_band", 0.02, 1e-12, 1e6, &o->medial_band, err);
    if (st) return st;
    o->grid2d = (int)g2;
    o->grid3d = (int)g3;
    o->surface = (size_t)ns;
    o->medial_draws = (size_t)nd;
    o->pairs = (size_t)np;
    o->seed = (uint64_t)seed;
    *repeats = (int)rep;
    return DFL_OK;
}

/* Reads every key (the method and shape sections through copies, which
 * the original then claims). */
static dfl_status study_from_cfg(const dfl_cfg *cfg, study_cfg *s, dfl_err *err)
{
    memset(s, 0, sizeof *s);
    dfl_status st = words_from_cfg(cfg, "study", "methods", NULL, 1, &s->methods, err);
    if (!st) st = words_from_cfg(cfg, "study", "shapes", NULL, 1, &s->shapes, err);
    if (!st) st = protocol_from_cfg(cfg, &s->po, &s->repeats, err);
    for (size_t i = 0; !st && i < s->methods.n; i++)
        st = method_from_cfg(cfg, s->methods.w[i], &s->m[i], err);
    if (st) return st;
    for (size_t j = 0; j < s->shapes.n; j++) {
        dfl_shape shape;
        double lo[3], hi[3];
        long maxv;
        if ((st = shape_from_cfg(cfg, s->shapes.w[j], &shape, lo, hi, &maxv, err))) return st;
        const int dim = shape.dim;
        dfl_shape_free(&shape);
        /* each value's copy through the kind's cost reader: kind, ranges */
        for (size_t i = 0; i < s->methods.n; i++) {
            char why[160];
            if (not_applicable(cfg, &s->m[i], s->shapes.w[j], dim, why, sizeof why)) continue;
            for (size_t v = 0; v < s->m[i].values.n; v++) {
                dfl_cfg *w;
                if ((st = method_copy(cfg, &s->m[i], s->shapes.w[j], dim, lo, hi,
                                      s->m[i].values.w[v], &w, err)))
                    return st;
                dfl_cost c;
                memset(&c, 0, sizeof c);
                st = dfl_field_cost_from_cfg(w, s->m[i].sec, &c, err);
                /* the factory pass once per method and shape: the other values
                 * change only the swept key, whose range the cost reader
                 * has just checked (a shape may change the keys a kind
                 * reads, a value does not) */
                if (!st && v == 0 && dfl_cfg_validating(cfg))
                    st = method_validate(w, &s->m[i], err);
                dfl_cfg_free(w);
                if (st) return value_err(cfg, &s->m[i], s->m[i].values.w[v], st, err);
            }
        }
    }
    for (size_t i = 0; i < s->methods.n; i++) dfl_cfg_claim_section(cfg, s->methods.w[i]);
    return DFL_OK;
}

static double rss_bytes(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (double)ru.ru_maxrss * 1024.0;
}

static dfl_status put_metrics(dfl_table *t, const char *pre, const dfl_metrics *m, dfl_err *err)
{
    char c[64];
    dfl_status st;
#define PUT(name, v)                                              \
    snprintf(c, sizeof c, "%s%s", pre, name);                     \
    if ((st = dfl_table_set_double(t, c, v, err))) return st;
    snprintf(c, sizeof c, "%scount", pre);
    if ((st = dfl_table_set_int(t, c, (long)m->count, err))) return st;
    PUT("l1", m->l1);
    PUT("rms", m->rms);
    PUT("linf", m->linf);
#undef PUT
    return DFL_OK;
}

/* The target columns of a row whose build has a target (field_cfg.h); a
 * kind without one leaves them empty.  They are set after every other
 * column, and compare_run adds them at the end when no row has a target,
 * so the columns before them are those of a table without them.  linf is
 * the row's measured linf (NaN or inf: not met, by the comparison). */
static dfl_status put_target(dfl_table *t, const dfl_field_target *tg, double linf,
                             dfl_err *err)
{
    if (tg->met < 0) return DFL_OK;
    dfl_status st;
    if ((st = dfl_table_set_double(t, "target", tg->value, err))) return st;
    if ((st = dfl_table_set_int(t, "target_met", tg->met, err))) return st;
    if ((st = dfl_table_set_int(t, "target_over", (long)tg->over, err))) return st;
    return dfl_table_set_int(t, "target_linf_met", linf <= tg->value, err);
}

static dfl_status row_head(dfl_table *t, const method *m, const char *kind, const char *ssec,
                           int dim, const char *v, const char *skipped, dfl_err *err)
{
    char setting[160];
    if (strcmp(m->key, "none") == 0 || !v[0]) setting[0] = '\0';
    else snprintf(setting, sizeof setting, "%s=%s", m->key, v);
    dfl_status st = dfl_table_row(t, err);
    if (!st) st = dfl_table_set_string(t, "method", m->sec, err);
    if (!st) st = dfl_table_set_string(t, "kind", kind, err);
    if (!st) st = dfl_table_set_string(t, "shape", ssec, err);
    if (!st) st = dfl_table_set_int(t, "dim", dim, err);
    if (!st) st = dfl_table_set_string(t, "setting", setting, err);
    if (!st) st = dfl_table_set_string(t, "skipped", skipped, err);
    return st;
}

/* One method at one value on a shape's points: build, check, measure, row. */
static dfl_status run_one(const dfl_cfg *cfg, const method *m, const char *ssec,
                          const cmp_points *p, const char *v, int repeats, dfl_table *t,
                          dfl_err *err)
{
    dfl_cfg *w;
    dfl_status st = method_copy(cfg, m, ssec, p->dim, p->lo, p->hi, v, &w, err);
    if (st) return st;
    const char *kind = "";
    dfl_cfg_string(w, m->sec, "kind", &kind, NULL);
    method again;  /* marks the study's own keys read in the copy */
    if ((st = method_from_cfg(w, m->sec, &again, err))) goto done;
    dfl_field f = {0};
    dfl_field_target tg;
    const double rss0 = rss_bytes(), t0 = omp_get_wtime();
    if ((st = dfl_field_from_cfg_target(w, m->sec, &f, &tg, err))) {
        if (st == DFL_E_NUMERIC) {
            /* the method cannot represent this shape at this setting (a
             * sample or footpoint it needs is not finite): a row saying so */
            char why[DFL_ERR_MSG_MAX + 32];
            snprintf(why, sizeof why, "build failed: %s", err ? err->msg : "");
            fprintf(stderr, "dflab: compare_methods: [%s] %s=%s on [%s]: %s\n", m->sec, m->key,
                    v, ssec, why);
            st = row_head(t, m, kind, ssec, p->dim, v, why, err);
        } else {
            st = value_err(cfg, m, v, st, err);
        }
        goto done;
    }
    const double build_s = omp_get_wtime() - t0, rss = rss_bytes() - rss0;
    if ((st = study_keys_read(w, m, err))) goto field;
    if ((st = dfl_cfg_check_used_in(w, m->sec, err))) goto field;
    if (f.dim != p->dim) {
        st = dfl_cfg_reject(w, m->sec, "kind", err, "the field has dimension %d, [%s] %d",
                            f.dim, ssec, p->dim);
        goto field;
    }
    cmp_planes pl;
    const double val = atof(v);
    for (int a = 0; a < p->dim; a++) {
        pl.origin[a] = m->faces == 1 ? p->lo[a] : 0.0;
        pl.step[a] = m->faces == 1 ? (p->hi[a] - p->lo[a]) / (2 * val) : 0.5 * val;
    }
    if (m->faces && !(val > 0)) {
        st = dfl_cfg_reject(cfg, m->sec, "faces", err, "value '%s' is not a positive number", v);
        goto field;
    }
    cmp_result r;
    if ((st = cmp_measure(&f, p, m->unsigned_ref, repeats, m->faces ? &pl : NULL, &r, err)))
        goto field;
    size_t bytes;
    if ((st = row_head(t, m, kind, ssec, p->dim, v, "", err))) goto field;
    if (dfl_field_bytes(&f, &bytes) && (st = dfl_table_set_int(t, "bytes", (long)bytes, err)))
        goto field;
    const double qps = r.eval_seconds > 0 ? (double)p->m / r.eval_seconds : INFINITY;
    if ((st = dfl_table_set_double(t, "build_s", build_s, err))) goto field;
    if ((st = dfl_table_set_double(t, "queries_per_s", qps, err))) goto field;
    if ((st = dfl_table_set_double(t, "build_rss_growth", rss, err))) goto field;
    if ((st = put_metrics(t, "", &r.whole, err))) goto field;
    if ((st = dfl_table_set_double(t, "eikonal_mean", r.whole.gdef_mean, err))) goto field;
    if ((st = dfl_table_set_double(t, "eikonal_max", r.whole.gdef_max, err))) goto field;
    if ((st = put_metrics(t, "band_", &r.band, err))) goto field;
    if ((st = put_metrics(t, "off_", &r.off, err))) goto field;
    if ((st = dfl_table_set_double(t, "grad_linf", r.grad_linf, err))) goto field;
    if ((st = dfl_table_set_double(t, "c0_jump", r.c0_jump, err))) goto field;
    if ((st = dfl_table_set_double(t, "c1_jump", r.c1_jump, err))) goto field;
    if ((st = dfl_table_set_int(t, "nonfinite", (long)r.nonfinite, err))) goto field;
    if ((st = dfl_table_set_int(t, "n_grid", (long)p->ngrid, err))) goto field;
    if ((st = dfl_table_set_int(t, "n_surface", (long)p->nsurface, err))) goto field;
    if ((st = dfl_table_set_int(t, "n_medial", (long)p->nmedial, err))) goto field;
    if ((st = dfl_table_set_int(t, "n_pairs", (long)p->npairs, err))) goto field;
    st = put_target(t, &tg, r.whole.linf, err);
field:
    dfl_field_destroy(&f);
done:
    dfl_cfg_free(w);
    return st;
}

static dfl_status run_shape(const dfl_cfg *cfg, const study_cfg *s, const char *ssec,
                            dfl_table *t, dfl_err *err)
{
    dfl_shape shape;
    cmp_points_opts po = s->po;
    long maxv;
    dfl_status st = shape_from_cfg(cfg, ssec, &shape, po.lo, po.hi, &maxv, err);
    if (st) return st;
    cmp_points p;
    st = cmp_points_build(&shape, &po, &p, err);
    const int dim = shape.dim;
    dfl_shape_free(&shape);
    if (st) return st;
    for (size_t i = 0; !st && i < s->methods.n; i++) {
        const method *m = &s->m[i];
        char why[160];
        if (not_applicable(cfg, m, ssec, dim, why, sizeof why)) {
            fprintf(stderr, "dflab: compare_methods: [%s] skipped on [%s]: %s\n", m->sec, ssec,
                    why);
            const char *kind = "";
            dfl_cfg_string(cfg, m->sec, "kind", &kind, NULL);
            st = row_head(t, m, kind, ssec, dim, "", why, err);
            continue;
        }
        for (size_t v = 0; !st && v < m->values.n; v++) {
            if ((long)v >= maxv) {
                char why[160];
                snprintf(why, sizeof why, "beyond [%s] max_values = %ld (its reduced sweep)",
                         ssec, maxv);
                const char *kind = "";
                dfl_cfg_string(cfg, m->sec, "kind", &kind, NULL);
                st = row_head(t, m, kind, ssec, dim, m->values.w[v], why, err);
                continue;
            }
            st = run_one(cfg, m, ssec, &p, m->values.w[v], s->repeats, t, err);
        }
    }
    cmp_points_free(&p);
    return st;
}

static dfl_status compare_run(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_table *t,
                              dfl_err *err)
{
    (void)ctx;
    study_cfg *s = malloc(sizeof *s);
    if (!s) return dfl_err_set(err, DFL_E_NOMEM, "compare_methods: out of memory");
    dfl_status st = study_from_cfg(cfg, s, err);
    if (!st) st = dfl_cfg_check_used(cfg, err);
    for (size_t j = 0; !st && j < s->shapes.n; j++) st = run_shape(cfg, s, s->shapes.w[j], t, err);
    static const char *const tcols[] = {"target", "target_met", "target_over",
                                        "target_linf_met"};
    for (size_t k = 0; !st && k < 4; k++) st = dfl_table_add_col(t, tcols[k], err);
    free(s);
    return st;
}

/* Peak: the error points of the largest shape and the larger of the
 * largest shape's own bytes (dfl_shape_cost, held while its points are
 * made) and the largest single field with its shape (fields are built one
 * at a time); work: every shape's build, every field's build, the
 * reference (about 50 exact distances per point for the medial band's
 * bisection) and repeats + 2 evaluations of every point per field. */
static dfl_status compare_estimate(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_cost *cost,
                                   dfl_err *err)
{
    (void)ctx;
    study_cfg *s = malloc(sizeof *s);
    if (!s) return dfl_err_set(err, DFL_E_NOMEM, "compare_methods: out of memory");
    dfl_status st = words_from_cfg(cfg, "study", "methods", NULL, 1, &s->methods, err);
    if (!st) st = words_from_cfg(cfg, "study", "shapes", NULL, 1, &s->shapes, err);
    if (!st) st = protocol_from_cfg(cfg, &s->po, &s->repeats, err);
    for (size_t i = 0; !st && i < s->methods.n; i++)
        st = method_from_cfg(cfg, s->methods.w[i], &s->m[i], err);
    double big = 0, pts_bytes = 0, shape_big = 0;
    char big_sec[NAME_MAX_LEN] = "", shape_sec[NAME_MAX_LEN] = "";
    for (size_t j = 0; !st && j < s->shapes.n; j++) {
        const char *ssec = s->shapes.w[j];
        const int dim = dfl_shape_dim_guess(cfg, ssec);
        long maxv = MAX_LIST;
        if ((st = dfl_cfg_int_opt(cfg, ssec, "max_values", MAX_LIST, 1, MAX_LIST, &maxv, err)))
            break;
        const double n = dim == 2 ? s->po.grid2d : s->po.grid3d;
        const double m = pow(n, dim) + (double)s->po.surface + (double)s->po.medial_draws;
        pts_bytes = fmax(pts_bytes, m * (8.0 * (3 * dim + 4) + 2));
        const dfl_cost_class cls = dfl_shape_cost_class(cfg, ssec);
        dfl_cost_add_work(cost, "study", "shapes", cls, 50 * m, "the reference of [%s]", ssec);
        /* the shape built once for its points and reference (each field
         * builds its own again: dfl_field_cost_from_cfg counts that) */
        dfl_cost sc;
        memset(&sc, 0, sizeof sc);
        if ((st = dfl_shape_cost(cfg, ssec, &sc, err))) break;
        for (int k = 0; k < DFL_COST_NCLASSES; k++) cost->evals[k] += sc.evals[k];
        if (sc.bytes > shape_big) {
            shape_big = sc.bytes;
            snprintf(shape_sec, sizeof shape_sec, "%s", ssec);
        }
        const double lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};
        for (size_t i = 0; !st && i < s->methods.n; i++) {
            char why[160];
            if (not_applicable(cfg, &s->m[i], ssec, dim, why, sizeof why)) continue;
            for (size_t v = 0; !st && v < s->m[i].values.n && (long)v < maxv; v++) {
                dfl_cfg *w;
                if ((st = method_copy(cfg, &s->m[i], ssec, dim, lo, hi, s->m[i].values.w[v], &w,
                                      err)))
                    break;
                dfl_cost c;
                memset(&c, 0, sizeof c);
                st = dfl_field_cost_from_cfg(w, s->m[i].sec, &c, err);
                dfl_cfg_free(w);
                if (st) {
                    st = value_err(cfg, &s->m[i], s->m[i].values.w[v], st, err);
                    break;
                }
                for (int k = 0; k < DFL_COST_NCLASSES; k++) cost->evals[k] += c.evals[k];
                if (c.bytes > big) {
                    big = c.bytes;
                    snprintf(big_sec, sizeof big_sec, "%s", s->m[i].sec);
                }
                dfl_cost_add_work(cost, "study", "methods", DFL_COST_DECODE,
                                  m * (s->repeats + 2), "evaluations of [%s]", s->m[i].sec);
            }
        }
    }
    if (!st) {
        /* the sections and keys named are the original's (strings of the
         * copies and of s do not outlive this call) */
        dfl_cost_add_bytes(cost, "study", "shapes", pts_bytes, "the error points");
        /* the points are held with the shape of the reference, then with
         * one field at a time (which counts its own shape) */
        if (shape_big > big)
            dfl_cost_add_bytes(cost, "study", "shapes", shape_big, "the shape [%s]", shape_sec);
        else if (big_sec[0])
            dfl_cost_add_bytes(cost, "study", "methods", big, "the largest field, of [%s]",
                               big_sec);
    }
    free(s);
    return st;
}

DFL_STUDY_DEFINE_ESTIMATED(compare_methods, compare_run, compare_estimate,
                           "every method on every shape at a sweep of resolutions, one protocol: "
                           "errors by region, defects, continuity, bytes, build and query times");
