/* io/config dfl_cfg_reject's message is "<where>: <formatted message>"
 * for a key of the file, a --set key and a key that is absent, with the
 * status DFL_E_INPUT, a NULL err, and truncation of a long message. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

#include "experiments/cfg/cfg_util.h"

Test(config_reject, reject_names_where_the_key_was_written)
{
    dfl_cfg *cfg = tu_cfg("r.ini", "[study]\nband = -2\n\n[grid]\nn = 3\n");
    dfl_err err = {0};
    cr_assert_eq(dfl_cfg_reject(cfg, "study", "band", &err, "expected band > 0, got %g", -2.0),
                 DFL_E_INPUT);
    cr_expect_eq(err.code, DFL_E_INPUT);
    cr_expect_str_eq(err.msg, "r.ini:2: [study] band: expected band > 0, got -2");
    /* exactly dfl_cfg_where's text, then ": " and the message */
    char w[512], want[1024];
    snprintf(want, sizeof want, "%s: n = %d is odd",
             dfl_cfg_where(cfg, "grid", "n", w, sizeof w), 3);
    cr_assert_eq(dfl_cfg_reject(cfg, "grid", "n", &err, "n = %d is odd", 3), DFL_E_INPUT);
    cr_expect_str_eq(err.msg, want);
    cr_expect(strstr(err.msg, "r.ini:5: [grid] n") == err.msg, "%s", err.msg);
    /* a key that is not in the file still names the file and the key */
    cr_assert_eq(dfl_cfg_reject(cfg, "grid", "lo", &err, "missing"), DFL_E_INPUT);
    cr_expect_str_eq(err.msg, "r.ini: [grid] lo: missing");
    /* err may be NULL */
    cr_expect_eq(dfl_cfg_reject(cfg, "grid", "n", NULL, "x"), DFL_E_INPUT);
    dfl_cfg_free(cfg);
}

Test(config_reject, reject_truncates_to_the_message_size)
{
    dfl_cfg *cfg = tu_cfg("t.ini", "[s]\nk = 1\n");
    char longmsg[3000];
    memset(longmsg, 'x', sizeof longmsg - 1);
    longmsg[sizeof longmsg - 1] = '\0';
    dfl_err err = {0};
    cr_assert_eq(dfl_cfg_reject(cfg, "s", "k", &err, "%s", longmsg), DFL_E_INPUT);
    cr_expect_eq(strlen(err.msg), DFL_ERR_MSG_MAX - 1);
    cr_expect(strncmp(err.msg, "t.ini:2: [s] k: xxx", 19) == 0, "%.40s", err.msg);
    dfl_cfg_free(cfg);
}
