/* Helpers for tests of src/io/config (and of code that reads configs).
 *
 *   cfgu_parse(text)               text parsed as "t.ini"; asserts success
 *   cfgu_load(path)                dfl_cfg_load; asserts success
 *   cfgu_expect_fail(path, want)   dfl_cfg_load fails with DFL_E_INPUT, message holds want[]
 *   cfgu_string(c, sec, key)       raw value of an existing single-valued key
 */
#ifndef DFL_TESTS_CONFIG_UTIL_H
#define DFL_TESTS_CONFIG_UTIL_H

#include "io/config.h"

/* The configuration parsed from text under the name "t.ini" (fatal
 * assertion on failure; the caller frees it). */
dfl_cfg *cfgu_parse(const char *text);
/* dfl_cfg_load(path) (fatal assertion on failure; the caller frees it). */
dfl_cfg *cfgu_load(const char *path);
/* Expects dfl_cfg_load(path) to fail with DFL_E_INPUT and a NULL result,
 * its message holding each of the nwant strings (fatal assertions).
 * Returns nothing; the message is copied to msg (size >= DFL_ERR_MSG_MAX)
 * when msg is not NULL. */
void cfgu_expect_fail(const char *path, const char *const *want, int nwant, char *msg);
/* Value of [sec] key via dfl_cfg_string (fatal assertion that it exists). */
const char *cfgu_string(const dfl_cfg *c, const char *sec, const char *key);

#endif
