/* curveprobe: rays normal to curves, level-set crossings along rays,
 * statistics, the maximum of a field on a curve.  Expected values come from
 * closed forms: the parabola y = x^2 (curvature, arc length, distances),
 * fields whose level sets along a ray are known, hand-made ray sets. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/vec.h"
#include "field/curveprobe.h"
#include "field/exact.h"
#include "geom/curvature.h"
#include "geom/footpoint.h"


/* ---- test fields: u(x, y) of closed form, no jets ---- */
typedef struct tfield {
    int kind;
} tfield;

static void tf_eval(const void *ctx, size_t m, const double *p, double *val, double *grad)
{
    const tfield *f = ctx;
    for (size_t i = 0; i < m; i++) {
        const double x = p[2 * i], y = p[2 * i + 1];
        double v = 0;
        switch (f->kind) {
        case 0: v = 2.0 * fabs(y); break;            /* linear in |y| */
        case 1: v = y * y; break;                    /* quadratic */
        case 2: v = y * (2.0 - y); break;            /* rises to 1 at y = 1, falls */
        case 3: v = 1.0 - (x - 0.3) * (x - 0.3); break; /* max 1 at x = 0.3 */
        default: v = NAN;
        }
        val[i] = v;
        if (grad) grad[2 * i] = grad[2 * i + 1] = 0;
    }
}

static const dfl_field_ops tf_ops = {"test", tf_eval, NULL, NULL, NULL};

static dfl_field tfield_make(tfield *t) { return (dfl_field){2, &tf_ops, t}; }

/* a one-ray set from o along v */
static dfl_rayset one_ray(double *o, double *v, double *t, double *kap, int *side, int *kind)
{
    *t = 0, *kap = 0, *side = 1, *kind = DFL_RAY_SIDE;
    return (dfl_rayset){1, o, v, t, kap, side, kind, 0, 0};
}

static void line_curve(double ax, double ay, double bx, double by, dfl_bspline *c)
{
    const double cp[4] = {ax, ay, bx, by};
    cr_assert_eq(dfl_bspline_init(2, 2, 2, cp, NULL, 0, c, NULL), DFL_OK);
}

/* C(s) = (2s - 1, (2s - 1)^2), s in [0, 1]: the parabola y = x^2, |x| <= 1 */
static void parabola(dfl_bspline *c)
{
    const double cp[6] = {-1, 1, 0, -1, 1, 1};
    cr_assert_eq(dfl_bspline_init_bezier(2, 3, cp, c, NULL), DFL_OK);
}

static double parabola_arc(double x) { return 0.5 * (x * sqrt(1 + 4 * x * x) + 0.5 * asinh(2 * x)); }

Test(curveprobe, rays_of_a_segment)
{
    dfl_bspline c;
    line_curve(0, 0, 2, 0, &c);
    const double jt[1] = {0.5};
    dfl_rayset rs;
    cr_assert_eq(dfl_curveprobe_rays(&c, 5, 3, jt, 1, &rs, NULL), DFL_OK);
    cr_assert_eq(rs.n, 2 * 5 + 2 * 3 + 2);
    for (size_t i = 0; i < 5; i++) {
        for (int s = 0; s < 2; s++) {
            const size_t k = 2 * i + (size_t)s;
            cr_expect_float_eq(rs.o[2 * k], 0.5 * (double)i, 1e-13, "origin %zu", i);
            cr_expect_eq(rs.o[2 * k + 1], 0.0);
            /* left normal of T = (1, 0) is (0, 1) */
            cr_expect_float_eq(rs.v[2 * k], 0.0, 1e-15);
            cr_expect_float_eq(rs.v[2 * k + 1], s ? -1.0 : 1.0, 1e-15);
            cr_expect_eq(rs.side[k], s ? -1 : 1);
            cr_expect_eq(rs.kind[k], DFL_RAY_SIDE);
            cr_expect_eq(rs.kappa[k], 0.0);
        }
    }
    /* caps: th = pi/4, pi/2, 3pi/4; v = cos th N + sin th T_out */
    for (int e = 0; e < 2; e++)
        for (int j = 1; j <= 3; j++) {
            const size_t k = 10 + (size_t)(3 * e + j - 1);
            const double th = DFL_PI * j / 4.0;
            cr_expect_eq(rs.kind[k], DFL_RAY_CAP);
            cr_expect_float_eq(rs.o[2 * k], e ? 2.0 : 0.0, 1e-15);
            cr_expect_float_eq(rs.v[2 * k], e ? sin(th) : -sin(th), 1e-15);
            cr_expect_float_eq(rs.v[2 * k + 1], cos(th), 1e-15);
        }
    cr_expect_eq(rs.kind[16], DFL_RAY_JOINT);
    cr_expect_float_eq(rs.o[32], 1.0, 1e-15);
    cr_expect_float_eq(rs.v[33], 1.0, 1e-15);
    cr_expect_float_eq(rs.v[35], -1.0, 1e-15);
    dfl_curveprobe_free(&rs);
    dfl_bspline_free(&c);
}

Test(curveprobe, parabola_arc_length_and_curvature)
{
    dfl_bspline c;
    parabola(&c);
    dfl_rayset rs;
    const size_t ns = 41;
    cr_assert_eq(dfl_curveprobe_rays(&c, ns, 0, NULL, 0, &rs, NULL), DFL_OK);
    cr_assert_eq(rs.n, 2 * ns);
    const double L = parabola_arc(1) - parabola_arc(-1);
    size_t nflat = 0, ncurv = 0;
    for (size_t i = 0; i < ns; i++) {
        const double x = rs.o[4 * i], y = rs.o[4 * i + 1];
        cr_expect_float_eq(y, x * x, 1e-14, "origin on the curve");
        /* uniform in arc length */
        cr_expect_float_eq(parabola_arc(x) - parabola_arc(-1), L * (double)i / (double)(ns - 1),
                           1e-9, "arc of origin %zu", i);
        /* kappa of y = x^2: 2 / (1 + 4x^2)^(3/2) > 0, turning left; this is
         * geom/curvature.h's kappa for the right normal n = (T_y, -T_x) */
        cr_expect_float_eq(rs.kappa[2 * i], 2.0 / pow(1 + 4 * x * x, 1.5), 1e-12);
        {
            double D[3 * 2];
            dfl_bspline_eval(&c, rs.t[2 * i], 2, D);
            const double sp = hypot(D[2], D[3]), n[2] = {D[3] / sp, -D[2] / sp};
            cr_expect_float_eq(rs.kappa[2 * i], dfl_curvature_curve2(D + 2, D + 4, n), 1e-12);
        }
        /* left normal (-2x, 1) / sqrt(1 + 4x^2) */
        const double nn = sqrt(1 + 4 * x * x);
        cr_expect_float_eq(rs.v[4 * i], -2 * x / nn, 1e-12);
        cr_expect_float_eq(rs.v[4 * i + 1], 1 / nn, 1e-12);
        nflat += 2 * (fabs(rs.kappa[2 * i]) <= rs.kflat);
        ncurv += 2 * (fabs(rs.kappa[2 * i]) > rs.kcurved);
    }
    /* tertiles of |kappa| over the 2 ns side rays (pairs share kappa) */
    cr_expect(rs.kflat < rs.kcurved);
    cr_expect(labs((long)nflat - (long)(2 * ns) / 3) <= 2, "flat %zu", nflat);
    cr_expect(labs((long)ncurv - (long)(2 * ns) / 3) <= 2, "curved %zu", ncurv);
    dfl_curveprobe_free(&rs);
    dfl_bspline_free(&c);
}

Test(curveprobe, valid_and_on_branch_on_a_parabola)
{
    dfl_bspline c, c2;
    parabola(&c);
    parabola(&c2);
    dfl_shape sh;
    dfl_field ex;
    cr_assert_eq(dfl_shape_param_curve(&c2, NULL, 0, &sh, NULL), DFL_OK);
    cr_assert_eq(dfl_field_exact_new(&sh, &ex, NULL), DFL_OK);
    dfl_rayset rs;
    cr_assert_eq(dfl_curveprobe_rays(&c, 3, 0, NULL, 0, &rs, NULL), DFL_OK);
    /* rays 2, 3: from the vertex (0, 0) up (inner side) and down */
    cr_assert_float_eq(rs.o[4], 0.0, 1e-14);
    int ok[6];
    /* (0, 0.25): nearest point of y = x^2 is the vertex (radius of
     * curvature 1/2 > 0.25) */
    cr_assert_eq(dfl_curveprobe_valid(&ex, &rs, 0.25, 1e-9, 1, ok, NULL), DFL_OK);
    cr_expect(ok[2] && ok[3]);
    /* (0, 1): min_x x^2 + (x^2 - 1)^2 = 3/4 at x^2 = 1/2: d = 0.866 < 1 */
    cr_assert_eq(dfl_curveprobe_valid(&ex, &rs, 1.0, 1e-9, 1, ok, NULL), DFL_OK);
    cr_expect(!ok[2], "above the centre of curvature");
    cr_expect(ok[3], "outer side");
    double s[6] = {0.1, 0.1, 0.25, 0.8, 1.0, NAN};
    cr_assert_eq(dfl_curveprobe_on_branch(&ex, &rs, s, 1e-9, 2, ok, NULL), DFL_OK);
    cr_expect(ok[2] && ok[3] && !ok[5]);
    s[2] = 1.0;
    cr_assert_eq(dfl_curveprobe_on_branch(&ex, &rs, s, 1e-9, 2, ok, NULL), DFL_OK);
    cr_expect(!ok[2]);
    cr_expect_eq(dfl_curveprobe_valid(&ex, &rs, -1.0, 1e-9, 1, ok, NULL), DFL_E_INPUT);
    dfl_curveprobe_free(&rs);
    dfl_field_destroy(&ex);
    dfl_bspline_free(&c);
}

Test(curveprobe, first_crossings_along_a_ray)
{
    double o[2] = {0.2, 0}, v[2] = {0, 1}, t, kap;
    int side, kind;
    dfl_rayset rs = one_ray(o, v, &t, &kap, &side, &kind);
    tfield tf;
    dfl_field u = tfield_make(&tf);
    double s;
    const dfl_cross_opts opt = {3.0, 16, 10};
    /* u = 2|y| is linear along the ray: the interpolation is exact */
    tf.kind = 0;
    cr_assert_eq(dfl_curveprobe_cross(&u, &rs, 0.37, &opt, 1, &s, NULL), DFL_OK);
    cr_expect_float_eq(s, 0.185, 1e-15);
    /* u = y^2: s = sqrt(level); bracket 3 / 16 / 16^10 */
    tf.kind = 1;
    cr_assert_eq(dfl_curveprobe_cross(&u, &rs, 0.5, &opt, 1, &s, NULL), DFL_OK);
    cr_expect(fabs(s - sqrt(0.5)) <= 3.0 / 16 / pow(16, 10), "s %.17g", s);
    /* y (2 - y) = 0.75 at y = 0.5 and 1.5: the first one */
    tf.kind = 2;
    cr_assert_eq(dfl_curveprobe_cross(&u, &rs, 0.75, &opt, 1, &s, NULL), DFL_OK);
    cr_expect_float_eq(s, 0.5, 1e-12);
    /* never reached: max of y (2 - y) is 1 */
    cr_assert_eq(dfl_curveprobe_cross(&u, &rs, 1.5, &opt, 1, &s, NULL), DFL_OK);
    cr_expect(isnan(s));
    /* already above at the origin */
    cr_assert_eq(dfl_curveprobe_cross(&u, &rs, -1.0, &opt, 1, &s, NULL), DFL_OK);
    cr_expect_eq(s, 0.0);
    /* bad options */
    const dfl_cross_opts bad = {3.0, 0, 10};
    cr_expect_eq(dfl_curveprobe_cross(&u, &rs, 0.5, &bad, 1, &s, NULL), DFL_E_INPUT);
    /* many rays in parallel give the same answers */
    enum { N = 300 };
    static double oo[2 * N], vv[2 * N], tt[N], kk[N], ss[N];
    static int sd[N], kd[N];
    for (int i = 0; i < N; i++) {
        oo[2 * i] = i, oo[2 * i + 1] = 0, vv[2 * i] = 0, vv[2 * i + 1] = 1;
        tt[i] = kk[i] = 0, sd[i] = 1, kd[i] = 0;
    }
    dfl_rayset many = {N, oo, vv, tt, kk, sd, kd, 0, 0};
    tf.kind = 1;
    cr_assert_eq(dfl_curveprobe_cross(&u, &many, 0.5, &opt, 2, ss, NULL), DFL_OK);
    for (int i = 0; i < N; i++) cr_expect(fabs(ss[i] - sqrt(0.5)) <= 1e-12);
}

Test(curveprobe, statistics_by_group)
{
    /* rays: 0..3 SIDE (kappa 0, 0, 2, 2 with sides +1, -1, +1, -1),
     * 4 CAP, 5 JOINT, 6 invalid, 7 unresolved, 8 beyond */
    double o[18] = {0}, v[18] = {0}, t[9] = {0};
    double kap[9] = {0, 0, 2, 2, 0, 0, 0, 0, 0};
    int side[9] = {1, -1, 1, -1, 0, 1, 1, 1, 1};
    int kind[9] = {0, 0, 0, 0, DFL_RAY_CAP, DFL_RAY_JOINT, 0, 0, 0};
    dfl_rayset rs = {9, o, v, t, kap, side, kind, 0.0, 1.0};
    const double lv = 0.5;
    /* r = (s - 0.5) / 0.5 */
    double s[9] = {0.55, 0.45, 0.5, 0.75, 0.6, 1.0, 9.0, NAN, 3.0};
    int valid[9] = {1, 1, 1, 1, 1, 1, 0, 1, 1};
    int branch[9] = {1, 1, 1, 1, 1, 1, 1, 1, 0};
    dfl_ray_stats st;
    dfl_curveprobe_stats(&rs, s, valid, branch, lv, &st);
    cr_expect_eq(st.valid, 8);
    cr_expect_eq(st.unresolved, 1);
    cr_expect_eq(st.beyond, 1);
    cr_expect_float_eq(st.merged, 2.0 / 8.0, 1e-15);
    cr_expect_float_eq(st.max, 1.0, 1e-15);
    cr_expect_eq(st.argmax, 5);
    cr_expect_float_eq(st.min, -0.1, 1e-15);
    cr_expect_float_eq(st.mean, (0.1 - 0.1 + 0 + 0.5 + 0.2 + 1.0) / 6, 1e-15);
    cr_expect_float_eq(st.joint_max, 1.0, 1e-15);
    cr_expect_float_eq(st.cap_max, 0.2, 1e-15);
    cr_expect_float_eq(st.side_max, 0.5, 1e-15);
    cr_expect_float_eq(st.flat_mean, 0.0, 1e-15);       /* rays 0, 1 */
    cr_expect_float_eq(st.curved_mean, 0.25, 1e-15);    /* rays 2, 3 */
    cr_expect_float_eq(st.inner_mean, 0.0, 1e-15);    /* ray 2: kappa side > 0 */
    cr_expect_float_eq(st.outer_mean, 0.5, 1e-15);     /* ray 3 */
    /* no valid ray: NAN everywhere, argmax -1 */
    int none[9] = {0};
    dfl_curveprobe_stats(&rs, s, none, NULL, lv, &st);
    cr_expect(st.valid == 0 && isnan(st.max) && isnan(st.mean) && isnan(st.merged));
    cr_expect_eq(st.argmax, (size_t)-1);
}

Test(curveprobe, maximum_on_a_curve)
{
    dfl_bspline c;
    line_curve(-1, 0, 1, 0, &c);
    tfield tf = {3};
    dfl_field u = tfield_make(&tf);
    const double t[5] = {0, 0.25, 0.5, 0.75, 1};
    double mx, tm;
    cr_assert_eq(dfl_curveprobe_max(&u, &c, t, 5, 4, 12, 2, &mx, &tm, NULL), DFL_OK);
    /* 1 - (x - 0.3)^2 on x = 2t - 1: max 1 at t = 0.65 */
    cr_expect_float_eq(mx, 1.0, 1e-14);
    cr_expect_float_eq(tm, 0.65, 1e-7);
    const double bad[3] = {0, 0.5, 0.4};
    cr_expect_eq(dfl_curveprobe_max(&u, &c, bad, 3, 4, 2, 1, &mx, NULL, NULL), DFL_E_INPUT);
    cr_expect_eq(dfl_curveprobe_max(&u, &c, t, 1, 4, 2, 1, &mx, NULL, NULL), DFL_E_INPUT);
    dfl_bspline_free(&c);
}

Test(curveprobe, bad_curves)
{
    dfl_bspline c;
    const double cp[6] = {0, 0, 0, 1, 1, 1};
    cr_assert_eq(dfl_bspline_init(3, 2, 2, cp, NULL, 0, &c, NULL), DFL_OK);
    dfl_rayset rs;
    cr_expect_eq(dfl_curveprobe_rays(&c, 5, 0, NULL, 0, &rs, NULL), DFL_E_INPUT);
    cr_expect_eq(rs.n, 0);
    dfl_bspline_free(&c);
    line_curve(0, 0, 1, 0, &c);
    cr_expect_eq(dfl_curveprobe_rays(&c, 1, 0, NULL, 0, &rs, NULL), DFL_E_INPUT);
    dfl_bspline_free(&c);
}
