/* End-to-end: the hvb25_accuracy study on small grids, with expected
 * numbers derived, not copied from a run:
 *   - an order-1 proxy grid of a plane is the plane: error 0 (rounding)
 *     under every filter, everywhere;
 *   - an order-2 grid of a sphere (SDF input, analytic curvature, double)
 *     is the sphere: Hermite and trilinear blends of 8 copies of the exact
 *     distance are exact everywhere; nearest is exact in the band;
 *   - half storage at the cell centres: the decoded distance there is
 *     |rounded displacement|, within 2^-11 relative of the exact |d|;
 *   - the trilinear grid peer's worst error on the sphere is at its centre,
 *     sqrt(3) h / 2 (8 samples at (+-h/2)^3 of the cone |x| - r);
 *   - bad keys exit 2 naming the key. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/e2e_util.h"

#define PLANE "[shape]\nkind = plane\npoint = 0.05 -0.1 0.02\nnormal = 1 2 -2\n"
#define SPHERE "[shape]\nkind = sphere\ncenter = 0 0 0\nradius = 0.5\n"
#define TORUS \
    "[shape]\nkind = torus\ncenter = 0 0 0\naxis = 0 0 1\nmajor = 0.6\nminor = 0.25\n"

static long run_text(const char *ini, long nrows, char *csv, size_t ncsv)
{
    e2e_table t = {0};
    const long n = e2e_ini_table(&t, "t.ini", ini, "hvb25_accuracy", nrows);
    snprintf(csv, ncsv, "%s", t.csv);
    return n;
}

Test(e2e_hvb25_accuracy, order1_plane_is_exact, .timeout = 60)
{
    char csv[700];
    run_text("[study]\nname = hvb25_accuracy\nfilters = nearest trilinear hermite\n" PLANE
             "[field]\nkind = proxy\norder = 1\nres = 6\ninput = sdf\nstorage = double\n"
             "[eval]\nn = 23\n",
             3, csv, sizeof csv);
    for (long r = 0; r < 3; r++) {
        cr_expect(e2e_csv_get(csv, r, "linf") < 1e-13, "row %ld: linf %g", r,
                  e2e_csv_get(csv, r, "linf"));
        cr_expect_eq(e2e_csv_get(csv, r, "count"), 23.0 * 23 * 23);
        cr_expect_eq(e2e_csv_get(csv, r, "scalars"), 3.0 * 216);
        /* 3 doubles per cell + one sign byte (the plane has an inside) */
        cr_expect_eq(e2e_csv_get(csv, r, "bytes"), 216.0 * 25);
    }
}

Test(e2e_hvb25_accuracy, order2_sphere_is_exact, .timeout = 60)
{
    char csv[700];
    run_text("[study]\nname = hvb25_accuracy\nfilters = nearest trilinear hermite\nband = 0.1\n" SPHERE
             "[field]\nkind = proxy\norder = 2\nres = 8\ninput = sdf\ncurvature = analytic\n"
             "storage = double\n[eval]\nn = 25\n",
             3, csv, sizeof csv);
    cr_expect(e2e_csv_get(csv, 0, "linf_band") < 1e-10, "nearest in the band: %g",
              e2e_csv_get(csv, 0, "linf_band"));
    cr_expect(e2e_csv_get(csv, 0, "count_band") > 100);
    for (long r = 1; r < 3; r++)
        cr_expect(e2e_csv_get(csv, r, "linf") < 1e-10, "row %ld everywhere: %g", r,
                  e2e_csv_get(csv, r, "linf"));
}

/* Eval nodes = the 8^3 cell centres (lo = -1 + h/2, hi = 1 - h/2, n = 8). */
Test(e2e_hvb25_accuracy, half_storage_at_cell_centres, .timeout = 60)
{
    char csv[700];
    const char *fmt = "[study]\nname = hvb25_accuracy\n" TORUS
                      "[field]\nkind = proxy\norder = 1\nres = 8\ninput = sdf\nstorage = %s\n"
                      "[eval]\nn = 8\nlo = -0.875 -0.875 -0.875\nhi = 0.875 0.875 0.875\n";
    char ini[1024];
    snprintf(ini, sizeof ini, fmt, "half");
    run_text(ini, 1, csv, sizeof csv);
    /* max |d| over the centres: the corner (0.875, 0.875, 0.875) */
    const double c = 0.875, rho = sqrt(2 * c * c) - 0.6, dmax = sqrt(rho * rho + c * c) - 0.25;
    const double linf = e2e_csv_get(csv, 0, "linf");
    cr_expect(linf <= ldexp(1.0, -11) * dmax * (1 + 1e-6), "half: %g > %g", linf,
              ldexp(1.0, -11) * dmax);
    cr_expect(linf > 0, "half must round");
    snprintf(ini, sizeof ini, fmt, "double");
    run_text(ini, 1, csv, sizeof csv);
    cr_expect(e2e_csv_get(csv, 0, "linf") < 1e-14, "double: %g", e2e_csv_get(csv, 0, "linf"));
}

Test(e2e_hvb25_accuracy, trilinear_peer_worst_at_the_sphere_centre, .timeout = 60)
{
    char csv[700];
    run_text("[study]\nname = hvb25_accuracy\n" SPHERE
             "[field]\nkind = gridpeer\nmethod = trilinear0\nres = 8\n[eval]\nn = 17\n",
             1, csv, sizeof csv);
    const double h = 0.25;
    cr_expect(fabs(e2e_csv_get(csv, 0, "worst_err") - sqrt(3.0) * h / 2) < 1e-15);
    cr_expect(fabs(e2e_csv_get(csv, 0, "worst_x")) < 1e-15);
    cr_expect(fabs(e2e_csv_get(csv, 0, "worst_d") + 0.5) < 1e-15);
    /* the centre is medial: its footpoint (r e_x: the sphere's gradient at its
     * centre is the first axis, geom/shape.h) is r |e_x - (1,1,1)/sqrt 3| =
     * r sqrt(2 - 2/sqrt 3) from its cell centre's, in cells of h = r/2 */
    cr_expect(fabs(e2e_csv_get(csv, 0, "worst_jump") - 2 * sqrt(2 - 2 / sqrt(3.0))) < 1e-12);
    cr_expect(e2e_csv_get(csv, 0, "linf_off") < e2e_csv_get(csv, 0, "linf"));
    cr_expect_eq(e2e_csv_get(csv, 0, "scalars"), 512);
}

Test(e2e_hvb25_accuracy, bad_keys_exit_2, .timeout = 60)
{
    e2e_expect_bad_config("[study]\nname = hvb25_accuracy\nfilters = nearest bilinear\n" SPHERE
                          "[field]\nkind = proxy\n",
                          "filters", "bilinear");
    e2e_expect_bad_config("[study]\nname = hvb25_accuracy\n" SPHERE
                          "[field]\nkind = proxy\nres = 0\n",
                          "res", NULL);
    e2e_expect_bad_config("[study]\nname = hvb25_accuracy\n" SPHERE
                          "[field]\nkind = gridpeer\nmethod = taylor3\n",
                          "method", "taylor3");
    e2e_expect_bad_config("[study]\nname = hvb25_accuracy\nfilters = nearest\n" SPHERE
                          "[field]\nkind = gridpeer\n",
                          "filters", "proxy field");
    e2e_expect_bad_config("[study]\nname = hvb25_accuracy\nreference = nope\n" SPHERE
                          "[field]\nkind = exact\n",
                          "reference", "nope");
}

/* [field] clip_radius with [study] filters: every filter's clip is
 * clip_radius cell sizes (0.5 * h, h = 0.25), not its default. */
Test(e2e_hvb25_accuracy, clip_radius_with_filters, .timeout = 60)
{
    char csv[1400];
    run_text("[study]\nname = hvb25_accuracy\nfilters = nearest trilinear hermite\n" SPHERE
             "[field]\nkind = proxy\norder = 1\nres = 8\ninput = sdf\nstorage = double\n"
             "clip_radius = 0.5\n[eval]\nn = 9\n",
             3, csv, sizeof csv);
    for (long r = 0; r < 3; r++)
        cr_expect_eq(e2e_csv_get(csv, r, "clip"), 0.125, "row %ld: clip %g", r,
                     e2e_csv_get(csv, r, "clip"));
}

#define CONE "[shape]\nkind = cone\na = 0 0 -0.6\nb = 0 0 0.6\nra = 0.5\nrb = 0.1\n"

/* A proxy is exact along its footpoint's normal line up to the focal point
 * (decode.h: v = x_c - p is along n, so v_t = v_b = 0, a = v_n and phi =
 * v_n), and a cell centre lies before it (its nearest point is p).  So on
 * the nodes = the 8^3 cell centres, nearest decoding (its clip h is never
 * active there: |x_c - p| - h < |phi|) reproduces the exact SDF of any shape
 * whose footpoints are exact: torus and capped cone, SDF input, order 1 and
 * 2, double storage, to rounding. */
Test(e2e_hvb25_accuracy, torus_and_cone_exact_at_cell_centres, .timeout = 120)
{
    const char *shapes[2] = {TORUS, CONE};
    for (int s = 0; s < 2; s++)
        for (int order = 1; order <= 2; order++) {
            char ini[1024], csv[700];
            snprintf(ini, sizeof ini,
                     "[study]\nname = hvb25_accuracy\nfilters = nearest\n%s"
                     "[field]\nkind = proxy\norder = %d\nres = 8\ninput = sdf\nstorage = double\n"
                     "[eval]\nn = 8\nlo = -0.875 -0.875 -0.875\nhi = 0.875 0.875 0.875\n",
                     shapes[s], order);
            run_text(ini, 1, csv, sizeof csv);
            cr_expect(e2e_csv_get(csv, 0, "linf") < 1e-12, "%s order %d: linf %g",
                      s ? "cone" : "torus", order, e2e_csv_get(csv, 0, "linf"));
            cr_expect_eq(e2e_csv_get(csv, 0, "count"), 512.0);
        }
}

/* The order-2 proxy of a cell centred in the torus's equator plane has its
 * footpoint on the inner or outer equator, where the osculating torus is
 * the torus itself (decode.h 2., DESIGN "Exactness invariants"): with the
 * clip off (a radius of 100 cells never binds inside the box), nearest
 * decoding is exact at every point of those cells, here a 33 x 33 x 33
 * node slab |z| <= h/4 (N = 9, the centre layer k = 4 is z = 0). */
Test(e2e_hvb25_accuracy, torus_order2_exact_in_equator_cells, .timeout = 120)
{
    char csv[700];
    const double h = 2.0 / 9;
    const char *fmt =
        "[study]\nname = hvb25_accuracy\n" TORUS
        "[field]\nkind = proxy\norder = 2\nres = 9\ninput = sdf\ncurvature = analytic\n"
        "storage = double\nfilter = nearest\nclip_radius = 100\n"
        "[eval]\nn = 33\nlo = -1 -1 %.17g\nhi = 1 1 %.17g\n";
    char ini[1024];
    snprintf(ini, sizeof ini, fmt, -h / 4, h / 4);
    run_text(ini, 1, csv, sizeof csv);
    cr_expect(e2e_csv_get(csv, 0, "linf") < 1e-10, "linf %g", e2e_csv_get(csv, 0, "linf"));
    cr_expect_eq(e2e_csv_get(csv, 0, "count"), 33.0 * 33 * 33);
    /* the same slab one layer up (z = h, cells k = 5) is not exact: the
     * tilted osculating tori err like rho^3 */
    snprintf(ini, sizeof ini, fmt, h - h / 4, h + h / 4);
    run_text(ini, 1, csv, sizeof csv);
    cr_expect(e2e_csv_get(csv, 0, "linf") > 1e-6, "off the equator: linf %g",
              e2e_csv_get(csv, 0, "linf"));
}

/* wrong_footpoints is judged by the truth.  Sphere of radius 0.5, SDF
 * input, 8^3 cells of size 0.25 (tol 0.025): without noise every stored
 * footpoint is the exact one (0 wrong).  noise_at = (0.55, 0.05, 0.05) is
 * cell (6, 4, 4), centre (0.625, 0.125, 0.125), d = 0.149; moving its
 * footpoint p by 1 puts p' either off the sphere or, on it, at chord 1 from
 * p, so |x_c - p'| >= 1 - d = 0.85 > d + tol: exactly 1 wrong, and the
 * method's certificate (uncertified) still says 0. */
Test(e2e_hvb25_accuracy, wrong_footpoints_by_the_truth, .timeout = 60)
{
    char csv[700];
    run_text("[study]\nname = hvb25_accuracy\n" SPHERE
             "[field]\nkind = proxy\norder = 1\nres = 8\ninput = sdf\nnoise = 0, 1\n"
             "noise_at = 0.55 0.05 0.05\n[eval]\nn = 9\n",
             2, csv, sizeof csv);
    cr_expect_eq(e2e_csv_get(csv, 0, "wrong_footpoints"), 0);
    cr_expect_eq(e2e_csv_get(csv, 1, "wrong_footpoints"), 1);
    cr_expect_eq(e2e_csv_get(csv, 1, "uncertified"), 0);
}
