#include "util/config_util.h"

#include <criterion/criterion.h>
#include <string.h>

dfl_cfg *cfgu_parse(const char *text)
{
    dfl_cfg *c = NULL;
    dfl_err err;
    dfl_status st = dfl_cfg_parse_string("t.ini", text, &c, &err);
    cr_assert_eq(st, DFL_OK, "%s", err.msg);
    return c;
}

dfl_cfg *cfgu_load(const char *path)
{
    dfl_cfg *c = NULL;
    dfl_err err;
    dfl_status st = dfl_cfg_load(path, &c, &err);
    cr_assert_eq(st, DFL_OK, "%s", err.msg);
    return c;
}

void cfgu_expect_fail(const char *path, const char *const *want, int nwant, char *msg)
{
    dfl_cfg *c = (dfl_cfg *)&c; /* must be reset to NULL */
    dfl_err err;
    dfl_err_clear(&err);
    dfl_status st = dfl_cfg_load(path, &c, &err);
    cr_assert_eq(st, DFL_E_INPUT, "%s: status %d, message '%s'", path, (int)st, err.msg);
    cr_assert_null(c, "%s: a failed load must leave no config", path);
    for (int i = 0; i < nwant; i++)
        cr_assert(strstr(err.msg, want[i]), "%s: message '%s' lacks '%s'", path, err.msg, want[i]);
    if (msg) memcpy(msg, err.msg, sizeof err.msg);
}

const char *cfgu_string(const dfl_cfg *c, const char *sec, const char *key)
{
    const char *v = NULL;
    dfl_err err;
    cr_assert_eq(dfl_cfg_string(c, sec, key, &v, &err), DFL_OK, "%s", err.msg);
    return v;
}
