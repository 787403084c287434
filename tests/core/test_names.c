/* core/names: lookup, the '|' list and the parse message. */
#include <criterion/criterion.h>
#include <string.h>

#include "core/names.h"
#include "util/names_check.h"

static const char *const fruit[] = {"apple", "pear", "plum"};

Test(core_names, find_is_exact)
{
    cr_expect_eq(dfl_names_find(fruit, 3, "apple"), 0);
    cr_expect_eq(dfl_names_find(fruit, 3, "plum"), 2);
    cr_expect_eq(dfl_names_find(fruit, 3, "Plum"), -1);
    cr_expect_eq(dfl_names_find(fruit, 3, "pea"), -1);
    cr_expect_eq(dfl_names_find(fruit, 3, "pears"), -1);
    cr_expect_eq(dfl_names_find(fruit, 3, ""), -1);
    cr_expect_eq(dfl_names_find(fruit, 0, "apple"), -1);
    cr_expect_eq(dfl_names_find(fruit, 2, "plum"), -1, "only the first count names");
}

Test(core_names, at_is_total)
{
    cr_expect_str_eq(dfl_names_at(fruit, 3, 0), "apple");
    cr_expect_str_eq(dfl_names_at(fruit, 3, 2), "plum");
    cr_expect_str_eq(dfl_names_at(fruit, 3, 3), "?");
    cr_expect_str_eq(dfl_names_at(fruit, 3, -1), "?");
}

/* The X-macro columns build an enum, its count and its table. */
#define TEST_LIST(X) X(TEST_A, "a", 0) X(TEST_B, "bee", 1) X(TEST_C, "c", 2)
typedef enum test_code { TEST_LIST(DFL_NAMES_CODE) } test_code;
enum { TEST_COUNT = 0 TEST_LIST(DFL_NAMES_ONE) };
DFL_NAMES_DEFINE(test_code, TEST_LIST, TEST_COUNT, letter_names, letter_name, letter_parse,
                 "letter")

Test(core_names, x_macro_columns)
{
    cr_assert_eq(TEST_COUNT, 3);
    cr_expect_eq((int)TEST_A, 0);
    cr_expect_eq((int)TEST_B, 1);
    cr_expect_eq((int)TEST_C, 2);
    dfl_err err;
    NAMES_CHECK(test_code, TEST_COUNT, letter_names, letter_name, letter_parse, "a|bee|c", "d",
                TEST_B, err);
    cr_expect_str_eq(err.msg, "unknown letter 'd' (expected one of a|bee|c)");
}

Test(core_names, list_and_truncation)
{
    char buf[64];
    cr_expect_str_eq(dfl_names_list(fruit, 3, buf, sizeof buf), "apple|pear|plum");
    cr_expect_str_eq(dfl_names_list(fruit, 1, buf, sizeof buf), "apple");
    cr_expect_str_eq(dfl_names_list(fruit, 0, buf, sizeof buf), "");
    char small[8];
    cr_expect_str_eq(dfl_names_list(fruit, 3, small, sizeof small), "apple|p");
    char one[1] = {'x'};
    cr_expect_str_eq(dfl_names_list(fruit, 3, one, sizeof one), "");
}

Test(core_names, parse_reports_the_names)
{
    int i = 7;
    dfl_err err;
    cr_expect_eq(dfl_names_parse("fruit", fruit, 3, "pear", &i, &err), DFL_OK);
    cr_expect_eq(i, 1);
    i = 7;
    cr_expect_eq(dfl_names_parse("fruit", fruit, 3, "kiwi", &i, &err), DFL_E_INPUT);
    cr_expect_eq(i, 7, "untouched on failure");
    cr_expect_str_eq(err.msg, "unknown fruit 'kiwi' (expected one of apple|pear|plum)");
    cr_expect_eq(dfl_names_parse("fruit", fruit, 3, "kiwi", &i, NULL), DFL_E_INPUT);
}
