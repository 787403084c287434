/* The contract of a name table made by DFL_NAMES_DEFINE (core/names.h),
 * checked against the names a test spells out in list order.
 *
 *   NAMES_CHECK(type, count, names, name_fn, parse_fn, list, bad, keep, err)
 *
 * list is the expected names joined by '|' ("a|bee|c"), the name of code i
 * being the i-th; the test asserts the code values themselves.  Checked,
 * with Criterion expectations (the number of names with an assertion):
 *   - list has count names; name_fn((type)i) and names[i] are the i-th, and
 *     parse_fn of it gives i back;
 *   - name_fn of count and of -1 is "?";
 *   - parse_fn(bad) fails with DFL_E_INPUT, leaves a variable holding keep
 *     unchanged, and its message quotes 'bad' and holds list.
 * The failed parse's message stays in err (a dfl_err variable) for the
 * test's own checks.  list and bad are string literals. */
#ifndef DFL_TESTS_NAMES_CHECK_H
#define DFL_TESTS_NAMES_CHECK_H

#include <criterion/criterion.h>
#include <string.h>

#include "core/status.h"

#define NAMES_CHECK(type, count, names, name_fn, parse_fn, list, bad, keep, err)              \
    do {                                                                                  \
        char nc_buf[] = list;                                                             \
        int nc_i = 0;                                                                     \
        char *nc_save = NULL;                                                             \
        for (char *nc_tok = strtok_r(nc_buf, "|", &nc_save); nc_tok;                      \
             nc_tok = strtok_r(NULL, "|", &nc_save), nc_i++) {                            \
            cr_assert_lt(nc_i, (int)(count), "more names than codes: %s", nc_tok);         \
            cr_expect_str_eq(name_fn((type)nc_i), nc_tok);                                \
            cr_expect_str_eq((names)[nc_i], nc_tok);                                      \
            type nc_v = (type)-1;                                                         \
            cr_expect_eq(parse_fn(nc_tok, &nc_v, NULL), DFL_OK, "%s", nc_tok);            \
            cr_expect_eq((int)nc_v, nc_i, "%s", nc_tok);                                  \
        }                                                                                 \
        cr_assert_eq(nc_i, (int)(count));                                                 \
        cr_expect_str_eq(name_fn((type)(count)), "?");                                    \
        cr_expect_str_eq(name_fn((type)-1), "?");                                         \
        type nc_kept = (keep);                                                            \
        cr_expect_eq(parse_fn(bad, &nc_kept, &(err)), DFL_E_INPUT);                       \
        cr_expect_eq(nc_kept, (keep));                                                    \
        cr_expect(strstr((err).msg, "'" bad "'") && strstr((err).msg, list), "%s",        \
                  (err).msg);                                                             \
    } while (0)

#endif
