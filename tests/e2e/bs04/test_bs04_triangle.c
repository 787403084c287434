/* End-to-end: the bs04_triangle study (Figs. 9-10).  Expected values: the
 * vertex angle from the geometry, the in-plane limit of |grad t| recomputed
 * here from the edge planes by finite differences of the R0-conjunction
 * (independent of the study's closed form), the prism bound
 * |grad h| in [min(1, .), max(1, .)], and a brute-force maximum of |grad h|
 * over random sphere points by finite differences of h. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "core/vec.h"
#include "io/config.h"
#include "rfunc/tri3d.h"
#include "util/e2e_util.h"

#define CFG "configs/paper/bs04/bs04_triangle.ini"

/* R0-conjunction of the two edge planes at vertex A (inward unit normals
 * m1, m2 in the plane), as a function of the in-plane point. */
static double t2(const double *m1, const double *m2, const double *A, const double *x)
{
    double w[3] = {x[0] - A[0], x[1] - A[1], x[2] - A[2]};
    const double p1 = dfl_vec3_dot(w, m1), p2 = dfl_vec3_dot(w, m2);
    return p1 + p2 - sqrt(p1 * p1 + p2 * p2);
}

Test(e2e_bs04_triangle, vertex_gradient_vs_theory, .timeout = 60)
{
    char out[512], csv[700];
    e2e_run_table(CFG,
                  "--set 'study.vertices=0' --set study.radii=1e-3 --set study.samples=800 "
                  "--set study.slice_n=10 --set study.theory_samples=20000",
                  "bs04_triangle", 2, out, sizeof out, csv, sizeof csv);
    /* the triangle of the config */
    dfl_cfg *cfg;
    dfl_err err;
    double *v;
    size_t n;
    cr_assert_eq(dfl_cfg_load(CFG, &cfg, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_cfg_points(cfg, "field", "triangles", 3, 3, &v, &n, &err), DFL_OK, "%s",
                 err.msg);
    dfl_cfg_free(cfg);
    const double *A = v, *B = v + 3, *C = v + 6;
    double ab[3], ac[3], nrm[3], m1[3], m2[3];
    for (int j = 0; j < 3; j++) ab[j] = B[j] - A[j], ac[j] = C[j] - A[j];
    const double alpha =
        acos(dfl_vec3_dot(ab, ac) / sqrt(dfl_vec3_dot(ab, ab) * dfl_vec3_dot(ac, ac)));
    dfl_vec3_cross(ab, ac, nrm);
    const double nn = sqrt(dfl_vec3_dot(nrm, nrm));
    for (int j = 0; j < 3; j++) nrm[j] /= nn;
    /* inward edge normals: n x AB points to C; AC x n points to B */
    dfl_vec3_cross(nrm, ab, m1);
    dfl_vec3_cross(ac, nrm, m2);
    const double l1 = sqrt(dfl_vec3_dot(m1, m1)), l2 = sqrt(dfl_vec3_dot(m2, m2));
    for (int j = 0; j < 3; j++) m1[j] /= l1, m2[j] /= l2;
    cr_assert(dfl_vec3_dot(m1, ac) > 0 && dfl_vec3_dot(m2, ab) > 0);
    /* the in-plane limit: max and min of |grad t| by central differences
     * over the exterior of the angle (t is homogeneous of degree 1) */
    double e1[3], e2[3];
    for (int j = 0; j < 3; j++) e1[j] = ab[j] / sqrt(dfl_vec3_dot(ab, ab));
    dfl_vec3_cross(nrm, e1, e2);
    double qmax = 0, qmin = INFINITY;
    for (int i = 0; i < 20000; i++) {
        const double th = alpha + (2 * DFL_PI - alpha) * (i + 0.5) / 20000.0;
        double x[3], g[3] = {0, 0, 0};
        for (int j = 0; j < 3; j++) x[j] = A[j] + cos(th) * e1[j] + sin(th) * e2[j];
        const double hs = 1e-6;
        for (int a = 0; a < 2; a++) {
            const double *dir = a ? e2 : e1;
            double xp[3], xm[3];
            for (int j = 0; j < 3; j++) xp[j] = x[j] + hs * dir[j], xm[j] = x[j] - hs * dir[j];
            const double d = (t2(m1, m2, A, xp) - t2(m1, m2, A, xm)) / (2 * hs);
            for (int j = 0; j < 3; j++) g[j] += d * dir[j];
        }
        const double q = sqrt(dfl_vec3_dot(g, g));
        qmax = fmax(qmax, q);
        qmin = fmin(qmin, q);
    }
    double plane[2][2];
    for (long r = 0; r < 2; r++) {
        char *trim = e2e_csv_cell(csv, r, "tri_trim");
        const int prism = strcmp(trim, "prism") == 0;
        cr_assert_str_eq(trim, r == 0 ? "prism" : "conditional");
        free(trim);
        const double rad = e2e_csv_get(csv, (size_t)r, "radius");
        cr_expect(fabs(e2e_csv_get(csv, (size_t)r, "alpha_deg") - alpha * 180 / DFL_PI) < 1e-9);
        cr_expect(fabs(e2e_csv_get(csv, (size_t)r, "theory_plane_max") - qmax) < 1e-4,
                  "theory max %.9g vs %.9g", e2e_csv_get(csv, (size_t)r, "theory_plane_max"), qmax);
        cr_expect(fabs(e2e_csv_get(csv, (size_t)r, "theory_plane_min") - qmin) < 1e-4);
        /* measured on the plane: the limit up to O(r / height) */
        plane[r][0] = e2e_csv_get(csv, (size_t)r, "plane_grad_min");
        plane[r][1] = e2e_csv_get(csv, (size_t)r, "plane_grad_max");
        cr_expect(fabs(plane[r][1] - qmax) < 5 * rad, "plane max %.9g vs %.9g", plane[r][1], qmax);
        cr_expect(fabs(plane[r][0] - qmin) < 5 * rad);
        const double gmin = e2e_csv_get(csv, (size_t)r, "grad_min");
        const double gmax = e2e_csv_get(csv, (size_t)r, "grad_max");
        if (prism) /* |grad h|^2 is a weighted mean of 1 and |grad t|^2 */
            cr_expect(gmin >= fmin(1.0, qmin) - 5 * rad && gmax <= fmax(1.0, qmax) + 5 * rad,
                      "prism: [%g, %g] vs [%g, %g]", gmin, gmax, fmin(1.0, qmin), fmax(1.0, qmax));
        /* brute force: random sphere points, |grad h| by central differences */
        dfl_rfunc_tri_opts o = dfl_rfunc_tri_defaults();
        o.trim = prism ? DFL_RFUNC_TRI_PRISM : DFL_RFUNC_TRI_CONDITIONAL;
        dfl_rfunc_tri tri;
        cr_assert_eq(dfl_rfunc_tri_init(A, B, C, &o, &tri, NULL), DFL_OK);
        uint64_t rng = 7;
        double bmax = 0, bmin = INFINITY;
        for (int i = 0; i < 20000; i++) {
            const double z = 2 * dfl_rng_splitmix(&rng, 0.0, 1.0) - 1;
            const double ph = 2 * DFL_PI * dfl_rng_splitmix(&rng, 0.0, 1.0), s = sqrt(1 - z * z);
            const double x[3] = {A[0] + rad * s * cos(ph), A[1] + rad * s * sin(ph), A[2] + rad * z};
            const double w[3] = {x[0] - A[0], x[1] - A[1], x[2] - A[2]};
            if (fabs(dfl_vec3_dot(w, nrm)) < 1e-3 * rad)
                continue; /* h = |f| has a kink on the plane */
            double g[3];
            const double hs = 1e-7 * rad;
            for (int j = 0; j < 3; j++) {
                double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]};
                xp[j] += hs;
                xm[j] -= hs;
                g[j] = (dfl_rfunc_tri_eval(&tri, xp, NULL) - dfl_rfunc_tri_eval(&tri, xm, NULL)) /
                       (xp[j] - xm[j]);
            }
            const double q = sqrt(dfl_vec3_dot(g, g));
            bmax = fmax(bmax, q);
            bmin = fmin(bmin, q);
        }
        cr_expect(fabs(bmax - gmax) < 2e-2, "%s: brute-force max %g vs %g", prism ? "prism" : "cond",
                  bmax, gmax);
        cr_expect(fabs(bmin - gmin) < 2e-2, "brute-force min %g vs %g", bmin, gmin);
    }
    /* in the plane (f = 0) the conditional term a f^k vanishes: same values */
    cr_expect(fabs(plane[0][0] - plane[1][0]) < 1e-12 && fabs(plane[0][1] - plane[1][1]) < 1e-12);
    free(v);
}

Test(e2e_bs04_triangle, bad_input)
{
    e2e_expect_bad_config("[study]\nname = bs04_triangle\nslices = z 0.1\n[field]\nkind = rfunc\n"
                          "triangles = 0 0 0; 1 0 0; 2 0 0\n",
                          "[field] triangles", "degenerate");
    e2e_expect_bad_config("[study]\nname = bs04_triangle\nslices = z 0.1\nvertices = 0 3\n"
                          "[field]\nkind = rfunc\ntriangles = 0 0 0; 1 0 0; 0 1 0\n",
                          "[study] vertices", NULL);
    e2e_expect_bad_config("[study]\nname = bs04_triangle\nslices = z 0.1\n[field]\nkind = rfunc\n"
                          "triangles = 0 0 0; 1 0 0; 0 1 0; 0 0 1; 1 0 1; 0 1 1\n",
                          "[field] of bs04_triangle", NULL);
}
