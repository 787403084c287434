/* Tests for dfl_dir_link_or_copy (src/io/dirs.c): the result is a copy of
 * its own, never a second name of the source. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "io/dirs.h"
#include "util/tmpdir.h"

Test(dirs_copy, editing_the_copy_in_place_leaves_the_source)
{
    char dir[64], src[128], dst[192];
    tmpdir_new(dir, sizeof dir);
    tmpdir_write(dir, "a.vti", "0123456789", src, sizeof src);
    snprintf(dst, sizeof dst, "%s/b.vti", dir);
    dfl_err err = {0};
    cr_assert_eq(dfl_dir_link_or_copy(src, dst, &err), DFL_OK, "%s", err.msg);
    struct stat a, b;
    cr_assert_eq(stat(src, &a), 0);
    cr_assert_eq(stat(dst, &b), 0);
    cr_expect_neq(a.st_ino, b.st_ino, "the copy is a hard link of the source");
    cr_expect_eq(a.st_nlink, 1);
    /* an in-place write (no new file, as an editor's "save" may do) */
    FILE *fp = fopen(dst, "r+b");
    cr_assert_not_null(fp);
    fputs("XY", fp);
    fclose(fp);
    size_t n;
    char *s = dfl_file_read_all(src, &n), *d = dfl_file_read_all(dst, NULL);
    cr_expect_str_eq(s, "0123456789");
    cr_expect_str_eq(d, "XY23456789");
    free(s), free(d);
    /* an existing dst is replaced */
    cr_assert_eq(dfl_dir_link_or_copy(src, dst, &err), DFL_OK, "%s", err.msg);
    d = dfl_file_read_all(dst, NULL);
    cr_expect_str_eq(d, "0123456789");
    free(d);
    cr_expect_eq(tmpdir_count(dir), 2); /* no temporary left */
    tmpdir_remove(dir);
}

Test(dirs_copy, a_fifo_source_is_refused_at_once, .timeout = 10)
{
    char dir[64], src[128], dst[192];
    tmpdir_file(dir, sizeof dir, "f", src, sizeof src);
    cr_assert_eq(mkfifo(src, 0600), 0);
    snprintf(dst, sizeof dst, "%s/g", dir);
    dfl_err err = {0};
    cr_expect_eq(dfl_dir_link_or_copy(src, dst, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "a FIFO"), "%s", err.msg);
    cr_expect_eq(tmpdir_count(dir), 1);
    tmpdir_remove(dir);
}
