/* proxy/input.c: the interface's checks and the NAN curvature. */
#include <criterion/criterion.h>
#include <math.h>

#include "proxy/input.h"

Test(input, empty_input_and_nan_curvature)
{
    dfl_proxy_input in = {0};
    dfl_err err;
    cr_assert_eq(dfl_proxy_input_query(&in, 0, NULL, 0, NULL, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_proxy_input_query(NULL, 0, NULL, 0, NULL, &err), DFL_E_INPUT);
    dfl_proxy_input_free(&in);
    dfl_proxy_input_free(NULL);
    dfl_curvature c;
    dfl_curvature_set_nan(&c);
    cr_assert(isnan(c.k1) && isnan(c.k2) && isnan(c.K) && isnan(c.H));
    for (int j = 0; j < 3; j++) cr_assert(isnan(c.e1[j]) && isnan(c.e2[j]) && isnan(c.n[j]));
}
