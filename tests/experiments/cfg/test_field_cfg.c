/* The field-kind table: every row is reachable by its name, an unknown
 * kind is refused with the accepted names, and dfl_field_from_cfg hands
 * the section to the row's factory. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

#include "cfg_util.h"
#include "cfg/field_cfg.h"
#include "cfg/rfunc_cfg.h"
#include "io/config.h"

Test(field_cfg, table_rows)
{
    size_t n;
    const dfl_field_kind *kinds = dfl_field_kinds(&n);
    cr_assert_geq(n, 2); /* other modules add rows (tests/experiments/cfg/test_<kind>_cfg.c check theirs) */
    cr_expect_str_eq(kinds[0].name, "exact");
    cr_expect_str_eq(kinds[1].name, "rfunc");
    cr_expect_eq(kinds[1].build, dfl_rfunc_field_from_cfg);
    cr_expect_str_eq(kinds[2].name, "normalized");
    cr_expect_eq(kinds[2].build, dfl_rfunc_normalized_from_cfg);
    int have_pht = 0;
    for (size_t i = 0; i < n; i++)
        if (strcmp(kinds[i].name, "pht") == 0) have_pht = 1;
    cr_expect(have_pht, "the pht row");
    for (size_t i = 0; i < n; i++) {
        char text[64];
        snprintf(text, sizeof text, "[field]\nkind = %s\n", kinds[i].name);
        dfl_cfg *cfg = tu_cfg("f.ini", text);
        const dfl_field_kind *k = NULL;
        cr_expect_eq(dfl_field_kind_from_cfg(cfg, "field", &k, NULL), DFL_OK);
        cr_expect_eq(k, &kinds[i]);
        dfl_cfg_free(cfg);
    }
}

Test(field_cfg, unknown_kind_lists_the_rows)
{
    dfl_cfg *cfg = tu_cfg("f.ini", "[field]\nkind = magic\n");
    const dfl_field_kind *k = NULL;
    dfl_err err;
    cr_expect_eq(dfl_field_kind_from_cfg(cfg, "field", &k, &err), DFL_E_INPUT);
    cr_expect_null(k);
    cr_expect(strstr(err.msg, "f.ini:2") && strstr(err.msg, "exact|rfunc") &&
                  strstr(err.msg, "magic"),
              "%s", err.msg);
    dfl_field f;
    cr_expect_eq(dfl_field_from_cfg(cfg, "field", &f, &err), DFL_E_INPUT);
    dfl_cfg_free(cfg);
    cfg = tu_cfg("f.ini", "[field]\njoin = requiv\n");
    cr_expect_eq(dfl_field_kind_from_cfg(cfg, "field", &k, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "kind"), "%s", err.msg);
    dfl_cfg_free(cfg);
}

/* Each kind's factory builds the field: exact from [shape], rfunc from
 * its own keys. */
Test(field_cfg, factories_build)
{
    dfl_cfg *cfg = tu_cfg("f.ini", "[field]\nkind = exact\n"
                                   "[shape]\nkind = circle\ncenter = 0 0\nradius = 1\n");
    dfl_field f;
    dfl_err err;
    cr_assert_eq(dfl_field_from_cfg(cfg, "field", &f, &err), DFL_OK, "%s", err.msg);
    const double x[2] = {2.0, 0.0};
    cr_expect_float_eq(dfl_field_eval1(&f, x, NULL), 1.0, 1e-15);
    dfl_field_destroy(&f);
    dfl_cfg_free(cfg);
    cfg = tu_cfg("f.ini", "[field]\nkind = rfunc\nvertices = 0 0; 1 0\n");
    cr_assert_eq(dfl_field_from_cfg(cfg, "field", &f, &err), DFL_OK, "%s", err.msg);
    const double y[2] = {0.5, 0.0};
    cr_expect_eq(dfl_field_eval1(&f, y, NULL), 0.0);
    dfl_field_destroy(&f);
    dfl_cfg_free(cfg);
}
