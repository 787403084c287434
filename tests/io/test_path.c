#include <criterion/criterion.h>

#include "io/path.h"

Test(path, base)
{
    cr_assert_str_eq(dfl_path_base("a/b.ini"), "b.ini");
    cr_assert_str_eq(dfl_path_base("/x/y/z"), "z");
    cr_assert_str_eq(dfl_path_base("b"), "b");
    cr_assert_str_eq(dfl_path_base("a/"), "");
    cr_assert_str_eq(dfl_path_base(""), "");
}

Test(path, stem)
{
    char buf[16];
    cr_assert_str_eq(dfl_path_stem("configs/paper/bs04/bs04_fields.ini", buf, sizeof buf),
                     "bs04_fields");
    cr_assert_str_eq(dfl_path_stem("a/b.c.ini", buf, sizeof buf), "b.c");
    cr_assert_str_eq(dfl_path_stem(".ini", buf, sizeof buf), ".ini");
    cr_assert_str_eq(dfl_path_stem("noext", buf, sizeof buf), "noext");
    cr_assert_str_eq(dfl_path_stem("d/abcdefghijklmnopqrstuvwxyz.ini", buf, 8), "abcdefg");
    char one[1] = {'x'};
    dfl_path_stem("a.b", one, 1);
    cr_assert_eq(one[0], '\0');
    dfl_path_stem("a.b", one, 0); /* size 0: buf untouched */
    cr_assert_eq(one[0], '\0');
}
