/* End-to-end: the bs04_triedge study (Fig. 11).  Expected values: the 2D
 * theory of bs04 Sec. 2.3 evaluated here with exact distances to the two
 * triangles (geom/polygonize.h's point-triangle distance, gradients by
 * central differences), and the bisector values 2^(-1/p) sin(theta/2) and
 * 2^(-1/p). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/vec.h"
#include "geom/polygonize.h"
#include "util/e2e_util.h"

#define CFG "configs/paper/bs04/bs04_triedge.ini"

Test(e2e_bs04_triedge, circle_vs_exact_distance_theory, .timeout = 60)
{
    char out[512], csv[700];
    e2e_run_table(CFG,
                  "--set study.dihedral=90 --set study.p=2 --set study.samples=720 "
                  "--set study.slice_n=10",
                  "bs04_triedge", 1, out, sizeof out, csv, sizeof csv);
    const double th = DFL_PI / 2, r = e2e_csv_get(csv, 0, "radius"), z0 = 0.35;
    /* the geometry the study documents (apex = 1 0.5, section = 0.35) */
    const double P[3] = {0, 0, 0}, Q[3] = {0, 0, 1}, R1[3] = {1, 0, 0.5},
                 R2[3] = {cos(th), sin(th), 0.5};
    double tmin = INFINITY, tmax = 0;
    for (int i = 0; i < 720; i++) {
        const double ph = 2 * DFL_PI * (i + 0.5) / 720;
        const double x[3] = {r * cos(ph), r * sin(ph), z0};
        double h[2], g[2][3];
        for (int t = 0; t < 2; t++) {
            const double *R = t ? R2 : R1;
            h[t] = dfl_point_triangle_dist(x, P, Q, R);
            for (int j = 0; j < 3; j++) {
                double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]};
                xp[j] += 1e-9;
                xm[j] -= 1e-9;
                g[t][j] = (dfl_point_triangle_dist(xp, P, Q, R) -
                           dfl_point_triangle_dist(xm, P, Q, R)) / (xp[j] - xm[j]);
            }
        }
        /* eq. 6 with p = 2 and its partials (u/h_i)^(p+1) */
        const double u = 1 / sqrt(1 / (h[0] * h[0]) + 1 / (h[1] * h[1]));
        const double F1 = pow(u / h[0], 3), F2 = pow(u / h[1], 3);
        double gu[3];
        for (int j = 0; j < 3; j++) gu[j] = F1 * g[0][j] + F2 * g[1][j];
        const double q = sqrt(gu[0] * gu[0] + gu[1] * gu[1] + gu[2] * gu[2]);
        tmin = fmin(tmin, q);
        tmax = fmax(tmax, q);
    }
    cr_expect(fabs(e2e_csv_get(csv, 0, "theory_min") - tmin) < 1e-5, "theory min %.9g vs %.9g",
              e2e_csv_get(csv, 0, "theory_min"), tmin);
    cr_expect(fabs(e2e_csv_get(csv, 0, "theory_max") - tmax) < 1e-5);
    cr_expect(fabs(e2e_csv_get(csv, 0, "grad_min") - tmin) < 5 * r);
    cr_expect(fabs(e2e_csv_get(csv, 0, "grad_max") - tmax) < 5 * r);
    /* bs04: |grad u| <= 1, minimum on the bisector */
    cr_expect(e2e_csv_get(csv, 0, "grad_max") <= 1 + 5 * r);
    cr_expect(fabs(e2e_csv_get(csv, 0, "argmin_deg") - 45) <= 0.5);
    cr_expect(e2e_csv_get(csv, 0, "eq13_violation") <= 5 * r);
    const double in = sqrt(0.5) * sin(th / 2), outv = sqrt(0.5);
    cr_expect(fabs(e2e_csv_get(csv, 0, "theory_bisector_in") - in) < 1e-15);
    cr_expect(fabs(e2e_csv_get(csv, 0, "theory_bisector_out") - outv) < 1e-15);
    cr_expect(fabs(e2e_csv_get(csv, 0, "bisector_in") - in) < 5 * r);
    cr_expect(fabs(e2e_csv_get(csv, 0, "bisector_out") - outv) < 5 * r);
    /* csv, config, manifest, the triangles, one slice (vti + exr) */
    cr_expect_eq(e2e_count_entries(out), 6);
}

Test(e2e_bs04_triedge, bad_input)
{
    e2e_expect_bad_config("[study]\nname = bs04_triedge\ndihedral = 180\nslices = z 0.35\n",
                          "[study] dihedral", "coplanar");
    e2e_expect_bad_config("[study]\nname = bs04_triedge\ndihedral = 90\nslices = z 0.35\n"
                          "join = rconj\np = 1\n",
                          "[study] p", NULL);
}
