/* Shared by the harnesses: the fuzzer's bytes as a C string. */
#ifndef DFL_TESTS_FUZZ_UTIL_H
#define DFL_TESTS_FUZZ_UTIL_H

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* A malloc'ed NUL-terminated copy of data[0..size) (a NUL inside ends the
 * string early, as it would for dfl_cfg_parse_string); NULL when out of
 * memory.  The caller frees it. */
static inline char *fuzz_text(const uint8_t *data, size_t size)
{
    char *t = malloc(size + 1);
    if (!t) return NULL;
    memcpy(t, data, size);
    t[size] = '\0';
    return t;
}

#endif
