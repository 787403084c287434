/* io/atomic.h's failure rule: where the user's place cannot hold files the
 * status is DFL_E_INPUT (exit 2), for the machine's failures DFL_E_IO. */
#include <criterion/criterion.h>
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "io/atomic.h"
#include "util/tmpdir.h"

Test(atomic, errno_status_names_the_users_place)
{
    static const int input[] = {EROFS, EACCES, EPERM, ENOTDIR, ENAMETOOLONG, ELOOP};
    static const int io[] = {ENOSPC, EIO, EDQUOT, ENOMEM, EMFILE, 0};
    for (size_t i = 0; i < sizeof input / sizeof input[0]; i++)
        cr_expect_eq(dfl_io_errno_status(input[i]), DFL_E_INPUT, "errno %d", input[i]);
    for (size_t i = 0; i < sizeof io / sizeof io[0]; i++)
        cr_expect_eq(dfl_io_errno_status(io[i]), DFL_E_IO, "errno %d", io[i]);
}

/* A regular file where a folder should be: mkdir below it is ENOTDIR,
 * and the file itself "not a directory"; both DFL_E_INPUT naming it. */
Test(atomic, mkdir_p_below_a_file_is_input)
{
    char t[256], f[600], d[700];
    tmpdir_new(t, sizeof t);
    tmpdir_write(t, "file", "x", f, sizeof f);
    dfl_err err;
    snprintf(d, sizeof d, "%s/sub", f);
    cr_expect_eq(dfl_mkdir_p(d, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "file") != NULL, "%s", err.msg);
    cr_expect_eq(dfl_mkdir_p(f, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "not a directory") != NULL, "%s", err.msg);
    dfl_atomic_file af;
    cr_expect_eq(dfl_atomic_open(d, &af, &err), DFL_E_INPUT, "%s", err.msg);
    tmpdir_remove(t);
}
