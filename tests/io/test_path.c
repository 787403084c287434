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

Test(path, beside)
{
    char b[64];
    cr_assert_str_eq(dfl_path_beside("configs/paper/bs04/x.ini", "../../shapes/S.ini", b, sizeof b),
                     "configs/shapes/S.ini");
    cr_assert_str_eq(dfl_path_beside("configs/paper/x.ini", "S.ini", b, sizeof b),
                     "configs/paper/S.ini");
    cr_assert_str_eq(dfl_path_beside("x.ini", "shapes/./S.ini", b, sizeof b), "shapes/S.ini");
    cr_assert_str_eq(dfl_path_beside("x.ini", "../S.ini", b, sizeof b), "../S.ini");
    cr_assert_str_eq(dfl_path_beside("a/x.ini", "../../S.ini", b, sizeof b), "../S.ini");
    cr_assert_str_eq(dfl_path_beside("../a/x.ini", "../../S.ini", b, sizeof b), "../../S.ini");
    cr_assert_str_eq(dfl_path_beside("a//b/x.ini", "c//d", b, sizeof b), "a/b/c/d");
    cr_assert_str_eq(dfl_path_beside("a/x.ini", "..", b, sizeof b), ".");
    /* absolute paths: rel as is (cleaned); ".." never climbs above "/" */
    cr_assert_str_eq(dfl_path_beside("configs/x.ini", "/etc/dflab/S.ini", b, sizeof b),
                     "/etc/dflab/S.ini");
    cr_assert_str_eq(dfl_path_beside("/tmp/d/x.ini", "../../../S.ini", b, sizeof b), "/S.ini");
    cr_assert_str_eq(dfl_path_beside("/x.ini", "S.ini", b, sizeof b), "/S.ini");
    cr_assert_str_eq(dfl_path_beside("/x.ini", "..", b, sizeof b), "/");
    /* too small: NULL, never an overflow */
    char s[8];
    cr_assert_null(dfl_path_beside("configs/x.ini", "S.ini", s, sizeof s)); /* 13 chars */
    cr_assert_str_eq(dfl_path_beside("c/x.ini", "S.ini", s, sizeof s), "c/S.ini");
    cr_assert_null(dfl_path_beside("c/x.ini", "S.ini", s, 7));
    cr_assert_null(dfl_path_beside("x", "/", s, 1));
    cr_assert_str_eq(dfl_path_beside("x", "/", s, 2), "/");
}
