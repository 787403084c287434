/* The read record's validation pass (src/io/config_log.c, io/config.h):
 * dfl_cfg_validating is false until dfl_cfg_validate_only; in a validation
 * pass dfl_cfg_check_used stops the study (DFL_E_INTERNAL, validated)
 * once every key is known, and still names an unknown key first. */
#include <criterion/criterion.h>
#include <string.h>

#include "io/config.h"
#include "util/config_util.h"

Test(config_log, validating_only_after_validate_only)
{
    dfl_cfg *cfg = cfgu_parse("[a]\nk = 1\n");
    cr_expect_not(dfl_cfg_validating(cfg));
    cr_expect_not(dfl_cfg_validated(cfg));
    long v;
    dfl_err err;
    cr_assert_eq(dfl_cfg_int(cfg, "a", "k", 0, 9, &v, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(dfl_cfg_check_used(cfg, &err), DFL_OK, "no pass: check_used goes on");
    dfl_cfg_validate_only(cfg);
    cr_expect(dfl_cfg_validating(cfg));
    cr_expect_not(dfl_cfg_validated(cfg), "validated only once check_used stops it");
    cr_expect_eq(dfl_cfg_check_used(cfg, &err), DFL_E_INTERNAL);
    cr_expect(dfl_cfg_validated(cfg));
    dfl_cfg_free(cfg);
}

Test(config_log, a_validation_pass_names_an_unknown_key_first)
{
    dfl_cfg *cfg = cfgu_parse("[a]\nk = 1\ntypo = 2\n");
    dfl_cfg_validate_only(cfg);
    long v;
    dfl_err err;
    cr_assert_eq(dfl_cfg_int(cfg, "a", "k", 0, 9, &v, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(dfl_cfg_check_used(cfg, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "typo") && strstr(err.msg, "t.ini:3"), "%s", err.msg);
    cr_expect_not(dfl_cfg_validated(cfg));
    cr_expect(dfl_cfg_validating(cfg));
    dfl_cfg_free(cfg);
}

/* a sweep point is a config of its own: a pass is set per copy */
Test(config_log, a_sweep_point_copy_is_not_a_pass_of_its_own)
{
    dfl_cfg *cfg = cfgu_parse("[a]\nk = 1, 2\n");
    dfl_cfg_validate_only(cfg);
    dfl_cfg *pt;
    dfl_err err;
    cr_assert_eq(dfl_cfg_sweep_point(cfg, 1, &pt, &err), DFL_OK, "%s", err.msg);
    cr_expect_not(dfl_cfg_validating(pt));
    dfl_cfg_validate_only(pt);
    cr_expect(dfl_cfg_validating(pt));
    dfl_cfg_free(pt);
    dfl_cfg_free(cfg);
}
