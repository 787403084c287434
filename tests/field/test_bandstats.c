/* bandstats: hand-computed statistics of tiny samples. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "field/bandstats.h"

Test(bandstats, hand_computed_band)
{
    /* nodes: ref 0 (u 0: zero set), 0.1, 0.2, 0.5 (outside band 0.3) */
    const double ref[4] = {0.0, 0.1, 0.2, 0.5};
    const double u[4] = {0.0, 0.12, 0.15, 7.0};
    const double gu[8] = {0, 0, 0.6, 0.8, 0, 0.5, 3, 4};
    dfl_bandstats b;
    cr_assert_eq(dfl_bandstats_compute(4, 2, u, gu, ref, 0.3, &b, NULL), DFL_OK);
    cr_expect_eq(b.count, 3);
    /* errors 0, 0.02, -0.05 */
    cr_expect_float_eq(b.bias, (0.02 - 0.05) / 3, 1e-15);
    cr_expect_float_eq(b.l1, 0.07 / 3, 1e-15);
    cr_expect_float_eq(b.rms, sqrt((0.02 * 0.02 + 0.05 * 0.05) / 3), 1e-15);
    cr_expect_float_eq(b.linf, 0.05, 1e-15);
    /* relative: 0.02/0.1, -0.05/0.2 over the nodes with ref != 0 */
    cr_expect_float_eq(b.rel_bias, (0.2 - 0.25) / 2, 1e-15);
    /* |grad u| 1 and 0.5 (the u = 0 node is left out) */
    cr_expect_eq(b.gcount, 2);
    cr_expect_float_eq(b.gmin, 0.5, 1e-15);
    cr_expect_float_eq(b.gmax, 1.0, 1e-15);
    cr_expect_float_eq(b.gmean, 0.75, 1e-15);
    /* every node */
    cr_assert_eq(dfl_bandstats_compute(4, 2, u, gu, ref, INFINITY, &b, NULL), DFL_OK);
    cr_expect_eq(b.count, 4);
    cr_expect_float_eq(b.gmax, 5.0, 1e-15);
    /* no gradient: NAN gradient statistics */
    cr_assert_eq(dfl_bandstats_compute(4, 2, u, NULL, ref, 0.3, &b, NULL), DFL_OK);
    cr_expect(isnan(b.gmin) && isnan(b.gmean) && b.gcount == 0);
}

Test(bandstats, empty_band_and_errors)
{
    const double ref[2] = {1.0, 2.0}, u[2] = {1.0, NAN};
    dfl_bandstats b;
    cr_assert_eq(dfl_bandstats_compute(2, 2, u, NULL, ref, 0.5, &b, NULL), DFL_OK);
    cr_expect(b.count == 0 && isnan(b.bias) && isnan(b.linf));
    dfl_err err;
    cr_expect_eq(dfl_bandstats_compute(2, 2, u, NULL, ref, 3.0, &b, &err), DFL_E_NUMERIC);
    cr_expect(strstr(err.msg, "node 1") != NULL, "%s", err.msg);
    cr_expect_eq(dfl_bandstats_compute(2, 2, u, NULL, ref, 0.0, &b, NULL), DFL_E_INPUT);
    cr_expect_eq(dfl_bandstats_compute(2, 2, u, NULL, ref, NAN, &b, NULL), DFL_E_INPUT);
}
