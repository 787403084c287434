/* Tests for the finders of src/io/manifest.c (dfl_json_find_string and
 * dfl_json_find_number): each reads only inside its text. */
#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>

#include "io/manifest.h"

/* text in a malloc'ed block of exactly strlen(text) + 1 bytes, so that
 * AddressSanitizer sees any read past the terminating NUL. */
static char *exact(const char *text)
{
    const size_t n = strlen(text) + 1;
    char *t = malloc(n);
    cr_assert_not_null(t);
    memcpy(t, text, n);
    return t;
}

Test(manifest_find, u_escape_at_the_end_reads_nothing_past_it)
{
    /* a \u escape with 0..3 of its 4 digits before the end of the text */
    const char *cases[] = {"{\"k\": \"\\u", "{\"k\": \"\\u0", "{\"k\": \"\\u00", "{\"k\": \"\\u004"};
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char *t = exact(cases[i]);
        char buf[16];
        dfl_json_find_string(t, "k", buf, sizeof buf);
        cr_assert(strlen(buf) < sizeof buf);
        free(t);
    }
}

Test(manifest_find, u_escape_decodes_ascii)
{
    char *t = exact("{\"k\": \"a\\u0041b\"}");
    char buf[16];
    cr_assert_eq(dfl_json_find_string(t, "k", buf, sizeof buf), 1);
    cr_assert_str_eq(buf, "aAb");
    free(t);
}

Test(manifest_find, short_u_escape_is_not_a_string)
{
    /* \u with fewer than 4 hex digits is not JSON: the field is absent */
    char *t = exact("{\"k\": \"\\u4x\"}");
    char buf[16];
    cr_assert_eq(dfl_json_find_string(t, "k", buf, sizeof buf), 0);
    cr_assert_str_eq(buf, "");
    free(t);
}
