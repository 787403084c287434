/* The common field interface (src/field/field.c): the placeholder a
 * validation pass returns in place of a field it did not build. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "field/field.h"

Test(field, placeholder_is_nan_everywhere_with_its_dimension)
{
    for (int dim = 2; dim <= 3; dim++) {
        dfl_field f;
        memset(&f, 0, sizeof f);
        dfl_field_placeholder(dim, &f);
        cr_expect_eq(f.dim, dim);
        cr_expect_str_eq(f.ops->name, "placeholder");
        cr_expect_null(f.ops->jet);
        size_t b = 7;
        cr_expect_eq(dfl_field_bytes(&f, &b), 0, "bytes unknown");
        cr_expect_eq(b, 7);
        double pts[9] = {0, 1, 2, 3, 4, 5, 6, 7, 8};
        double val[3] = {0, 0, 0}, grad[9], sentinel = 12345.0;
        for (int i = 0; i < 9; i++) grad[i] = 0.0;
        double tail[2] = {sentinel, sentinel};
        f.ops->eval(f.ctx, 3 * 2 / dim, pts, val, grad);
        const int m = 3 * 2 / dim;
        for (int i = 0; i < m; i++) {
            cr_expect(isnan(val[i]), "value %d", i);
            for (int j = 0; j < dim; j++) cr_expect(isnan(grad[i * dim + j]), "grad %d.%d", i, j);
        }
        /* nothing past m points is written */
        for (int i = m * dim; i < 9; i++) cr_expect_eq(grad[i], 0.0, "grad[%d] past the batch", i);
        if (m < 3) cr_expect_eq(val[m], 0.0);
        cr_expect_eq(tail[0], sentinel);
        double v1 = dfl_field_eval1(&f, pts, NULL); /* no gradient asked: none written */
        cr_expect(isnan(v1));
        dfl_field_destroy(&f);
        cr_expect_null(f.ops, "destroy zeroes the field");
    }
}
