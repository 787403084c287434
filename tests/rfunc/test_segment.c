/* bs04 sec. 2.1 / 3.1 / 3.2.1: fields of single segments and triangles. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "rfunc/region.h"
#include "rfunc/rfield.h"
#include "rfunc/segment.h"
#include "rfunc/tri3d.h"
#include "rfunc/trim.h"
#include "rfunc_util.h"

static const dfl_rfunc_trim all_trims[4] = {DFL_RFUNC_TRIM_DISK, DFL_RFUNC_TRIM_DISK_SMOOTH,
                                            DFL_RFUNC_TRIM_STRIP, DFL_RFUNC_TRIM_STRIP_SMOOTH};

static int smooth_trim(dfl_rfunc_trim t)
{
    return t == DFL_RFUNC_TRIM_DISK_SMOOTH || t == DFL_RFUNC_TRIM_STRIP_SMOOTH;
}

/* eq. 2 and eq. 3 against their textbook forms at random points. */
Test(rfunc_segment, line_and_disk_functions_match_eq2_eq3)
{
    const double a[2] = {0.3, -0.2}, b[2] = {1.7, 0.9};
    dfl_rfunc_seg s;
    cr_assert_eq(dfl_rfunc_seg_init(2, a, b, DFL_RFUNC_TRIM_DISK, &s, NULL), DFL_OK);
    const double d = hypot(b[0] - a[0], b[1] - a[1]);
    const double xc = 0.5 * (a[0] + b[0]), yc = 0.5 * (a[1] + b[1]);
    uint64_t rng = 1;
    for (int i = 0; i < 200; i++) {
        const double x[2] = {tu_uniform(&rng, -2, 3), tu_uniform(&rng, -2, 3)};
        const double f2 = ((x[0] - a[0]) * (b[1] - a[1]) - (x[1] - a[1]) * (b[0] - a[0])) / d;
        const double t3 =
            ((d / 2) * (d / 2) - (x[0] - xc) * (x[0] - xc) - (x[1] - yc) * (x[1] - yc)) / d;
        cr_assert_float_eq(dfl_rfunc_seg_line(&s, x, NULL), f2, 1e-14);
        cr_assert_float_eq(dfl_rfunc_seg_trim(&s, x, NULL), t3, 1e-13);
        /* eq. 4 literally. */
        const double h4 = sqrt(f2 * f2 + (fabs(t3) - t3) * (fabs(t3) - t3) / 4);
        cr_assert_float_eq(dfl_rfunc_seg_eval(&s, x, NULL), h4, 1e-13 * (1 + h4));
    }
    /* First-order normalization of t on the trim circle: |grad t| = 1. */
    for (int i = 0; i < 16; i++) {
        const double th = 2 * DFL_PI * i / 16;
        const double x[2] = {xc + 0.5 * d * cos(th), yc + 0.5 * d * sin(th)};
        double g[2];
        cr_assert(fabs(dfl_rfunc_seg_trim(&s, x, g)) < 1e-14);
        cr_assert_float_eq(hypot(g[0], g[1]), 1.0, 1e-14);
    }
}

/* eq. 5 literally (the smooth trim), and the strip trim's |grad t| = 1 on its
 * two lines. */
Test(rfunc_segment, smooth_composition_and_strip_trim)
{
    const double a[2] = {-1.0, 0.5}, b[2] = {0.5, -0.25};
    dfl_rfunc_seg s5, st;
    cr_assert_eq(dfl_rfunc_seg_init(2, a, b, DFL_RFUNC_TRIM_DISK_SMOOTH, &s5, NULL), DFL_OK);
    cr_assert_eq(dfl_rfunc_seg_init(2, a, b, DFL_RFUNC_TRIM_STRIP, &st, NULL), DFL_OK);
    uint64_t rng = 7;
    for (int i = 0; i < 200; i++) {
        const double x[2] = {tu_uniform(&rng, -3, 3), tu_uniform(&rng, -3, 3)};
        const double f = dfl_rfunc_seg_line(&s5, x, NULL), t = dfl_rfunc_seg_trim(&s5, x, NULL);
        const double g = sqrt(t * t + f * f * f * f) - t;
        const double h5 = sqrt(f * f + g * g / 4);
        /* The literal form cancels for t > 0; compare to its own rounding. */
        cr_assert(fabs(dfl_rfunc_seg_eval(&s5, x, NULL) - h5) <= 1e-12 * (1 + fabs(t)));
    }
    const double d = hypot(b[0] - a[0], b[1] - a[1]);
    const double e[2] = {(b[0] - a[0]) / d, (b[1] - a[1]) / d}, n[2] = {e[1], -e[0]};
    for (int i = -5; i <= 5; i++) {
        double g[2];
        const double xa[2] = {a[0] + 0.3 * i * n[0], a[1] + 0.3 * i * n[1]};
        cr_assert(fabs(dfl_rfunc_seg_trim(&st, xa, g)) < 1e-14);
        cr_assert_float_eq(hypot(g[0], g[1]), 1.0, 1e-13);
        /* t > 0 strictly between the lines, < 0 outside. */
        const double xin[2] = {xa[0] + 0.1 * e[0], xa[1] + 0.1 * e[1]};
        const double xout[2] = {xa[0] - 0.1 * e[0], xa[1] - 0.1 * e[1]};
        cr_assert(dfl_rfunc_seg_trim(&st, xin, NULL) > 0);
        cr_assert(dfl_rfunc_seg_trim(&st, xout, NULL) < 0);
    }
}

/* h = 0 on the segment (exactly at the end points), the exact distance near
 * interior points for eq. 4, positive elsewhere. */
Test(rfunc_segment, zero_on_segment_and_distance_nearby)
{
    const double a[2] = {0.0, 0.0}, b[2] = {2.0, 1.0};
    const double d = sqrt(5.0);
    const double n[2] = {1.0 / d, -2.0 / d};
    for (int k = 0; k < 4; k++) {
        dfl_rfunc_seg s;
        cr_assert_eq(dfl_rfunc_seg_init(2, a, b, all_trims[k], &s, NULL), DFL_OK);
        cr_assert_eq(dfl_rfunc_seg_eval(&s, a, NULL), 0.0);
        cr_assert_eq(dfl_rfunc_seg_eval(&s, b, NULL), 0.0);
        for (int i = 1; i < 20; i++) {
            const double l = i / 20.0;
            const double x[2] = {l * b[0], l * b[1]};
            double g[2];
            const double h = dfl_rfunc_seg_eval(&s, x, g);
            cr_assert(h <= 1e-15 && isfinite(g[0]) && isfinite(g[1]));
            /* Near interior points: eq. 4 is |f|; eq. 5 differs by
             * |f|^7 / (32 t^2) (trim.h), far below 1e-12 at delta = 1e-3. */
            const double delta = 1e-3;
            const double y[2] = {x[0] + delta * n[0], x[1] + delta * n[1]};
            cr_assert_float_eq(dfl_rfunc_seg_eval(&s, y, NULL), delta, 1e-15 + 1e-12 * delta);
        }
        /* Off the segment on its line, beyond b: positive. */
        const double x[2] = {3.0, 1.5};
        cr_assert(dfl_rfunc_seg_eval(&s, x, NULL) > 0.1);
    }
}

/* Normalization order of one segment from jets along the normal: eq. 4
 * gives h = |f| (all derivatives beyond the first vanish exactly); eq. 5
 * gives h = s + s^7/(32 t^2) - s^11/(64 t^4) + O(s^13) (trim.h).  With the
 * disk, t = t0 - s^2/d exactly along the normal (the linear term
 * 2 n.(x - c)/d vanishes on the segment), t^-2 = t0^-2 sum_k (k+1)
 * (s^2/(d t0))^k, so the s^7, s^9, s^11 coefficients are 1/(32 t0^2),
 * 2/(32 d t0^3), 3/(32 d^2 t0^4) - 1/(64 t0^4); with the strip t is
 * constant along the normal: 1/(32 t0^2) and -1/(64 t0^4) only. */
Test(rfunc_segment, normalization_order_by_trim)
{
    const double a[2] = {-0.4, 0.1}, b[2] = {1.1, 0.7};
    const double d = hypot(b[0] - a[0], b[1] - a[1]);
    const double n[2] = {(b[1] - a[1]) / d, -(b[0] - a[0]) / d};
    const int K = 12;
    for (int k = 0; k < 4; k++) {
        dfl_rfunc_seg s;
        cr_assert_eq(dfl_rfunc_seg_init(2, a, b, all_trims[k], &s, NULL), DFL_OK);
        for (int i = 1; i < 10; i++) {
            const double l = i / 10.0;
            const double x[2] = {a[0] + l * (b[0] - a[0]), a[1] + l * (b[1] - a[1])};
            for (int sgn = -1; sgn <= 1; sgn += 2) {
                const double dir[2] = {sgn * n[0], sgn * n[1]};
                dfl_jet j;
                dfl_err err;
                cr_assert_eq(dfl_rfunc_seg_jet(&s, x, dir, K, &j, &err), DFL_OK, "%s", err.msg);
                cr_assert(dfl_jet_order(&j) >= K);
                cr_assert_eq(dfl_jet_coeff(&j, 0), 0.0);
                cr_assert_float_eq(dfl_jet_deriv(&j, 1), 1.0, 1e-14);
                const double t0 = dfl_rfunc_seg_trim(&s, x, NULL);
                for (int m = 2; m <= K; m++) {
                    double expect = 0.0;
                    if (smooth_trim(all_trims[k]) && m == 7) expect = 1.0 / (32 * t0 * t0);
                    if (all_trims[k] == DFL_RFUNC_TRIM_DISK_SMOOTH && m == 9)
                        expect = 2.0 / (32 * d * t0 * t0 * t0);
                    if (smooth_trim(all_trims[k]) && m == 11)
                        expect = -1.0 / (64 * t0 * t0 * t0 * t0);
                    if (all_trims[k] == DFL_RFUNC_TRIM_DISK_SMOOTH && m == 11)
                        expect += 3.0 / (32 * d * d * t0 * t0 * t0 * t0);
                    const double c = dfl_jet_coeff(&j, m);
                    cr_assert(fabs(c - expect) <= 1e-9 * (1 + fabs(expect)),
                              "trim %s l=%g coeff %d = %.17g, expected %.17g",
                              dfl_rfunc_trim_name(all_trims[k]), l, m, c, expect);
                }
            }
        }
    }
}

/* The R-equivalence of one segment is that segment's field, in values,
 * gradients and jets (u = h_min * 1^(-1/p) exactly). */
Test(rfunc_segment, requiv_of_one_segment_is_the_segment)
{
    const double v[4] = {0.2, 0.1, 1.3, -0.6};
    for (int k = 0; k < 4; k++)
        for (int p = 1; p <= 12; p++) {
            dfl_field f;
            dfl_rfunc_seg s;
            cr_assert_eq(dfl_rfunc_seg_init(2, v, v + 2, all_trims[k], &s, NULL), DFL_OK);
            cr_assert_eq(dfl_rfield_polyline(2, v, 2, false, DFL_RFUNC_REQUIV, p, all_trims[k], &f,
                                             NULL),
                         DFL_OK);
            uint64_t rng = 11;
            for (int i = 0; i < 50; i++) {
                const double x[2] = {tu_uniform(&rng, -2, 3), tu_uniform(&rng, -2, 2)};
                double gu[2], gh[2];
                const double u = dfl_field_eval1(&f, x, gu);
                const double h = dfl_rfunc_seg_eval(&s, x, gh);
                cr_assert_eq(u, h);
                cr_assert_float_eq(gu[0], gh[0], 1e-15);
                cr_assert_float_eq(gu[1], gh[1], 1e-15);
                /* Ray length h / (4 |grad h|): well inside the series'
                 * radius of convergence, so that the coefficients of
                 * h^-p decay and rounding stays relative to the largest. */
                const double th = tu_uniform(&rng, 0, 2 * DFL_PI);
                const double len = 0.25 * h / fmax(1.0, hypot(gh[0], gh[1]));
                const double dir[2] = {len * cos(th), len * sin(th)};
                dfl_jet ju, jh;
                cr_assert_eq(dfl_field_jet(&f, x, dir, 8, &ju, NULL), DFL_OK);
                cr_assert_eq(dfl_rfunc_seg_jet(&s, x, dir, 8, &jh, NULL), DFL_OK);
                /* u = ((h/c)^-p)^(-1/p) c: equal up to the rounding of two
                 * Miller recurrences, ~ (p+1) K eps relative to the largest
                 * coefficient (p <= 12, K = 8: below 1e-12). */
                double big = 0.0;
                for (int m = 0; m <= 8; m++) big = fmax(big, fabs(dfl_jet_coeff(&jh, m)));
                for (int m = 0; m <= 8; m++)
                    cr_assert(fabs(dfl_jet_coeff(&ju, m) - dfl_jet_coeff(&jh, m)) <= 1e-12 * big,
                              "trim %d p %d m %d: %.17g vs %.17g", k, p, m,
                              dfl_jet_coeff(&ju, m), dfl_jet_coeff(&jh, m));
            }
            dfl_field_destroy(&f);
        }
}

/* 3D space-curve segment: f = sqrt(s^2 + q^2) is the distance to the line;
 * h is the distance near interior points in every normal direction, and the
 * jets along any normal are exact (eq. 4) resp. order 6 (eq. 5). */
Test(rfunc_segment, space_curve_segment)
{
    const double a[3] = {0.1, -0.3, 0.2}, b[3] = {1.0, 0.4, -0.5};
    double e[3], d = 0;
    for (int j = 0; j < 3; j++) d += (b[j] - a[j]) * (b[j] - a[j]);
    d = sqrt(d);
    for (int j = 0; j < 3; j++) e[j] = (b[j] - a[j]) / d;
    uint64_t rng = 5;
    for (int k = 0; k < 4; k++) {
        dfl_rfunc_seg s;
        cr_assert_eq(dfl_rfunc_seg_init(3, a, b, all_trims[k], &s, NULL), DFL_OK);
        for (int i = 0; i < 40; i++) {
            const double l = tu_uniform(&rng, 0.1, 0.9);
            double x[3], w[3], nrm = 0, de = 0;
            for (int j = 0; j < 3; j++) {
                x[j] = a[j] + l * (b[j] - a[j]);
                w[j] = tu_uniform(&rng, -1, 1);
                de += w[j] * e[j];
            }
            for (int j = 0; j < 3; j++) w[j] -= de * e[j];
            nrm = tu_norm(3, w);
            for (int j = 0; j < 3; j++) w[j] /= nrm;
            cr_assert(dfl_rfunc_seg_eval(&s, x, NULL) <= 1e-15);
            double y[3];
            for (int j = 0; j < 3; j++) y[j] = x[j] + 1e-3 * w[j];
            cr_assert_float_eq(dfl_rfunc_seg_line(&s, y, NULL), 1e-3, 1e-15);
            cr_assert_float_eq(dfl_rfunc_seg_eval(&s, y, NULL), 1e-3, 1e-15);
            dfl_jet jt;
            cr_assert_eq(dfl_rfunc_seg_jet(&s, x, w, 10, &jt, NULL), DFL_OK);
            cr_assert_float_eq(dfl_jet_deriv(&jt, 1), 1.0, 1e-14);
            for (int m = 2; m <= 6; m++) cr_assert(fabs(dfl_jet_coeff(&jt, m)) <= 1e-12);
            const double t0 = dfl_rfunc_seg_trim(&s, x, NULL);
            const double c7 = smooth_trim(all_trims[k]) ? 1.0 / (32 * t0 * t0) : 0.0;
            cr_assert(fabs(dfl_jet_coeff(&jt, 7) - c7) <= 1e-9 * (1 + c7));
        }
    }
}

/* Triangles: h = 0 on the triangle, |f| near interior points; jets along the
 * normal exact (eq. 4) or order 6 with d7 = 7!/(32 t0^2) (eq. 5), for both
 * trims.  The conditional trim equals the prism trim on the carrier plane
 * (eq. 15 with f = 0) and differs off it. */
Test(rfunc_segment, triangle_fields)
{
    const double A[3] = {0.0, 0.0, 0.1}, B[3] = {1.0, 0.2, 0.0}, C[3] = {0.3, 0.9, 0.4};
    dfl_rfunc_tri_opts opts[4] = {dfl_rfunc_tri_defaults(), dfl_rfunc_tri_defaults(),
                                  dfl_rfunc_tri_defaults(), dfl_rfunc_tri_defaults()};
    opts[1].smooth = 1;
    opts[2].trim = DFL_RFUNC_TRI_PRISM;
    opts[3].trim = DFL_RFUNC_TRI_PRISM;
    opts[3].smooth = 1;
    dfl_rfunc_tri tri[4];
    for (int k = 0; k < 4; k++) cr_assert_eq(dfl_rfunc_tri_init(A, B, C, &opts[k], &tri[k], NULL), DFL_OK);
    const double *n = tri[0].n;
    uint64_t rng = 3;
    for (int i = 0; i < 60; i++) {
        double u = tu_uniform(&rng, 0.05, 0.9), v = tu_uniform(&rng, 0.05, 0.9);
        if (u + v > 0.95) {
            u = 0.95 - u;
            v = 0.95 - v;
            if (u < 0.02 || v < 0.02) continue;
        }
        double x[3], y[3];
        for (int j = 0; j < 3; j++) {
            x[j] = A[j] + u * (B[j] - A[j]) + v * (C[j] - A[j]);
            y[j] = x[j] + 1e-3 * n[j];
        }
        /* Same trim value on the plane for both trims. */
        cr_assert_float_eq(dfl_rfunc_tri_trim_eval(&tri[0], x, NULL),
                           dfl_rfunc_tri_trim_eval(&tri[2], x, NULL), 1e-14);
        for (int k = 0; k < 4; k++) {
            cr_assert(dfl_rfunc_tri_eval(&tri[k], x, NULL) <= 1e-15);
            cr_assert_float_eq(dfl_rfunc_tri_eval(&tri[k], y, NULL), 1e-3, 1e-15);
            dfl_jet jt;
            dfl_err err;
            cr_assert_eq(dfl_rfunc_tri_jet(&tri[k], x, n, 10, &jt, &err), DFL_OK, "%s", err.msg);
            cr_assert_float_eq(dfl_jet_deriv(&jt, 1), 1.0, 1e-14);
            for (int m = 2; m <= 6; m++) cr_assert(fabs(dfl_jet_coeff(&jt, m)) <= 1e-12);
            const double t0 = dfl_rfunc_tri_trim_eval(&tri[k], x, NULL);
            const double c7 = opts[k].smooth ? 1.0 / (32 * t0 * t0) : 0.0;
            cr_assert(fabs(dfl_jet_coeff(&jt, 7) - c7) <= 1e-8 * (1 + c7), "k=%d c7=%g vs %g", k,
                      dfl_jet_coeff(&jt, 7), c7);
        }
    }
    /* Off the plane above an edge midpoint the conditional term lowers t. */
    double x[3];
    for (int j = 0; j < 3; j++) x[j] = 0.5 * (A[j] + B[j]) + 0.3 * n[j];
    cr_assert(dfl_rfunc_tri_trim_eval(&tri[0], x, NULL) < dfl_rfunc_tri_trim_eval(&tri[2], x, NULL));
    /* Degenerate input. */
    const double D[3] = {2.0, 0.4, -0.1}; /* on the line A-B */
    dfl_rfunc_tri bad;
    cr_assert_eq(dfl_rfunc_tri_init(A, B, D, &opts[0], &bad, NULL), DFL_E_INPUT);
    dfl_rfunc_tri_opts odd = opts[0];
    odd.k = 3;
    cr_assert_eq(dfl_rfunc_tri_init(A, B, C, &odd, &bad, NULL), DFL_E_INPUT);
}

Test(rfunc_segment, degenerate_segment_is_input_error)
{
    const double a[2] = {1.0, 2.0};
    dfl_rfunc_seg s;
    dfl_err err;
    cr_assert_eq(dfl_rfunc_seg_init(2, a, a, DFL_RFUNC_TRIM_DISK, &s, &err), DFL_E_INPUT);
    cr_assert(strstr(err.msg, "degenerate") != NULL);
}

/* Degenerate means |b - a| <= 1e-12 times the size of the coordinates
 * (header), not only |b - a| = 0: at 1e6 a length of 1e-7 (1e-13
 * relative) is refused, a length of 1e-5 (1e-11 relative) accepted. */
Test(rfunc_segment, degenerate_is_relative_to_the_coordinates)
{
    const double a[3] = {1e6, -2e5, 3e5}, b_short[3] = {1e6 + 1e-7, -2e5, 3e5},
                 b_ok[3] = {1e6 + 1e-5, -2e5, 3e5};
    dfl_rfunc_seg s;
    dfl_err err;
    for (int dim = 2; dim <= 3; dim++) {
        cr_expect_eq(dfl_rfunc_seg_init(dim, a, b_short, DFL_RFUNC_TRIM_DISK, &s, &err),
                     DFL_E_INPUT, "dim %d", dim);
        cr_expect(strstr(err.msg, "degenerate") != NULL, "%s", err.msg);
        cr_expect_eq(dfl_rfunc_seg_init(dim, a, b_ok, DFL_RFUNC_TRIM_DISK, &s, &err), DFL_OK,
                     "dim %d", dim);
    }
}
