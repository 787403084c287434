/* The rfunc dfl_field: gradients vs finite differences, jets vs values,
 * finiteness everywhere, heterogeneous sets (bs04 Fig. 13a). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "rfunc/region.h"
#include "rfunc/rfield.h"
#include "rfunc/segment.h"
#include "rfunc_util.h"

static const dfl_rfunc_trim trims[4] = {DFL_RFUNC_TRIM_DISK, DFL_RFUNC_TRIM_DISK_SMOOTH,
                                        DFL_RFUNC_TRIM_STRIP, DFL_RFUNC_TRIM_STRIP_SMOOTH};
static const dfl_rfunc_join joins[3] = {DFL_RFUNC_REQUIV, DFL_RFUNC_RCONJ,
                                        DFL_RFUNC_REQUIV_CORRECTED};

static const double poly2[] = {0.0, 0.0, 1.0, 0.2, 1.6, 1.0, 2.5, 1.1, 3.0, 0.3};
static const double poly3[] = {0.0, 0.0, 0.0, 1.0, 0.2, 0.3, 1.5, 1.0, -0.2, 2.2, 1.3, 0.4};

/* Gradient of eval against central differences with step delta = 1e-6 u.
 * Truncation ~ delta^2 |u'''| / 6 with |u'''| <~ p^2 / u^2 near the parts,
 * i.e. ~ 1e-12 p^2 / 6 relative; rounding ~ eps u / delta = 2e-10; a
 * second-derivative jump of eq. 4 at t = 0 (h is C1 there) adds at most
 * ~ delta |jump u''| ~ 1e-6.  Tolerance: 1e-5 (|grad u| + 1e-3). */
static void check_fd(const dfl_field *f, const double *lo, const double *hi, int npts,
                     uint64_t seed, const char *what)
{
    uint64_t rng = seed;
    const int dim = f->dim;
    for (int i = 0; i < npts; i++) {
        double x[3] = {0, 0, 0};
        for (int j = 0; j < dim; j++) x[j] = tu_uniform(&rng, lo[j], hi[j]);
        double g[3], gf[3];
        const double u = dfl_field_eval1(f, x, g);
        cr_assert(isfinite(u) && u >= 0, "%s: u = %g", what, u);
        if (u < 1e-6) continue;
        tu_fd_grad(f, x, 1e-6 * u, gf);
        for (int j = 0; j < dim; j++)
            cr_assert(fabs(g[j] - gf[j]) <= 1e-5 * (tu_norm(dim, g) + 1e-3),
                      "%s: x = (%g %g %g) grad[%d] = %.12g, FD %.12g", what, x[0], x[1], x[2], j,
                      g[j], gf[j]);
        /* The jet's first derivative is the directional derivative. */
        double dir[3] = {0, 0, 0};
        for (int j = 0; j < dim; j++) dir[j] = tu_uniform(&rng, -1, 1);
        dfl_jet jt;
        dfl_err err;
        cr_assert_eq(dfl_field_jet(f, x, dir, 3, &jt, &err), DFL_OK, "%s: %s", what, err.msg);
        double dd = 0;
        for (int j = 0; j < dim; j++) dd += g[j] * dir[j];
        cr_assert(fabs(dfl_jet_coeff(&jt, 0) - u) <= 1e-12 * u, "%s: jet value", what);
        cr_assert(fabs(dfl_jet_deriv(&jt, 1) - dd) <= 1e-9 * (tu_norm(dim, g) * tu_norm(dim, dir)) + 1e-14,
                  "%s: jet d1 %.15g vs grad.dir %.15g", what, dfl_jet_deriv(&jt, 1), dd);
    }
}

Test(rfunc_field, gradients_vs_finite_differences)
{
    const double lo2[2] = {-1.0, -1.0}, hi2[2] = {4.0, 2.5};
    const double lo3[3] = {-1.0, -1.0, -1.0}, hi3[3] = {3.0, 2.0, 1.5};
    char what[128];
    for (int it = 0; it < 4; it++)
        for (int ij = 0; ij < 3; ij++)
            for (int p = joins[ij] == DFL_RFUNC_RCONJ ? 2 : 1; p <= 12; p++)
                for (int kind = 0; kind < 3; kind++) {
                    dfl_field f;
                    dfl_err err;
                    const int dim = kind == 2 ? 3 : 2;
                    const bool closed = kind == 1;
                    cr_assert_eq(dfl_rfield_polyline(dim, dim == 2 ? poly2 : poly3, dim == 2 ? 5 : 4,
                                                     closed, joins[ij], p, trims[it], &f, &err),
                                 DFL_OK, "%s", err.msg);
                    snprintf(what, sizeof what, "%dD %s %s %s p=%d", dim, closed ? "closed" : "open",
                             dfl_rfunc_join_name(joins[ij]), dfl_rfunc_trim_name(trims[it]), p);
                    check_fd(&f, dim == 2 ? lo2 : lo3, dim == 2 ? hi2 : hi3, 40,
                             1000 + 97 * it + 13 * ij + p + 1000 * kind, what);
                    dfl_field_destroy(&f);
                }
}

/* Triangles (both trims, eq. 4 and 5) and the heterogeneous 2D set. */
Test(rfunc_field, triangles_and_heterogeneous_fd)
{
    const double A[3] = {0, 0, 0}, B[3] = {1, 0, 0.1}, C[3] = {0.2, 1, 0}, D[3] = {1.2, 0.9, 0.5};
    const double lo3[3] = {-0.5, -0.5, -0.7}, hi3[3] = {1.7, 1.5, 1.2};
    char what[96];
    for (int opt = 0; opt < 4; opt++)
        for (int ij = 0; ij < 3; ij++)
            for (int p = 2; p <= 12; p += 5) {
                dfl_rfunc_tri_opts o = dfl_rfunc_tri_defaults();
                o.trim = opt & 1 ? DFL_RFUNC_TRI_PRISM : DFL_RFUNC_TRI_CONDITIONAL;
                o.smooth = opt >> 1;
                dfl_rfield *r;
                dfl_field f;
                cr_assert_eq(dfl_rfield_new(3, joins[ij], p, &r, NULL), DFL_OK);
                cr_assert_eq(dfl_rfield_add_triangle(r, A, B, C, &o, NULL), DFL_OK);
                cr_assert_eq(dfl_rfield_add_triangle(r, B, D, C, &o, NULL), DFL_OK);
                cr_assert_eq(dfl_rfield_add_vertex(r, B, 0, 1, NULL), DFL_OK);
                cr_assert_eq(dfl_rfield_add_vertex(r, C, 0, 1, NULL), DFL_OK);
                cr_assert_eq(dfl_rfield_finish(&r, &f, NULL), DFL_OK);
                snprintf(what, sizeof what, "triangles opt %d %s p=%d", opt,
                         dfl_rfunc_join_name(joins[ij]), p);
                check_fd(&f, lo3, hi3, 60, 77 + opt + 7 * ij + p, what);
                dfl_field_destroy(&f);
            }
    const double sq[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    const double sa[2] = {1.5, 0.2}, sb[2] = {2.5, 0.9}, pt[2] = {0.5, 1.8};
    const double lo2[2] = {-1, -1}, hi2[2] = {3.5, 3};
    for (int ij = 0; ij < 3; ij++)
        for (int p = 2; p <= 12; p += 5) {
            dfl_rfield *r;
            dfl_field f;
            cr_assert_eq(dfl_rfield_new(2, joins[ij], p, &r, NULL), DFL_OK);
            cr_assert_eq(dfl_rfield_add_region(r, sq, 4, NULL), DFL_OK);
            cr_assert_eq(dfl_rfield_add_segment(r, sa, sb, DFL_RFUNC_TRIM_DISK, NULL), DFL_OK);
            cr_assert_eq(dfl_rfield_add_point(r, pt, NULL), DFL_OK);
            cr_assert_eq(dfl_rfield_finish(&r, &f, NULL), DFL_OK);
            snprintf(what, sizeof what, "heterogeneous %s p=%d", dfl_rfunc_join_name(joins[ij]), p);
            check_fd(&f, lo2, hi2, 200, 5 + p + ij, what);
            dfl_field_destroy(&f);
        }
}

/* Fig. 13a: a square region, a segment and a point.  u = 0 on all three
 * (the whole square), u > 0 elsewhere, and R-equivalence of order p is
 * normalized to order p at a regular boundary point of the square (the
 * region field is the exact distance to the edge line there, region.h) and
 * at the point (|x - c| is exact): coefficient of s^(p+1) = -C/p with C the
 * sum of the other parts' h^-p (join.h). */
Test(rfunc_field, heterogeneous_set_fig13a)
{
    const double sq[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    const double sa[2] = {1.5, 0.2}, sb[2] = {2.5, 0.9}, pt[2] = {0.5, 1.8};
    dfl_rfunc_seg seg;
    dfl_rfunc_region reg;
    dfl_rfunc_point rp;
    cr_assert_eq(dfl_rfunc_seg_init(2, sa, sb, DFL_RFUNC_TRIM_DISK, &seg, NULL), DFL_OK);
    cr_assert_eq(dfl_rfunc_region_init(sq, 4, &reg, NULL), DFL_OK);
    cr_assert_eq(dfl_rfunc_point_init(2, pt, &rp, NULL), DFL_OK);
    /* The region field: the exact distance to the unit square outside it. */
    uint64_t rng = 3;
    for (int i = 0; i < 200; i++) {
        const double x[2] = {tu_uniform(&rng, -2, 3), tu_uniform(&rng, -2, 3)};
        const double dx = fmax(0, fmax(-x[0], x[0] - 1)), dy = fmax(0, fmax(-x[1], x[1] - 1));
        cr_assert_float_eq(dfl_rfunc_region_eval(&reg, x, NULL), hypot(dx, dy), 1e-15);
    }
    for (int p = 1; p <= 12; p++) {
        dfl_rfield *r;
        dfl_field f;
        cr_assert_eq(dfl_rfield_new(2, DFL_RFUNC_REQUIV, p, &r, NULL), DFL_OK);
        cr_assert_eq(dfl_rfield_add_region(r, sq, 4, NULL), DFL_OK);
        cr_assert_eq(dfl_rfield_add_segment(r, sa, sb, DFL_RFUNC_TRIM_DISK, NULL), DFL_OK);
        cr_assert_eq(dfl_rfield_add_point(r, pt, NULL), DFL_OK);
        cr_assert_eq(dfl_rfield_finish(&r, &f, NULL), DFL_OK);
        for (int i = 0; i < 100; i++) {
            const double x[2] = {tu_uniform(&rng, 0, 1), tu_uniform(&rng, 0, 1)};
            cr_assert_eq(dfl_field_eval1(&f, x, NULL), 0.0);
        }
        cr_assert_eq(dfl_field_eval1(&f, pt, NULL), 0.0);
        cr_assert_eq(dfl_field_eval1(&f, sa, NULL), 0.0);
        const double off[2] = {1.2, 1.4};
        cr_assert(dfl_field_eval1(&f, off, NULL) > 0);
        /* Edge x = 1 at y = 0.5, outward normal (1, 0). */
        const double xe[2] = {1.0, 0.5}, ne[2] = {1.0, 0.0};
        const double C1 = pow(dfl_rfunc_seg_eval(&seg, xe, NULL), -p) +
                          pow(dfl_rfunc_point_eval(&rp, xe, NULL), -p);
        /* At the point, any direction. */
        const double dp[2] = {0.6, -0.8};
        const double C2 = pow(dfl_rfunc_seg_eval(&seg, pt, NULL), -p) +
                          pow(dfl_rfunc_region_eval(&reg, pt, NULL), -p);
        const double *xs[2] = {xe, pt}, *ds[2] = {ne, dp};
        const double Cs[2] = {C1, C2};
        for (int k = 0; k < 2; k++) {
            dfl_jet j;
            dfl_err err;
            cr_assert_eq(dfl_field_jet(&f, xs[k], ds[k], 14, &j, &err), DFL_OK, "%s", err.msg);
            cr_assert_float_eq(dfl_jet_deriv(&j, 1), 1.0, 1e-14);
            for (int m = 2; m <= p; m++) cr_assert(fabs(dfl_jet_coeff(&j, m)) <= 1e-9 * Cs[k]);
            cr_assert_float_eq(dfl_jet_coeff(&j, p + 1), -Cs[k] / p, 1e-9 * Cs[k] / p,
                               "p=%d k=%d: %g vs %g", p, k, dfl_jet_coeff(&j, p + 1), -Cs[k] / p);
        }
        dfl_field_destroy(&f);
    }
    dfl_rfunc_region_free(&reg);
    const double bad[8] = {0, 0, 1, 0, 0.2, 0.2, 0, 1}; /* not convex */
    cr_assert_eq(dfl_rfunc_region_init(bad, 4, &reg, NULL), DFL_E_INPUT);
}

/* No NaN or Inf anywhere: vertices, points on segments, on the trim
 * boundaries, next to the set (1e-12 away), the bounding box, far away (up
 * to 1e8 times the size); every join, trim and p; values and gradients, and
 * jets in several directions. */
static void check_finite(const dfl_field *f, const double *x, const char *what, int expect_zero)
{
    double g[3] = {0, 0, 0};
    const double u = dfl_field_eval1(f, x, g);
    cr_assert(isfinite(u) && u >= 0, "%s: u = %g", what, u);
    for (int j = 0; j < f->dim; j++) cr_assert(isfinite(g[j]), "%s: grad", what);
    if (expect_zero) cr_assert(u <= 1e-15, "%s: u = %g on the set", what, u);
    const double dirs[4][3] = {{1, 0, 0}, {0.6, -0.8, 0}, {0, 0.3, 1}, {-1, -1, -1}};
    for (int k = 0; k < 4; k++) {
        dfl_jet jt;
        dfl_err err;
        cr_assert_eq(dfl_field_jet(f, x, dirs[k], 8, &jt, &err), DFL_OK, "%s: %s", what, err.msg);
        for (int m = 0; m <= 8; m++)
            cr_assert(!isnan(dfl_jet_deriv(&jt, m)) && isfinite(dfl_jet_deriv(&jt, m)),
                      "%s: jet d%d = %g", what, m, dfl_jet_deriv(&jt, m));
    }
}

Test(rfunc_field, finite_everywhere)
{
    char what[160];
    for (int it = 0; it < 4; it++)
        for (int ij = 0; ij < 3; ij++) {
            const int ps[4] = {1, 2, 7, 12};
            for (int ip = 0; ip < 4; ip++)
                for (int kind = 0; kind < 3; kind++) {
                    const int p = ps[ip];
                    if (joins[ij] == DFL_RFUNC_RCONJ && p == 1) continue;
                    const int dim = kind == 2 ? 3 : 2;
                    const double *v = dim == 2 ? poly2 : poly3;
                    const size_t n = dim == 2 ? 5 : 4;
                    const bool closed = kind == 1;
                    dfl_field f;
                    cr_assert_eq(dfl_rfield_polyline(dim, v, n, closed, joins[ij], p, trims[it], &f,
                                                     NULL),
                                 DFL_OK);
                    snprintf(what, sizeof what, "%dD %s %s %s p=%d", dim, closed ? "closed" : "open",
                             dfl_rfunc_join_name(joins[ij]), dfl_rfunc_trim_name(trims[it]), p);
                    const size_t nseg = closed ? n : n - 1;
                    for (size_t s = 0; s < nseg; s++) {
                        const double *a = v + s * dim, *b = v + ((s + 1) % n) * dim;
                        double x[3] = {0, 0, 0};
                        const double ls[5] = {0.0, 0.25, 0.5, 0.75, 1.0};
                        for (int il = 0; il < 5; il++) {
                            for (int j = 0; j < dim; j++) x[j] = a[j] + ls[il] * (b[j] - a[j]);
                            check_finite(&f, x, what, 1);
                            x[1] += 1e-12;
                            check_finite(&f, x, what, 0);
                        }
                        /* On the trim circle (disk) / strip line, off the segment. */
                        double c[3] = {0, 0, 0}, d = 0;
                        for (int j = 0; j < dim; j++) {
                            c[j] = 0.5 * (a[j] + b[j]);
                            d += (b[j] - a[j]) * (b[j] - a[j]);
                        }
                        d = sqrt(d);
                        const double nx = -(b[1] - a[1]) / d, ny = (b[0] - a[0]) / d;
                        for (int j = 0; j < dim; j++) x[j] = c[j];
                        x[0] += 0.5 * d * nx;
                        x[1] += 0.5 * d * ny;
                        check_finite(&f, x, what, 0);
                        for (int j = 0; j < dim; j++) x[j] = a[j];
                        x[0] += 0.3 * nx;
                        x[1] += 0.3 * ny;
                        check_finite(&f, x, what, 0);
                    }
                    const double far[6] = {-1.0, 1e3, -1e6, 1e8, 0.5, -3e7};
                    for (int i = 0; i < 6; i++)
                        for (int k = 0; k < 3; k++) {
                            double x[3] = {far[i], far[(i + k + 1) % 6], far[(i + 2 * k + 2) % 6]};
                            check_finite(&f, x, what, 0);
                        }
                    dfl_field_destroy(&f);
                }
        }
}
