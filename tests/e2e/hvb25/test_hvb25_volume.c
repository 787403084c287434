/* End-to-end: the volumes of hvb25_accuracy ([output] vti, vti_n), read
 * back through VTK (tests/e2e/common/check_volume.py), with what is
 * expected derived:
 *   - the reference is the sphere's SDF |x| - r at every node (its
 *     absolute value for an unsigned decoding), error = value - reference
 *     and grad_norm = |gradient| at every node;
 *   - an order-2 grid of a sphere decoded by Hermite is the sphere
 *     (test_hvb25_accuracy.c): |error| is rounding in the whole volume;
 *   - a sweep over res writes one collection per filter whose data sets
 *     are the points' volumes at times 0, 1;
 *   - without vti_n the volume is the error grid up to 33 nodes per axis;
 *   - vti = false writes none and leaves the vti column empty. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/e2e_util.h"

#define SPHERE "[shape]\nkind = sphere\ncenter = 0 0 0\nradius = 0.5\n"

static void check(const char *dir, const char *file, const char *opts)
{
    char *out = NULL;
    const int rc = e2e_python_run(dir, &out, "tests/e2e/common/check_volume.py '%s' %s", file, opts);
    cr_expect_eq(rc, 0, "%s: %s", file, out ? out : "");
    free(out);
}

/* One decoding of the sphere, as [field] gives it, into t's results: one
 * row, its volume volume.vti. */
static void run_one(e2e_table *t, const char *name, const char *field_and_more)
{
    char ini[1024];
    snprintf(ini, sizeof ini, "[study]\nname = hvb25_accuracy\n" SPHERE "%s", field_and_more);
    e2e_ini_table(t, name, ini, "hvb25_accuracy", 1);
}

Test(e2e_hvb25_volume, sphere_volumes_and_sweep_collection, .timeout = 120)
{
    char f[900];
    e2e_table t = {0};
    e2e_ini_table(&t, "t.ini",
                  "[study]\nname = hvb25_accuracy\nfilters = nearest hermite\n" SPHERE
                  "[field]\nkind = proxy\norder = 2\nres = 6, 8\ninput = sdf\n"
                  "curvature = analytic\nsigned = true\n"
                  "storage = double\n[eval]\nn = 21\n[output]\nvti_n = 13\n",
                  "hvb25_accuracy", 4);
    const char *dir = t.dir, *out = t.out;
    for (int pt = 0; pt < 2; pt++) {
        snprintf(f, sizeof f, "%s/volume_hermite_pt%03d.vti", out, pt);
        check(dir, f, "--n 13 --sphere 0 0 0 0.5 --max-error 1e-12");
        snprintf(f, sizeof f, "%s/volume_nearest_pt%03d.vti", out, pt);
        check(dir, f, "--n 13 --sphere 0 0 0 0.5");
    }
    char *c = e2e_csv_cell(t.csv, 1, "vti");
    cr_expect_str_eq(c, "volume_hermite_pt000.vti");
    free(c);
    snprintf(f, sizeof f, "%s/volume_hermite.pvd", out);
    check(dir, f, "--n 13 --sphere 0 0 0 0.5 --max-error 1e-12");
    char *pvd = e2e_slurp(f);
    cr_assert(pvd);
    cr_expect(strstr(pvd, "timestep=\"1\" group=\"\" part=\"0\" file=\"volume_hermite_pt001.vti\""),
              "%s", pvd);
    free(pvd);
    e2e_rmtree(t.dir);
}

Test(e2e_hvb25_volume, unsigned_reference_default_n_and_off, .timeout = 120)
{
    char f[900];
    e2e_table t = {0};
    /* volume.vti at the error grid (n = 17 < 33); signed = false: the
     * default, as the paper */
    run_one(&t, "t.ini",
            "[field]\nkind = proxy\norder = 1\nres = 6\ninput = sdf\nsigned = false\n"
            "storage = double\n[eval]\nn = 17\n");
    snprintf(f, sizeof f, "%s/volume.vti", t.out);
    check(t.dir, f, "--n 17 --sphere 0 0 0 0.5 --unsigned");
    /* an error grid above the cap: the volume has 33 nodes per axis */
    run_one(&t, "cap.ini",
            "[field]\nkind = proxy\norder = 1\nres = 4\ninput = sdf\nstorage = double\n"
            "[eval]\nn = 41\n");
    snprintf(f, sizeof f, "%s/volume.vti", t.out);
    check(t.dir, f, "--n 33 --sphere 0 0 0 0.5 --unsigned");
    run_one(&t, "off.ini",
            "[field]\nkind = proxy\norder = 1\nres = 6\ninput = sdf\nstorage = double\n"
            "[eval]\nn = 9\n[output]\nvti = false\n");
    snprintf(f, sizeof f, "%s/volume.vti", t.out);
    FILE *fp = fopen(f, "r");
    cr_expect_null(fp, "vti = false wrote %s", f);
    if (fp) fclose(fp);
    char *c = e2e_csv_cell(t.csv, 0, "vti");
    cr_expect_str_eq(c, "");
    free(c);
    e2e_rmtree(t.dir);
}
