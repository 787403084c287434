/* End-to-end: the bs04 normalization-order table against the theory.
 *
 * Expected values are derived here, independently of src/rfunc: the orders
 * (p for R-equivalence and its corrected form, p - 1 for R-conjunction,
 * min(., 6) for the smooth trim of eq. 5, whose own expansion at interior
 * points is h = |f| + |f|^7/(32 t^2)), the first non-zero Taylor coefficient
 * from the part fields written out in closed form (eq. 2-5 with the strip
 * t = d - sqrt(p1^2 + p2^2)), and the first derivative at the joining points
 * (2^(-1/p), 2 - 2^(1/p), 1). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/e2e_util.h"
#include "io/config.h"

#define CFG "configs/paper/bs04/bs04_normalization.ini"

typedef struct seg2 {
    double a[2], b[2], d, e[2], n[2];
} seg2;

static seg2 seg_make(const double *a, const double *b)
{
    seg2 s;
    memcpy(s.a, a, sizeof s.a);
    memcpy(s.b, b, sizeof s.b);
    s.d = hypot(b[0] - a[0], b[1] - a[1]);
    s.e[0] = (b[0] - a[0]) / s.d;
    s.e[1] = (b[1] - a[1]) / s.d;
    s.n[0] = s.e[1];
    s.n[1] = -s.e[0];
    return s;
}

/* trim: 0 disk, 1 disk_smooth, 2 strip. */
static double seg_t(const seg2 *s, int trim, const double *x)
{
    if (trim == 2) {
        const double p1 = (x[0] - s->a[0]) * s->e[0] + (x[1] - s->a[1]) * s->e[1];
        const double p2 = (s->b[0] - x[0]) * s->e[0] + (s->b[1] - x[1]) * s->e[1];
        return s->d - hypot(p1, p2);
    }
    const double cx = 0.5 * (s->a[0] + s->b[0]), cy = 0.5 * (s->a[1] + s->b[1]);
    return (0.25 * s->d * s->d - (x[0] - cx) * (x[0] - cx) - (x[1] - cy) * (x[1] - cy)) / s->d;
}

static double seg_h(const seg2 *s, int trim, const double *x)
{
    const double f = (x[0] - s->a[0]) * s->n[0] + (x[1] - s->a[1]) * s->n[1];
    const double t = seg_t(s, trim, x);
    if (trim == 1) {
        const double g = sqrt(t * t + f * f * f * f) - t;
        return sqrt(f * f + g * g / 4);
    }
    const double m = t < 0 ? -t : 0.0;
    return sqrt(f * f + m * m);
}

static int trim_index(const char *name)
{
    return strcmp(name, "disk") == 0 ? 0 : strcmp(name, "disk_smooth") == 0 ? 1 : 2;
}

Test(e2e_bs04_norm, table_matches_theory, .timeout = 60)
{
    char out[512], csv[700];
    /* one row per sweep point */
    const long rows = e2e_run_table(CFG, "--set 'field.p=1, 2, 3, 6, 7, 12'", "bs04_normalization",
                                    3 * 6 * 3, out, sizeof out, csv, sizeof csv);

    /* the shipped polyline */
    dfl_cfg *cfg;
    dfl_err err;
    cr_assert_eq(dfl_cfg_load(CFG, &cfg, &err), DFL_OK, "%s", err.msg);
    double *v;
    size_t nv;
    cr_assert_eq(dfl_cfg_points(cfg, "field", "vertices", 2, 2, &v, &nv, &err), DFL_OK, "%s",
                 err.msg);
    dfl_cfg_free(cfg);
    const size_t ns = nv - 1;
    seg2 s[16];
    cr_assert(ns <= 16);
    for (size_t i = 0; i < ns; i++) s[i] = seg_make(v + 2 * i, v + 2 * i + 2);

    int seen_rconj1 = 0;
    for (long r = 0; r < rows; r++) {
        char *join = e2e_csv_cell(csv, r, "join"), *trim = e2e_csv_cell(csv, r, "trim");
        char *status = e2e_csv_cell(csv, r, "status");
        const int p = (int)e2e_csv_get(csv, (size_t)r, "p");
        cr_expect_eq(p, (int)e2e_csv_get(csv, (size_t)r, "field.p"), "the swept key");
        const int it = trim_index(trim);
        const int rconj = strcmp(join, "rconj") == 0, corr = strcmp(join, "requiv_corrected") == 0;
        char what[128];
        snprintf(what, sizeof what, "%s p=%d %s", join, p, trim);
        if (rconj && p == 1) {
            seen_rconj1 = 1;
            cr_expect_str_eq(status, "n/a", "%s", what);
            cr_expect(isnan(e2e_csv_get(csv, (size_t)r, "measured_order")), "%s", what);
            free(join), free(trim), free(status);
            continue;
        }
        cr_expect_str_eq(status, "ok", "%s", what);
        /* the order */
        int want = rconj ? p - 1 : p;
        if (it == 1 && want > 6) want = 6;
        cr_expect_eq((int)e2e_csv_get(csv, (size_t)r, "order_theory"), want, "%s", what);
        cr_expect_eq((int)e2e_csv_get(csv, (size_t)r, "measured_order"), want, "%s", what);
        cr_expect_eq((int)e2e_csv_get(csv, (size_t)r, "measured_order_max"), want, "%s", what);
        cr_expect_eq((int)e2e_csv_get(csv, (size_t)r, "first_k"), want + 1, "%s", what);
        if (it == 1) cr_expect_eq((int)e2e_csv_get(csv, (size_t)r, "trim_limit"), 6, "%s", what);
        else cr_expect(isnan(e2e_csv_get(csv, (size_t)r, "trim_limit")), "%s", what);

        /* the first non-zero coefficient at the reported ray */
        const size_t i = (size_t)e2e_csv_get(csv, (size_t)r, "at_segment");
        const double l = e2e_csv_get(csv, (size_t)r, "at_fraction");
        cr_assert(i < ns && l > 0 && l < 1, "%s", what);
        const double x[2] = {s[i].a[0] + l * (s[i].b[0] - s[i].a[0]),
                             s[i].a[1] + l * (s[i].b[1] - s[i].a[1])};
        double sum = 0;
        if (rconj) {
            /* fold of the parts before i: a ^ b = a + b - (a^p + b^p)^(1/p) */
            if (i > 0) {
                double u = seg_h(&s[0], it, x);
                for (size_t j = 1; j < i; j++) {
                    const double b = seg_h(&s[j], it, x);
                    u = u + b - pow(pow(u, p) + pow(b, p), 1.0 / p);
                }
                sum += pow(u, 1.0 - p);
            }
            for (size_t j = i + 1; j < ns; j++) sum += pow(seg_h(&s[j], it, x), 1.0 - p);
        } else {
            for (size_t j = 0; j < ns; j++)
                if (j != i) sum += pow(seg_h(&s[j], it, x), -p);
            if (corr)
                for (size_t w = 1; w + 1 < nv; w++) {
                    double q = hypot(x[0] - v[2 * w], x[1] - v[2 * w + 1]);
                    q = fmax(q, fmax(seg_h(&s[w - 1], it, x), seg_h(&s[w], it, x)));
                    sum -= pow(q, -p);
                }
        }
        const int kj = rconj ? p : p + 1;
        const double t0 = seg_t(&s[i], it, x);
        double c = -sum / p;
        if (it == 1 && kj == 7) c += 1 / (32 * t0 * t0);
        if (it == 1 && kj > 7) c = 1 / (32 * t0 * t0);
        const double got = e2e_csv_get(csv, (size_t)r, "first_coef");
        cr_expect(fabs(got - c) <= 1e-9 * fabs(c), "%s: a_%d = %.17g, theory %.17g", what, want + 1,
                  got, c);
        cr_expect(fabs(e2e_csv_get(csv, (size_t)r, "first_deriv") - tgamma(want + 2.0) * c) <=
                      1e-9 * tgamma(want + 2.0) * fabs(c),
                  "%s", what);
        cr_expect(e2e_csv_get(csv, (size_t)r, "coef_relerr_max") < 1e-9, "%s", what);
        cr_expect(e2e_csv_get(csv, (size_t)r, "d1_maxdev") < 1e-12, "%s", what);

        /* free ends: d1 = 1 in every outward direction, order 1 */
        cr_expect(fabs(e2e_csv_get(csv, (size_t)r, "end_d1_min") - 1) < 1e-12, "%s", what);
        cr_expect(fabs(e2e_csv_get(csv, (size_t)r, "end_d1_max") - 1) < 1e-12, "%s", what);
        cr_expect_eq((int)e2e_csv_get(csv, (size_t)r, "end_order_min"), 1, "%s", what);
        /* along the end's normal: strip t = 0, h = |f| (the join's order);
         * disk h = s + s^3/(2 d^2) (order 2).  The corrected join may cancel
         * its own term there (checked in its own test below). */
        if (!corr) {
            const int jo = rconj ? p - 1 : p;
            const int en = it == 2 ? jo : (jo < 2 ? jo : 2);
            cr_expect_eq((int)e2e_csv_get(csv, (size_t)r, "end_normal_order_min"), en, "%s",
                         what);
        }
        /* joining points, outer bisector */
        const double jd1 = corr ? 1.0 : rconj ? 2 - pow(2, 1.0 / p) : pow(2, -1.0 / p);
        cr_expect(fabs(e2e_csv_get(csv, (size_t)r, "joint_d1_min") - jd1) < 1e-12, "%s", what);
        cr_expect(fabs(e2e_csv_get(csv, (size_t)r, "joint_d1_max") - jd1) < 1e-12, "%s", what);
        cr_expect_eq((int)e2e_csv_get(csv, (size_t)r, "joint_order_max"), corr ? 1 : 0, "%s",
                     what);
        free(join), free(trim), free(status);
    }
    cr_expect(seen_rconj1, "rconj p = 1 must be in the table");
    free(v);
}

/* A single segment: its field is h itself (nothing to join), so the
 * order is the trim's: every order the jet knows (eq. 4: h = |f|), 6 for
 * eq. 5; along the normal at an end point 2 (disk) or every order (strip). */
Test(e2e_bs04_norm, single_segment_trim_limits, .timeout = 30)
{
    char out[512], csv[700];
    e2e_run_table(CFG,
                  "--set 'field.vertices=0.1 0.2; 0.8 0.6' --set field.join=requiv"
                  " --set field.p=3 --set study.K=12",
                  "bs04_normalization", 3, out, sizeof out, csv, sizeof csv);
    const double a[2] = {0.1, 0.2}, b[2] = {0.8, 0.6};
    const seg2 s = seg_make(a, b);
    for (long r = 0; r < 3; r++) {
        char *trim = e2e_csv_cell(csv, r, "trim");
        const int it = trim_index(trim);
        if (it == 1) {
            cr_expect_eq((int)e2e_csv_get(csv, (size_t)r, "measured_order"), 6);
            const double l = e2e_csv_get(csv, (size_t)r, "at_fraction");
            const double x[2] = {a[0] + l * (b[0] - a[0]), a[1] + l * (b[1] - a[1])};
            const double t0 = seg_t(&s, 1, x);
            cr_expect_float_eq(e2e_csv_get(csv, (size_t)r, "first_coef"), 1 / (32 * t0 * t0),
                               1e-9 / (32 * t0 * t0));
        } else {
            cr_expect_eq((int)e2e_csv_get(csv, (size_t)r, "measured_order"), 12, "%s", trim);
            cr_expect_eq((int)e2e_csv_get(csv, (size_t)r, "capped"), 1, "%s", trim);
        }
        cr_expect_eq((int)e2e_csv_get(csv, (size_t)r, "end_normal_order_min"), it == 2 ? 12 : 2,
                     "%s", trim);
        free(trim);
    }
}

/* The corrected join's guard at a free end: where every guard picks a
 * part's field (trimmed fields exceed the vertex distance beyond their
 * ends), the sums telescope and u = h_i along the end's normal. */
Test(e2e_bs04_norm, corrected_end_cancellation, .timeout = 30)
{
    char out[512], csv[700];
    const long rows = e2e_run_table(CFG, "--set field.join=requiv_corrected --set field.p=2",
                                    "bs04_normalization", -1, out, sizeof out, csv, sizeof csv);
    for (long r = 0; r < rows; r++) {
        const double mo = e2e_csv_get(csv, (size_t)r, "end_normal_order_min");
        cr_expect_eq(mo, e2e_csv_get(csv, (size_t)r, "end_normal_order_theory"));
        cr_expect(mo <= 2); /* p = 2 or the trim's own s^3 term */
    }
}

Test(e2e_bs04_norm, bad_input_exits_2_without_files)
{
    static const char *const sets[][2] = {
        {"--set 'study.fractions=0.5 1.0'", "study.fractions"},
        {"--set study.K=40", "study.K"},
        {"--set field.curve=W", "field.curve"},
        {"--set field.kind=exact", "field.kind"},
        {"--set 'field.vertices=0 0; 0 0'", "field.vertices"},
        {"--set study.colour=red", "study.colour"},
    };
    e2e_expect_bad_runs(CFG, NULL, sets, sizeof sets / sizeof sets[0]);
}
