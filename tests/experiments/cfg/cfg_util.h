/* Helper shared by the config-glue tests (header-only, static). */
#ifndef DFL_TESTS_CFG_UTIL_H
#define DFL_TESTS_CFG_UTIL_H

#include <criterion/criterion.h>

#include "io/config.h"

/* The config text as file `file` (named in messages); asserts that it
 * parses.  Free with dfl_cfg_free. */
static inline dfl_cfg *tu_cfg(const char *file, const char *text)
{
    dfl_cfg *cfg;
    dfl_err err;
    cr_assert_eq(dfl_cfg_parse_string(file, text, &cfg, &err), DFL_OK, "%s", err.msg);
    return cfg;
}

#endif
