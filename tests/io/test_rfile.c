/* Tests for src/io/rfile.c: only regular files are read, and nothing
 * blocks on the way to refusing the others. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "io/rfile.h"
#include "util/tmpdir.h"

Test(rfile, fifo_directory_and_device_are_refused_at_once, .timeout = 10)
{
    char dir[64], fifo[128];
    tmpdir_file(dir, sizeof dir, "point.json", fifo, sizeof fifo);
    cr_assert_eq(mkfifo(fifo, 0600), 0);
    struct {
        const char *path, *want;
    } cases[] = {{fifo, "not a regular file (a FIFO)"},
                 {dir, "not a regular file (a directory)"},
                 {"/dev/null", "not a regular file (a device)"}};
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        dfl_err err = {0};
        char *text = (char *)1;
        cr_expect_eq(dfl_rfile_read(cases[i].path, "", 100, &text, NULL, &err), DFL_E_INPUT);
        cr_expect_null(text);
        cr_expect(strstr(err.msg, cases[i].path) == err.msg, "%s", err.msg);
        cr_expect(strstr(err.msg, cases[i].want), "%s", err.msg);
        FILE *fp = (FILE *)1;
        cr_expect_eq(dfl_rfile_open(cases[i].path, "config", &fp, &err), DFL_E_INPUT);
        cr_expect_null(fp);
        cr_expect(strstr(err.msg, cases[i].path) == err.msg, "%s", err.msg);
    }
    tmpdir_remove(dir);
}

Test(rfile, reads_a_whole_file_up_to_max_bytes)
{
    char dir[64], path[128];
    tmpdir_new(dir, sizeof dir);
    /* 70000 bytes: more than one read block */
    char *big = malloc(70001);
    cr_assert_not_null(big);
    memset(big, 'a', 70000);
    big[70000] = '\0';
    tmpdir_write(dir, "f", big, path, sizeof path);
    dfl_err err = {0};
    char *text;
    size_t len;
    cr_assert_eq(dfl_rfile_read(path, "", 70000, &text, &len, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(len, 70000);
    cr_expect_eq(strlen(text), 70000);
    free(text);
    cr_expect_eq(dfl_rfile_read(path, "", 69999, &text, &len, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "larger than 69999 bytes"), "%s", err.msg);
    cr_expect_null(text);
    cr_expect_eq(dfl_rfile_read("/nonexistent/x", "", 10, &text, &len, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "/nonexistent/x: cannot open: "), "%s", err.msg);
    FILE *fp;
    cr_expect_eq(dfl_rfile_open("/nonexistent/x", "config", &fp, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "/nonexistent/x: cannot open config: No such file"), "%s", err.msg);
    free(big);
    tmpdir_remove(dir);
}
