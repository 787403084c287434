/* End-to-end: the sjp10_3d study on a small config.  Expected values are
 * derived:
 *   - uniform level k: 8^k cells, (2^k + 1)^3 base vertices (all vertices
 *     of a uniform grid are base vertices), 8 dofs each;
 *   - a plane's SDF is linear, a tricubic polynomial: reproduced exactly,
 *     the adaptive fit stops at the one-cell mesh (8 base vertices, 64
 *     dofs), every validation error is rounding;
 *   - the sphere's SDF is smooth off its centre: the uniform grid's L1
 *     falls by more than 8 (the h^4 rate is 16) from level 2 to 3. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/e2e_util.h"

static const char *INI3 =
    "[study]\n"
    "name = sjp10_3d\n"
    "cases = sphere_case plane_case\n"
    "fit = fit\n"
    "eps = 1e-2\n"
    "uniform_levels = 2 3\n"
    "[fit]\n"
    "max_level = 3\n"
    "samples = 4\n"
    "lo = -1 -1 -1\n"
    "hi = 1 1 1\n"
    "[sphere_case]\n"
    "shape = sphere\n"
    "lo = -1 -1 -1\n"
    "hi = 1 1 1\n"
    "val_n = 17\n"
    "[plane_case]\n"
    "shape = plane\n"
    "lo = -1 -1 -1\n"
    "hi = 1 1 1\n"
    "val_n = 9\n"
    "midpoints = true\n"
    "cache = true\n"
    "[sphere]\n"
    "kind = sphere\n"
    "center = 0.1 0 0\n"
    "radius = 0.5\n"
    "[plane]\n"
    "kind = plane\n"
    "point = 0 0 0.1\n"
    "normal = 1 2 3\n";

Test(e2e_sjp10_3d, uniform_counts_plane_exact, .timeout = 120)
{
    e2e_table t = {0};
    e2e_ini_table(&t, "t3.ini", INI3, "sjp10_3d", 6);
    const char *csv = t.csv;
    double l1[4] = {0};
    for (long r = 0; r < 6; r++) {
        char *cs = e2e_csv_cell(csv, r, "case"), *m = e2e_csv_cell(csv, r, "method");
        cr_assert(cs && m);
        const double cells = e2e_csv_get(csv, (size_t)r, "cells");
        const double base = e2e_csv_get(csv, (size_t)r, "base_vertices");
        const int k = e2e_sjp10_counts(csv, r, 3);
        if (k >= 0 && strcmp(cs, "sphere_case") == 0)
            l1[k] = e2e_csv_get(csv, (size_t)r, "val_mean");
        if (strcmp(cs, "plane_case") == 0) {
            cr_expect_lt(e2e_csv_get(csv, (size_t)r, "val_max"), 1e-13, "row %ld", r);
            cr_expect_eq(e2e_csv_get(csv, (size_t)r, "val_points"), 9 * 9 * 9 + 8 * 8 * 8);
            if (strcmp(m, "pht") == 0) {
                cr_expect_eq(cells, 1);
                cr_expect_eq(base, 8);
            }
        } else {
            cr_expect_eq(e2e_csv_get(csv, (size_t)r, "val_points"), 17 * 17 * 17);
        }
        free(cs);
        free(m);
    }
    cr_expect_gt(l1[2] / l1[3], 8.0, "sphere L1 %g -> %g", l1[2], l1[3]);
    e2e_rmtree(t.dir);
}

/* The volumes (harness/field_out.h) read back through VTK: the reference
 * is the sphere's SDF at every node, error = value - reference; the
 * T-mesh level as cell data is the fit's level everywhere for a uniform fit
 * (level 2 and 3: constant), within 0..max_level for the adaptive one;
 * each case's collection over its uniform levels lists both, in order. */
Test(e2e_sjp10_3d, volumes_with_tmesh_levels, .timeout = 120)
{
    char f[900];
    e2e_table t = {0};
    e2e_ini_table(&t, "t3.ini",
                  "[study]\nname = sjp10_3d\ncases = sphere_case\nfit = fit\neps = 1e-2\n"
                  "uniform_levels = 2 3\n[fit]\nmax_level = 3\nsamples = 4\nlo = -1 -1 -1\n"
                  "hi = 1 1 1\n[sphere_case]\nshape = sphere\nlo = -1 -1 -1\nhi = 1 1 1\n"
                  "val_n = 17\n[sphere]\nkind = sphere\ncenter = 0.1 0 0\nradius = 0.5\n"
                  "[output]\nvti_n = 11\n",
                  "sjp10_3d", 3);
    const char *cases[][2] = {
        {"volume_sphere_case_pht_dflab_0.vti", "--cell level 0 3"},
        {"volume_sphere_case_uniform_2.vti", "--cell-const level 2"},
        {"volume_sphere_case_uniform_3.vti", "--cell-const level 3"},
        {"volume_sphere_case_uniform.pvd", "--cell level 2 3"},
    };
    for (int i = 0; i < 4; i++) {
        char *o = NULL, opts[200];
        snprintf(f, sizeof f, "%s/%s", t.out, cases[i][0]);
        snprintf(opts, sizeof opts, "--n 11 --sphere 0.1 0 0 0.5 %s", cases[i][1]);
        const int rc = e2e_python_run(t.dir, &o, "tests/e2e/common/check_volume.py '%s' %s", f, opts);
        cr_expect_eq(rc, 0, "%s: %s", f, o ? o : "");
        free(o);
    }
    char *c = e2e_csv_cell(t.csv, 2, "vti");
    cr_expect_str_eq(c, "volume_sphere_case_uniform_3.vti");
    free(c);
    e2e_rmtree(t.dir);
}
